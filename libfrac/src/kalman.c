/*
 * kalman.c - time-varying Joseph-form Kalman filter, steady-state
 * predictor (thesis (7.27)) and the integrating-disturbance extension
 * (thesis (7.26) with a_s = 1, notes 004b erratum 5). See frac/kalman.h.
 */
#include "frac/kalman.h"

#define DIM_OK(d) ((d) > 0 && (d) <= FRAC_MAT_MAX)

static void copy(frac_real *dst, const frac_real *src, size_t count)
{
    size_t i;
    for (i = 0; i < count; i++) dst[i] = src[i];
}

/* Positive definiteness by Cholesky of a copy (the factor is discarded). */
static int is_posdef(const frac_real *M, size_t n, frac_real *work)
{
    copy(work, M, n * n);
    return frac_mat_cholesky(work, n) == FRAC_OK;
}

int frac_kalman_init(frac_kalman *kf, const frac_kalman_params *prm, frac_real *storage, size_t len)
{
    size_t n, p, i;
    frac_real *s;
    if (kf == NULL || prm == NULL || storage == NULL) return FRAC_E_NULL;
    kf->ready = 0;
    n = prm->n;
    p = prm->p;
    if (!DIM_OK(n) || !DIM_OK(p) || prm->m > FRAC_MAT_MAX) return FRAC_E_DIM;
    if (prm->A == NULL || prm->C == NULL || prm->Q == NULL || prm->R == NULL || prm->P0 == NULL ||
        (prm->m > 0 && prm->B == NULL))
        return FRAC_E_NULL;
    if (len < FRAC_KALMAN_STORAGE(n, p)) return FRAC_E_STORAGE;
    if (!frac_mat_all_finite(prm->A, n * n) || !frac_mat_all_finite(prm->C, p * n) ||
        !frac_mat_all_finite(prm->Q, n * n) || !frac_mat_all_finite(prm->R, p * p) ||
        !frac_mat_all_finite(prm->P0, n * n) || (prm->m > 0 && !frac_mat_all_finite(prm->B, n * prm->m)) ||
        (prm->x0 != NULL && !frac_mat_all_finite(prm->x0, n)))
        return FRAC_E_NONFINITE;
    s = storage;
    kf->x = s;   s += n;
    kf->P = s;   s += n * n;
    kf->K = s;   s += n * p;
    kf->Cv = s;  s += p * n;
    kf->PCt = s; s += n * p;
    kf->Kc = s;  s += n * p;
    kf->S = s;   s += p * p;
    kf->nu = s;  s += p;
    kf->W1 = s;  s += n * n;
    kf->W2 = s;  s += n * n;
    kf->W3 = s;
    if (!is_posdef(prm->R, p, kf->W1) || !is_posdef(prm->P0, n, kf->W1)) return FRAC_E_NOT_POSDEF;
    kf->prm = *prm;
    for (i = 0; i < n; i++) kf->x[i] = prm->x0 != NULL ? prm->x0[i] : FRAC_R(0.0);
    copy(kf->P, prm->P0, n * n);
    for (i = 0; i < n * p; i++) kf->K[i] = FRAC_R(0.0);
    kf->ready = 1;
    return FRAC_OK;
}

int frac_kalman_reset(frac_kalman *kf, const frac_real *x0)
{
    size_t i, n;
    if (kf == NULL) return FRAC_E_NULL;
    if (!kf->ready) return FRAC_E_NOT_INIT;
    n = kf->prm.n;
    if (x0 != NULL && !frac_mat_all_finite(x0, n)) return FRAC_E_NONFINITE;
    for (i = 0; i < n; i++) kf->x[i] = x0 != NULL ? x0[i] : FRAC_R(0.0);
    copy(kf->P, kf->prm.P0, n * n);
    return FRAC_OK;
}

int frac_kalman_predict(frac_kalman *kf, const frac_real *u)
{
    const frac_kalman_params *m;
    size_t n;
    frac_real *xn;
    if (kf == NULL) return FRAC_E_NULL;
    if (!kf->ready) return FRAC_E_NOT_INIT;
    m = &kf->prm;
    n = m->n;
    if (m->m > 0) {
        if (u == NULL) return FRAC_E_NULL;
        if (!frac_mat_all_finite(u, m->m)) return FRAC_E_NONFINITE;
    }
    /* x = A x + B u, built in W3 so that a failure leaves x untouched */
    xn = kf->W3;
    frac_mat_vec(m->A, n, n, kf->x, xn);
    if (m->m > 0) frac_mat_vec_add(m->B, n, m->m, u, xn);
    if (!frac_mat_all_finite(xn, n)) return FRAC_E_NUMERIC;
    copy(kf->x, xn, n);
    /* P = A P A^T + Q (symmetric by construction) */
    frac_mat_sym_congruence(m->A, n, n, kf->P, m->Q, kf->W1, kf->W2);
    if (!is_posdef(kf->W2, n, kf->W1)) {
        copy(kf->P, m->P0, n * n);
        return FRAC_W_COV_RESET;
    }
    copy(kf->P, kf->W2, n * n);
    return FRAC_OK;
}

