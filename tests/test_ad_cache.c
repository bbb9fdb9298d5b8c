/* The adding-doubling layer cache (ad_cache.h; issue 28): solves of a
 * three-layer skin-like stack whose top two layers change from solve to
 * solve (as family members do) give bit for bit the results of solves
 * without the cache, with the unchanged bottom layer's solutions taken
 * from it; with a block too small for one solve (entries dropped and the
 * cache emptied again and again) still bit for bit. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/ad.h"
#include "engine/ad_cache.h"

/* Member j: epidermis absorption and dermis absorption vary, subcutis not. */
static void member(struct slab *s, int j)
{
	char *cause = NULL;
	struct layer L[3] = {
		{ 0.006, 1.43, 2.0 + 5.0 * j, 300.0, 0.8, 0.0 },
		{ 0.2, 1.40, 0.5 + 0.7 * j, 150.0, 0.82, 0.0 },
		{ INFINITY, 1.44, 1.0, 100.0, 0.75, 0.0 },
	};
	slab_init(s, 1.0, 1.44);
	for (int i = 0; i < 3; i++)
		assert_int_equal(slab_add(s, &L[i], &cause), 0);
	if (slab_check(s, &cause))
		fail_msg("%s", cause);
	slab_prepare(s);
}

/* Solve member j with cache c (NULL: none); its BRDF at 5 x 4 points, Rd,
 * the doubling count into v [24]. */
static void run(int j, struct ad_cache *c, double *v)
{
	struct slab s;
	member(&s, j);
	struct ad_opts o;
	ad_opts_default(&o);
	o.tol = 1e-3;
	o.threads = 2;
	o.cache = c;
	double th[2] = { 0.0, 0.9 };
	struct ad_result r;
	char *cause = NULL;
	if (ad_solve(&s, OPTICS_FRESNEL_EXACT, th, 2, &o, &r, &cause))
		fail_msg("%s", cause);
	int k = 0;
	for (int it = 0; it < 5; it++)
		for (int ip = 0; ip < 4; ip++)
			v[k++] = ad_brdf(&r, it & 1, 0.3 * it, 1.0 * ip, NULL);
	v[k++] = r.beam[0].rd.v;
	v[k++] = r.beam[1].tt.v;
	v[k++] = (double)r.doublings;
	v[k++] = r.rms_rel_err;
	ad_result_free(&r);
}

static void same_with(size_t bytes, long *hits)
{
	void *block = malloc(bytes);
	assert_non_null(block);
	struct ad_cache c;
	ad_cache_init(&c, block, bytes);
	for (int j = 0; j < 4; j++) {
		double a[24], b[24];
		run(j, NULL, a);
		run(j, &c, b);
		assert_memory_equal(a, b, sizeof a);
	}
	assert_true(c.n <= c.max);
	assert_true(c.top <= c.cap);
	*hits = c.hits;
	free(block);
}

static void test_same(void **state)
{
	(void)state;
	long hits;
	same_with((size_t)32 << 20, &hits);
	printf("# 32 MB block: %ld hits\n", hits);
	assert_true(hits > 0);
}

static void test_small_block(void **state)
{
	(void)state;
	long hits;
	same_with(AD_CACHE_MIN_BYTES, &hits);
	printf("# 1 MB block: %ld hits\n", hits);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_same),
		cmocka_unit_test(test_small_block),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
