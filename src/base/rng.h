/* rng: counter-based random numbers (Random123 Philox4x32-10).  A photon's
 * numbers are a pure function of (seed, stream, photon index, draw index), so
 * results do not depend on threads, ranks or scheduling.  `stream` separates
 * independent jobs (incidence angle, wavelength, ...) under one seed. */
#ifndef SKINBAKE_RNG_H
#define SKINBAKE_RNG_H
#include <stdint.h>
#include <Random123/philox.h>

struct rng {
	philox4x32_key_t key;	/* seed */
	philox4x32_ctr_t ctr;	/* photon index (2 words), draw counter, stream */
	philox4x32_ctr_t out;	/* last block of four 32-bit outputs */
	int used;		/* outputs of `out` already consumed, 0..4 */
};

static inline void rng_seed(struct rng *r, uint64_t seed, uint32_t stream, uint64_t photon)
{
	r->key.v[0] = (uint32_t)seed;
	r->key.v[1] = (uint32_t)(seed >> 32);
	r->ctr.v[0] = (uint32_t)photon;
	r->ctr.v[1] = (uint32_t)(photon >> 32);
	r->ctr.v[2] = 0;
	r->ctr.v[3] = stream;
	r->used = 4;
}

/* Uniform in the open interval (0, 1): never 0 (safe for log) nor 1.
 * 32 bits of resolution are ample for path lengths and angles. */
static inline __attribute__((always_inline)) double rng_uniform(struct rng *r)
{
	if (r->used == 4) {
		r->out = philox4x32(r->ctr, r->key);
		r->ctr.v[2]++;
		r->used = 0;
	}
	return ((double)r->out.v[r->used++] + 0.5) * 0x1.0p-32;
}
#endif
