/*
 * delay.c - shift registers on frac_delayline and the delay-augmented
 * model of seed 004 (7.9)-(7.18) (see frac/delay.h).
 */
#include "frac/delay.h"

int frac_delay_regs_init(frac_delay_regs *r, size_t d_i, frac_real *in_storage, size_t p,
                         const size_t *d_o, frac_delayline *lines, frac_real *out_storage)
{
    size_t j, off = 0;
    int st;
    if (r == NULL || lines == NULL) return FRAC_E_NULL;
    r->ready = 0;
    if (p == 0 || p > FRAC_MAT_MAX) return FRAC_E_DIM;
    st = frac_delayline_init(&r->in, in_storage, d_i, d_i);
    if (st != FRAC_OK) return st;
    for (j = 0; j < p; j++) {
        size_t d = d_o != NULL ? d_o[j] : 0;
        st = frac_delayline_init(&lines[j], d > 0 ? out_storage + off : NULL, d, d);
        if (st != FRAC_OK) return st;
        off += d;
    }
    r->out = lines;
    r->p = p;
    r->ready = 1;
    return FRAC_OK;
}

int frac_delay_regs_input(frac_delay_regs *r, frac_real u_bar, frac_real *u)
{
    if (r == NULL || u == NULL) return FRAC_E_NULL;
    if (!r->ready) return FRAC_E_NOT_INIT;
    return frac_delayline_step(&r->in, u_bar, u);
}

int frac_delay_regs_output(frac_delay_regs *r, const frac_real *y, frac_real *y_bar)
{
    size_t j;
    int st = FRAC_OK;
    if (r == NULL || y == NULL || y_bar == NULL) return FRAC_E_NULL;
    if (!r->ready) return FRAC_E_NOT_INIT;
    for (j = 0; j < r->p; j++) {
        if (frac_delayline_step(&r->out[j], y[j], &y_bar[j]) != FRAC_OK) st = FRAC_E_NONFINITE;
    }
    return st;
}

size_t frac_delay_aug_order(size_t n, size_t d_i, size_t p, const size_t *d_o)
{
    size_t j, nb = n + d_i;
    if (d_o != NULL) {
        for (j = 0; j < p; j++) nb += d_o[j];
    }
    return nb;
}

int frac_delay_augment(const frac_real *A, const frac_real *B, const frac_real *C, size_t n,
                       size_t d_i, size_t p, const size_t *d_o,
                       frac_real *A_bar, frac_real *B_bar, frac_real *E_bar, frac_real *C_bar)
{
    size_t nb, i, j, l, off;
    if (A == NULL || B == NULL || C == NULL || A_bar == NULL || B_bar == NULL || C_bar == NULL)
        return FRAC_E_NULL;
    if (n == 0 || p == 0 || p > FRAC_MAT_MAX) return FRAC_E_DIM;
    nb = frac_delay_aug_order(n, d_i, p, d_o);
    if (nb > FRAC_MAT_MAX) return FRAC_E_DIM;
    for (i = 0; i < nb * nb; i++) A_bar[i] = FRAC_R(0.0);
    for (i = 0; i < nb; i++) B_bar[i] = FRAC_R(0.0);
    if (E_bar != NULL) {
        for (i = 0; i < nb; i++) E_bar[i] = FRAC_R(0.0);
    }
    for (i = 0; i < p * nb; i++) C_bar[i] = FRAC_R(0.0);
    /* x block: A', and B' C_xi (input from xi_1), (7.12) corrected */
    for (i = 0; i < n; i++) {
        for (j = 0; j < n; j++) A_bar[i * nb + j] = A[i * n + j];
    }
    if (d_i > 0) {
        for (i = 0; i < n; i++) A_bar[i * nb + n] = B[i];
        /* A_xi: upper shift; B_xi, E_xi at the chain input (7.11) */
        for (i = 0; i + 1 < d_i; i++) A_bar[(n + i) * nb + n + i + 1] = FRAC_R(1.0);
        B_bar[n + d_i - 1] = FRAC_R(1.0);
        if (E_bar != NULL) E_bar[n + d_i - 1] = FRAC_R(-1.0);
    } else {
        for (i = 0; i < n; i++) {
            B_bar[i] = B[i];
            if (E_bar != NULL) E_bar[i] = -B[i];
        }
    }
    /* output chains (7.14)-(7.17) */
    off = n + d_i;
    for (j = 0; j < p; j++) {
        size_t d = d_o != NULL ? d_o[j] : 0;
        if (d == 0) {
            for (l = 0; l < n; l++) C_bar[j * nb + l] = C[j * n + l];
            continue;
        }
        for (i = 0; i + 1 < d; i++) A_bar[(off + i) * nb + off + i + 1] = FRAC_R(1.0);
        for (l = 0; l < n; l++) A_bar[(off + d - 1) * nb + l] = C[j * n + l]; /* B_beta C'_j */
        C_bar[j * nb + off] = FRAC_R(1.0);                                    /* C_beta */
        off += d;
    }
    return FRAC_OK;
}
