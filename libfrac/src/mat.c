/*
 * mat.c - small dense row-major linear algebra (frac/mat.h).
 *
 * The loops run over contiguous rows so that the inner products stream
 * through memory; this is what lets a compiler vectorise them on a host
 * and keeps a Cortex-M4F in its single-cycle load/MAC pattern.
 */
#include "frac/mat.h"

#define DIM_OK(d) ((d) > 0 && (d) <= FRAC_MAT_MAX)

/*
 * y = M x (acc = 0) or y += M x (acc = 1) for row-major M.
 * Four rows at a time with two partial sums per row (even and odd
 * columns): the four rows share every load of x, and the even/odd sums of
 * a row are the two lanes a compiler packs into one SIMD register (SSE2,
 * NEON). Each partial sum keeps its own summation order, since strict
 * IEEE code may not reassociate. Remaining rows: four partial sums each.
 * This is the inner loop of the Kalman predictor and LQG steps.
 */
static void gemv_kernel(const frac_real *M, size_t r, size_t c, const frac_real *x, frac_real *y, int acc)
{
    size_t i = 0, j;
    for (; i + 4 <= r; i += 4) {
        const frac_real *a = M + i * c, *b = a + c, *d = b + c, *f = d + c;
        frac_real a0 = FRAC_R(0.0), a1 = FRAC_R(0.0), b0 = FRAC_R(0.0), b1 = FRAC_R(0.0);
        frac_real d0 = FRAC_R(0.0), d1 = FRAC_R(0.0), f0 = FRAC_R(0.0), f1 = FRAC_R(0.0);
        for (j = 0; j + 2 <= c; j += 2) {
            const frac_real x0 = x[j], x1 = x[j + 1];
            a0 += a[j] * x0;
            a1 += a[j + 1] * x1;
            b0 += b[j] * x0;
            b1 += b[j + 1] * x1;
            d0 += d[j] * x0;
            d1 += d[j + 1] * x1;
            f0 += f[j] * x0;
            f1 += f[j + 1] * x1;
        }
        if (j < c) {
            a0 += a[j] * x[j];
            b0 += b[j] * x[j];
            d0 += d[j] * x[j];
            f0 += f[j] * x[j];
        }
        a0 += a1;
        b0 += b1;
        d0 += d1;
        f0 += f1;
        if (acc) {
            y[i] += a0;
            y[i + 1] += b0;
            y[i + 2] += d0;
            y[i + 3] += f0;
        } else {
            y[i] = a0;
            y[i + 1] = b0;
            y[i + 2] = d0;
            y[i + 3] = f0;
        }
    }
    for (; i < r; i++) {
        const frac_real *a = M + i * c;
        frac_real s0 = FRAC_R(0.0), s1 = FRAC_R(0.0), s2 = FRAC_R(0.0), s3 = FRAC_R(0.0);
        for (j = 0; j + 4 <= c; j += 4) {
            s0 += a[j] * x[j];
            s1 += a[j + 1] * x[j + 1];
            s2 += a[j + 2] * x[j + 2];
            s3 += a[j + 3] * x[j + 3];
        }
        /* the 0..3 remaining terms without a loop (a loop here gets
         * vectorised with run-time checks that cost more than it saves) */
        if (j + 2 <= c) {
            s1 += a[j] * x[j];
            s2 += a[j + 1] * x[j + 1];
            j += 2;
        }
        if (j < c) s0 += a[j] * x[j];
        s0 = (s0 + s1) + (s2 + s3);
        y[i] = acc ? y[i] + s0 : s0;
    }
}

int frac_mat_vec(const frac_real *M, size_t r, size_t c, const frac_real *x, frac_real *y)
{
    if (M == NULL || x == NULL || y == NULL) return FRAC_E_NULL;
    if (!DIM_OK(r) || !DIM_OK(c)) return FRAC_E_DIM;
    gemv_kernel(M, r, c, x, y, 0);
    return FRAC_OK;
}

