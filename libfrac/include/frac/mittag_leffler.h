/*
 * mittag_leffler.h - the two-parameter Mittag-Leffler function
 *     E_{a,b}(z) = sum_{k>=0} z^k / Gamma(a k + b)
 * for real z, 0 < a <= 2, real b: the exact reference for step responses
 * of fractional systems, e.g. 1/(1 + T s^l) has the step response
 * 1 - E_l(-t^l / T) (E_l = E_{l,1}) and the impulse response
 * t^(l-1)/T E_{l,l}(-t^l / T).
 *
 * Algorithm (C89 math only, double internally):
 *  1. |z| <= 1, or z > 0 with z^(1/a) <= 30: the power series, terms
 *     exp(k ln|z| - ln|Gamma(a k + b)|) (Lanczos Gamma, g = 7, 9 terms,
 *     reflection for negative arguments, 1/Gamma = 0 at its poles) until
 *     a term falls below 1e-17 of the sum. No cancellation in this range:
 *     sum |terms| <= E_{a,b}(|z|) <= e/a-ish times the result's scale.
 *  2. Otherwise the inverse Laplace transform at t = 1 of
 *     F(s) = s^(a-b)/(s^a - z), with the Bromwich line deformed to the
 *     Hankel contour made of the two rays s = r e^{+-i theta}:
 *         E_{a,b}(z) = sum of residues (1/a) s_p^(1-b) e^{s_p} of the
 *                      poles s_p^a = z inside the contour
 *                    + (1/pi) int_0^inf Im[e^s F(s) e^{i theta}]|_{s = r e^{i theta}} dr.
 *     theta = pi (the branch cut itself, Gorenflo, Loutchko & Luchko
 *     2002) except for z < 0 with |a - 1| <= 0.1, where the pole
 *     s_p = |z|^(1/a) e^{i pi/a} sits next to the cut and theta = 3 pi/4
 *     keeps it at a distance (it is then outside the contour). The
 *     substitution v = r^(a-b+1) removes the r^(a-b) endpoint singularity;
 *     the integral is done by adaptive Gauss–Kronrod (7/15 points, at most
 *     400 panels, relative tolerance 1e-14) on [0, 42/|cos theta|] with
 *     break points at r = |z|^(1/a) x {1/2, 1, 2} (the near-pole).
 *     Needs b < a + 1; larger b is reduced first with
 *     E_{a,b}(z) = (E_{a,b-a}(z) - 1/Gamma(b-a)) / z.
 *
 * Accuracy: compared with 40-digit mpmath power series
 * (tests/libfrac/fixtures/mittag_leffler_reference.py) the relative error
 * is below 1e-12 for 0.2 <= a <= 2, 0 < b <= 2 and -1e4 <= z <= 1e2
 * (absolute 1e-14 where |E| < 1e-2: such values come out of the contour
 * integral by cancellation; E_{1,1} = exp is evaluated directly). Smaller
 * a is accepted, but the b reduction then takes many steps and loses
 * digits. Cost: up to ~10^4 exp/pow calls: a design/test tool, not for
 * the control cycle.
 */
#ifndef FRAC_MITTAG_LEFFLER_H
#define FRAC_MITTAG_LEFFLER_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * *e = E_{a,b}(z). Returns FRAC_OK; FRAC_E_NULL; FRAC_E_PARAM (a outside
 * (0, 2] or b not finite, or |b| > 50); FRAC_E_NONFINITE (z not finite);
 * FRAC_E_NUMERIC (the result overflows, or the quadrature did not reach
 * its tolerance); *e is untouched on error.
 */
int frac_mittag_leffler(frac_real a, frac_real b, frac_real z, frac_real *e);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_MITTAG_LEFFLER_H */
