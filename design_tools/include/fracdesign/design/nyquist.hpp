// nyquist.hpp - closed-loop stability of a unity-feedback loop 1 + L(s) = 0 by the argument principle
// (Nyquist criterion), for the irrational loops of the seeds: fractional powers s^q on the principal
// branch, dead time e^{-tau s}, poles on the imaginary axis (indented into Re s > 0).
//
// The D contour runs up the imaginary axis from -j R to j R, skirting the origin and every axis pole on
// small half circles into Re s > 0, and closes on |s| = R in Re s > 0. For a real loop (L(conj s) =
// conj L(s)) the lower half mirrors the upper one, so the winding number of 1 + L around 0 is
//   N = [ 2 (D_axis + D_poles + D_tail) + D_0 ] / (2 pi)
// with D_axis the change of arg(1 + L) along j w, w in [w_lo, w_hi] minus the pole gaps, D_poles the
// changes along the upper pole half circles, D_0 the change along the half circle |s| = w_lo (from -j w_lo
// to j w_lo through w_lo), and D_tail = -arg(1 + L(j w_hi)), which is exact when |L(s)| < 1 on the rest of
// the contour (the caller chooses w_hi so; then 1 + L cannot wind around 0 there and ends at 1).
// The contour is clockwise, so N = P - Z: with no open-loop poles in Re s > 0 (P = 0) the closed loop is
// stable iff N = 0. Each change of arg is accumulated over steps whose phase increment stays below
// max_step, halving a step until it does (or it is shorter than 1e-13 relative: 1 + L ~ 0 on the path,
// a closed-loop pole on the contour, reported as not stable).
#pragma once
#include <complex>
#include <functional>
#include <string>
#include <vector>

namespace fracdesign::design {

struct NyquistResult {
    bool stable = false;        // N == 0 and no closed-loop pole on the contour
    int encirclements = 0;      // N = P - Z (clockwise encirclements of -1 by L, counted negative)
    double residual = 0.0;      // |N_computed - N|: how far the sum is from an integer (accuracy check)
    double min_distance = 0.0;  // min |1 + L(j w)| over the evaluated axis points, w in [w_lo, w_hi]
    double w_min = 0.0;         // where it occurs [rad/s]
    bool degenerate = false;    // 1 + L vanished on the contour (a closed-loop pole on the imaginary axis)
    std::string detail;         // one line for reports
};

// L(s) on the principal sheet, for any s with Re s >= 0. w_lo > 0 must be small enough that the half
// circle |s| = w_lo holds no closed-loop pole; w_hi such that |L| < 1 on j[w_hi, inf) and on |s| = R.
// axis_poles: open-loop poles j w_p, w_lo < w_p < w_hi, skirted at radius pole_radius * w_p.
NyquistResult nyquist_stability(const std::function<std::complex<double>(std::complex<double>)>& L, double w_lo,
                                double w_hi, const std::vector<double>& axis_poles = {}, double pole_radius = 1e-6,
                                double max_step = 0.2);

}  // namespace fracdesign::design
