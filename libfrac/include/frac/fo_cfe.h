/*
 * fo_cfe.h - s^r by continued-fraction expansion (CFE) of the Tustin or
 * Al-Alaoui generating function, realized as a biquad cascade.
 *
 * Generating functions (x = z^-1, T = sampling time):
 *     Tustin:     s ~ (2/T)     (1 - x)/(1 + x)
 *     Al-Alaoui:  s ~ (8/(7T))  (1 - x)/(1 + x/7)
 * so s^r ~ k^r f(x)^r with f(x)^r = (1 - x)^r (1 + a x)^-r, a = 1 or 1/7
 * (Chen & Vinagre 2003; Chen & Moore 2002). The CFE of f(x)^r truncated
 * after 2n terms is the n-th convergent P_n(x)/Q_n(x) with deg P = deg
 * Q = n; the convergents of this (regular C-) fraction are the diagonal
 * Padé approximants [n/n] of the power series of f(x)^r, so they are
 * computed here from the 2n + 1 Taylor coefficients (binomial series of
 * both factors, multiplied) by solving the n x n Padé equations with
 * partial pivoting, in double. tests/libfrac/fixtures/cfe_reference.py
 * expands the continued fraction itself (Viskovatov's algorithm) and
 * confirms that the two agree.
 *
 * Orders: the expansion is used for the fractional part rf = r - m,
 * m = trunc(r) (|rf| < 1), where it is stable and minimum phase (poles
 * and zeros on the real axis inside the unit circle). For |r| >= 1 the
 * integer part is realized by the generating function itself: s^-1 (an
 * integrator, pole at z = 1) for m < 0, s^+1 for m > 0. Tustin's s^+1 has
 * its pole at z = -1 (an undamped oscillation at Nyquist), so Tustin
 * rejects r >= 1 with FRAC_E_UNSTABLE; Al-Alaoui's pole is at -1/7 and
 * covers [-2, 2].
 *
 * Accuracy: the CFE is a series about z = 1 for the generating function,
 * not a band approximation; it is accurate at mid-to-high frequency and
 * degrades towards DC (where a finite-order rational cannot follow w^r).
 * Tustin n = 5 stays within 1 deg and 0.5 dB of (jw)^r only over about
 * [0.2/T, 0.7/T] rad/s (|r| <= 0.88; the phase error grows below, the
 * bilinear magnitude warping above); each step of n extends the band
 * downwards. Al-Alaoui's generating function itself deviates from jw at
 * high frequency, so its band is narrower still.
 * The test prints the tables.
 *
 * Storage: FRAC_CFE_STORAGE(n) reals (coefficients and state of
 * FRAC_CFE_NSEC(n) sections, enough for every order).
 */
#ifndef FRAC_FO_CFE_H
#define FRAC_FO_CFE_H

#include "frac/frac_types.h"
#include "frac/sos.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FRAC_CFE_NMAX 12
#define FRAC_CFE_NSEC(n) (((size_t)(n) + 3) / 2)
#define FRAC_CFE_STORAGE(n) ((FRAC_SOS_NCOEF + FRAC_SOS_NSTATE) * FRAC_CFE_NSEC(n))

typedef enum frac_cfe_rule {
    FRAC_CFE_TUSTIN = 1,
    FRAC_CFE_ALALAOUI = 2
} frac_cfe_rule;

typedef struct frac_cfe_params {
    frac_real order; /* r in [-2, 2] ([-2, 1) for Tustin) */
    frac_real ts;    /* sampling time, s */
    unsigned n;      /* expansion order, 1..FRAC_CFE_NMAX */
    int rule;        /* frac_cfe_rule */
} frac_cfe_params;

typedef struct frac_cfe {
    frac_sos sos;
    frac_cfe_params p;
    int ready;
} frac_cfe;

/*
 * Writes the sections into coeffs (room for FRAC_CFE_NSEC(p->n)) and
 * their number into *nsec (ceil of (roots)/2: the n expansion roots plus
 * |m| integer-order roots). Returns FRAC_OK; FRAC_E_NULL; FRAC_E_ORDER; FRAC_E_TS;
 * FRAC_E_DIM (n = 0 or > FRAC_CFE_NMAX); FRAC_E_PARAM (unknown rule);
 * FRAC_E_UNSTABLE (Tustin with r >= 1, or an expansion pole on or outside
 * the unit circle); FRAC_E_NUMERIC (singular Padé system, root finder).
 */
int frac_cfe_design(const frac_cfe_params *p, frac_real *coeffs, size_t *nsec);

/* Designs into storage (len >= FRAC_CFE_STORAGE(n)) and zeroes the state; + FRAC_E_STORAGE. */
int frac_cfe_init(frac_cfe *f, const frac_cfe_params *p, frac_real *storage, size_t len);
int frac_cfe_step(frac_cfe *f, frac_real x, frac_real *y);
int frac_cfe_reset(frac_cfe *f);
int frac_cfe_freqresp(const frac_cfe *f, frac_real w, frac_real *re, frac_real *im);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_FO_CFE_H */
