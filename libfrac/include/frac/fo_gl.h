/*
 * fo_gl.h - Grünwald–Letnikov fractional operator s^r with the
 * short-memory principle.
 *
 * Math (Podlubny 1999, ch. 7; seed 001 section 5.3 uses it at Ts = 2 ms):
 *     D^r x(kh) ~ h^-r * sum_{j=0}^{L-1} w_j x((k-j)h),
 *     w_0 = 1,  w_j = w_{j-1} (1 - (r + 1)/j)        (= (-1)^j binom(r, j)),
 * i.e. the power series of the backward-difference generating function
 * ((1 - z^-1)/h)^r truncated after L terms. r > 0 differentiates, r < 0
 * integrates (fractional integral of order -r), r = 0 is the identity.
 * Samples before the first step are 0 (zero initial history) unless
 * frac_gl_set_history() says otherwise.
 *
 * Accuracy: first order in h for smooth signals (the GL scheme), plus the
 * short-memory truncation error. For r > 0 the neglected tail of a signal
 * bounded by M is at most M h^-r |sum_{j>=L} w_j| ~ M (L h)^-r / |Gamma(1-r)|,
 * for r < 0 the truncated operator has the finite DC gain
 * h^-r sum_{j<L} w_j ~ (L h)^-r / Gamma(1-r) instead of infinity. In the
 * frequency domain the truncation error relative to the L = inf operator
 * is about (L h w)^-(1+r) / |Gamma(-r)| at w (w_j ~ j^(-r-1)/Gamma(-r)):
 * it falls fast for differentiators and slowly for integrators
 * (tests/libfrac/test_fo_gl.c prints the table).
 *
 * Storage: FRAC_GL_STORAGE(L) = 3 L reals of caller storage: L scaled
 * weights (stored in reverse order) and a mirrored history of 2 L samples
 * (every sample is written twice, at i and i + L), so the L most recent
 * samples are always one contiguous block and the step is a single
 * forward dot product with no wrap-around test.
 *
 * Cost: L multiply-adds per step (time and instructions linear in L, no
 * data-dependent branches), evaluated with four partial sums.
 */
#ifndef FRAC_FO_GL_H
#define FRAC_FO_GL_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FRAC_GL_STORAGE(L) (3 * (size_t)(L))
#define FRAC_FO_ORDER_MAX FRAC_R(2.0)

typedef struct frac_gl {
    frac_real *wrev;  /* L weights, wrev[i] = h^-r w_{L-1-i} */
    frac_real *hist;  /* 2 L mirrored history */
    size_t L;         /* memory length (number of terms) */
    size_t pos;       /* start of the contiguous window in hist, 0 <= pos < L */
    frac_real order;  /* r */
    frac_real ts;     /* h */
    frac_real last;   /* last finite output */
    int ready;
} frac_gl;

/*
 * Computes the weights for order r in [-2, 2], sampling time ts and memory
 * L >= 1 into `storage` (len >= FRAC_GL_STORAGE(L)) and zeroes the history.
 * Returns FRAC_OK; FRAC_E_NULL; FRAC_E_ORDER (r outside [-2, 2] or not
 * finite); FRAC_E_TS (ts not finite or <= 0); FRAC_E_DIM (L == 0);
 * FRAC_E_STORAGE (len too small); FRAC_E_NUMERIC (h^-r w_j overflows
 * frac_real).
 */
int frac_gl_init(frac_gl *gl, frac_real order, frac_real ts, size_t L, frac_real *storage, size_t len);

/* One sample: *y = h^-r sum_j w_j x_{k-j}. FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE. */
int frac_gl_step(frac_gl *gl, frac_real x, frac_real *y);

/*
 * Sets the whole history to the constant x (as if x had been applied for
 * L samples) and the held output to the operator's response to it.
 * x = 0 is a plain reset. FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE.
 */
int frac_gl_set_history(frac_gl *gl, frac_real x);

/*
 * The next output is exactly g x + *y0 with g = frac_gl_feedthrough() =
 * h^-r and *y0 the free response (the next step's output for x = 0).
 */
int frac_gl_free_response(const frac_gl *gl, frac_real *y0);
frac_real frac_gl_feedthrough(const frac_gl *gl);

/*
 * Frequency response of the truncated operator at w (rad/s):
 * h^-r sum_{j<L} w_j e^{-j w h j}, in double. FRAC_OK, FRAC_E_NULL,
 * FRAC_E_NOT_INIT, FRAC_E_PARAM (w not finite or negative).
 */
int frac_gl_freqresp(const frac_gl *gl, frac_real w, frac_real *re, frac_real *im);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_FO_GL_H */