int frac_mat_vec_add(const frac_real *M, size_t r, size_t c, const frac_real *x, frac_real *y)
{
    if (M == NULL || x == NULL || y == NULL) return FRAC_E_NULL;
    if (!DIM_OK(r) || !DIM_OK(c)) return FRAC_E_DIM;
    gemv_kernel(M, r, c, x, y, 1);
    return FRAC_OK;
}

int frac_mat_mul(const frac_real *A, size_t m, size_t k, const frac_real *B, size_t n, frac_real *C)
{
    size_t i, j, l;
    if (A == NULL || B == NULL || C == NULL) return FRAC_E_NULL;
    if (!DIM_OK(m) || !DIM_OK(k) || !DIM_OK(n)) return FRAC_E_DIM;
    for (i = 0; i < m; i++) {
        frac_real *crow = C + i * n;
        for (j = 0; j < n; j++) crow[j] = FRAC_R(0.0);
        /* i-l-j order: row l of B is added to row i of C, both contiguous */
        for (l = 0; l < k; l++) {
            const frac_real a = A[i * k + l];
            const frac_real *brow = B + l * n;
            for (j = 0; j < n; j++) crow[j] += a * brow[j];
        }
    }
    return FRAC_OK;
}

int frac_mat_mul_bt(const frac_real *A, size_t m, size_t k, const frac_real *B, size_t n, frac_real *C)
{
    size_t i, j, l;
    if (A == NULL || B == NULL || C == NULL) return FRAC_E_NULL;
    if (!DIM_OK(m) || !DIM_OK(k) || !DIM_OK(n)) return FRAC_E_DIM;
    for (i = 0; i < m; i++) {
        const frac_real *arow = A + i * k;
        for (j = 0; j < n; j++) {
            const frac_real *brow = B + j * k;
            frac_real s = FRAC_R(0.0);
            for (l = 0; l < k; l++) s += arow[l] * brow[l];
            C[i * n + j] = s;
        }
    }
    return FRAC_OK;
}

int frac_mat_symmetrize(frac_real *P, size_t n)
{
    size_t i, j;
    if (P == NULL) return FRAC_E_NULL;
    if (!DIM_OK(n)) return FRAC_E_DIM;
    for (i = 0; i < n; i++) {
        for (j = i + 1; j < n; j++) {
            frac_real s = FRAC_R(0.5) * (P[i * n + j] + P[j * n + i]);
            P[i * n + j] = s;
            P[j * n + i] = s;
        }
    }
    return FRAC_OK;
}

int frac_mat_sym_congruence(const frac_real *A, size_t r, size_t n, const frac_real *P,
                            const frac_real *Q, frac_real *work, frac_real *P_out)
{
    size_t i, j, l;
    if (A == NULL || P == NULL || work == NULL || P_out == NULL) return FRAC_E_NULL;
    if (!DIM_OK(r) || !DIM_OK(n)) return FRAC_E_DIM;
    /* work = A P (r x n) */
    frac_mat_mul(A, r, n, P, n, work);
    /* upper triangle of (A P) A^T, mirrored: r(r+1)/2 inner products */
    for (i = 0; i < r; i++) {
        const frac_real *wrow = work + i * n;
        for (j = i; j < r; j++) {
            const frac_real *arow = A + j * n;
            frac_real s = FRAC_R(0.0);
            for (l = 0; l < n; l++) s += wrow[l] * arow[l];
            if (Q != NULL) s += FRAC_R(0.5) * (Q[i * r + j] + Q[j * r + i]);
            P_out[i * r + j] = s;
            P_out[j * r + i] = s;
        }
    }
    return FRAC_OK;
}

