/*
 * foprocess.h - simulator of the fractional process with dead time
 *     G(s) = K e^{-tau s} / (1 + T s^l),   0 < l <= 2
 * (seed 001 eq. (1); T in s^l, l > 1 underdamped), for tests and the HIL
 * rig. Delay line + fractional operator:
 *     v_k = u(k Ts - tau)           (delay line, linear interpolation
 *                                    between the two taps around tau/Ts)
 *     y_k + T D^l y_k = K v_k       (D^l from fo_op.h, any realization)
 * Every realization's next output is affine in its input,
 * D^l y_k = g y_k + f_k (g = frac_fo_feedthrough, f_k = the free
 * response), so the algebraic loop is solved exactly each step:
 *     y_k = (K v_k - T f_k) / (1 + T g).
 * With Grünwald–Letnikov this is the implicit GL scheme of the seed 001
 * note, section 7: y_k = (K v_k - T h^-l sum_{j>=1} w_j y_{k-j}) /
 * (T h^-l + 1); with full memory it converges to the exact step response
 * 1 - E_l(-t^l/T) at first order in h (test_foprocess.c: relative RMS
 * error <= 1e-3 with h = 5e-4 T^(1/l) over 10 T^(1/l) for l in
 * {0.5, 1.2, 1.92}).
 *
 * The delay: d = floor(tau/Ts), mu = tau/Ts - d,
 * v = (1 - mu) u_{k-d} + mu u_{k-d-1}; exact when tau is a multiple of Ts.
 * Before the first input every past sample is 0 (process at rest).
 *
 * Storage: frac_foprocess_storage_len(p) reals = the operator's storage
 * (frac_fo_storage_len) + d + 1 delay taps.
 */
#ifndef FRAC_FOPROCESS_H
#define FRAC_FOPROCESS_H

#include "frac/frac_types.h"
#include "frac/delayline.h"
#include "frac/fo_op.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct frac_foprocess_params {
    frac_real k;       /* static gain K, finite */
    frac_real t;       /* T > 0 (units s^l) */
    frac_real lambda;  /* l in (0, 2] */
    frac_real tau;     /* dead time >= 0, s */
    frac_real ts;      /* sampling time, s */
    frac_fo_params op; /* realization of s^l: method, memory, wb, wh, n (order, ts are taken from above) */
} frac_foprocess_params;

typedef struct frac_foprocess {
    frac_fo op;
    frac_delayline dl;
    frac_real k, t, mu;
    frac_real last;
    int ready;
} frac_foprocess;

/* Reals of storage needed (0 if p is NULL or tau/ts is not finite). */
size_t frac_foprocess_storage_len(const frac_foprocess_params *p);

/*
 * Returns FRAC_OK; FRAC_E_NULL; FRAC_E_GAIN (K not finite, T not finite
 * or <= 0); FRAC_E_ORDER (l outside (0, 2]); FRAC_E_PARAM (tau negative or
 * not finite, tau/ts above 1e7 samples); FRAC_E_TS; FRAC_E_STORAGE; and
 * the realization's own codes (FRAC_E_BAND, FRAC_E_DIM, ...);
 * FRAC_E_NUMERIC (1 + T g = 0: the loop cannot be solved).
 */
int frac_foprocess_init(frac_foprocess *g, const frac_foprocess_params *p, frac_real *storage, size_t len);

/* One sample: input u_k, output y_k. FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE. */
int frac_foprocess_step(frac_foprocess *g, frac_real u, frac_real *y);

/* Back to rest (all past inputs and outputs 0). */
int frac_foprocess_reset(frac_foprocess *g);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_FOPROCESS_H */
