/*
 * fodamp.h - collocated fractional damping law of seed 002 with its
 * feed-forward prefilter:
 *     u = F(s) ref - C(s) meas,
 *     C(s) = Kc s^a Ghat^-1(s),     Ghat^-1(s) = N(s) / (s^m D(s)),
 *     F(s) = (1 + fa s^fbeta) / (1 + fb s)
 * seed 002 (23)/(47)/(48) and (51)/(52): Ghat(s) = s^2/(1 + 0.0071 s)^2 is
 * the known part (m = 2 zeros at the origin) and its inverse is
 * approximated by N(s) = 1 + 0.0142 s (D = 1), so
 * C(s) = 5.31 (1 + 0.0142 s)/s^1.2 (a = 0.8, the rounded 0.78, notes 002
 * section 7), F(s) = (1 + 0.116 s^0.55)/(1 + 0.011 s); u is the motor
 * reference theta_m*, ref the tip reference theta_2*, meas the base moment
 * Gamma_c (Fig. 7).
 * N(s) = 1 + n1 s + n2 s^2 and D(s) = 1 + d1 s + d2 s^2 are general
 * (D Hurwitz), so the exact inverse (1 + 0.0071 s)^2 (n1 = 0.0142,
 * n2 = 5.041e-5) is also accepted.
 *
 * Realization: the exponent a - m is split into k pure integrators and a
 * fractional order r = a - m + k, k the smallest integer >= max(0,
 * floor(m - a)) with deg N <= k + deg D (so the rational part
 * R(s) = Kc N(s)/(s^k D(s)) is proper; the robot gets k = 1, r = -0.2).
 * s^r runs on the chosen fractional realization (fo_op.h); R(s) is mapped
 * by the bilinear transform (its integrator poles land exactly on z = 1,
 * its zeros at (c + s0)/(c - s0), c = 2/Ts; surplus poles add zeros at
 * z = -1) into at most two biquads. The prefilter is w = ref +
 * fa D^fbeta ref followed by 1/(1 + fb s), bilinear (fb = 0: no lag).
 * The bilinear map keeps the phase of the integrators exact and warps
 * the frequency of R's corner by (2/Ts) tan(w Ts/2) vs w, i.e. < 0.1 %
 * below 0.1 pi/Ts.
 *
 * Storage: frac_fodamp_storage_len(p) reals.
 */
#ifndef FRAC_FODAMP_H
#define FRAC_FODAMP_H

#include "frac/frac_types.h"
#include "frac/sos.h"
#include "frac/fo_op.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FRAC_FODAMP_NSEC 2

typedef struct frac_fodamp_params {
    frac_real kc;           /* Kc > 0 */
    frac_real alpha;        /* a, (0, 2) */
    unsigned m;             /* zeros of Ghat at the origin, 0..2 */
    frac_real n1, n2;       /* N(s) = 1 + n1 s + n2 s^2 */
    frac_real d1, d2;       /* D(s) = 1 + d1 s + d2 s^2, Hurwitz */
    frac_real fa, fbeta;    /* prefilter numerator 1 + fa s^fbeta, fa >= 0, fbeta in [0, 2] */
    frac_real fb;           /* prefilter lag 1/(1 + fb s), fb >= 0, s */
    frac_real ts;           /* sampling time, s */
    frac_fo_params op;      /* realization of s^r and s^fbeta: method, memory, wb, wh, n */
} frac_fodamp_params;

typedef struct frac_fodamp {
    frac_fo opc;            /* s^r of C */
    frac_fo opf;            /* s^fbeta of F */
    frac_sos rat;           /* R(s), bilinear */
    frac_real rcoef[FRAC_SOS_NCOEF * FRAC_FODAMP_NSEC];
    frac_real rstate[FRAC_SOS_NSTATE * FRAC_FODAMP_NSEC];
    frac_real fa, la, lb;   /* prefilter: w = ref + fa D^fbeta ref; y = la y + lb (w + w_prev) */
    frac_real fy, fw;       /* prefilter lag state */
    frac_real r;            /* fractional order of C's operator */
    unsigned k;             /* integrators in R */
    frac_real ts;
    frac_real last;
    int ready;
} frac_fodamp;

/* Reals of storage for p (0 for NULL or invalid orders). */
size_t frac_fodamp_storage_len(const frac_fodamp_params *p);

/*
 * Returns FRAC_OK; FRAC_E_NULL; FRAC_E_GAIN (Kc not finite or <= 0,
 * n/d/fa/fb not finite, fa < 0, fb < 0); FRAC_E_ORDER (a outside (0, 2),
 * fbeta outside [0, 2]); FRAC_E_DIM (m > 2); FRAC_E_UNSTABLE (D not
 * Hurwitz); FRAC_E_TS; FRAC_E_STORAGE; the realization's codes.
 */
int frac_fodamp_init(frac_fodamp *c, const frac_fodamp_params *p, frac_real *storage, size_t len);

/*
 * One sample: u = F ref - C meas. FRAC_OK; FRAC_E_NULL; FRAC_E_NOT_INIT;
 * FRAC_E_NONFINITE (state untouched, *u = last output).
 */
int frac_fodamp_step(frac_fodamp *c, frac_real ref, frac_real meas, frac_real *u);

/* Zero state. */
int frac_fodamp_reset(frac_fodamp *c);

/* Discrete frequency responses of C and of F at w rad/s (0 < w <= pi/Ts). */
int frac_fodamp_freqresp_c(const frac_fodamp *c, frac_real w, frac_real *re, frac_real *im);
int frac_fodamp_freqresp_f(const frac_fodamp *c, frac_real w, frac_real *re, frac_real *im);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_FODAMP_H */