int frac_kalman_update(frac_kalman *kf, const frac_real *y)
{
    const frac_kalman_params *m;
    size_t n, p, pv, i, j, l;
    size_t idx[FRAC_MAT_MAX];
    frac_real *W1, *W2, *W3;
    if (kf == NULL || y == NULL) return FRAC_E_NULL;
    if (!kf->ready) return FRAC_E_NOT_INIT;
    m = &kf->prm;
    n = m->n;
    p = m->p;
    W1 = kf->W1;
    W2 = kf->W2;
    W3 = kf->W3;
    /* the finite measurement components and their rows of C */
    pv = 0;
    for (j = 0; j < p; j++) {
        if (FRAC_ISFINITE(y[j])) idx[pv++] = j;
    }
    if (pv == 0) return FRAC_W_MEAS_SKIPPED;
    for (j = 0; j < pv; j++) copy(kf->Cv + j * n, m->C + idx[j] * n, n);
    /* PCt = P Cv^T (n x pv), S = Cv P Cv^T + R_vv (pv x pv) */
    frac_mat_mul_bt(kf->P, n, n, kf->Cv, pv, kf->PCt);
    frac_mat_mul(kf->Cv, pv, n, kf->PCt, pv, kf->S);
    for (i = 0; i < pv; i++) {
        for (j = 0; j < pv; j++) kf->S[i * pv + j] += m->R[idx[i] * p + idx[j]];
    }
    frac_mat_symmetrize(kf->S, pv);
    if (frac_mat_cholesky(kf->S, pv) != FRAC_OK) {
        copy(kf->P, m->P0, n * n);
        return FRAC_W_COV_RESET;
    }
    /* Kc = PCt S^-1, row by row (S symmetric: row i of Kc solves S k = PCt row i) */
    for (i = 0; i < n; i++) frac_mat_cholesky_solve(kf->S, pv, kf->PCt + i * pv, kf->Kc + i * pv);
    /* innovation and the new estimate, built in W3 */
    for (j = 0; j < pv; j++) {
        const frac_real *crow = kf->Cv + j * n;
        frac_real s = y[idx[j]];
        for (l = 0; l < n; l++) s -= crow[l] * kf->x[l];
        kf->nu[j] = s;
    }
    copy(W3, kf->x, n);
    frac_mat_vec_add(kf->Kc, n, pv, kf->nu, W3);
    if (!frac_mat_all_finite(W3, n)) return FRAC_E_NUMERIC;
    copy(kf->x, W3, n);
    /* gain with skipped columns zero, for the caller */
    for (i = 0; i < n * p; i++) kf->K[i] = FRAC_R(0.0);
    for (i = 0; i < n; i++) {
        for (j = 0; j < pv; j++) kf->K[i * p + idx[j]] = kf->Kc[i * pv + j];
    }
    /* Joseph form: W1 = I - Kc Cv; W2 = W1 P W1^T */
    frac_mat_mul(kf->Kc, n, pv, kf->Cv, n, W1);
    for (i = 0; i < n * n; i++) W1[i] = -W1[i];
    for (i = 0; i < n; i++) W1[i * n + i] += FRAC_R(1.0);
    frac_mat_sym_congruence(W1, n, n, kf->P, NULL, W3, W2);
    /* + Kc R_vv Kc^T: PCt <- Kc R_vv (n x pv), then added symmetrically */
    for (i = 0; i < n; i++) {
        for (j = 0; j < pv; j++) {
            frac_real s = FRAC_R(0.0);
            for (l = 0; l < pv; l++) s += kf->Kc[i * pv + l] * m->R[idx[l] * p + idx[j]];
            kf->PCt[i * pv + j] = s;
        }
    }
    for (i = 0; i < n; i++) {
        for (j = i; j < n; j++) {
            frac_real s = FRAC_R(0.0);
            for (l = 0; l < pv; l++) {
                s += FRAC_R(0.5) * (kf->PCt[i * pv + l] * kf->Kc[j * pv + l] +
                                    kf->PCt[j * pv + l] * kf->Kc[i * pv + l]);
            }
            W2[i * n + j] += s;
            if (j != i) W2[j * n + i] += s;
        }
    }
    if (!is_posdef(W2, n, W1)) {
        copy(kf->P, m->P0, n * n);
        return FRAC_W_COV_RESET;
    }
    copy(kf->P, W2, n * n);
    return pv < p ? FRAC_W_MEAS_SKIPPED : FRAC_OK;
}

