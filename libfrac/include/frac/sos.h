/*
 * sos.h - cascade of second-order sections (biquads), direct form II
 * transposed (DF2T).
 *
 * Each section i implements
 *     H_i(z) = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2)
 * with the DF2T recursion (two states s1, s2 per section):
 *     y  = b0 x + s1
 *     s1 = b1 x - a1 y + s2
 *     s2 = b2 x - a2 y
 * and the cascade output is the last section's y. A first-order section
 * has b2 = a2 = 0. DF2T needs two states per section (the minimum) and
 * has good round-off behaviour in floating point; the transposed form
 * keeps the recursion in the order CMSIS-DSP's arm_biquad_cascade_df2T
 * uses, so coefficient tables move between the two by negating a1, a2.
 *
 * Coefficient layout: FRAC_SOS_NCOEF = 5 reals per section,
 *     {b0, b1, b2, a1, a2}, sections in cascade order.
 * State layout: FRAC_SOS_NSTATE = 2 reals per section {s1, s2}.
 * Both buffers are caller storage; the coefficients are read, never
 * written, and must outlive the object.
 *
 * Cost per sample: 5 multiplies and 4 additions per section.
 *
 * Numerical caveats: poles close to z = 1 (corner frequencies far below
 * the sampling rate) make a biquad's coefficients sensitive. Realizations
 * in this library therefore pair a low-frequency pole with a
 * high-frequency one in each section (see fo_oustaloup.h), which keeps the
 * pole-position error near machine precision even in float.
 *
 * Bad input: a non-finite x returns FRAC_E_NONFINITE with *y = the last
 * finite output and the states untouched.
 */
#ifndef FRAC_SOS_H
#define FRAC_SOS_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FRAC_SOS_NCOEF 5
#define FRAC_SOS_NSTATE 2

typedef struct frac_sos {
    const frac_real *coeffs; /* 5 * nsec, {b0,b1,b2,a1,a2} per section */
    frac_real *state;        /* 2 * nsec, {s1,s2} per section */
    size_t nsec;             /* number of sections, >= 1 */
    frac_real last;          /* last finite output */
    int ready;
} frac_sos;

/*
 * Validates the coefficients and zeroes the state.
 * Returns FRAC_OK; FRAC_E_NULL (f, coeffs or state NULL); FRAC_E_DIM
 * (nsec == 0); FRAC_E_PARAM (a non-finite coefficient); FRAC_E_UNSTABLE (a
 * section with a pole strictly outside the unit circle, by the Jury
 * conditions |a2| <= 1 and |a1| <= 1 + a2; poles on the circle, such as
 * an integrator's z = 1, are accepted).
 */
int frac_sos_init(frac_sos *f, size_t nsec, const frac_real *coeffs, frac_real *state);

/* Zeroes the state and the held output. FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT. */
int frac_sos_reset(frac_sos *f);

/*
 * Sets the state to the steady state of a constant input x applied
 * forever: every section holds its DC response, so the next outputs equal
 * H(1) x. Needs H_i(1) finite for every section (no pole at z = 1):
 * FRAC_E_NUMERIC otherwise (state untouched). Also FRAC_E_NULL,
 * FRAC_E_NOT_INIT, FRAC_E_NONFINITE.
 */
int frac_sos_set_steady(frac_sos *f, frac_real x);

/*
 * One sample through the cascade (DF2T recursion above).
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE.
 */
int frac_sos_step(frac_sos *f, frac_real x, frac_real *y);

/*
 * n samples, x and y may alias. Stops at the first non-finite sample:
 * returns FRAC_E_NONFINITE with y[i] = the last finite output for that
 * and every later i (the state is the one after the last good sample).
 */
int frac_sos_process(frac_sos *f, const frac_real *x, frac_real *y, size_t n);

/*
 * Output the next step would produce for x = 0 (the free response), and
 * the direct feed-through g = prod b0_i: the next output is exactly
 * g x + *y0. Used to solve algebraic loops (a process y = u - T D(y)).
 * FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT.
 */
int frac_sos_free_response(const frac_sos *f, frac_real *y0);
frac_real frac_sos_feedthrough(const frac_sos *f);

/*
 * Frequency response H(e^{j theta}) of a coefficient table at the
 * normalised frequency theta = w Ts (rad/sample), evaluated in double.
 * FRAC_OK, FRAC_E_NULL, FRAC_E_DIM, FRAC_E_NUMERIC (a pole on the circle
 * at theta).
 */
int frac_sos_freqresp(const frac_real *coeffs, size_t nsec, frac_real theta, frac_real *re, frac_real *im);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_SOS_H */
