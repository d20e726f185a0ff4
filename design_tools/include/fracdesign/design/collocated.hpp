// collocated.hpp - seed 002 (Feliu-Batlle, Feliu-Talegon, San-Millan 2020)
// robust fractional-order damping of the collocated (base moment) loop.
//
// Plant G = Ghat(s) P(s, p, q) with P the damped PZI factor (42)/(46) of
// models/collocated.hpp and Ghat = s^2 G_m(s), G_m = 1/(1 + eps s)^2 (41)/(43) (eps = 0.0071 s on
// the paper's robot; each CollocatedPlant carries its own).
// Controller (23)/(47): C(s) = K_c s^alpha Ghat^-1(s), with
//   alpha = 2 phi0/pi (case 1: a1 < w_c0 < z1, eq. (6)) or 2 - 2 phi0/pi (case 2: w_c0 < a1, eq. (9)),
//   K_c   = 1 / (w_c0^alpha |P(j w_c0, p0, q0)|)                          (24).
// The robot implementation replaces (1 + eps s)^2 by 1 + 2 eps s (48), so the loop is
//   L = K_c s^alpha (1 + 2 eps s) G_m(s) P(s)                                (49),
// eps of the controller being the nominal plant's.
// Phase margins follow the notes' convention PM = 180 deg + angle(L), angle wrapped to (-360, 0].
#pragma once
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fracdesign/design/nyquist.hpp"
#include "fracdesign/models/collocated.hpp"

