/* skinbake bake --vary: the family bake's options and summary (the work is
 * family/family.h). */
#include "config.h"
#include "cli/cmd_bake_family.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "cli/cli.h"

static const char *CMD = "bake";

int bake_vary_parse(struct opt_ctx *x, const struct opt *o, const char *v)
{
	struct bake_vary *bv = o->dest;
	const char *eq = strchr(v, '=');
	if (eq == NULL || eq == v || (size_t)(eq - v) >= sizeof bv->axis[0].key) {
		opt_error(x, "--vary = '%s' is not KEY=LO:HI:N[:SPACING] or KEY=V1,V2,...", v);
		return -1;
	}
	char key[sizeof bv->axis[0].key], label[96];
	memcpy(key, v, (size_t)(eq - v));
	key[eq - v] = '\0';
	snprintf(label, sizeof label, "--vary %s", key);
	for (int a = 0; a < bv->n; a++)
		if (strcmp(bv->axis[a].key, key) == 0) {
			opt_error(x, "--vary %s is given twice (one axis per key)", key);
			return -1;
		}
	char *spec = xstrdup(eq + 1), *save = NULL, *cause = NULL;
	double lo = 0, hi = 0, list[FAMILY_MAX_NODES];
	long n = 0;
	enum family_spacing sp = FAMILY_SPACING_DE;
	int rc = -1;
	if (strchr(spec, ',')) {
		sp = FAMILY_SPACING_LIST;
		for (char *t = strtok_r(spec, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
			if (n == FAMILY_MAX_NODES) {
				opt_error(x, "%s: more than %d values", label, FAMILY_MAX_NODES);
				goto out;
			}
			if (opt_double(x, label, t, -1e300, 1e300, 0, NULL, &list[n++]) != 0)
				goto out;
		}
	} else {
		char *f[5];
		int k = 0;
		for (char *t = strtok_r(spec, ":", &save); t && k < 5; t = strtok_r(NULL, ":", &save))
			f[k++] = t;
		if (k != 3 && k != 4) {
			opt_error(x, "%s = '%s' is not LO:HI:N[:SPACING] or V1,V2,...", label, eq + 1);
			goto out;
		}
		char l2[128];
		snprintf(l2, sizeof l2, "%s: N", label);
		if (opt_double(x, label, f[0], -1e300, 1e300, 0, NULL, &lo) || opt_double(x, label, f[1], -1e300, 1e300, 0,
		    NULL, &hi) || opt_long(x, l2, f[2], 2, FAMILY_MAX_NODES, 0, NULL, &n))
			goto out;
		if (k == 4) {
			if (strcmp(f[3], "lin") == 0)
				sp = FAMILY_SPACING_LIN;
			else if (strcmp(f[3], "log") == 0)
				sp = FAMILY_SPACING_LOG;
			else if (strcmp(f[3], "de") != 0) {
				opt_error(x, "%s: spacing '%s' is not one of de, log, lin", label, f[3]);
				goto out;
			}
		}
	}
	if (family_axis_init(&bv->axis[bv->n], key, lo, hi, (int)n, sp, list, &cause) != 0) {
		opt_error(x, "--vary %s", cause);
		goto out;
	}
	bv->n++;
	rc = 0;
out:
	free(cause);
	free(spec);
	return rc;
}

/* "epidermis.melanin: 8 nodes (de) 0.005 0.0196 ... 0.3" */
static void print_axis(const struct family_axis *a)
{
	printf("  %s: %d nodes (%s%s)", a->key, a->n, family_spacing_name(a->spacing),
	    a->spacing == FAMILY_SPACING_DE && a->de_fallback ? ", colour hardly changes: uniform" : "");
	for (int i = 0; i < a->n; i++)
		printf(" %.4g", a->node[i]);
	printf("%s%s\n", *a->unit ? " " : "", a->unit);
}

int bake_family_run(const struct bake_spec *s, const struct skin_params *p, const char *label, const char *out,
    const struct bake_vary *vary, int quiet, const char *cmdline)
{
	static struct family_plan pl;
	memset(&pl, 0, sizeof pl);
	pl.base = p;
	pl.preset = label;
	pl.n_axes = vary->n;
	memcpy(pl.axis, vary->axis, sizeof pl.axis);
	pl.spec = *s;
	pl.spec.rank = cli_par.rank;
	pl.spec.n_ranks = cli_par.size;
	pl.spec.allreduce = cli_par.allreduce;
	pl.command = cmdline;
	char *cause = NULL;
	int n_members, rc = CLI_EXIT_OK;
	if (family_check_out(out, &cause) != 0 || family_place_nodes(&pl, &cause) != 0 ||
	    family_plan_check(&pl, &n_members, &cause) != 0) {
		rc = cli_usage_error(CMD, "%s", cause);
		free(cause);
		return rc;
	}
	struct cli_progress pr;
	cli_progress_start(&pr, "family");
	if (cli_par.rank != 0)
		pr.tty = 0;
	pl.progress = cli_progress_update;
	pl.progress_user = &pr;
	struct family *f = NULL;
	double t0 = util_now();
	int e = family_bake(&pl, out, &f, &cause);
	cli_progress_end(&pr);
	if (e != 0) {
		rc = e == -1 ? cli_usage_error(CMD, "%s", cause) : cli_fail(CMD, "%s", cause);
		free(cause);
		return rc;
	}
	for (const char *l = cli_par.rank == 0 ? f->notes : NULL; l && *l; l = strchr(l, '\n') + 1)
		fprintf(stderr, "skinbake bake: %.*s\n", (int)(strchr(l, '\n') - l), l);	/* never silent, even with --quiet */
	if (!quiet && cli_par.rank == 0) {
		printf("skinbake bake: %s family -> %s\n  %d members x %d wavelengths x %d incidence angles, table %d x %d, "
		    "solver %s\n", label, out, n_members, s->n_wl, s->n_ti, s->n_to, s->n_phi, f->solver);
		for (int a = 0; a < f->n_axes; a++)
			print_axis(&f->axis[a]);
		printf("  largest member RMS relative error %.4f, %.2f s\n", f->rms_rel_err, util_now() - t0);
	}
	family_free(f);
	return rc;
}
