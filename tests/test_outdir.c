/* Output directories replaced as a whole (src/base/outdir.c): fresh and
 * existing targets, abort, refused targets, stale staging of dead runs,
 * the retired set put back, symbolic links.  Kills during the swap are in
 * tests/outdir_kill.sh. */
#include "config.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/outdir.h"
#include "base/util.h"

static char root[256];

static void put(const char *dir, const char *name, const char *text)
{
	char *p = xasprintf("%s/%s", dir, name);
	FILE *fp = fopen(p, "w");
	assert_non_null(fp);
	fputs(text, fp);
	fclose(fp);
	free(p);
}

/* The content of DIR/NAME ("" if missing; static buffer). */
static const char *get(const char *dir, const char *name)
{
	static char buf[64];
	char *p = xasprintf("%s/%s", dir, name);
	FILE *fp = fopen(p, "r");
	free(p);
	buf[0] = '\0';
	if (fp != NULL) {
		size_t n = fread(buf, 1, sizeof buf - 1, fp);
		buf[n] = '\0';
		fclose(fp);
	}
	return buf;
}

static int exists(const char *dir, const char *name)
{
	char *p = xasprintf("%s/%s", dir, name);
	struct stat st;
	int e = lstat(p, &st) == 0;
	free(p);
	return e;
}

/* Entries of DIR whose names start with PREFIX. */
static int count_prefix(const char *dir, const char *prefix)
{
	char *cmd = xasprintf("ls -A '%s' | grep -c '^%s'", dir, prefix);
	FILE *fp = popen(cmd, "r");
	int n = -1;
	assert_int_equal(fscanf(fp, "%d", &n), 1);
	pclose(fp);
	free(cmd);
	return n;
}

/* A kind as the writers declare theirs: the manifest names it, data.txt
 * and the files it lists belong to it. */
static const char *const set_names[] = { "data.txt", NULL };
static const struct outdir_kind set_kind = { "test set", "manifest.json", "format", "test-set", set_names };
static const struct outdir_kind other_kind = { "other set", "manifest.json", "format", "other-set", NULL };

static void write_set(const char *target, const char *gen)
{
	struct outdir o;
	char *cause = NULL;
	if (outdir_begin(&o, target, &set_kind, &cause) != 0)
		fail_msg("%s: %s", target, cause);
	put(outdir_path(&o), "data.txt", gen);
	put(outdir_path(&o), "manifest.json", "{\"format\": \"test-set\", \"files\": [\"listed.txt\", \"sub/x\"]}");
	assert_int_equal(outdir_commit(&o, &cause), 0);
}

