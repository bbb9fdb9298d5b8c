/* lock: one writer at a time for an output (a directory or a checkpoint
 * file).  The lock is flock(2) on a file beside the output,
 * PARENT/.NAME.lock, which holds "PID HOST COMMAND-LINE" of the holder so
 * that a second writer is told who is running.  The kernel releases the
 * flock when its holder dies (also on SIGKILL), so a lock file left by a
 * killed run is taken over by the next one; a held lock file is removed by
 * its holder on release.  Not re-entrant: taking the same lock twice in one
 * process is refused like a second process. */
#ifndef SKINBAKE_LOCK_H
#define SKINBAKE_LOCK_H

struct lock;

/* Take the lock of PATH (a directory or file, existing or not; its parent
 * must exist).  NULL and *cause (caller frees) when another process holds
 * it: "PATH is being written by process PID (COMMAND) on HOST ...". */
struct lock *lock_take(const char *path, char **cause);
/* Release and remove the lock file; lock_release(NULL) is a no-op. */
void lock_release(struct lock *l);
/* The lock file's name for PATH; caller frees. */
char *lock_path(const char *path);
#endif
