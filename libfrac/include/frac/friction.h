/*
 * friction.h - static friction models for torque compensation.
 *
 * Seed 004 (M. Wang, TUM 2022), Sec. 5.2, with sgn(v) replaced everywhere
 * by the smooth tanh(k v) the thesis implements (k = 60, Table 8.6):
 *  - linear (5.2):      tau_f = b1 v + b0 tanh(k v)
 *  - asymmetric (5.3):  tau_f = (b1n g_n + b1p g_p) v + (b0n g_n + b0p g_p) tanh(k v),
 *                       where the printed side selectors min(sgn(-v)+1, 1)
 *                       and min(sgn(v)+1, 1) are smoothed as the partition
 *                       of unity g_n = (1 - tanh(k v))/2, g_p = (1 + tanh(k v))/2.
 *                       They tend to the printed selectors for |k v| >> 1,
 *                       and with equal sides the model is exactly (5.2)
 *                       (substituting tanh into min(.) literally would let
 *                       both sides act near v = 0 and double the torque).
 *                       Table 5.2 lists only three of the four parameters
 *                       (notes 004b erratum 17): all four are inputs here.
 *  - Stribeck (5.4):    tau_f = (b1s + (b2s - b1s) exp(-|v / v_s|^delta)) tanh(k v)
 *                              + b3s v
 * v is the driven-side motor velocity dtheta_M in rad/s and tau_f the
 * driven-side torque in Nm. Which velocity is used (measured or reference)
 * is the caller's choice (notes 004b erratum 18: the thesis prints the
 * measured one).
 * Cost: one tanh (plus one exp and one pow for Stribeck) per evaluation.
 */
#ifndef FRAC_FRICTION_H
#define FRAC_FRICTION_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum frac_friction_model {
    FRAC_FRICTION_LINEAR = 0,
    FRAC_FRICTION_ASYMMETRIC = 1,
    FRAC_FRICTION_STRIBECK = 2
} frac_friction_model;

typedef struct frac_friction_params {
    int model;      /* frac_friction_model */
    frac_real k;    /* tanh smoothing gain, > 0 (thesis: 60) */
    /* linear (5.2): viscous b1 [Nm s/rad], Coulomb b0 [Nm] */
    frac_real b1, b0;
    /* asymmetric (5.3): viscous and Coulomb for v < 0 (n) and v > 0 (p) */
    frac_real b1n, b1p, b0n, b0p;
    /* Stribeck (5.4): Coulomb b1s, static b2s, viscous b3s, Stribeck velocity v_s > 0, exponent delta > 0 */
    frac_real b1s, b2s, b3s, v_s, delta;
} frac_friction_params;

typedef struct frac_friction {
    frac_friction_params p;
    frac_real last; /* last output, held on a rejected input */
    int ready;
} frac_friction;

/*
 * Validates and copies the parameters. The fields of the models not
 * selected are ignored. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_PARAM (unknown
 * model, a used parameter non-finite, k <= 0, v_s <= 0 or delta <= 0).
 */
int frac_friction_init(frac_friction *f, const frac_friction_params *p);

/*
 * Friction torque estimate tau_f(v). Returns FRAC_OK, FRAC_E_NULL,
 * FRAC_E_NOT_INIT, FRAC_E_NONFINITE (v not finite: *tau gets the last
 * finite output).
 */
int frac_friction_eval(frac_friction *f, frac_real v, frac_real *tau);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_FRICTION_H */
