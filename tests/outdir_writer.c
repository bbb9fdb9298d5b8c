/* Test helper for tests/outdir_kill.sh: writes a complete set into an output
 * directory through outdir, every file holding the generation GEN:
 * f0.txt .. f<N-1>.txt, sub/g.txt and manifest.json (the marker), each through
 * a temporary name renamed into place as the real writers do.
 * usage: outdir_writer TARGET GEN N */
#include "config.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/outdir.h"
#include "base/util.h"

static int put(const char *dir, const char *name, const char *gen, char **cause)
{
	char *path = xasprintf("%s/%s", dir, name);
	struct outfile f;
	int rc = outfile_open(&f, path, cause);
	if (rc == 0) {
		fprintf(f.fp, "%s\n", gen);
		rc = outfile_commit(&f, cause);
	}
	free(path);
	return rc;
}

int main(int argc, char **argv)
{
	if (argc != 4) {
		fprintf(stderr, "usage: outdir_writer TARGET GEN N\n");
		return 2;
	}
	int n = atoi(argv[3]);
	char *cause = NULL;
	struct outdir o;
	/* Marker only (its content is the generation), any file. */
	const struct outdir_kind kind = { "test set", "manifest.json", NULL, NULL, NULL };
	if (outdir_begin(&o, argv[1], &kind, &cause) != 0) {
		fprintf(stderr, "outdir_writer: %s\n", cause);
		free(cause);
		return 2;
	}
	const char *dir = outdir_path(&o);
	int rc = 0;
	for (int i = 0; rc == 0 && i < n; i++) {
		char name[32];
		snprintf(name, sizeof name, "f%d.txt", i);
		rc = put(dir, name, argv[2], &cause);
	}
	char *sub = xasprintf("%s/sub", dir);
	if (rc == 0 && mkdir(sub, 0777) != 0) {
		cause = xasprintf("%s: %s", sub, strerror(errno));
		rc = -1;
	}
	free(sub);
	if (rc == 0)
		rc = put(dir, "sub/g.txt", argv[2], &cause);
	if (rc == 0)
		rc = put(dir, "manifest.json", argv[2], &cause);
	if (rc != 0) {
		outdir_abort(&o);
	} else
		rc = outdir_commit(&o, &cause);
	if (rc != 0) {
		fprintf(stderr, "outdir_writer: %s\n", cause);
		free(cause);
		return 1;
	}
	return 0;
}
