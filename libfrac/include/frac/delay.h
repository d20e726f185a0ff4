/*
 * delay.h - input/output delay models of a sampled loop: signal shift
 * registers and the delay-augmented state-space model.
 *
 * Seed 004 (M. Wang, TUM 2022), Sec. 7.3-7.5, notes 004b section 7: the
 * torque command reaches the drive d_i samples late (PLC -> POWERLINK ->
 * ACOPOS, Exp. D: d_i = 4 at T = 1.2 ms) and chosen measurements reach
 * the PLC d_o samples late (the IMU over CAN, Exp. D: d_o = 3 on
 * y_3 = dpsi_L only).
 *
 * 1. Shift registers (frac_delay_regs), built on frac/delayline.h:
 *      input  (7.8):  u[k] = u_bar[k - d_i]
 *      output (7.13): y_bar_j[k] = y_j[k - d_o[j]]   (d_o[j] = 0: undelayed)
 *    The physical delays, for plant emulation, HIL and tests.
 *
 * 2. Augmented model (frac_delay_augment), thesis (7.9)-(7.18), for a
 *    single input (the motor torque) and p outputs:
 *      x_bar = [x; xi_1..xi_{d_i}; beta_{j,1}..beta_{j,d_o[j]} for each
 *               delayed output j in increasing j]
 *      xi_i[k+1] = xi_{i+1}[k],  xi_{d_i}[k+1] = u_bar[k] - z_bar[k]   (7.9)-(7.11)
 *      x[k+1] = A' x[k] + B' xi_1[k]                                    (7.12)
 *      beta_{j,i}[k+1] = beta_{j,i+1}[k],  beta_{j,d_o}[k+1] = C'_j x[k]  (7.14)-(7.16)
 *      y_bar_j = beta_{j,1} (delayed j),  y_bar_j = C'_j x (others)     (7.17)
 *    i.e. (7.18) A_bar = [[A', B' C_xi, 0], [0, A_xi, 0], [B_beta C'_3, 0, A_beta]],
 *    B_bar = [0; B_xi; 0], E_bar = [0; E_xi; 0] with E_xi = [0..0, -1]^T.
 *    Corrections applied (notes 004b section 7.3/7.4): the top block row
 *    of (7.12) is [A', B' C_xi] (printed [A' B' 0]); (7.15) uses d_o
 *    throughout (printed mixes d_i); the disturbance enters at the
 *    delay-chain input as in (7.12)/(7.18), not via E' into x as (7.17).
 *    With d_i = 0 the chain is empty: B_bar = [B'; 0], E_bar = [-B'; 0].
 *    Order: n_bar = n + d_i + sum_j d_o[j] (Exp. D: 16 + 4 + 3 = 23).
 */
#ifndef FRAC_DELAY_H
#define FRAC_DELAY_H

#include "frac/delayline.h"
#include "frac/mat.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct frac_delay_regs {
    frac_delayline in;    /* u_bar -> u, delay d_i */
    frac_delayline *out;  /* p lines, caller storage */
    size_t p;
    int ready;
} frac_delay_regs;

/*
 * Input register of d_i samples in `in_storage` (d_i entries, NULL if
 * d_i = 0) and p output registers: `lines` (p objects) with the delays
 * d_o[0..p-1] (NULL: none delayed), their samples in `out_storage`
 * (sum d_o entries, NULL if 0). All registers start at 0.
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM (p = 0 or > FRAC_MAT_MAX).
 */
int frac_delay_regs_init(frac_delay_regs *r, size_t d_i, frac_real *in_storage, size_t p,
                         const size_t *d_o, frac_delayline *lines, frac_real *out_storage);

/*
 * One sample of the input register: *u = u_bar[k - d_i].
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE (u_bar
 * not finite: register untouched, *u = last output).
 */
int frac_delay_regs_input(frac_delay_regs *r, frac_real u_bar, frac_real *u);

/*
 * One sample of the output registers: y_bar[j] = y[j][k - d_o[j]].
 * A non-finite y[j] leaves register j untouched and y_bar[j] at its last
 * value; the others are stepped. Returns FRAC_OK, FRAC_E_NONFINITE (some
 * y[j] not finite), FRAC_E_NULL, FRAC_E_NOT_INIT.
 */
int frac_delay_regs_output(frac_delay_regs *r, const frac_real *y, frac_real *y_bar);

/* Order n + d_i + sum d_o of the augmented model (d_o may be NULL). */
size_t frac_delay_aug_order(size_t n, size_t d_i, size_t p, const size_t *d_o);

/*
 * Builds the augmented model (7.18) from the ZOH model A' (n x n),
 * B' (n, single input), C' (p x n): A_bar (n_bar x n_bar), B_bar (n_bar),
 * E_bar (n_bar), C_bar (p x n_bar), n_bar = frac_delay_aug_order(...).
 * E_bar may be NULL. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM (n or p = 0
 * or n_bar > FRAC_MAT_MAX).
 */
int frac_delay_augment(const frac_real *A, const frac_real *B, const frac_real *C, size_t n,
                       size_t d_i, size_t p, const size_t *d_o,
                       frac_real *A_bar, frac_real *B_bar, frac_real *E_bar, frac_real *C_bar);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_DELAY_H */
