/* family: a family bake (one preset varied over up to three of its numeric
 * keys, one bake per member), its directory (written and read here), and
 * the interpolation between members.  The module is four files: family.c
 * (axes, the directory written), family_load.c (read back), family_run.c
 * (node placement and the bake of the members, over MPI ranks too),
 * family_interp.c (between members).
 *
 * Directory (format "skinbake-family", FAMILY_FORMAT_VERSION):
 *   family.json   the axes (key, unit, spacing, interpolation coordinate,
 *                 nodes), the base preset, the bake settings, and per member
 *                 its parameters, its diffuse albedo at the first incidence
 *                 node (per wavelength, linear sRGB, CIELAB D65), its
 *                 subsurface radius per R, G, B and its table's error
 *   preset.ini    the base preset, resolved (`bake --preset-file` takes it)
 *   mNNNN/        one bake directory per member (bakefile.h); member index
 *                 m = i0 + n0 (i1 + n1 i2), i_a the node index on axis a
 *   swatches.png  the members' albedo, 8-bit sRGB: axis 0 across, then
 *                 axis 1 down, axis 2 in blocks down
 * The directory is built in DIR.staging (the preset first, then the
 * members one by one, family.json last) and renamed into place.
 *
 * Node spacing per axis: lin (uniform in the value), log (uniform in its
 * logarithm), de (the default: equal CIEDE2000 steps of the albedo colour
 * along the axis, from a pilot of FAMILY_PILOT points with the other axes
 * at their middle; nodes are dense where the colour changes fastest), or
 * a list of values.  Interpolation between members: per axis 4-point
 * Lagrange (cubic; quadratic or linear with 3 or 2 nodes) in the axis'
 * coordinate, log(value) when every node is > 0 and the spacing is not lin,
 * else the value; a tensor product over the axes; positive quantities
 * (tables, albedos, radii) are blended as logarithms.  Measured on
 * fair-oily: cubic in log of the albedo with de nodes is within 0.3 % of a
 * direct solve at off-node melanin and 0.06 % for blood (docs/maps.md). */
#ifndef SKINBAKE_FAMILY_H
#define SKINBAKE_FAMILY_H
#include <math.h>
#include <stddef.h>
#include "bake/bake.h"
#include "bake/bakefile.h"
#include "skin/tissue.h"

#define FAMILY_FORMAT_VERSION 1
#define FAMILY_MAX_AXES 3
#define FAMILY_MAX_NODES 64
#define FAMILY_MAX_MEMBERS 4096
#define FAMILY_PILOT 17
/* Bytes kept for adding-doubling layer solutions shared by the members
 * (engine/ad_cache.h). */
#define FAMILY_AD_CACHE_BYTES ((size_t)64 << 20)
#define FAMILY_STENCIL_MAX 64	/* 4^FAMILY_MAX_AXES */

enum family_spacing { FAMILY_SPACING_LIN, FAMILY_SPACING_LOG, FAMILY_SPACING_DE, FAMILY_SPACING_LIST };

struct family_axis {
	char key[64];			/* numeric preset key, e.g. "epidermis.melanin" */
	char unit[16];			/* the key's unit, "" for pure numbers */
	enum family_spacing spacing;
	double lo, hi;			/* the range asked for (the nodes' ends) */
	int n;				/* nodes, 2..FAMILY_MAX_NODES */
	double node[FAMILY_MAX_NODES];	/* ascending; for de filled by family_place_nodes */
	int log_coord;			/* interpolation coordinate: 1 log(value), 0 value */
	double key_lo, key_hi;		/* the key's allowed range */
	int n_pilot;			/* de: pilot points (0 otherwise) */
	double pilot_value[FAMILY_PILOT];	/* de: the pilot's values of the key */
	double pilot_de[FAMILY_PILOT];	/* de: cumulative CIEDE2000 of the albedo from the first */
	int de_fallback;		/* de: the colour hardly changes (< 0.5 total), nodes are uniform */
};

