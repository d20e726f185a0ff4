// fo_realization.hpp - rational realizations of the project's fractional
// models, for the tools that need a state space (the gap diagnosis replays
// its nominal sample by sample; docs/gap.md "Fractional nominal models").
//
// s^r, 0 <= r < 1, by Oustaloup's recursive approximation over [wb, wh]
// with 2N + 1 real pole/zero pairs (seed 001 eq. (7); the same corners as
// libfrac's frac_oustaloup_design, frac/fo_oustaloup.h, but continuous, so
// that a zero-order hold at the data's sample time adds the sample-and-hold
// of a recorded, held input exactly):
//     s^r ~ K prod_{k=-N}^{N} (s + w'_k)/(s + w_k),
//     w'_k = wb (wh/wb)^((k + N + (1 - r)/2)/(2N + 1)),
//     w_k  = wb (wh/wb)^((k + N + (1 + r)/2)/(2N + 1)),
// K chosen so that |O(j wg)| = wg^r at the band's geometric centre wg
// (as libfrac does; for the plain method this is the textbook wh^r).
//
// The process of seed 001 eq. (1) without its dead time,
//     y = K/(1 + T s^lambda) v,  0 < lambda <= 2,
// is realized as the unity loop around F(s) = s^(n - lambda)/(T s^n),
// n = ceil(lambda) exact integrators and the Oustaloup filter of the
// remaining order r = n - lambda in [0, 1): y = F/(1 + F) K v. The
// integrators keep the static gain exactly K (an Oustaloup filter of
// s^lambda itself tends to wb^lambda at DC, a static gain error of about
// T wb^lambda), and lambda > 1 (the underdamped process of seed 001 Sec. 5,
// lambda = 1.92) needs no improper filter. Where |F| >> 1 (below the
// process's corner T^(-1/lambda)) the loop also divides F's own error by
// |1 + F|. The dead time is not part of the state space: callers apply it
// as an input delay (the gap replay: whole + fractional samples).
#pragma once
#include <complex>

#include "fracdesign/models/foprocess.hpp"
#include "fracdesign/models/lti.hpp"

namespace fracdesign {

struct OustaloupBand {
    double wb = 0;  // lower band edge [rad/s], > 0
    double wh = 0;  // upper band edge [rad/s], > wb
    int N = 0;      // 2N + 1 pole/zero pairs, in [1, kOustaloupNMax]
    void validate() const;  // std::invalid_argument naming the field and the allowed range
};
constexpr int kOustaloupNMax = 40;

// The default band for a record of `record_seconds` sampled at Ts:
// wb = 2 pi/(100 T_rec) (two decades below the record's lowest frequency),
// wh = 100 pi/Ts (two decades above Nyquist), N = ceil(1.5 decades), so
// 2N + 1 >= 3 pole/zero pairs per decade. The accuracy this gives is
// stated and tested in docs/gap.md ("Fractional nominal models").
OustaloupBand default_oustaloup_band(double Ts, double record_seconds);

// Continuous Oustaloup filter of s^r (0 <= r < 1; r = 0 gives the
// identity with no states), one input and one output.
StateSpace oustaloup_state_space(double r, const OustaloupBand& band);

// The continuous rational realization of K/(1 + T s^lambda) described
// above (input "u", output "y"; states "oustaloup_i" then "integrator_j").
// std::invalid_argument for an invalid process or band.
StateSpace foprocess_realization(const FoProcess& p, const OustaloupBand& band);

// max over a log grid of 200 points per decade in [w_lo, w_hi] of
// |G_r(j w) - G(j w)| / |G(j w)|, G the exact K/(1 + T (j w)^lambda)
// (the dead time left out of both).
double foprocess_realization_error(const FoProcess& p, const OustaloupBand& band, double w_lo, double w_hi);

}  // namespace fracdesign