int frac_kalman_pred_init(frac_kalman_pred *kp, const frac_kalman_pred_params *prm,
                          frac_real *storage, size_t len)
{
    size_t n, p, i;
    if (kp == NULL || prm == NULL || storage == NULL) return FRAC_E_NULL;
    kp->ready = 0;
    n = prm->n;
    p = prm->p;
    if (!DIM_OK(n) || !DIM_OK(p) || prm->m > FRAC_MAT_MAX) return FRAC_E_DIM;
    if (prm->A == NULL || prm->C == NULL || prm->L == NULL || (prm->m > 0 && prm->B == NULL))
        return FRAC_E_NULL;
    if (len < FRAC_KALMAN_PRED_STORAGE(n, p)) return FRAC_E_STORAGE;
    if (!frac_mat_all_finite(prm->A, n * n) || !frac_mat_all_finite(prm->C, p * n) ||
        !frac_mat_all_finite(prm->L, n * p) || (prm->m > 0 && !frac_mat_all_finite(prm->B, n * prm->m)) ||
        (prm->e0 != NULL && !frac_mat_all_finite(prm->e0, n)))
        return FRAC_E_NONFINITE;
    kp->prm = *prm;
    kp->e = storage;
    kp->tmp = storage + n;
    kp->nu = storage + 2 * n;
    for (i = 0; i < n; i++) kp->e[i] = prm->e0 != NULL ? prm->e0[i] : FRAC_R(0.0);
    for (i = 0; i < p; i++) kp->nu[i] = FRAC_R(0.0);
    kp->ready = 1;
    return FRAC_OK;
}

int frac_kalman_pred_step(frac_kalman_pred *kp, const frac_real *u, const frac_real *y, frac_real *y_hat)
{
    const frac_kalman_pred_params *m;
    size_t n, p, i, j;
    int status = FRAC_OK;
    frac_real *e, *t, *nu;
    if (kp == NULL || y == NULL) return FRAC_E_NULL;
    if (!kp->ready) return FRAC_E_NOT_INIT;
    m = &kp->prm;
    n = m->n;
    p = m->p;
    if (m->m > 0) {
        if (u == NULL) return FRAC_E_NULL;
        if (!frac_mat_all_finite(u, m->m)) return FRAC_E_NONFINITE;
    }
    e = kp->e;
    t = kp->tmp;
    nu = kp->nu;
    /* innovation y - C e; a skipped output contributes nothing */
    frac_mat_vec(m->C, p, n, e, nu);
    for (j = 0; j < p; j++) {
        if (y_hat != NULL) y_hat[j] = nu[j];
        if (FRAC_ISFINITE(y[j])) {
            nu[j] = y[j] - nu[j];
        } else {
            nu[j] = FRAC_R(0.0);
            status = FRAC_W_MEAS_SKIPPED;
        }
    }
    /* t = A e + B u + L nu; L column by column (p is small, n long) */
    frac_mat_vec(m->A, n, n, e, t);
    if (m->m > 0) frac_mat_vec_add(m->B, n, m->m, u, t);
    for (j = 0; j < p; j++) {
        const frac_real nj = nu[j];
        const frac_real *lcol = m->L + j;
        for (i = 0; i < n; i++) t[i] += lcol[i * p] * nj;
    }
    if (!frac_mat_all_finite(t, n)) return FRAC_E_NUMERIC;
    /* swap the buffers: the new estimate becomes current without a copy */
    kp->e = t;
    kp->tmp = e;
    return status;
}

int frac_kalman_augment_disturbance(const frac_real *A, const frac_real *B, const frac_real *E,
                                    const frac_real *C, size_t n, size_t m, size_t p,
                                    frac_real *A_e, frac_real *B_e, frac_real *C_e)
{
    size_t i, j, ne;
    if (A == NULL || E == NULL || C == NULL || A_e == NULL || C_e == NULL) return FRAC_E_NULL;
    if (m > 0 && (B == NULL || B_e == NULL)) return FRAC_E_NULL;
    if (n == 0 || n + 1 > FRAC_MAT_MAX || !DIM_OK(p) || m > FRAC_MAT_MAX) return FRAC_E_DIM;
    ne = n + 1;
    for (i = 0; i < n; i++) {
        for (j = 0; j < n; j++) A_e[i * ne + j] = A[i * n + j];
        A_e[i * ne + n] = E[i];
        A_e[n * ne + i] = FRAC_R(0.0);
        for (j = 0; j < m; j++) B_e[i * m + j] = B[i * m + j];
    }
    A_e[n * ne + n] = FRAC_R(1.0); /* a_s = 1, erratum 5 */
    for (j = 0; j < m; j++) B_e[n * m + j] = FRAC_R(0.0);
    for (i = 0; i < p; i++) {
        for (j = 0; j < n; j++) C_e[i * ne + j] = C[i * n + j];
        C_e[i * ne + n] = FRAC_R(0.0);
    }
    return FRAC_OK;
}
