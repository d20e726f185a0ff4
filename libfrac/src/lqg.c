/*
 * lqg.c - state-difference LQG with the structured delay-augmented
 * predictor of seed 004 (7.18)-(7.27) (see frac/lqg.h).
 */
#include "frac/lqg.h"

int frac_lqg_init(frac_lqg *c, const frac_lqg_params *prm, frac_real *storage, size_t len)
{
    size_t j, nb, off;
    if (c == NULL || prm == NULL || storage == NULL) return FRAC_E_NULL;
    c->ready = 0;
    if (prm->A == NULL || prm->B == NULL || prm->C == NULL || prm->K == NULL || prm->L == NULL)
        return FRAC_E_NULL;
    if (prm->n == 0 || prm->p == 0 || prm->p > FRAC_MAT_MAX || prm->n > FRAC_MAT_MAX ||
        prm->d_i > FRAC_MAT_MAX)
        return FRAC_E_DIM;
    nb = prm->n + prm->d_i;
    off = nb;
    for (j = 0; j < prm->p; j++) {
        size_t d = prm->d_o != NULL ? prm->d_o[j] : 0;
        if (d > FRAC_MAT_MAX) return FRAC_E_DIM;
        c->yoff[j] = d > 0 ? off : 0;
        c->ylen[j] = d;
        off += d;
        nb += d;
    }
    if (nb + 1 > FRAC_MAT_MAX) return FRAC_E_DIM;
    if (len < FRAC_LQG_STORAGE(nb + 1, prm->p)) return FRAC_E_STORAGE;
    if (!frac_mat_all_finite(prm->A, prm->n * prm->n) || !frac_mat_all_finite(prm->B, prm->n) ||
        !frac_mat_all_finite(prm->C, prm->p * prm->n) || !frac_mat_all_finite(prm->K, nb) ||
        !frac_mat_all_finite(prm->L, (nb + 1) * prm->p))
        return FRAC_E_NONFINITE;
    c->prm = *prm;
    c->prm.d_o = NULL; /* copied into ylen */
    c->nb = nb;
    c->ne = nb + 1;
    c->e = storage;
    c->tmp = storage + c->ne;
    c->nu = storage + 2 * c->ne;
    c->cx = c->nu + prm->p;
    c->ready = 1;
    return frac_lqg_reset(c);
}

int frac_lqg_reset(frac_lqg *c)
{
    size_t i;
    if (c == NULL) return FRAC_E_NULL;
    if (!c->ready) return FRAC_E_NOT_INIT;
    for (i = 0; i < c->ne; i++) c->e[i] = FRAC_R(0.0);
    for (i = 0; i < c->prm.p; i++) c->nu[i] = c->cx[i] = FRAC_R(0.0);
    c->last_u = FRAC_R(0.0);
    return FRAC_OK;
}

frac_real frac_lqg_friction_estimate(const frac_lqg *c)
{
    if (c == NULL || !c->ready) return FRAC_R(0.0);
    return -c->e[c->nb];
}

int frac_lqg_step(frac_lqg *c, frac_real u_star, const frac_real *y_ref, const frac_real *y, frac_real *u)
{
    size_t n, p, nb, ne, d_i, i, j;
    const frac_real *A, *B, *C, *K, *L;
    frac_real *e, *t, *nu, *cx;
    frac_real es, fb, eu, ubar;
    int status = FRAC_OK;
    if (c == NULL || y_ref == NULL || y == NULL || u == NULL) return FRAC_E_NULL;
    if (!c->ready) return FRAC_E_NOT_INIT;
    n = c->prm.n;
    p = c->prm.p;
    nb = c->nb;
    ne = c->ne;
    d_i = c->prm.d_i;
    A = c->prm.A;
    B = c->prm.B;
    C = c->prm.C;
    K = c->prm.K;
    L = c->prm.L;
    e = c->e;
    t = c->tmp;
    nu = c->nu;
    cx = c->cx;
    if (!FRAC_ISFINITE(u_star)) {
        *u = c->last_u;
        return FRAC_E_NONFINITE;
    }
    if (!frac_mat_all_finite(y_ref, p)) {
        *u = c->last_u;
        return FRAC_E_NONFINITE;
    }
    /* C' x_hat and the innovation e_y - C_e e_hat; C_e picks beta_{j,1} for a delayed output */
    frac_mat_vec(C, p, n, e, cx);
    for (j = 0; j < p; j++) {
        frac_real s = cx[j];
        if (FRAC_ISFINITE(y[j])) {
            nu[j] = (y_ref[j] - y[j]) - (c->yoff[j] != 0 ? e[c->yoff[j]] : s);
        } else {
            nu[j] = FRAC_R(0.0);
            status = FRAC_W_MEAS_SKIPPED;
        }
    }
    /* control law (7.21): u = u* + K e_x - e_z, e_z = e_s (c_s = 1) */
    es = e[nb];
    frac_mat_vec(K, 1, nb, e, &fb);
    fb -= es;
    ubar = u_star + fb;
    eu = -fb; /* (7.20) */
    /* predictor (7.27) with the structure of (7.18)/(7.26) */
    /* model part of (7.27): x rows A' x + B' (input), the shifts, a_s = 1 */
    frac_mat_vec(A, n, n, e, t);
    {
        /* input of x: xi_1 (the delayed command) or, with d_i = 0, e_u + E e_z = e_u - e_s */
        const frac_real in = d_i > 0 ? e[n] : eu - es;
        for (i = 0; i < n; i++) t[i] += B[i] * in;
    }
    if (d_i > 0) {
        for (i = 0; i + 1 < d_i; i++) t[n + i] = e[n + i + 1];
        t[n + d_i - 1] = eu - es; /* B_xi e_u + E_xi e_z (7.11) */
    }
    for (j = 0; j < p; j++) {
        size_t o = c->yoff[j], d = c->ylen[j];
        if (d == 0) continue;
        for (i = 0; i + 1 < d; i++) t[o + i] = e[o + i + 1];
        t[o + d - 1] = cx[j]; /* B_beta C'_j x (7.15)-(7.16) */
    }
    t[nb] = es; /* a_s = 1 (erratum 5) */
    /* + L_e nu, column by column: p is small (3), ne long */
    for (j = 0; j < p; j++) {
        const frac_real nj = nu[j];
        const frac_real *lcol = L + j;
        for (i = 0; i < ne; i++) t[i] += lcol[i * p] * nj;
    }
    if (!FRAC_ISFINITE(ubar) || !frac_mat_all_finite(t, ne)) {
        *u = c->last_u;
        return FRAC_E_NUMERIC;
    }
    c->e = t;
    c->tmp = e;
    c->last_u = ubar;
    *u = ubar;
    return status;
}
