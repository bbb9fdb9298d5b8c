/* lock: flock on PARENT/.NAME.lock naming its holder (lock.h). */
#include "config.h"
#include "base/lock.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/util.h"

struct lock {
	char *path;	/* the lock file */
	int fd;		/* open, flock'ed */
};

char *lock_path(const char *path)
{
	char *t = xstrdup(path);
	size_t n = strlen(t);
	while (n > 1 && t[n - 1] == '/')
		t[--n] = '\0';
	char *slash = strrchr(t, '/'), *r;
	if (slash == NULL)
		r = xasprintf(".%s.lock", t);
	else {
		*slash = '\0';
		r = xasprintf("%s/.%s.lock", slash == t ? "" : t, slash + 1);
	}
	free(t);
	return r;
}

/* "PID HOST COMMAND LINE" of this process, one line. */
static char *holder_line(void)
{
	char host[HOST_NAME_MAX + 1] = "localhost", cmd[512] = "";
	gethostname(host, sizeof host);
	host[sizeof host - 1] = '\0';
	int fd = open("/proc/self/cmdline", O_RDONLY);
	ssize_t n = fd >= 0 ? read(fd, cmd, sizeof cmd - 1) : -1;
	if (fd >= 0)
		close(fd);
	if (n < 0)
		n = 0;
	cmd[n] = '\0';
	for (ssize_t i = 0; i < n; i++)
		if (cmd[i] == '\0' || cmd[i] == '\n')
			cmd[i] = ' ';
	while (n > 0 && cmd[n - 1] == ' ')
		cmd[--n] = '\0';
	return xasprintf("%ld %s %s\n", (long)getpid(), host, cmd);
}

/* The refusal, from what the holder wrote into the lock file. */
static char *busy_cause(const char *path, int fd)
{
	char b[700] = "";
	ssize_t n = pread(fd, b, sizeof b - 1, 0);
	b[n > 0 ? n : 0] = '\0';
	char *nl = strchr(b, '\n');
	if (nl)
		*nl = '\0';
	long pid = 0;
	char host[256] = "?";
	int used = 0;
	if (sscanf(b, "%ld %255s %n", &pid, host, &used) < 2 || pid <= 0)
		return xasprintf("%s is being written by another process (its lock %s is held); wait for it to finish "
		    "or stop it", path, "file");
	return xasprintf("%s is being written by process %ld (%s) on %s; wait for it to finish or stop it", path, pid,
	    used > 0 && b[used] ? b + used : "command unknown", host);
}

struct lock *lock_take(const char *path, char **cause)
{
	char *lp = lock_path(path);
	for (int attempt = 0; attempt < 100; attempt++) {
		int fd = open(lp, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
		if (fd < 0) {
			*cause = xasprintf("%s: cannot create the lock file: %s", lp, strerror(errno));
			break;
		}
		if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
			int e = errno;
			*cause = e == EWOULDBLOCK ? busy_cause(path, fd)
						  : xasprintf("%s: cannot lock: %s", lp, strerror(e));
			close(fd);
			break;
		}
		/* The holder before us may have removed the file after we opened
		 * it: the lock is ours only if the name still leads to our file. */
		struct stat a, b;
		if (fstat(fd, &a) != 0 || stat(lp, &b) != 0 || a.st_ino != b.st_ino || a.st_dev != b.st_dev) {
			close(fd);
			continue;
		}
		char *line = holder_line();
		size_t len = strlen(line);
		int ok = ftruncate(fd, 0) == 0 && pwrite(fd, line, len, 0) == (ssize_t)len;
		free(line);
		if (!ok) {
			*cause = xasprintf("%s: cannot write the lock file: %s", lp, strerror(errno));
			unlink(lp);
			close(fd);
			break;
		}
		struct lock *l = xmalloc(sizeof *l);
		l->path = lp;
		l->fd = fd;
		return l;
	}
	if (*cause == NULL)
		*cause = xasprintf("%s: the lock file keeps changing", lp);
	free(lp);
	return NULL;
}

void lock_release(struct lock *l)
{
	if (l == NULL)
		return;
	unlink(l->path);	/* while still held: a waiter re-checks the name */
	close(l->fd);
	free(l->path);
	free(l);
}
