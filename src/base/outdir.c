/* outdir: output directories replaced as a whole through a staging
 * directory and one atomic swap (outdir.h describes the protocol). */
#include "config.h"
#include "base/outdir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <ftw.h>
#include <json-c/json.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/lock.h"
#include "base/util.h"

/* Host part of staging names: a PID means something only on its own host
 * (an output directory on a cluster's shared disk is seen from many). */
static char *host_name(void)
{
	char h[HOST_NAME_MAX + 1] = "";
	if (gethostname(h, sizeof h) != 0 || h[0] == '\0')
		snprintf(h, sizeof h, "localhost");
	h[sizeof h - 1] = '\0';
	for (char *s = h; *s; s++)
		if (*s == '/')
			*s = '_';
	return xstrdup(h);
}

static char *side_name(const char *parent, const char *name, const char *kind)
{
	char *host = host_name();
	char *s = xasprintf("%s/.%s.%s.%s.%ld", parent, name, kind, host, (long)getpid());
	free(host);
	return s;
}

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
	(void)st;
	(void)ftw;
	if (flag == FTW_DP)
		rmdir(path);
	else
		unlink(path);
	return 0;	/* carry on: remove as much as can be removed */
}

/* rm -rf without following symbolic links. */
static void remove_tree(const char *path)
{
	struct stat st;
	if (lstat(path, &st) != 0)
		return;
	if (!S_ISDIR(st.st_mode)) {
		unlink(path);
		return;
	}
	nftw(path, remove_one, 16, FTW_DEPTH | FTW_PHYS);
}

static int sync_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
	(void)ftw;
	if (flag != FTW_F && flag != FTW_DP)
		return 0;
	if (flag == FTW_F && !S_ISREG(st->st_mode))
		return 0;
	int fd = open(path, O_RDONLY | (flag == FTW_DP ? O_DIRECTORY : 0));
	if (fd < 0)
		return -1;
	int rc = fsync(fd);
	if (rc != 0 && errno == EINVAL)
		rc = 0;	/* a file system without fsync (some FUSE): nothing to wait for */
	close(fd);
	return rc;
}

static int sync_dir(const char *path)
{
	int fd = open(path, O_RDONLY | O_DIRECTORY);
	if (fd < 0)
		return -1;
	int rc = fsync(fd);
	close(fd);
	return rc;
}

static int is_empty_dir(const char *path)
{
	DIR *d = opendir(path);
	if (d == NULL)
		return 0;
	struct dirent *e;
	int empty = 1;
	while (empty && (e = readdir(d)) != NULL)
		if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
			empty = 0;
	closedir(d);
	return empty;
}

/* Does NAME (an entry of the target's parent) look like ".TARGET.KIND.HOST.PID"
 * of a process that is gone?  Sets *kind_retired for retired sets. */
static int is_stale(const char *entry, const char *target_name, int *kind_retired)
{
	size_t n = strlen(target_name);
	if (entry[0] != '.' || strncmp(entry + 1, target_name, n) != 0 || entry[n + 1] != '.')
		return 0;
	const char *rest = entry + n + 2, *host;
	if (strncmp(rest, "staging.", 8) == 0) {
		host = rest + 8;
		*kind_retired = 0;
	} else if (strncmp(rest, "retired.", 8) == 0) {
		host = rest + 8;
		*kind_retired = 1;
	} else
		return 0;
	const char *dot = strrchr(host, '.');
	if (dot == NULL || dot == host)
		return 0;
	char *end;
	errno = 0;
	long pid = strtol(dot + 1, &end, 10);
	if (*end != '\0' || errno != 0 || pid <= 0 || pid > INT_MAX)
		return 0;
	char *me = host_name();
	int same_host = strlen(me) == (size_t)(dot - host) && strncmp(me, host, (size_t)(dot - host)) == 0;
	free(me);
	if (!same_host)
		return 0;	/* cannot tell whether it is alive */
	return kill((pid_t)pid, 0) != 0 && errno == ESRCH;
}

/* Split TARGET into parent and name (trailing slashes dropped); -1 for
 * names that cannot be replaced. */
