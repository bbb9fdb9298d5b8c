/* Layer solutions kept by their exact inputs (see ad_cache.h). */
#include "config.h"
#include "engine/ad_cache.h"

#include <string.h>

/* Entry layout in doubles: HDR header values, then the key arrays mu[n],
 * w[n], mu_e[ne], ext_e[ne], Hpp, Hpm [n x (n + ne)], then the solution
 * R, T [n x (n + ne)], dT[ne], doublings, t_drop, eigen. */
enum { HDR = 8, TAIL = 3 };

static size_t mat(int n, int ne)
{
	return (size_t)n * (size_t)(n + ne);
}

static size_t key_len(int n, int ne)
{
	return HDR + 2 * (size_t)n + 2 * (size_t)ne + 2 * mat(n, ne);
}

static size_t entry_len(int n, int ne)
{
	return key_len(n, ne) + 2 * mat(n, ne) + (size_t)ne + TAIL;
}

void ad_cache_init(struct ad_cache *c, void *block, size_t bytes)
{
	/* One index slot per 4 kB: entries are larger at every useful size. */
	int max = (int)(bytes / 4096);
	size_t ib = (size_t)max * (sizeof(uint64_t) + sizeof(size_t) + sizeof(unsigned));
	ib = (ib + 15) / 16 * 16;
	char *b = block;
	c->hash = (uint64_t *)b;
	c->off = (size_t *)(b + (size_t)max * sizeof(uint64_t));
	c->used = (unsigned *)(b + (size_t)max * (sizeof(uint64_t) + sizeof(size_t)));
	c->mem = (double *)(b + ib);
	c->cap = (bytes - ib) / sizeof(double);
	c->max = max;
	c->n = 0;
	c->top = 0;
	c->hits = c->misses = 0;
}

/* The header values of in's key. */
static void header(const struct ad_layer_in *in, double *hdr)
{
	const double v[HDR] = { in->n, in->ne, in->tau, in->omega, in->dtau_max, in->n_index,
		in->doubling_only, 0.0 };
	memcpy(hdr, v, sizeof v);
}

/* The key of in, written to k [key_len] (k == NULL: only hashed). */
static uint64_t key_of(const struct ad_layer_in *in, double *k)
{
	const int n = in->n, ne = in->ne;
	double hdr[HDR];
	header(in, hdr);
	struct { const double *p; size_t len; } part[] = {
		{ hdr, HDR }, { in->mu, (size_t)n }, { in->w, (size_t)n }, { in->mu_e, (size_t)ne },
		{ in->ext_e, (size_t)ne }, { in->Hpp, mat(n, ne) }, { in->Hpm, mat(n, ne) },
	};
	uint64_t h = 1469598103934665603ULL;
	for (size_t j = 0; j < sizeof part / sizeof part[0]; j++) {
		for (size_t i = 0; i < part[j].len; i++) {
			uint64_t u;
			memcpy(&u, &part[j].p[i], sizeof u);
			h = (h ^ u) * 1099511628211ULL;
			h ^= h >> 29;
		}
		if (k) {
			memcpy(k, part[j].p, sizeof(double) * part[j].len);
			k += part[j].len;
		}
	}
	return h;
}

/* 1 if entry e holds the key of in. */
static int same_key(const double *e, const struct ad_layer_in *in)
{
	const int n = in->n, ne = in->ne;
	if (e[0] != n || e[1] != ne)
		return 0;
	double hdr[HDR];
	header(in, hdr);
	const double *p = e;
	if (memcmp(p, hdr, sizeof hdr))
		return 0;
	p += HDR;
	const double *arr[] = { in->mu, in->w, in->mu_e, in->ext_e, in->Hpp, in->Hpm };
	size_t len[] = { (size_t)n, (size_t)n, (size_t)ne, (size_t)ne, mat(n, ne), mat(n, ne) };
	for (int j = 0; j < 6; j++) {
		if (memcmp(p, arr[j], sizeof(double) * len[j]))
			return 0;
		p += len[j];
	}
	return 1;
}

static int lookup(struct ad_cache *c, const struct ad_layer_in *in, struct ad_layer_out *out)
{
	uint64_t h = key_of(in, NULL);
	for (int i = 0; i < c->n; i++) {
		if (c->hash[i] != h)
			continue;
		const double *e = c->mem + c->off[i];
		if (!same_key(e, in))
			continue;
		const int n = in->n, ne = in->ne;
		const double *s = e + key_len(n, ne);
		memcpy(out->R, s, sizeof(double) * mat(n, ne));
		s += mat(n, ne);
		memcpy(out->T, s, sizeof(double) * mat(n, ne));
		s += mat(n, ne);
		memcpy(out->dT, s, sizeof(double) * (size_t)ne);
		s += ne;
		out->doublings = (int)s[0];
		out->t_drop = s[1];
		out->eigen = (int)s[2];
		c->used[i]++;
		c->hits++;
		return 1;
	}
	c->misses++;
	return 0;
}

int ad_cache_get(struct ad_cache *c, const struct ad_layer_in *in, struct ad_layer_out *out)
{
	int hit;
#pragma omp critical(ad_cache)
	hit = lookup(c, in, out);
	return hit;
}

/* Drop the entries not used since the last compaction (all when too few
 * were). */
static void compact(struct ad_cache *c)
{
	int m = 0;
	size_t top = 0;
	for (int i = 0; i < c->n; i++) {
		if (!c->used[i])
			continue;
		const double *e = c->mem + c->off[i];
		size_t len = entry_len((int)e[0], (int)e[1]);
		memmove(c->mem + top, e, sizeof(double) * len);
		c->hash[m] = c->hash[i];
		c->off[m] = top;
		c->used[m] = 0;
		top += len;
		m++;
	}
	c->n = m;
	c->top = top;
	if (c->top > c->cap / 2 || c->n > c->max / 2)
		c->n = 0;
	if (c->n == 0)
		c->top = 0;
}

static void insert(struct ad_cache *c, const struct ad_layer_in *in, const struct ad_layer_out *out)
{
	const int n = in->n, ne = in->ne;
	size_t len = entry_len(n, ne);
	if (len > c->cap / 4)
		return;
	if (c->n == c->max || c->top + len > c->cap)
		compact(c);
	double *e = c->mem + c->top;
	uint64_t h = key_of(in, e);
	double *s = e + key_len(n, ne);
	memcpy(s, out->R, sizeof(double) * mat(n, ne));
	s += mat(n, ne);
	memcpy(s, out->T, sizeof(double) * mat(n, ne));
	s += mat(n, ne);
	memcpy(s, out->dT, sizeof(double) * (size_t)ne);
	s += ne;
	s[0] = out->doublings;
	s[1] = out->t_drop;
	s[2] = out->eigen;
	c->hash[c->n] = h;
	c->off[c->n] = c->top;
	c->used[c->n] = 0;
	c->n++;
	c->top += len;
}

void ad_cache_put(struct ad_cache *c, const struct ad_layer_in *in, const struct ad_layer_out *out)
{
#pragma omp critical(ad_cache)
	insert(c, in, out);
}
