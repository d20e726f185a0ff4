/*
 * fopid.h - fractional PI^l D^m controller with derivative filter, output
 * limits, anti-windup and bumpless manual/auto transfer; covers the
 * FO-PI^a and FO-PD^m of seed 001 (with the positive feedback delta = 1/K
 * that turns the PD into an offset-free loop).
 *
 * Control law (ISA form with set-point weights b, c):
 *     u = kp (b r - y) + ki s^-l (r - y) + kd s^m / (1 + tf s) (c r - y)
 *         + delta y
 * seed 001 (5): FO-PI^a: kp + ki/s^a (kd = 0, l = a);
 * seed 001 (29): FO-PD^m: kp + kd s^m (ki = 0);
 * seed 001 (36)-(41), Fig. 12: PD with positive feedback of the plant
 * output: C = C^ + delta, u = C (r - y) + delta y, delta = 1/K, i.e. pass
 * kp = K^p + delta and delta = 1/K; the loop then has a fictitious
 * integrator and the steady-state errors of (43)/(45):
 * a/(K^p + delta) for an input step a, -a K^p/(K^p + delta) for a sensor
 * step a (test_fopid_seed001.c).
 *
 * Discrete realization (Ts):
 *  - Integral: x_I += Ts ki D^(1-l) e, i.e. s^-l = s^-1 s^(1-l) with an
 *    exact (backward-Euler) integrator after the fractional operator of
 *    order 1 - l (realization chosen in `op`). The integrator keeps true
 *    integral action (zero steady-state error) for every realization and
 *    memory length, holds the state that anti-windup and bumpless transfer
 *    act on, and with Grünwald–Letnikov it is exact: (1 - z^-1)^-1
 *    (1 - z^-1)^(1-l) = (1 - z^-1)^-l, the GL operator of order -l,
 *    whose truncation error then only involves the faster-decaying
 *    weights of order 1 - l.
 *  - Derivative: D^m of (c r - y) (realization `op`), then the first-order
 *    filter 1/(1 + tf s) discretized pole-matched,
 *    f += (1 - e^{-Ts/tf}) (D^m - f) (tf = 0: no filter).
 *  - Anti-windup (output limits umin < umax; +-inf allowed):
 *      FRAC_FOPID_AW_NONE      integrate always;
 *      FRAC_FOPID_AW_CLAMP     conditional integration: the increment is
 *                              dropped when the unsaturated output is beyond
 *                              a limit and the increment pushes further out;
 *      FRAC_FOPID_AW_BACKCALC  x_I += Ts (ki D^(1-l) e + (u - v)/tt), v the
 *                              unsaturated, u the saturated output.
 *  - Manual mode: u = clamp(u_man); the integral state tracks
 *    x_I = u - (P + D + delta y) every sample, so switching to automatic
 *    starts exactly from u (bumpless); switching to manual takes the last
 *    output as u_man (bumpless the other way too).
 * The fractional operators run on the error in every mode, so their
 * memories are warm at a switch.
 *
 * Cost per sample: the two operators (see fo_op.h) + ~20 flops.
 * Storage: frac_fopid_storage_len(p) reals for the two operators.
 */
#ifndef FRAC_FOPID_H
#define FRAC_FOPID_H

#include "frac/frac_types.h"
#include "frac/fo_op.h"

#ifdef __cplusplus
extern "C" {
#endif

enum frac_fopid_aw {
    FRAC_FOPID_AW_NONE = 0,
    FRAC_FOPID_AW_CLAMP = 1,
    FRAC_FOPID_AW_BACKCALC = 2
};

enum frac_fopid_mode {
    FRAC_FOPID_AUTO = 0,
    FRAC_FOPID_MANUAL = 1
};

typedef struct frac_fopid_params {
    frac_real kp, ki, kd;   /* gains, finite */
    frac_real lambda;       /* integral order l, (0, 2) (used when ki != 0) */
    frac_real mu;           /* derivative order m, [0, 2] (used when kd != 0) */
    frac_real tf;           /* derivative filter time constant >= 0, s */
    frac_real b, c;         /* set-point weights of P and D (1 = act on the error) */
    frac_real delta;        /* positive feedback gain of y (seed 001: 1/K; 0 = none) */
    frac_real umin, umax;   /* output limits, umin < umax (may be -+inf) */
    int antiwindup;         /* enum frac_fopid_aw */
    frac_real tt;           /* back-calculation time constant > 0, s (AW_BACKCALC) */
    frac_real ts;           /* sampling time, s */
    frac_fo_params op;      /* realization of the fractional operators: method, memory, wb, wh, n */
} frac_fopid_params;

typedef struct frac_fopid {
    frac_fo opi;            /* D^(1-l) */
    frac_fo opd;            /* D^m */
    frac_fopid_params p;
    frac_real xi;           /* integral (and bias) state */
    frac_real df;           /* filtered derivative */
    frac_real af;           /* filter factor 1 - e^{-Ts/tf} */
    frac_real uman;         /* manual output */
    frac_real last;         /* last output */
    int mode;
    int ready;
} frac_fopid;

/* Reals of storage for p (both operators). */
size_t frac_fopid_storage_len(const frac_fopid_params *p);

/*
 * Returns FRAC_OK; FRAC_E_NULL; FRAC_E_GAIN (a gain, delta, b, c not
 * finite; tf < 0; tt <= 0 with back-calculation); FRAC_E_ORDER (l outside
 * (0, 2) with ki != 0, m outside [0, 2] with kd != 0); FRAC_E_LIMITS
 * (!(umin < umax)); FRAC_E_PARAM (unknown anti-windup mode); FRAC_E_TS;
 * FRAC_E_STORAGE; the realization's codes. Starts in automatic mode with
 * zero state.
 */
int frac_fopid_init(frac_fopid *c, const frac_fopid_params *p, frac_real *storage, size_t len);

/*
 * One sample: set point r, measurement y, output *u.
 * Returns FRAC_OK; FRAC_W_SATURATED (output at a limit); FRAC_E_NULL;
 * FRAC_E_NOT_INIT; FRAC_E_NONFINITE (r or y not finite: state untouched,
 * *u = last output).
 */
int frac_fopid_step(frac_fopid *c, frac_real r, frac_real y, frac_real *u);

/*
 * Mode switch (bumpless both ways, see above). FRAC_OK, FRAC_E_NULL,
 * FRAC_E_NOT_INIT, FRAC_E_PARAM (unknown mode).
 */
int frac_fopid_set_mode(frac_fopid *c, int mode);

/* Manual output value (used in manual mode). FRAC_E_NONFINITE leaves it unchanged. */
int frac_fopid_set_manual(frac_fopid *c, frac_real u_man);

/* Zero state (operators, integrator, filter), last output 0. */
int frac_fopid_reset(frac_fopid *c);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_FOPID_H */
