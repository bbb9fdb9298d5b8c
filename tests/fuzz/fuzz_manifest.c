/* Fuzz target: manifest.json of a bake directory (src/bake/bakefile.c,
 * bake_load).  bake_load reads a directory, so the target keeps one: the
 * tables of a small real bake (tests/fuzz/data/bake, symbolic links) beside
 * manifest.json, a link to the fuzz input.  A manifest that loads is then
 * evaluated as `eval` and the exporters do. */
#define _GNU_SOURCE
#include "config.h"
#include "fuzz.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bake/bake.h"
#include "bake/bakefile.h"

static char dir[4096];
static char *files[6];

static void cleanup(void)
{
	for (int i = 0; i < 6 && files[i] != NULL; i++) {
		unlink(files[i]);
		free(files[i]);
	}
	rmdir(dir);
}

static char *join(const char *a, const char *b)
{
	size_t n = strlen(a) + strlen(b) + 2;
	char *s = malloc(n);
	snprintf(s, n, "%s/%s", a, b);
	return s;
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	(void)argc;
	(void)argv;
	static const char *const tables[] = { "brdf.exr", "brdf_rgb.exr", "albedo.exr", "albedo.png" };
	const char *tmp = getenv("TMPDIR");
	snprintf(dir, sizeof dir, "%s/skinbake-fuzz-bake.XXXXXX", tmp && *tmp ? tmp : "/tmp");
	if (mkdtemp(dir) == NULL)
		fuzz_fail("cannot create %s", dir);
	atexit(cleanup);
	for (int i = 0; i < 4; i++) {
		char *from = join(fuzz_datadir(), "bake"), *src = join(from, tables[i]);
		files[i] = join(dir, tables[i]);
		if (symlink(src, files[i]) != 0)
			fuzz_fail("cannot link %s to %s", files[i], src);
		free(from);
		free(src);
	}
	files[4] = join(dir, "manifest.json");
	if (symlink(fuzz_file((const uint8_t *)"", 0), files[4]) != 0)
		fuzz_fail("cannot link %s", files[4]);
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char *cause = NULL;
	fuzz_file(data, size);
	struct bake *b = bake_load(dir, &cause);
	if (b == NULL) {
		if (cause == NULL || *cause == '\0')
			fuzz_fail("manifest refused without a message");
		fuzz_refused(cause);
		return 0;
	}
	double f[BAKE_MAX_WL], e[BAKE_MAX_WL], rgb[3];
	if (b->n_wl < 1 || b->n_wl > BAKE_MAX_WL)
		fuzz_fail("bake_load accepted %d wavelengths", b->n_wl);
	static const double angles[][3] = { { 0, 0, 0 }, { 0.5, 0.7, 1.0 }, { 1.5, 1.5, 3.1 }, { -1, 2, 7 } };
	for (size_t i = 0; i < sizeof angles / sizeof angles[0]; i++) {
		bake_eval_diffuse(b, angles[i][0], angles[i][1], angles[i][2], f, e);
		bake_eval_specular(b, angles[i][0], angles[i][1], angles[i][2], f);
		bake_eval_rgb(b, angles[i][0], angles[i][1], angles[i][2], rgb);
	}
	bake_free(b);
	return 0;
}
