/*
 * lqg.h - state-difference LQG step with delay-augmented predictor and
 * integrating friction (disturbance) state.
 *
 * Seed 004 (M. Wang, TUM 2022), Sec. 6.4 and 7.6, notes 004b sections 6-7.
 * The controller works on differences reference - actual: e_x = x* - x,
 * e_y = y* - y, e_u = u* - u, e_z = z* - z = -z (z: friction torque at the
 * input). One step of cycle k, with the estimate e_hat = e_hat[k] (a
 * priori, from the previous step):
 *
 *   e_y    = y_ref - y                               (bar e_y of (7.19))
 *   u      = u* + K e_hat_x - e_hat_z                (7.21); (6.45) for d = 0
 *   e_u    = u* - u = -(K e_hat_x - e_hat_z)         (7.20)
 *   e_hat  <- A_e e_hat + B_e e_u + L (e_y - C_e e_hat)   (7.27), predictor
 *
 * with the augmented model of frac/delay.h ((7.18): state order
 * [x; xi_1..xi_{d_i}; beta_j for each delayed output j]) extended by the
 * disturbance state e_s (7.26) with a_s = 1 (notes 004b erratum 5: the
 * printed 0 would forget the friction estimate), c_s = 1, e_z = e_s, and
 * the disturbance entering at the delay-chain input E_xi = [0..0, -1]^T
 * ((7.10)-(7.12); with d_i = 0 it enters as -B' in x).
 *
 * The step exploits the structure of A_e instead of multiplying the dense
 * (n_bar+1)^2 matrix: the delay states only shift (xi_i <- xi_{i+1},
 * beta <- beta shifted, beta_last <- C'_j x), so one step costs
 * n^2 + (p + 1) n + (n_bar + 1) p + n_bar multiply-adds
 * (Exp. D: n = 16, n_bar = 23, p = 3: 415; the dense form needs 767).
 * frac_delay_augment + frac_kalman_augment_disturbance + frac_kalman_pred
 * compute the same thing densely (the tests check both agree).
 *
 * Inputs per step: u_star = feedforward torque already sent d_i samples
 * early (u_bar*[k] = u*[k + d_i], thesis Sec. 8.6, see frac/trajlut.h),
 * y_ref = references of the measured outputs with the delayed ones
 * delayed by d_o (y_bar_3*[k] = y_3*[k - d_o]), y = measurements as
 * received (delayed ones late). Gains K (dlqr, (7.24)) and L (dual dlqr,
 * (7.27)) come from the design tools.
 *
 * Bad input: non-finite u_star or y_ref: FRAC_E_NONFINITE, estimate
 * untouched, *u = last output. Non-finite y_j: that innovation is dropped
 * (FRAC_W_MEAS_SKIPPED), the control law and the prediction go on. An
 * estimate that would become non-finite: FRAC_E_NUMERIC, state untouched.
 */
#ifndef FRAC_LQG_H
#define FRAC_LQG_H

#include "frac/mat.h"

#ifdef __cplusplus
extern "C" {
#endif

/* frac_real entries of caller storage: n_e = n_bar + 1 estimate states, p outputs. */
#define FRAC_LQG_STORAGE(n_e, p) (2 * (n_e) + 2 * (p))

typedef struct frac_lqg_params {
    size_t n;            /* plant order (ZOH model) */
    size_t d_i;          /* input delay, samples */
    size_t p;            /* measured outputs */
    const size_t *d_o;   /* p output delays in samples (copied at init), NULL: none */
    const frac_real *A;  /* n x n  A' */
    const frac_real *B;  /* n      B' (single input: the motor torque) */
    const frac_real *C;  /* p x n  C' */
    const frac_real *K;  /* n_bar  K_bar, n_bar = n + d_i + sum d_o */
    const frac_real *L;  /* (n_bar + 1) x p  L_e */
} frac_lqg_params;

typedef struct frac_lqg {
    frac_lqg_params prm;
    size_t nb, ne;                /* n_bar and n_bar + 1 */
    size_t yoff[FRAC_MAT_MAX];    /* index of beta_{j,1}, 0 for an undelayed output */
    size_t ylen[FRAC_MAT_MAX];    /* d_o[j] */
    frac_real *e, *tmp, *nu, *cx; /* estimate, next estimate, innovation, C' x_hat */
    frac_real last_u;
    int ready;
} frac_lqg;

/*
 * Validates (finite matrices; n_bar + 1 <= FRAC_MAT_MAX) and lays out
 * storage (len >= FRAC_LQG_STORAGE(n_bar + 1, p)); the estimate starts at 0.
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM, FRAC_E_STORAGE, FRAC_E_NONFINITE.
 */
int frac_lqg_init(frac_lqg *c, const frac_lqg_params *prm, frac_real *storage, size_t len);

/*
 * One control cycle (see above): writes the torque command u_bar[k] to *u
 * and advances the estimate. Returns FRAC_OK, FRAC_W_MEAS_SKIPPED,
 * FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE, FRAC_E_NUMERIC.
 */
int frac_lqg_step(frac_lqg *c, frac_real u_star, const frac_real *y_ref, const frac_real *y, frac_real *u);

/* Estimate back to 0, last output 0. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT. */
int frac_lqg_reset(frac_lqg *c);

/* Friction estimate: -e_hat_z = z_hat (Nm), the torque the law adds. 0 if c is not ready. */
frac_real frac_lqg_friction_estimate(const frac_lqg *c);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_LQG_H */
