// fopi_fopd.hpp - FO-PI^alpha and FO-PD^mu tuning for the delayed underdamped
// fractional plant G(s) = K e^{-tau s} / (1 + T s^lambda), 1 < lambda <= 2
// (seed 001, Gharab & Feliu-Batlle 2023, Sections 3-4).
//
// The tuning is closed form in normalised units (seed 001 eq. (4), (10), (14)):
//   Tl = T^(1/lambda), w_cn = w_c Tl, tau_n = tau / Tl, phi_mn = phi_m + tau_n w_cn.
// Erratum E1 (notes/001 section 2.2) is applied: the paper prints tau_n = tau/T^lambda;
// tau / T^(1/lambda) is the one consistent with t_n = t / T^(1/lambda) and the
// only one that reproduces the published controller (52).
//
// Feasibility is never clipped: every test is reported with its value and bound.
//  - delay limit (17): phi_m > 0, i.e. tau_n < phi_mn / w_cn (nothing more: a phi_mn beyond pi is
//    no reason to refuse a design, the delay only turns the phase further; stability is decided by
//    the Nyquist test);
//  - low-frequency condition (18) of the PI, with the exact boundary
//    phi_mn < pi - arg(1 + (j w_cn)^lambda)  (notes/001 section 3.2; the printed
//    fits of Theorem 1 are not used: they fail numerical checks, notes/001 3.5);
//  - Robust High-Frequency Condition (22)/(35): the delay-free loop magnitude
//    |C_n(jw) G_n*(jw)| strictly decreasing beyond w_cn (rhfc_max_slope < 0);
//  - PD only: the stability condition K_pn + delta_n > 0 with delta_n = 1 (Section 4.3);
//  - closed-loop stability of the real loop with the delay, C(s) G(s) (the PD's C^ G, eq. (40)), by the
//    argument principle (design/nyquist.hpp): no encirclement of -1 (value: +-min |1 + L(j w)|).
#pragma once
#include <complex>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace fracdesign::design {

// Parameters of G(s) = K e^{-tau s} / (1 + T s^lambda) (seed 001 eq. (1)); SI units
// (T in s^lambda, tau in s).
struct GharabPlant {
    double K = 1.0;
    double T = 1.0;
    double lambda = 1.5;
    double tau = 0.0;
    // Throws std::invalid_argument naming the field unless K != 0 finite, T > 0,
    // 1 < lambda <= 2 and tau >= 0.
    void validate() const;
    // G(j w) with the delay.
    std::complex<double> freq(double w) const;
};

enum class FoKind { PI, PD };

// Specification: crossover w_c (rad/s), phase margin phi_m (rad), order alpha (PI)
// or mu (PD).
struct FoSpec {
    double wc = 1.0;
    double phim = 0.5;
    double order = 1.0;
};

struct FeasibilityTest {
    std::string name;    // "delay_limit", "low_frequency", "rhfc", "pd_stability", "nyquist"
    bool pass = false;
    double value = 0.0;  // the tested quantity (e.g. phi_mn, K_in, worst slope)
    double bound = 0.0;  // its limit
    std::string detail;  // human-readable explanation
};

struct FoDesign {
    FoKind kind = FoKind::PI;
    GharabPlant plant;
    FoSpec spec;
    // normalisation (eq. (4), (10) with erratum E1)
    double Tl = 0.0, wcn = 0.0, taun = 0.0, phimn = 0.0;
    // normalised gains: PI (15)-(16): K_pn, K_in; PD (31)-(32): K_pn, K_dn
    double Kpn = 0.0, Kin = 0.0, Kdn = 0.0;
    // real gains (14): C(s) = Kp + Ki s^-alpha  or  C^(s) = Kp + Kd s^mu;
    // PD with positive feedback delta = 1/K (Section 4.2, eq. (41)): C = Kp + delta + Kd s^mu.
    double Kp = 0.0, Ki = 0.0, Kd = 0.0, delta = 0.0;
    std::vector<FeasibilityTest> tests;
    bool feasible() const;
    // First failing test's explanation, empty when feasible.
    std::string reason() const;
    // Controller (the part acting on the loop, C^ for the PD) at s = j w, real units.
    std::complex<double> controller(double w) const;
    // Open loop C(jw) G(jw) (delay included); equals -e^{j phi_m} at w_c (eq. (6), (30)).
    std::complex<double> loop(double w) const;
};

// Closed-form tuning plus every feasibility test. Throws std::invalid_argument on
// a malformed plant or spec (w_c <= 0, order outside (0,1] for the PI or (0,2)
// for the PD, non-finite values); an infeasible but well-formed spec returns a
// design whose tests say why.
FoDesign tune_fo(FoKind kind, const GharabPlant& plant, const FoSpec& spec);

// RHFC (eq. (22)/(35)) margin: the largest slope d ln m / d ln w of
// m(w) = |C_n(jw)| / |1 + (jw)^lambda| on [w_cn, max(1000 w_cn, 1000)] (beyond, m falls like
// w^-lambda or w^(mu - lambda)), from the analytic slope, every local maximum bracketed on a log
// grid (400 points per decade, 20000 on [0.8, 1.25] around the plant resonance) and refined by
// golden section to 1e-12 in ln w; +inf where m has a zero or a pole. The RHFC holds when it is < 0.
double rhfc_max_slope(FoKind kind, double wcn, double lambda, double order, double Kpn, double Kx);

// Exact upper bound of the PI low-frequency condition (18): pi - arg(1 + (j w_cn)^lambda).
double lf_phimn_bound(double wcn, double lambda);

// Relative tolerance of the band edges of feasible_bands.
constexpr double kEdgeTol = 1e-10;

// Crossover intervals [lo, hi] (rad/s, real units) where the design at phase margin spec.phim and
// order spec.order is feasible (every test passes), searched on [w_lo, w_hi]: a log grid of `grid`
// points brackets each change of verdict, and the edge is refined to kEdgeTol relative as the root
// of the switching test's continuous margin (K_in for (18), K_pn + 1 for the PD condition, minus the
// RHFC slope) by TOMS 748 (Boost.Math), or by bisection on the verdict (the Nyquist test). A band
// narrower than the grid step can be missed. spec.wc is ignored.
std::vector<std::pair<double, double>> feasible_bands(FoKind kind, const GharabPlant& plant, const FoSpec& spec,
                                                      double w_lo, double w_hi, int grid = 600);

nlohmann::json to_json(const FoDesign& d);

}  // namespace fracdesign::design