static int split_target(const char *target, char **parent, char **name, char **cause)
{
	size_t len = strlen(target);
	while (len > 1 && target[len - 1] == '/')
		len--;
	char *t = xstrdup(target);
	t[len] = '\0';
	char *slash = strrchr(t, '/');
	const char *base = slash ? slash + 1 : t;
	if (*t == '\0' || strcmp(base, ".") == 0 || strcmp(base, "..") == 0 || *base == '\0') {
		*cause = *t == '\0' ? xstrdup("the output directory name is empty")
				    : xasprintf("%s: cannot replace this directory as a whole; name the output "
					"directory itself (e.g. %s/out)", target, strcmp(t, "/") == 0 ? "" : t);
		free(t);
		return -1;
	}
	*name = xstrdup(base);
	if (slash == NULL)
		*parent = xstrdup(".");
	else if (slash == t)
		*parent = xstrdup("/");
	else {
		*slash = '\0';
		*parent = xstrdup(t);
	}
	free(t);
	return 0;
}

int outdir_clean_stale(const char *target)
{
	char *parent, *name, *cause = NULL;
	if (split_target(target, &parent, &name, &cause) != 0) {
		free(cause);
		return 0;
	}
	DIR *d = opendir(parent);
	int found = 0;
	if (d != NULL) {
		char *full = xasprintf("%s/%s", parent, name);
		struct dirent *e;
		while ((e = readdir(d)) != NULL) {
			int retired;
			if (!is_stale(e->d_name, name, &retired))
				continue;
			found++;
			char *p = xasprintf("%s/%s", parent, e->d_name);
			struct stat st;
			/* A retired set is complete: it goes back if nothing replaced it. */
			if (!(retired && lstat(full, &st) != 0 && errno == ENOENT && rename(p, full) == 0))
				remove_tree(p);
			free(p);
		}
		closedir(d);
		free(full);
	}
	free(parent);
	free(name);
	return found;
}

static void outdir_free(struct outdir *o)
{
	lock_release(o->lock);
	free(o->target);
	free(o->parent);
	free(o->name);
	free(o->staging);
	free(o->retired);
	memset(o, 0, sizeof *o);
}

/* Does LIST (an array of names, or an object keyed by name) name ENTRY or
 * a path under it? */
static int listed(const char *entry, json_object *list)
{
	size_t n = strlen(entry);
	if (list && json_object_is_type(list, json_type_object)) {
		json_object_object_foreach(list, key, val) {
			(void)val;
			if (strncmp(key, entry, n) == 0 && (key[n] == '\0' || key[n] == '/'))
				return 1;
		}
	} else if (list && json_object_is_type(list, json_type_array)) {
		for (size_t i = 0; i < json_object_array_length(list); i++) {
			const char *key = json_object_get_string(json_object_array_get_idx(list, i));
			if (key && strncmp(key, entry, n) == 0 && (key[n] == '\0' || key[n] == '/'))
				return 1;
		}
	}
	return 0;
}

/* Is ENTRY (a name in an output directory) part of an output of kind K
 * whose manifest is J? */
static int entry_ours(const char *entry, const struct outdir_kind *k, json_object *j)
{
	if (k->names == NULL || strcmp(entry, k->marker) == 0)
		return 1;
	for (const char *const *p = k->names; *p; p++)
		if (fnmatch(*p, entry, FNM_PERIOD) == 0)
			return 1;
	json_object *files = NULL, *sums = NULL;
	if (j && json_object_is_type(j, json_type_object)) {
		json_object_object_get_ex(j, "files", &files);
		json_object_object_get_ex(j, "checksums", &sums);
	}
	return listed(entry, files) || listed(entry, sums);
}

/* TARGET, an existing non-empty directory: a complete output of kind K and
 * nothing else? */