namespace fracdesign::design {

// alpha from phi0 (rad): case 1 -> 2 phi0/pi (6), case 2 -> 2 - 2 phi0/pi (9).
// Throws std::invalid_argument unless 0 < phi0 <= pi/2 and case is 1 or 2.
double feliu_alpha(double phi0, int theorem_case);

struct FdDesign {
    int theorem_case = 1;     // 1: a1 < w_c0 < z1 (Theorem 5.1), 2: w_c0 < a1 (Theorem 5.2)
    double phi0 = 0.0;        // rad
    double wc0 = 0.0;         // rad/s
    double alpha_exact = 0.0; // (6) or (9)
    double alpha = 0.0;       // used (alpha_exact, or the rounded/overridden value)
    double Kc = 0.0;          // (24)
    bool q_approx = true;     // (1 + eps s)^2 ~ 1 + 2 eps s as in (48)
    CollocatedPlant nominal;
};

// Theorem 5 design at the nominal plant. alpha_override > 0 replaces the exact alpha
// (the paper rounds 0.78 to 0.8). Throws std::invalid_argument naming the problem when
// w_c0 is not in (0, a1) or (a1, z1) (no theorem covers it) or phi0 is out of range.
FdDesign design_fd(const CollocatedPlant& nominal, double phi0, double wc0, double alpha_override = 0.0,
                   bool q_approx = true);

// Loops of the robot: FO (49) and the integer PI comparison L = (Kp + Ki/s) s^2 G_m P (Sec. 5.2, (54)).
std::complex<double> loop_fd(const FdDesign& d, const CollocatedPlant& p, double w, bool damped = true);
std::complex<double> loop_pi(double Kp, double Ki, const CollocatedPlant& p, double w, bool damped = true);

// L of (49) (or (47) with q_approx false) at complex s, Re s >= 0, s^alpha on the principal branch.
std::complex<double> loop_fd_s(const FdDesign& d, const CollocatedPlant& p, std::complex<double> s, bool damped = true);
// Closed-loop stability of that loop by the argument principle (design/nyquist.hpp). On |s| = r,
// Re s >= 0: |L| <= K_c r^alpha |q|max sum_i k_i/(r^2 - 2 zeta_i a_i r - a_i^2) with |1 + e s| <= 1 + e r and
// |1 + eps s|^2 >= 1 + eps^2 r^2; w_hi lies beyond the last r of a geometric scan where that bound
// reaches 1/2. Undamped modes (zeta_i = 0) are poles j a_i on the axis and are skirted.
NyquistResult loop_fd_nyquist(const FdDesign& d, const CollocatedPlant& p, bool damped = true);

struct Crossover {
    double w = 0.0;       // rad/s
    double pm_deg = 0.0;  // 180 + angle(L), angle in (-360, 0]
};
// Crossovers of |L| = 1 on (w_lo, w_hi): log grid + bisection to 1e-12 relative.
std::vector<Crossover> crossovers(const std::function<std::complex<double>(double)>& L, double w_lo, double w_hi,
                                  int grid = 4000);
// The two crossovers of the modes, where the theorem case puts them:
//  case 1 (Tables 1-2): mode 1 in (a1, z1), mode 2 the highest one above a2 (P < 0 there, PM = 180 - 90 alpha);
//  case 2 (Theorem 2/5.2): mode 1 in (0, a1), mode 2 the highest one in (z1, a2) (P > 0 there, angle(L) =
//  90 alpha = 180 - phi0, so PM = -phi0 in the (-360, 0] convention: the point is phi0 above -1).
// Throws std::runtime_error if either is missing.
std::pair<Crossover, Crossover> modal_crossovers(const std::function<std::complex<double>(double)>& L,
                                                 const CollocatedPlant& p, int theorem_case = 1);

// Robust crossover range (Theorem 1/2 eq. (7), design step 4): min and max over m2 in [m2_lo, m2_hi]
// (`points` samples of arm.plant) of the mode-1 crossover of the undamped loop, searched in (a1, z1)
// (case 1) or (0, a1) (case 2). Throws std::runtime_error unless each sample has exactly one root there.
std::pair<double, double> crossover_range(const FdDesign& d, const CollocatedArm& arm, double m2_lo, double m2_hi,
                                          int points = 221);

// Closed loop theta2/theta2* (50) with the prefilter F (51) = (1 + f_n s^beta)/(1 + f_d s),
// tip transfer G_2 (39) with the damped denominators of (46).
struct Prefilter {
    double fn = 0.0, fd = 0.0, beta = 1.0;
    std::complex<double> at(double w) const;
};
std::complex<double> closed_loop_tip(const std::function<std::complex<double>(double)>& L, const Prefilter& F,
                                     const CollocatedPlant& p, double w, bool damped = true);
// -3 dB bandwidth of |H| (first w where |H| < 10^(-3/20)), searched on [1e-3, 1e3] rad/s.
double bandwidth_3db(const std::function<std::complex<double>(double)>& H);
// Extent of the +-tol_db band of |H| from w -> 0 up to its first exit (Sec. 5.2).
double flat_band(const std::function<std::complex<double>(double)>& H, double tol_db = 0.3);

struct PrefilterResult {
    Prefilter F;
    double band = 0.0;  // rad/s
    int evaluations = 0;
};
// Maximises flat_band(H) of the nominal damped loop over 0 < f_n, 0 < f_d, 0 < beta <= beta_max
// (Sec. 5.2; the paper names neither optimiser nor grid), globally: the band is a knife edge in
// f_n (at its optimum a low-frequency dip and the ripple peak both touch +-tol_db, and 0.5 % in
// f_n drops it from 7.5 to below 6 rad/s), so the search runs on the minimax form
// r(x, W) = max_{w <= W} |20 log10 |H|| (band >= W <=> r <= tol): per (f_d, beta) the best band
// B = max{W : min_{f_n} r <= tol} (f_n by scan + golden section, W by bisection), B over a
// 9 x 10 grid in (log f_d, beta), then Nelder-Mead from the 2 best grid points and `start`.
// Finds 7.528 rad/s at f_n = 0.1152, beta = 0.545 (the paper's (52): 7.515 rad/s at 0.116,
// 0.55; the band is flat in f_d below about 0.02 s). `evaluations` counts evaluations of r.
PrefilterResult optimise_prefilter(const std::function<std::complex<double>(double)>& L, const CollocatedPlant& p,
                                   double beta_max = 1.0, double tol_db = 0.3, const Prefilter* start = nullptr);

nlohmann::json to_json(const FdDesign& d);

}  // namespace fracdesign::design
