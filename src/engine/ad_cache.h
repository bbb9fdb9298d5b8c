/* ad_cache: layer solutions (ad_layer_solve's R, T, dT and diagnostics)
 * kept by their exact inputs, so that a solve met again (the same optical
 * thickness, albedo, phase matrices, nodes, beams, index and start: the
 * same bytes) is copied instead of solved.  Family members differ in a few
 * layers only (issue 28): the others' solutions repeat from member to
 * member at every wavelength, quadrature and Fourier order.  A hit gives
 * the bytes the solve gave, so outputs are the same with or without it.
 *
 * The kernel rule: the cache owns no memory.  The caller gives one block
 * (ad_cache_init) and frees it after the last solve; the cache carves its
 * index and its entries from it and never grows.  When the block is full,
 * the entries not used since the last time it was full are dropped (those
 * used again are kept), or all of them when that frees too little.
 * Lookups and inserts are serialized (OpenMP critical section). */
#ifndef SKINBAKE_AD_CACHE_H
#define SKINBAKE_AD_CACHE_H
#include <stddef.h>
#include <stdint.h>
#include "engine/ad_layer.h"

struct ad_cache {
	uint64_t *hash;		/* [max] key hash per entry */
	size_t *off;		/* [max] entry offset in mem (doubles) */
	unsigned *used;		/* [max] hits since the last compaction */
	int n, max;		/* entries, index capacity */
	double *mem;		/* entries, back to back */
	size_t cap, top;	/* doubles in mem, doubles used */
	long hits, misses;	/* statistics */
};

/* Smallest block worth giving (bytes). */
#define AD_CACHE_MIN_BYTES ((size_t)1 << 20)

/* Bind c to block [bytes], bytes >= AD_CACHE_MIN_BYTES, 16-byte aligned
 * (malloc's); the cache starts empty. */
void ad_cache_init(struct ad_cache *c, void *block, size_t bytes);

/* 1 and out filled (R, T, dT copied into the caller's arrays) if the
 * solution of in is kept, else 0. */
int ad_cache_get(struct ad_cache *c, const struct ad_layer_in *in, struct ad_layer_out *out);

/* Keep out as the solution of in (nothing when it does not fit). */
void ad_cache_put(struct ad_cache *c, const struct ad_layer_in *in, const struct ad_layer_out *out);
#endif