static int check_kind(const char *target, const struct outdir_kind *k, char **cause)
{
	char *m = xasprintf("%s/%s", target, k->marker);
	json_object *j = NULL, *v;
	int rc = -1;
	if (access(m, F_OK) != 0) {
		*cause = xasprintf("%s is a directory without %s, not a %s: it would be replaced as a whole; name a new "
		    "or empty directory", target, k->marker, k->what);
		goto out;
	}
	if (k->key != NULL) {
		j = json_object_from_file(m);
		const char *val = j && json_object_object_get_ex(j, k->key, &v) && json_object_is_type(v, json_type_string)
		    ? json_object_get_string(v) : NULL;
		if (val == NULL || strcmp(val, k->value) != 0) {
			*cause = xasprintf("%s holds %s, but not of a %s (%s \"%s\" expected, %s%s%s): it would be replaced "
			    "as a whole; name a new or empty directory", target, k->marker, k->what, k->key, k->value,
			    val ? "\"" : "", val ? val : j ? "none" : "not JSON", val ? "\" found" : "");
			goto out;
		}
	}
	DIR *d = opendir(target);
	struct dirent *e;
	rc = 0;
	while (rc == 0 && d && (e = readdir(d)) != NULL) {
		if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0 || entry_ours(e->d_name, k, j))
			continue;
		*cause = xasprintf("%s holds '%s', which is not part of a %s: it would be removed with the old output; "
		    "move it away or name another directory", target, e->d_name, k->what);
		rc = -1;
	}
	if (d)
		closedir(d);
out:
	if (j)
		json_object_put(j);
	free(m);
	return rc;
}

/* PATH made absolute with its symbolic links resolved as far as it exists;
 * caller frees. */
static char *resolved(const char *path)
{
	char *r = realpath(path, NULL);
	if (r != NULL)
		return r;
	char *parent, *name, *cause = NULL;
	if (split_target(path, &parent, &name, &cause) != 0) {
		free(cause);
		return xstrdup(path);
	}
	char *rp = resolved(parent);
	r = xasprintf("%s/%s", strcmp(rp, "/") == 0 ? "" : rp, name);
	free(rp);
	free(parent);
	free(name);
	return r;
}

/* Is directory A equal to, or above, B? */
static int contains(const char *a, const char *b)
{
	size_t n = strlen(a);
	return strncmp(a, b, n) == 0 && (b[n] == '\0' || b[n] == '/' || (n == 1 && a[0] == '/'));
}

static int check_inputs(const char *target, const char *const *inputs, char **cause)
{
	char *t = resolved(target);
	int rc = 0;
	for (const char *const *p = inputs; rc == 0 && p && *p; p++) {
		char *in = resolved(*p);
		if (strcmp(t, in) == 0)
			*cause = xasprintf("%s is also an input of this command (%s): writing it would destroy what is read; "
			    "name another output directory", target, *p), rc = -1;
		else if (contains(t, in))
			*cause = xasprintf("the input %s is inside %s, which would be replaced as a whole; name another output "
			    "directory", *p, target), rc = -1;
		else if (contains(in, t))
			*cause = xasprintf("%s is inside the input %s: writing it would change an input; name an output "
			    "directory outside it", target, *p), rc = -1;
		free(in);
	}
	free(t);
	return rc;
}

int outdir_check(const char *target, const struct outdir_kind *kind, const char *const *inputs, char **cause)
{
	char *parent, *name;
	if (split_target(target, &parent, &name, cause) != 0)
		return -1;
	free(parent);
	free(name);
	struct stat st;
	if (stat(target, &st) != 0) {
		if (errno == ENOENT && lstat(target, &st) == 0) {
			*cause = xasprintf("%s is a symbolic link to a directory that does not exist", target);
			return -1;
		}
		if (errno != ENOENT) {
			*cause = xasprintf("%s: %s", target, strerror(errno));
			return -1;
		}
	} else if (!S_ISDIR(st.st_mode)) {
		*cause = xasprintf("%s exists and is not a directory", target);
		return -1;
	} else if (!is_empty_dir(target) && check_kind(target, kind, cause) != 0)
		return -1;
	return check_inputs(target, inputs, cause);
}