static int setup(void **state)
{
	(void)state;
	snprintf(root, sizeof root, "%s/test_outdir.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
	return mkdtemp(root) == NULL ? -1 : 0;
}

static int teardown(void **state)
{
	(void)state;
	char *cmd = xasprintf("rm -rf '%s'", root);
	int rc = system(cmd);
	free(cmd);
	return rc;
}

static void test_fresh_and_replace(void **state)
{
	(void)state;
	char *t = xasprintf("%s/a/b/out", root), *parent = xasprintf("%s/a/b", root);
	write_set(t, "1");	/* parents created */
	assert_string_equal(get(t, "data.txt"), "1");
	write_set(t, "2");
	assert_string_equal(get(t, "data.txt"), "2");
	assert_int_equal(count_prefix(parent, "\\.out\\."), 0);	/* no staging or lock left */
	put(t, "listed.txt", "x");	/* named by the manifest's "files": part of the old set */
	char *sub = xasprintf("%s/sub", t);
	mkdir(sub, 0777);
	write_set(t, "3");
	assert_false(exists(t, "listed.txt"));
	assert_false(exists(t, "sub"));
	free(sub);
	free(t);
	free(parent);
}

static void test_abort(void **state)
{
	(void)state;
	char *t = xasprintf("%s/ab", root), *cause = NULL;
	write_set(t, "1");
	struct outdir o;
	assert_int_equal(outdir_begin(&o, t, &set_kind, &cause), 0);
	put(outdir_path(&o), "data.txt", "2");
	outdir_abort(&o);
	outdir_abort(&o);	/* harmless twice */
	assert_string_equal(get(t, "data.txt"), "1");
	assert_int_equal(count_prefix(root, "\\.ab\\."), 0);
	free(t);
}

static void refused_kind(const char *target, const struct outdir_kind *k, const char *part)
{
	struct outdir o;
	char *cause = NULL;
	assert_int_equal(outdir_begin(&o, target, k, &cause), -1);
	assert_non_null(cause);
	if (strstr(cause, part) == NULL)
		fail_msg("'%s': message '%s' lacks '%s'", target, cause, part);
	free(cause);
}

static void refused(const char *target, const char *marker, const char *part)
{
	(void)marker;
	refused_kind(target, &set_kind, part);
}

static void test_refused(void **state)
{
	(void)state;
	char *file = xasprintf("%s/file", root), *home = xasprintf("%s/home", root);
	char *dot = xasprintf("%s/.", root), *dotdot = xasprintf("%s/x/..", root);
	put(root, "file", "x");
	mkdir(home, 0777);
	put(home, "letter.txt", "x");
	refused("", "manifest.json", "empty");
	refused(".", "manifest.json", "cannot replace");
	refused(dot, "manifest.json", "cannot replace");
	refused(dotdot, "manifest.json", "cannot replace");
	refused("/", "manifest.json", "cannot replace");
	refused(file, "manifest.json", "not a directory");
	refused(home, "manifest.json", "without manifest.json");
	assert_true(exists(home, "letter.txt"));
	/* A complete set plus a user's file; another kind's set; a manifest
	 * that is not JSON. */
	char *set = xasprintf("%s/set", root);
	write_set(set, "1");
	put(set, "notes.txt", "mine");
	refused(set, "manifest.json", "holds 'notes.txt', which is not part of a test set");
	assert_string_equal(get(set, "notes.txt"), "mine");
	refused_kind(set, &other_kind, "not of a other set (format \"other-set\" expected, \"test-set\" found)");
	put(home, "manifest.json", "{ not json");
	refused(home, "manifest.json", "not JSON");
	/* A symbolic link to nothing. */
	char *dangling = xasprintf("%s/dangling", root);
	assert_int_equal(symlink("nowhere", dangling), 0);
	refused(dangling, "manifest.json", "symbolic link to a directory that does not exist");
	free(set);
	free(dangling);
	char *cause = NULL;
	assert_int_equal(util_mkdirs("", &cause), -1);	/* once read past a 1-byte buffer */
	free(cause);
	/* An empty directory is fine, and a trailing '/' too. */
	char *empty = xasprintf("%s/empty/", root);
	mkdir(empty, 0777);
	write_set(empty, "1");
	assert_string_equal(get(empty, "data.txt"), "1");
	free(file);
	free(home);
	free(dot);
	free(dotdot);
	free(empty);
}

/* The PID of a process that has exited. */
static long dead_pid(void)
{
	pid_t p = fork();
	if (p == 0)
		_exit(0);
	waitpid(p, NULL, 0);
	return (long)p;
}

static void test_stale(void **state)
{
	(void)state;
	char host[256];
	gethostname(host, sizeof host);
	char *t = xasprintf("%s/st", root);
	write_set(t, "1");
	char *dead = xasprintf("%s/.st.staging.%s.%ld", root, host, dead_pid());
	char *live = xasprintf("%s/.st.staging.%s.%ld", root, host, (long)getppid());
	char *other = xasprintf("%s/.st.staging.other-host.%ld", root, dead_pid());
	char *unrelated = xasprintf("%s/.stx.staging.%s.%ld", root, host, dead_pid());
	mkdir(dead, 0777);
	put(dead, "brdf.exr", "half");
	mkdir(live, 0777);
	mkdir(other, 0777);
	mkdir(unrelated, 0777);
	assert_int_equal(outdir_clean_stale(t), 1);
	struct stat st;
	assert_int_not_equal(stat(dead, &st), 0);
	assert_int_equal(stat(live, &st), 0);	/* a running process's: kept */
	assert_int_equal(stat(other, &st), 0);	/* another host's: cannot tell, kept */
	assert_int_equal(stat(unrelated, &st), 0);	/* another target's */
	/* A retired set (killed between the two renames without exchange) goes back. */
	char *retired = xasprintf("%s/.st.retired.%s.%ld", root, host, dead_pid());
	assert_int_equal(rename(t, retired), 0);
	assert_int_equal(outdir_clean_stale(t), 1);
	assert_string_equal(get(t, "data.txt"), "1");
	/* begin cleans up the same way. */
	mkdir(dead, 0777);
	write_set(t, "2");
	assert_int_not_equal(stat(dead, &st), 0);
	free(t);
	free(dead);
	free(live);
	free(other);
	free(unrelated);
	free(retired);
}

static void test_symlink(void **state)
{
	(void)state;
	char *real = xasprintf("%s/real", root), *link = xasprintf("%s/link", root);
	write_set(real, "1");
	assert_int_equal(symlink("real", link), 0);
	write_set(link, "2");
	struct stat st;
	assert_int_equal(lstat(link, &st), 0);
	assert_true(S_ISLNK(st.st_mode));	/* the link stays a link ... */
	assert_string_equal(get(real, "data.txt"), "2");	/* ... to the new set */
	assert_int_equal(count_prefix(root, "\\.real\\."), 0);
	free(real);
	free(link);
}

/* The output equal to, inside, or holding an input. */
static void test_inputs(void **state)
{
	(void)state;
	char *in = xasprintf("%s/in", root), *inner = xasprintf("%s/in/x", root), *cause = NULL;
	char *same = xasprintf("%s/./in/", root), *other = xasprintf("%s/in2", root);
	write_set(in, "1");
	const char *inputs[] = { in, NULL }, *inputs_inner[] = { inner, NULL };
	assert_int_equal(outdir_check(same, &set_kind, inputs, &cause), -1);
	assert_non_null(strstr(cause, "is also an input"));
	free(cause);
	cause = NULL;
	assert_int_equal(outdir_check(inner, &set_kind, inputs, &cause), -1);
	assert_non_null(strstr(cause, "inside the input"));
	free(cause);
	cause = NULL;
	assert_int_equal(outdir_check(in, &set_kind, inputs_inner, &cause), -1);
	assert_non_null(strstr(cause, "would be replaced as a whole"));
	free(cause);
	cause = NULL;
	assert_int_equal(outdir_check(other, &set_kind, inputs, &cause), 0);	/* "in2" is not inside "in" */
	free(in);
	free(inner);
	free(same);
	free(other);
}

/* A second writer is refused while the first holds the lock, with the
 * first's process id; after the first commits, a writer goes ahead. */
static void test_lock(void **state)
{
	(void)state;
	char *t = xasprintf("%s/locked", root), *cause = NULL;
	int go[2], done[2];
	assert_int_equal(pipe(go), 0);
	assert_int_equal(pipe(done), 0);
	pid_t child = fork();
	if (child == 0) {
		struct outdir o;
		char c = outdir_begin(&o, t, &set_kind, &cause) == 0 ? 'y' : 'n';
		put(outdir_path(&o), "data.txt", "child");
		put(outdir_path(&o), "manifest.json", "{\"format\": \"test-set\"}");
		if (write(go[1], &c, 1) != 1 || read(done[0], &c, 1) != 1)
			_exit(1);
		_exit(outdir_commit(&o, &cause) == 0 ? 0 : 1);
	}
	char c = 0;
	assert_int_equal(read(go[0], &c, 1), 1);
	assert_int_equal(c, 'y');
	struct outdir o;
	assert_int_equal(outdir_begin(&o, t, &set_kind, &cause), -1);
	char *pid = xasprintf("process %ld (", (long)child);
	if (strstr(cause, pid) == NULL || strstr(cause, "is being written by") == NULL)
		fail_msg("message '%s' lacks '%s'", cause, pid);
	free(cause);
	free(pid);
	assert_int_equal(write(done[1], "x", 1), 1);
	int status;
	waitpid(child, &status, 0);
	assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	assert_string_equal(get(t, "data.txt"), "child");
	write_set(t, "2");
	assert_string_equal(get(t, "data.txt"), "2");
	assert_int_equal(count_prefix(root, "\\.locked\\."), 0);	/* the lock file is removed too */
	free(t);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_fresh_and_replace),
		cmocka_unit_test(test_abort),
		cmocka_unit_test(test_refused),
		cmocka_unit_test(test_stale),
		cmocka_unit_test(test_symlink),
		cmocka_unit_test(test_inputs),
		cmocka_unit_test(test_lock),
	};
	return cmocka_run_group_tests(tests, setup, teardown);
}
