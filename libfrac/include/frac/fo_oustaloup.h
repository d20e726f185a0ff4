/*
 * fo_oustaloup.h - Oustaloup and refined Oustaloup approximations of s^r,
 * discretized into a biquad cascade (frac/sos.h).
 *
 * Continuous approximation over the band [wb, wh] with order N
 * (2N + 1 pole/zero pairs; seed 002 note section 11):
 *     s^r ~ K prod_{k=-N}^{N} (s + w'_k) / (s + w_k),
 *     w'_k = wb (wh/wb)^((k + N + (1 - r)/2) / (2N + 1)),
 *     w_k  = wb (wh/wb)^((k + N + (1 + r)/2) / (2N + 1)).
 * Refined Oustaloup (Xue, Zhao & Chen 2006; FOMCON's new_fod), b = 10,
 * d = 9, 0 < r < 1 only:
 *     s^r ~ K (d s^2 + b wh s) / (d (1 - r) s^2 + b wh s + d r wb wh) * prod(...)
 * The published form has the constant term d r, which assumes
 * wb wh = 1 rad^2/s^2 (all its examples use [1e-3, 1e3]); the factor
 * wb wh restores scale invariance and reduces to it when wb wh = 1.
 * Outside (0, 1) that factor has a right-half-plane pole, so the refined
 * method rejects such orders (FRAC_E_ORDER).
 * The gain K is set so that |H(j wg)| = wg^r at the geometric band centre
 * wg = sqrt(wb wh); for the plain method this is the textbook K = wh^r,
 * for the refined one it removes the (d/b)^r = -0.92 r dB offset that
 * new_fod's K = (d wh / b)^r leaves across the band.
 *
 * Accuracy of the continuous filter: the magnitude ripple and the
 * mid-band phase ripple fall quickly with the density (2N + 1)/decades,
 * but the plain filter's phase falls short of r 90 deg near the band
 * edges by about r (w/wh) rad (and r (wb/w) rad), whatever N: cutting the
 * pole/zero distribution at wh acts like a first-order lag at wh. One
 * decade inside the band that is ~5.7 r deg, so the plain method meets
 * 1 deg only about two decades inside. The refined factor compensates
 * both edges: within [10 wb, wh/10] it stays within 0.5 deg (r <= 0.9;
 * 0.56 deg at r = 0.99) and 0.05 dB for N = 5
 * (tests/libfrac/test_fo_oustaloup.c prints the tables).
 *
 * Discretization: Tustin (bilinear) with prewarped band edges. The analog
 * band is [Wb, Wh] with W = (2/Ts) tan(w Ts/2), so the digital response is
 * exactly H_d(e^{jwTs}) = H_a(j (2/Ts) tan(w Ts/2)): the digital filter's
 * band edges land on wb and wh, and because (j (2/Ts) tan(w Ts/2))^r
 * has the phase r 90 deg exactly, the bilinear map adds no phase error
 * at all to the power law; its only effect is the magnitude factor
 * (tan(w Ts/2)/(w Ts/2))^r, below 0.1 r dB for w < 0.3 pi/Ts.
 * Matched pole-zero was rejected: it maps each corner exactly but adds a
 * phase error per factor that accumulates over 2N + 1 factors near
 * Nyquist, and needs a separate gain match. Requires wh < pi/Ts.
 *
 * Realization: each real pole/zero maps to z = (c - w)/(c + w), c = 2/Ts.
 * Sections pair the lowest remaining corner with the highest (k with
 * 2N - k): poles near z = 1 never share a quadratic, so the biquad
 * coefficients stay well conditioned. In float the lowest pole, about
 * wb Ts below z = 1, is resolved to 6e-8, so the response keeps a relative
 * accuracy of about 6e-8/(wb Ts): keep wb Ts >= 1e-5 for 1 %. N + 1 sections
 * (N + 2 refined); cost 5 multiplies and 4 adds per section per sample.
 *
 * Storage: FRAC_OUSTALOUP_STORAGE(N, refined) reals: the coefficient
 * table (5 per section) followed by the DF2T state (2 per section).
 */
#ifndef FRAC_FO_OUSTALOUP_H
#define FRAC_FO_OUSTALOUP_H

#include "frac/frac_types.h"
#include "frac/sos.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FRAC_OUSTALOUP_NMAX 16
#define FRAC_OUSTALOUP_NSEC(N, refined) ((size_t)(N) + 1 + ((refined) ? 1 : 0))
#define FRAC_OUSTALOUP_STORAGE(N, refined) \
    ((FRAC_SOS_NCOEF + FRAC_SOS_NSTATE) * FRAC_OUSTALOUP_NSEC(N, refined))

typedef struct frac_oustaloup_params {
    frac_real order; /* r: [-2, 2] plain, (0, 1) refined */
    frac_real wb;    /* lower band edge, rad/s, > 0 */
    frac_real wh;    /* upper band edge, rad/s, wb < wh < pi/ts */
    frac_real ts;    /* sampling time, s */
    unsigned n;      /* N, 1..FRAC_OUSTALOUP_NMAX */
    int refined;     /* nonzero: refined Oustaloup */
} frac_oustaloup_params;

typedef struct frac_oustaloup {
    frac_sos sos;
    frac_oustaloup_params p;
    int ready;
} frac_oustaloup;

/*
 * Validates p and writes the FRAC_OUSTALOUP_NSEC(p->n, p->refined)
 * sections into coeffs (5 reals each). Returns FRAC_OK; FRAC_E_NULL;
 * FRAC_E_ORDER; FRAC_E_TS; FRAC_E_BAND (wb <= 0, wh <= wb, wh >= pi/ts,
 * non-finite); FRAC_E_DIM (N = 0 or > FRAC_OUSTALOUP_NMAX); FRAC_E_NUMERIC.
 */
int frac_oustaloup_design(const frac_oustaloup_params *p, frac_real *coeffs);

/*
 * Designs into the first part of `storage` (len >= FRAC_OUSTALOUP_STORAGE)
 * and zeroes the state. Codes as frac_oustaloup_design, plus
 * FRAC_E_STORAGE.
 */
int frac_oustaloup_init(frac_oustaloup *o, const frac_oustaloup_params *p, frac_real *storage, size_t len);

/* One sample. FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE. */
int frac_oustaloup_step(frac_oustaloup *o, frac_real x, frac_real *y);

/* Zero state. */
int frac_oustaloup_reset(frac_oustaloup *o);

/* Digital frequency response at w rad/s (0 <= w <= pi/ts). */
int frac_oustaloup_freqresp(const frac_oustaloup *o, frac_real w, frac_real *re, frac_real *im);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_FO_OUSTALOUP_H */