struct family_member {
	double param[FAMILY_MAX_AXES];	/* the axes' values, in the keys' units */
	double *albedo_wl;		/* [n_wl] directional-hemispherical diffuse albedo at albedo_theta_i [-] */
	double albedo_rgb[3];		/* the same in linear sRGB (D65) [-] */
	double albedo_lab[3];		/* CIELAB of albedo_rgb, D65 white */
	double sss_radius_rgb_cm[3];	/* mean exit radius of the diffuse light per R, G, B [cm] */
	double rms_rel_err;		/* the member table's RMS relative error [-] */
	double seconds;			/* its bake's wall time [s] */
};

struct family {
	char *dir;
	char *preset;			/* base preset name or file */
	char *preset_ini;		/* the base preset, resolved INI text */
	int n_axes;
	struct family_axis axis[FAMILY_MAX_AXES];
	int n_members;			/* product of the axes' node counts */
	struct family_member *member;	/* [n_members] */
	int n_wl;
	double *wl_nm;			/* [n_wl] [nm] */
	double *rgb_from_wl;		/* [3][n_wl] spectral -> linear sRGB */
	double albedo_theta_i;		/* incidence of the members' albedos and radii [rad] */
	double rms_rel_err;		/* the largest member table error [-] */
	char *solver;			/* method of the members' tables ("ad+mc" when they differ) */
	char *notes;			/* lines for the user: the members' Monte Carlo fallbacks; NULL: none */
	struct bake_spec *spec;		/* the members' bake settings (slabs not filled) */
	struct bake **bake;		/* [n_members] member tables, NULL until family_load_tables */
	double *log_albedo;		/* [n_members][n_wl] log of albedo_wl, NULL until family_albedo_prepare */
};

/* ---- axes ---- */

/* Set up axis a for KEY over [lo, hi] with n nodes and the given spacing,
 * or (spacing LIST) the n ascending values list[].  Checks: KEY is a
 * numeric preset key, the values are within its range, log needs lo > 0,
 * 2 <= n <= FAMILY_MAX_NODES, a list ascends strictly.  Nodes of lin, log
 * and list are set here, de ones by family_place_nodes.  -1 and *cause. */
int family_axis_init(struct family_axis *a, const char *key, double lo, double hi, int n, enum family_spacing spacing,
    const double *list, char **cause);
const char *family_spacing_name(enum family_spacing s);
/* The axis' interpolation coordinate of value v: log(v) on a log_coord
 * axis, else v.  Every blend between members (family_stencil), the maps'
 * fit and the exporters' sub-grids and blend maps work in it. */
static inline double family_axis_coord(const struct family_axis *a, double v)
{
	return a->log_coord ? log(v) : v;
}
/* The value at coordinate c (family_axis_coord's inverse). */
static inline double family_axis_value(const struct family_axis *a, double c)
{
	return a->log_coord ? exp(c) : c;
}
/* Where v lies between the first node (0) and the last (1) in the
 * coordinate, clamped to [0, 1]. */
static inline double family_axis_t(const struct family_axis *a, double v)
{
	double c0 = family_axis_coord(a, a->node[0]), c1 = family_axis_coord(a, a->node[a->n - 1]);
	double t = (family_axis_coord(a, v) - c0) / (c1 - c0);
	return t < 0 ? 0 : t > 1 ? 1 : t;
}

/* ---- the bake ---- */

struct family_plan {
	const struct skin_params *base;	/* the preset all members start from */
	const char *preset;		/* its name or file, for the records */
	int n_axes;			/* 1..FAMILY_MAX_AXES */
	struct family_axis axis[FAMILY_MAX_AXES];
	struct bake_spec spec;		/* every member's bake: wavelengths, angles, grid, accuracy,
					 * threads and the MPI fields (rank, n_ranks, allreduce); slabs unused */
	const char *command;		/* command line, for the records */
	void (*progress)(void *user, long done, long total);	/* members baked; may be NULL */
	void *progress_user;
};

/* Check a plan before any work (after family_place_nodes): the number of
 * members (at most FAMILY_MAX_MEMBERS) and every member's parameters and
 * layer stacks.  -1 and *cause naming the member and the problem. */
