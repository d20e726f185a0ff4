/*
 * mat.h - small dense linear algebra in caller storage.
 *
 * Layout: every matrix is a contiguous row-major array of frac_real;
 * element (i, j) of an r x c matrix M is M[i * c + j]. Vectors are plain
 * arrays. No function allocates; dimensions are runtime values bounded by
 * the compile-time capacity FRAC_MAT_MAX (default 64, override with
 * -DFRAC_MAT_MAX=n when the whole library is built), which is what the
 * Kalman/LQG steps of the flexible arm need (seed 004: 16..48 states).
 *
 * Aliasing: an output array must not overlap any input array unless the
 * function says otherwise (in-place factorisations).
 *
 * Common error returns: FRAC_E_NULL (a pointer is NULL), FRAC_E_DIM (a
 * dimension is 0 or above FRAC_MAT_MAX). The products do not test for
 * non-finite values (they are the inner loops of the filters, which test
 * their inputs and results themselves).
 *
 * Cost: matvec r*c multiply-adds, matmul m*k*n, Cholesky n^3/6, each solve
 * n^2; all bounded by the dimensions, no data-dependent iteration.
 */
#ifndef FRAC_MAT_H
#define FRAC_MAT_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifndef FRAC_MAT_MAX
#define FRAC_MAT_MAX 64
#endif

/* y = M x, M r x c. */
int frac_mat_vec(const frac_real *M, size_t r, size_t c, const frac_real *x, frac_real *y);

/* y += M x, M r x c (accumulate; y is read and written). */
int frac_mat_vec_add(const frac_real *M, size_t r, size_t c, const frac_real *x, frac_real *y);

/* C = A B, A m x k, B k x n, C m x n. */
int frac_mat_mul(const frac_real *A, size_t m, size_t k, const frac_real *B, size_t n, frac_real *C);

/* C = A B^T, A m x k, B n x k, C m x n. */
int frac_mat_mul_bt(const frac_real *A, size_t m, size_t k, const frac_real *B, size_t n, frac_real *C);

/*
 * Symmetric congruence plus term: P_out = A P A^T + Q (Q may be NULL for
 * no term), A r x n, P n x n symmetric, Q and P_out r x r. `work` holds
 * r * n entries (A P). The result is symmetrised exactly,
 * P_out = (P_out + P_out^T) / 2, so rounding cannot make it drift from
 * symmetry over many steps (the covariance propagation of the Kalman
 * filter, thesis (6.21)-(6.26) in discrete form).
 */
int frac_mat_sym_congruence(const frac_real *A, size_t r, size_t n, const frac_real *P,
                            const frac_real *Q, frac_real *work, frac_real *P_out);

/* P = (P + P^T) / 2 in place, P n x n. */
int frac_mat_symmetrize(frac_real *P, size_t n);

/*
 * Cholesky factorisation P = L L^T of a symmetric matrix, in place: the
 * lower triangle of P receives L, the strict upper triangle is set to 0.
 * Only the lower triangle of the input is read.
 * Returns FRAC_OK, FRAC_E_NOT_POSDEF (a pivot <= 0 or non-finite: P is
 * not positive definite; P is then partly overwritten), FRAC_E_NULL,
 * FRAC_E_DIM.
 */
int frac_mat_cholesky(frac_real *P, size_t n);

/*
 * Solves L L^T x = b with the factor from frac_mat_cholesky; b and x may
 * be the same array. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM.
 */
int frac_mat_cholesky_solve(const frac_real *L, size_t n, const frac_real *b, frac_real *x);

/*
 * LDL^T factorisation of a symmetric matrix without pivoting, in place:
 * the strict lower triangle receives the unit lower factor L, the
 * diagonal receives D, the strict upper triangle is set to 0. Works for
 * indefinite but strongly regular matrices (no square roots).
 * Returns FRAC_OK, FRAC_E_NUMERIC (a zero or non-finite pivot),
 * FRAC_E_NULL, FRAC_E_DIM.
 */
int frac_mat_ldl(frac_real *P, size_t n);

/*
 * Solves L D L^T x = b with the factor from frac_mat_ldl; b and x may be
 * the same array. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM.
 */
int frac_mat_ldl_solve(const frac_real *LD, size_t n, const frac_real *b, frac_real *x);

/* Nonzero when all `count` entries of v are finite. */
int frac_mat_all_finite(const frac_real *v, size_t count);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_MAT_H */