int frac_mat_cholesky(frac_real *P, size_t n)
{
    size_t i, j, l;
    if (P == NULL) return FRAC_E_NULL;
    if (!DIM_OK(n)) return FRAC_E_DIM;
    for (j = 0; j < n; j++) {
        frac_real d = P[j * n + j];
        for (l = 0; l < j; l++) d -= P[j * n + l] * P[j * n + l];
        /* the negated test also rejects NaN */
        if (!(d > FRAC_R(0.0)) || !FRAC_ISFINITE(d)) return FRAC_E_NOT_POSDEF;
        d = FRAC_SQRT(d);
        P[j * n + j] = d;
        for (i = j + 1; i < n; i++) {
            frac_real s = P[i * n + j];
            for (l = 0; l < j; l++) s -= P[i * n + l] * P[j * n + l];
            P[i * n + j] = s / d;
            P[j * n + i] = FRAC_R(0.0);
        }
    }
    return FRAC_OK;
}

int frac_mat_cholesky_solve(const frac_real *L, size_t n, const frac_real *b, frac_real *x)
{
    size_t i, l;
    if (L == NULL || b == NULL || x == NULL) return FRAC_E_NULL;
    if (!DIM_OK(n)) return FRAC_E_DIM;
    /* forward: L z = b */
    for (i = 0; i < n; i++) {
        frac_real s = b[i];
        for (l = 0; l < i; l++) s -= L[i * n + l] * x[l];
        x[i] = s / L[i * n + i];
    }
    /* backward: L^T x = z */
    for (i = n; i-- > 0;) {
        frac_real s = x[i];
        for (l = i + 1; l < n; l++) s -= L[l * n + i] * x[l];
        x[i] = s / L[i * n + i];
    }
    return FRAC_OK;
}

int frac_mat_ldl(frac_real *P, size_t n)
{
    size_t i, j, l;
    if (P == NULL) return FRAC_E_NULL;
    if (!DIM_OK(n)) return FRAC_E_DIM;
    for (j = 0; j < n; j++) {
        frac_real d = P[j * n + j];
        for (l = 0; l < j; l++) d -= P[j * n + l] * P[j * n + l] * P[l * n + l];
        if (d == FRAC_R(0.0) || !FRAC_ISFINITE(d)) return FRAC_E_NUMERIC;
        P[j * n + j] = d;
        for (i = j + 1; i < n; i++) {
            frac_real s = P[i * n + j];
            for (l = 0; l < j; l++) s -= P[i * n + l] * P[j * n + l] * P[l * n + l];
            P[i * n + j] = s / d;
            P[j * n + i] = FRAC_R(0.0);
        }
    }
    return FRAC_OK;
}

int frac_mat_ldl_solve(const frac_real *LD, size_t n, const frac_real *b, frac_real *x)
{
    size_t i, l;
    if (LD == NULL || b == NULL || x == NULL) return FRAC_E_NULL;
    if (!DIM_OK(n)) return FRAC_E_DIM;
    for (i = 0; i < n; i++) {
        frac_real s = b[i];
        for (l = 0; l < i; l++) s -= LD[i * n + l] * x[l];
        x[i] = s;
    }
    for (i = 0; i < n; i++) x[i] /= LD[i * n + i];
    for (i = n; i-- > 0;) {
        frac_real s = x[i];
        for (l = i + 1; l < n; l++) s -= LD[l * n + i] * x[l];
        x[i] = s;
    }
    return FRAC_OK;
}

int frac_mat_all_finite(const frac_real *v, size_t count)
{
    /* 0 * v[i] is 0 for a finite entry and NaN for NaN or +-Inf, and NaN
     * survives the sum: one multiply-add per entry, no branch (valid
     * without -ffast-math, which the build never uses) */
    frac_real z0 = FRAC_R(0.0), z1 = FRAC_R(0.0);
    size_t i = 0;
    if (v == NULL) return 0;
    for (; i + 2 <= count; i += 2) {
        z0 += FRAC_R(0.0) * v[i];
        z1 += FRAC_R(0.0) * v[i + 1];
    }
    if (i < count) z0 += FRAC_R(0.0) * v[i];
    return (z0 + z1) == FRAC_R(0.0);
}
