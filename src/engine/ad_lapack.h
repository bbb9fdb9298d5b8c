/* The LAPACK routines adding-doubling calls, straight from OpenBLAS (which
 * exports LAPACK's Fortran entry points): no LAPACKE, whose library and its
 * reference LAPACK, libtmglib and libgfortran cost about 1 ms of dynamic
 * loading per process, and whose plain calls scan every input for NaNs.
 * The calls resolve to the same OpenBLAS routines LAPACKE called (it was
 * linked after libopenblas), so results are bit for bit those of before.
 * Column-major, 32-bit integers (OpenBLAS's LP64 build); each returns
 * LAPACK's info (0 = success). */
#ifndef SKINBAKE_AD_LAPACK_H
#define SKINBAKE_AD_LAPACK_H
#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "base/util.h"

/* Fortran prototypes; the trailing size_t is gfortran's hidden length of
 * a character argument. */
void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
    const int *ldb, int *info);
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info, size_t uplo_len);
void dstev_(const char *jobz, const int *n, double *d, double *e, double *z, const int *ldz,
    double *work, int *info, size_t jobz_len);
void dsyevd_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda, double *w,
    double *work, const int *lwork, int *iwork, const int *liwork, int *info, size_t jobz_len,
    size_t uplo_len);

/* Solve A X = B (LU with partial pivoting), A n x n, B n x nrhs. */
static inline int ad_dgesv(int n, int nrhs, double *a, int lda, int *ipiv, double *b, int ldb)
{
	int info = 0;
	dgesv_(&n, &nrhs, a, &lda, ipiv, b, &ldb, &info);
	return info;
}

/* 1 when an m x n column-major block holds a NaN. */
static inline int ad_has_nan(int m, int n, const double *a, int lda)
{
	for (int j = 0; j < n; j++)
		for (int i = 0; i < m; i++)
			if (isnan(a[i + (size_t)lda * j]))
				return 1;
	return 0;
}

/* ad_dgesv refusing NaNs in A or B as LAPACKE_dgesv did (-4, -7). */
static inline int ad_dgesv_checked(int n, int nrhs, double *a, int lda, int *ipiv, double *b,
    int ldb)
{
	if (ad_has_nan(n, n, a, lda))
		return -4;
	if (ad_has_nan(n, nrhs, b, ldb))
		return -7;
	return ad_dgesv(n, nrhs, a, lda, ipiv, b, ldb);
}

/* Cholesky A = L L^T of the lower triangle, in place. */
static inline int ad_dpotrf_lower(int n, double *a, int lda)
{
	int info = 0;
	dpotrf_("L", &n, a, &lda, &info, 1);
	return info;
}

void dsyevr_(const char *jobz, const char *range, const char *uplo, const int *n, double *a,
    const int *lda, const double *vl, const double *vu, const int *il, const int *iu,
    const double *abstol, int *m, double *w, double *z, const int *ldz, int *isuppz, double *work,
    const int *lwork, int *iwork, const int *liwork, int *info, size_t jobz_len, size_t range_len,
    size_t uplo_len);

/* Doubles and ints of workspace ad_dsyevr needs for order n. */
static inline size_t ad_dsyevr_work(int n)
{
	return 26 * (size_t)n + 1;
}
static inline size_t ad_dsyevr_iwork(int n)
{
	return 10 * (size_t)n + 2 * (size_t)n + 1;
}

/* Eigenvalues (ascending, into w) and orthonormal eigenvectors (into z,
 * column j for w[j]) of the symmetric n x n matrix whose lower triangle a
 * holds (destroyed; relatively robust representations). */
static inline int ad_dsyevr(int n, double *a, int lda, double *w, double *z, int ldz, double *work,
    int *iwork)
{
	int info = 0, m = 0, lwork = (int)ad_dsyevr_work(n), liwork = 10 * n + 1, il = 1, iu = n;
	double vl = 0.0, vu = 0.0, abstol = 0.0;
	int *isuppz = iwork + 10 * n + 1;
	dsyevr_("V", "A", "L", &n, a, &lda, &vl, &vu, &il, &iu, &abstol, &m, w, z, &ldz, isuppz,
	    work, &lwork, iwork, &liwork, &info, 1, 1, 1);
	return info != 0 ? info : (m == n ? 0 : -1);
}

/* Doubles and ints of workspace ad_dsyevd needs for order n. */
static inline size_t ad_dsyevd_work(int n)
{
	return 1 + 6 * (size_t)n + 2 * (size_t)n * (size_t)n;
}
static inline size_t ad_dsyevd_iwork(int n)
{
	return 3 + 5 * (size_t)n;
}

/* Eigenvalues (ascending, into w) and orthonormal eigenvectors (into a,
 * column j for w[j]) of the symmetric n x n matrix whose lower triangle a
 * holds (divide and conquer); work and iwork as ad_dsyevd_work and
 * ad_dsyevd_iwork say. */
static inline int ad_dsyevd(int n, double *a, int lda, double *w, double *work, int *iwork)
{
	int info = 0, lwork = (int)ad_dsyevd_work(n), liwork = (int)ad_dsyevd_iwork(n);
	dsyevd_("V", "L", &n, a, &lda, w, work, &lwork, iwork, &liwork, &info, 1, 1);
	return info;
}

/* Eigenvalues (into d) and eigenvectors (z, ldz >= n) of the symmetric
 * tridiagonal matrix with diagonal d[n] and off-diagonal e[n - 1]; NaNs in
 * d or e are refused as LAPACKE_dstev did (-4, -5). */
static inline int ad_dstev(int n, double *d, double *e, double *z, int ldz)
{
	for (int i = 0; i < n; i++)
		if (isnan(d[i]) || (i + 1 < n && isnan(e[i])))
			return isnan(d[i]) ? -4 : -5;
	double *work = xmalloc(sizeof(double) * (size_t)(n > 1 ? 2 * n - 2 : 1));
	int info = 0;
	dstev_("V", &n, d, e, z, &ldz, work, &info, 1);
	free(work);
	return info;
}
#endif