int outdir_begin(struct outdir *o, const char *target, const struct outdir_kind *kind, char **cause)
{
	memset(o, 0, sizeof *o);
	if (outdir_check(target, kind, NULL, cause) != 0 || split_target(target, &o->parent, &o->name, cause) != 0)
		return -1;
	if (util_mkdirs(o->parent, cause) != 0) {
		outdir_free(o);
		return -1;
	}
	/* A symbolic link to a directory: replace the directory it names, beside itself. */
	char *real = realpath(target, NULL);
	struct stat st;
	if (real != NULL && lstat(target, &st) == 0 && S_ISLNK(st.st_mode)) {
		free(o->parent);
		free(o->name);
		if (split_target(real, &o->parent, &o->name, cause) != 0) {
			free(real);
			outdir_free(o);
			return -1;
		}
	}
	free(real);
	o->target = strcmp(o->parent, "/") == 0 ? xasprintf("/%s", o->name) : xasprintf("%s/%s", o->parent, o->name);
	/* Locked before anything beside the target is touched: the staging of
	 * a live writer is never taken for stale, and the check is repeated
	 * under the lock (another writer may have finished meanwhile). */
	if ((o->lock = lock_take(o->target, cause)) == NULL || outdir_check(o->target, kind, NULL, cause) != 0) {
		outdir_free(o);
		return -1;
	}
	outdir_clean_stale(o->target);
	o->staging = side_name(o->parent, o->name, "staging");
	o->retired = side_name(o->parent, o->name, "retired");
	remove_tree(o->staging);	/* our own PID: left by an earlier outdir in this process */
	if (mkdir(o->staging, 0777) != 0) {
		*cause = xasprintf("%s: cannot create the staging directory: %s", o->staging, strerror(errno));
		outdir_free(o);
		return -1;
	}
	return 0;
}

const char *outdir_path(const struct outdir *o)
{
	return o->staging;
}

/* Put staging in place of target; 0, or -1 with *cause and nothing changed. */
static int swap_in(struct outdir *o, char **cause)
{
	struct stat st;
	int exists = lstat(o->target, &st) == 0;
	if (!exists && rename(o->staging, o->target) == 0)
		return 0;	/* a fresh target */
	if (!exists && errno != EEXIST && errno != ENOTEMPTY)
		goto fail;
#ifdef RENAME_EXCHANGE
	if (renameat2(AT_FDCWD, o->staging, AT_FDCWD, o->target, RENAME_EXCHANGE) == 0)
		return 0;	/* o->staging now holds the old set */
	if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP)
		goto fail;
#endif
	/* No atomic exchange here: the target is briefly absent, never mixed. */
	if (rename(o->target, o->retired) != 0)
		goto fail;
	if (rename(o->staging, o->target) != 0) {
		int e = errno;
		rename(o->retired, o->target);
		errno = e;
		goto fail;
	}
	free(o->staging);
	o->staging = o->retired;	/* the old set, to be removed */
	o->retired = NULL;
	return 0;
fail:
	*cause = xasprintf("%s: cannot move the new files into place: %s", o->target, strerror(errno));
	return -1;
}

int outdir_commit(struct outdir *o, char **cause)
{
	if (o->staging == NULL) {
		*cause = xstrdup("outdir_commit without outdir_begin");
		return -1;
	}
	/* Data first, then the name: after a power cut the set is complete too. */
	if (nftw(o->staging, sync_one, 16, FTW_DEPTH | FTW_PHYS) != 0) {
		*cause = xasprintf("%s: cannot flush the new files to disk: %s", o->staging, strerror(errno));
		outdir_abort(o);
		return -1;
	}
	if (swap_in(o, cause) != 0) {
		outdir_abort(o);
		return -1;
	}
	sync_dir(o->parent);
	remove_tree(o->staging);	/* the old set; if this is cut short, the next run finishes it */
	outdir_free(o);
	return 0;
}

void outdir_abort(struct outdir *o)
{
	if (o->staging != NULL)
		remove_tree(o->staging);
	outdir_free(o);
}

void outdir_fail(struct outdir *o, char **cause)
{
	char *m = cause ? *cause : NULL, *at;
	size_t n = o->staging ? strlen(o->staging) : 0;
	while (m != NULL && n > 0 && (at = strstr(m, o->staging)) != NULL) {
		char *r = xasprintf("%.*s%s%s", (int)(at - m), m, o->target, at + n);
		free(m);
		m = r;
	}
	if (cause)
		*cause = m;
	outdir_abort(o);
}