int family_plan_check(const struct family_plan *pl, int *n_members, char **cause);
/* Skin parameters of the member at parameter point x[n_axes] (a copy of
 * the base with the keys set; caller frees with preset_free); NULL and
 * *cause when a value is refused. */
struct skin_params *family_params(const struct skin_params *base, const struct family_axis *axis, int n_axes,
    const double *x, char **cause);
/* Place the nodes of de axes (pilot bakes of the albedo only, on every
 * rank alike).  -1 and *cause when a pilot bake fails. */
int family_place_nodes(struct family_plan *pl, char **cause);
/* A family directory, for base/outdir.h: family.json of format
 * "skinbake-family", the base preset, the swatches and the members. */
extern const struct outdir_kind family_outdir_kind;
/* Check DIR can take a family: absent, empty, or an earlier family
 * directory (which is replaced) holding nothing else (outdir_check).  -1
 * and *cause otherwise. */
int family_check_out(const char *dir, char **cause);
/* Bake every member and write the family directory DIR.  Members are
 * spread over MPI ranks (member m on rank m % n_ranks, each bake on one
 * rank with its threads) and gathered to rank 0 round by round through
 * spec.allreduce; rank 0 writes.  The tables do not depend on the ranks.
 * On success *out (rank 0; may be NULL) holds the family as written
 * (caller frees with family_free).  -1 and *cause when a member's bake
 * is refused (by its solver) or DIR.checkpoint cannot be used (stale
 * without spec.resume, of another family, damaged, resume under MPI), -2
 * when the directory cannot be written.  One process saves every finished
 * member's result in DIR.checkpoint (checkpoint.h, at most every
 * spec.checkpoint_s seconds); with spec.resume those members are written
 * from it, not baked again (whole members: one killed half way starts
 * over).  The checkpoint is removed once DIR is in place. */
int family_bake(const struct family_plan *pl, const char *dir, struct family **out, char **cause);

/* ---- the directory ---- */

/* Read DIR/family.json (not the tables).  NULL and *cause naming the file,
 * the field, the value and what was expected when it is missing, corrupt
 * or of another format version. */
struct family *family_load(const char *dir, char **cause);
/* Read every member's bake directory into f->bake; -1 and *cause. */
int family_load_tables(struct family *f, char **cause);
void family_free(struct family *f);	/* NULL is a no-op */
/* Node indices of member m. */
void family_member_index(const struct family *f, int m, int idx[FAMILY_MAX_AXES]);
/* Write DIR/family.json and DIR/swatches.png for f (f->dir is ignored). */
int family_write_index(const char *dir, const struct family *f, const char *command, char **cause);

/* ---- between members ---- */

/* Members and weights that interpolate at x[n_axes] (clamped to each
 * axis' nodes). */
struct family_stencil {
	int n;
	int member[FAMILY_STENCIL_MAX];
	double w[FAMILY_STENCIL_MAX];	/* sum to 1; cubic weights may be negative */
};
void family_stencil(const struct family *f, const double *x, struct family_stencil *st);
/* Blend values v[member * stride]: exp(sum w log v) when all are > 0,
 * else sum w v. */
double family_blend(const struct family_stencil *st, const double *v, size_t stride);
/* Precompute what family_albedo needs (the members' log albedos), for
 * many calls; not thread-safe itself, the calls after it are. */
void family_albedo_prepare(struct family *f);
/* The diffuse albedo at x: per wavelength (albedo_wl[n_wl], may be NULL)
 * and in linear sRGB; the subsurface radius per R, G, B [cm] (may be NULL). */
void family_albedo(const struct family *f, const double *x, double *albedo_wl, double rgb[3], double radius_rgb_cm[3]);
/* A bake interpolated at x from the member tables (family_load_tables
 * first): tables, albedos, radii and the top surface's index and
 * roughness blended; the specular stacks of the nearest member.  Caller
 * frees with bake_free. */
struct bake *family_bake_at(const struct family *f, const double *x);
/* Whether x is inside the family's range on every axis; if not, the first
 * axis outside into *axis. */
int family_contains(const struct family *f, const double *x, int *axis);
#endif
