/*
 * kalman.h - discrete Kalman filters in caller storage.
 *
 * Model: x[k+1] = A x[k] + B u[k] + w[k], y[k] = C x[k] + v[k], with
 * cov(w) = Q, cov(v) = R; n states, m inputs (m may be 0), p outputs.
 * All matrices are row-major (frac/mat.h) and held by pointer: the caller
 * keeps them alive and unchanged while the filter is used.
 *
 * Two forms:
 *  1. frac_kalman: time-varying filter, predict and update as separate
 *     steps. Update in Joseph form
 *        K = P C^T (C P C^T + R)^-1,  x += K (y - C x),
 *        P = (I - K C) P (I - K C)^T + K R K^T,
 *     which keeps P symmetric positive semidefinite under rounding; every
 *     covariance result is also symmetrised exactly. Seed 004 designs the
 *     same filter through the dual LQR (thesis (6.21)-(6.26), discrete in
 *     Sec. 7.4); this is its recursive form.
 *  2. frac_kalman_pred: steady-state predictor, thesis (7.27)
 *        e[k+1] = A e[k] + B u[k] + L (y[k] - C e[k]),
 *     with the a-priori gain L = A P C^T (C P C^T + R)^-1 from the filter
 *     DARE (notes 004b section 7.6 / check 30). Cost per step:
 *     n^2 + n m + 2 n p multiply-adds.
 *
 * Disturbance state: frac_kalman_augment_disturbance builds the extended
 * model of thesis (6.40)/(7.26) with an integrating disturbance
 * e_s[k+1] = a_s e_s[k], a_s = 1 (notes 004b erratum 5: (7.26) prints 0
 * in the bottom-right corner, (7.25) states a_s = 1; 1 is used, so the
 * filter can hold a constant friction estimate).
 *
 * Bad input (ARCHITECTURE.md): a non-finite u returns FRAC_E_NONFINITE
 * with the state untouched; a non-finite measurement component is skipped
 * (FRAC_W_MEAS_SKIPPED): the update uses the finite components only, the
 * prediction always continues. A covariance that loses positive
 * definiteness or becomes non-finite (tested by a Cholesky factorisation
 * after every covariance step) is reset to the initial P0 and the step
 * returns FRAC_W_COV_RESET.
 */
#ifndef FRAC_KALMAN_H
#define FRAC_KALMAN_H

#include "frac/mat.h"

