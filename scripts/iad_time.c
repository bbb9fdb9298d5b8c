/* Times Prahl's ez_RT (iad's adding-doubling, m = 0 only) on one slab:
 *   iad_time A TAU G N Q REPS  ->  "q Q R UR1 T UT1 ms_per_solve X"
 * Built by scripts/bench-iad.sh against an iad source tree (never part of
 * skinbake; iad's code is not in this repository). */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

void ez_RT(int n, double nslab, double ntopslide, double nbottomslide, double a, double b, double g,
    double *UR1, double *UT1, double *URU, double *UTU);

static double cpu_seconds(void)
{
	struct timespec t;
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
	if (argc != 7) {
		fprintf(stderr, "usage: iad_time A TAU G N Q REPS\n");
		return 2;
	}
	double a = atof(argv[1]), tau = atof(argv[2]), g = atof(argv[3]), n = atof(argv[4]);
	int q = atoi(argv[5]), reps = atoi(argv[6]);
	double ur1 = 0.0, ut1 = 0.0, uru = 0.0, utu = 0.0;
	double c0 = cpu_seconds();
	for (int k = 0; k < reps; k++)
		ez_RT(q, n, 1.0, 1.0, a, tau, g, &ur1, &ut1, &uru, &utu);
	double ms = 1e3 * (cpu_seconds() - c0) / reps;
	printf("q %d R %.8f T %.8f ms_per_solve %.4f\n", q, ur1, ut1, ms);
	return 0;
}
