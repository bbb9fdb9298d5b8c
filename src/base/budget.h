/* budget: the memory and disk a piece of work will need, checked before it
 * starts (issue 23 item 5), so that a documented but too large size ends at
 * once with exit status 2 and the numbers, instead of an out-of-memory
 * abort or a full disk after minutes of work.  Memory is compared with the
 * kernel's estimate of what can be had without swapping (MemAvailable in
 * /proc/meminfo), disk with what the output's file system has free for
 * this user (statvfs); each need is an estimate from the sizes of the
 * buffers and files, stated as such in the message. */
#ifndef SKINBAKE_BUDGET_H
#define SKINBAKE_BUDGET_H

/* Bytes of memory available now (MemAvailable), or -1 when unknown. */
double budget_memory_available(void);
/* Bytes free on the file system that holds PATH (or its nearest existing
 * parent), or -1 when unknown. */
double budget_disk_available(const char *path);
/* 0 when MEM bytes of memory and DISK bytes under OUT (either may be 0)
 * fit; -1 and *cause (caller frees): "WHAT needs about X GB of memory
 * (estimated), Y GB are available; LOWER" otherwise.  Unknown amounts pass. */
int budget_check(const char *what, double mem, double disk, const char *out, const char *lower,
    char **cause);
#endif