#ifdef __cplusplus
extern "C" {
#endif

/* frac_real entries of caller storage the time-varying filter needs. */
#define FRAC_KALMAN_STORAGE(n, p) (4 * (n) * (n) + 4 * (n) * (p) + (p) * (p) + (p) + (n))

typedef struct frac_kalman_params {
    size_t n, m, p;            /* states (1..FRAC_MAT_MAX), inputs (0..), outputs (1..FRAC_MAT_MAX) */
    const frac_real *A;        /* n x n */
    const frac_real *B;        /* n x m (may be NULL when m = 0) */
    const frac_real *C;        /* p x n */
    const frac_real *Q;        /* n x n process noise covariance, symmetric PSD */
    const frac_real *R;        /* p x p measurement noise covariance, symmetric PD */
    const frac_real *P0;       /* n x n initial covariance, symmetric PD (also the reset value) */
    const frac_real *x0;       /* n initial estimate (NULL: zero) */
} frac_kalman_params;

typedef struct frac_kalman {
    frac_kalman_params prm;
    frac_real *x;   /* n: current estimate (a priori after predict, a posteriori after update) */
    frac_real *P;   /* n x n: its covariance */
    frac_real *K;   /* n x p: gain of the last update (0 columns for skipped outputs) */
    frac_real *Cv, *PCt, *Kc, *S, *nu, *W1, *W2, *W3; /* workspace */
    int ready;
} frac_kalman;

/*
 * Validates the model (finite matrices, R and P0 positive definite by
 * Cholesky) and lays out `storage` (len >= FRAC_KALMAN_STORAGE(n, p)).
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM, FRAC_E_STORAGE,
 * FRAC_E_NONFINITE (a non-finite matrix entry), FRAC_E_NOT_POSDEF (R or P0).
 */
int frac_kalman_init(frac_kalman *kf, const frac_kalman_params *prm, frac_real *storage, size_t len);

/*
 * Time update x = A x + B u, P = A P A^T + Q (u: m entries, NULL if m = 0).
 * Returns FRAC_OK, FRAC_W_COV_RESET (P lost definiteness: P = P0, x was
 * still predicted), FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE (u not
 * finite; nothing changed), FRAC_E_NUMERIC (x would become non-finite;
 * nothing changed).
 */
int frac_kalman_predict(frac_kalman *kf, const frac_real *u);

/*
 * Measurement update in Joseph form with the finite components of y
 * (p entries). Returns FRAC_OK, FRAC_W_MEAS_SKIPPED (some or all
 * components non-finite and skipped; with none left x and P are
 * unchanged), FRAC_W_COV_RESET (C P C^T + R or the new P not positive
 * definite: P = P0; x keeps the update only if it was computed),
 * FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NUMERIC (x would become non-finite;
 * nothing changed).
 */
int frac_kalman_update(frac_kalman *kf, const frac_real *y);

/* Sets x = x0 (NULL: zero) and P = P0. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE. */
int frac_kalman_reset(frac_kalman *kf, const frac_real *x0);

/* frac_real entries of caller storage the predictor needs. */
#define FRAC_KALMAN_PRED_STORAGE(n, p) (2 * (n) + (p))

typedef struct frac_kalman_pred_params {
    size_t n, m, p;
    const frac_real *A;  /* n x n */
    const frac_real *B;  /* n x m (NULL when m = 0) */
    const frac_real *C;  /* p x n */
    const frac_real *L;  /* n x p predictor gain */
    const frac_real *e0; /* n initial estimate (NULL: zero) */
} frac_kalman_pred_params;

typedef struct frac_kalman_pred {
    frac_kalman_pred_params prm;
    frac_real *e;   /* n: estimate e[k] (a priori) */
    frac_real *tmp; /* n: next estimate under construction */
    frac_real *nu;  /* p: innovation of the last step */
    int ready;
} frac_kalman_pred;

/*
 * Validates (finite matrices) and lays out storage
 * (len >= FRAC_KALMAN_PRED_STORAGE(n, p)). Returns FRAC_OK, FRAC_E_NULL,
 * FRAC_E_DIM, FRAC_E_STORAGE, FRAC_E_NONFINITE.
 */
int frac_kalman_pred_init(frac_kalman_pred *kp, const frac_kalman_pred_params *prm,
                          frac_real *storage, size_t len);

/*
 * One step of (7.27): e = A e + B u + L (y - C e). A non-finite y_j gives
 * innovation 0 on output j (the prediction continues). y_hat (p entries,
 * may be NULL) receives C e[k] of the estimate before the step.
 * Returns FRAC_OK, FRAC_W_MEAS_SKIPPED, FRAC_E_NULL, FRAC_E_NOT_INIT,
 * FRAC_E_NONFINITE (u not finite; nothing changed), FRAC_E_NUMERIC (the
 * next estimate would be non-finite; nothing changed).
 */
int frac_kalman_pred_step(frac_kalman_pred *kp, const frac_real *u, const frac_real *y, frac_real *y_hat);

/*
 * Integrating-disturbance extension, thesis (6.40)/(7.26), a_s = 1
 * (erratum 5), c_s = 1:
 *   A_e = [[A, E], [0, 1]]  ((n+1) x (n+1)),  B_e = [B; 0]  ((n+1) x m),
 *   C_e = [C, 0]            (p x (n+1)).
 * E (n entries) is the disturbance input column; the thesis does not print
 * it (notes 004b erratum 4), friction acting at the motor torque gives
 * E = -B' (thesis (7.10): the disturbance is subtracted from the input).
 * B_e may be NULL (and B with it) when m = 0.
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM (n + 1 > FRAC_MAT_MAX).
 */
int frac_kalman_augment_disturbance(const frac_real *A, const frac_real *B, const frac_real *E,
                                    const frac_real *C, size_t n, size_t m, size_t p,
                                    frac_real *A_e, frac_real *B_e, frac_real *C_e);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_KALMAN_H */
