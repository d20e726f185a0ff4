// antenna_fit.hpp - frequency-domain identification of the damping of the
// seed 000 antenna (Haro-Olmo et al. 2023, Sec. 5.2, eqs. (26)-(29)).
//
// Cost (eq. 26, with the squared modulus of notes 000 sec. 5.1):
//   J = sum_p W(w_p) |G_exp(j w_p) - G(j w_p; theta)|^2
// with the weights of eq. (27):
//   constant:    W_p = 1/N
//   1/w:         W_p = (1/w_p) / sum_i (1/w_i)          (w in rad/s)
// so J equals the paper's MSE (eq. 28) or WMSE (eq. 29).
//
// Residual form for complex data: Ceres sees 2N real residuals
//   r_2p = sqrt(W_p) Re(G_exp - G),  r_2p+1 = sqrt(W_p) Im(G_exp - G),
// whose sum of squares is J (Ceres reports cost = J/2). G comes from the
// issue-5 model (models/antenna.hpp). Derivatives: analytic (default, see
// antenna_frf_with_gradient) or automatic (ceres::Jet through the model
// template); both give the same fit. zeta and gamma, which span decades, are
// optimised as their logarithms; alpha and lambda directly; all in bounds.
//
// Search: Levenberg-Marquardt from `starts` points (the first the centre of
// the box, the others drawn uniformly in the box - log box for zeta, gamma -
// by a generator seeded with `seed`), because the lightly damped resonances
// make J very non-convex (notes 000 sec. 5.2). The best end point wins.
// Covariance: ceres::Covariance at the optimum, scaled by the residual
// variance s^2 = J_min/(2N - p) (each complex point counts as two real ones),
// mapped back to natural parameters by the delta method.
#pragma once
#include <array>
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fracdesign/models/antenna.hpp"

namespace fracdesign {
namespace ident {

enum class FrfWeighting { Constant, InverseOmega };

const char* weighting_name(FrfWeighting w);   // "const", "1/w"
const char* structure_name(AntennaStructure s);  // "I" ... "VI"
AntennaStructure parse_structure(const std::string& s);  // std::invalid_argument if unknown

// A measured frequency response: w_p > 0 strictly increasing, rad/s.
struct Frf {
    std::vector<double> w;
    std::vector<std::complex<double>> G;
    // std::invalid_argument naming the first bad point (size mismatch, fewer
    // than 8 points, w not positive/increasing, non-finite value).
    void validate() const;
};

// Weights W_p of eq. (27), summing to 1.
std::vector<double> frf_weights(const std::vector<double>& w, FrfWeighting weighting);

// The grid of notes 000 sec. 4.2: w_k = k 2 pi 1000/160000 rad/s, k = k0..k1
// (N = 7907 for bins 94..8000).
std::vector<double> haro_grid(int k0 = 94, int k1 = 8000);

// Bounds on the four damping parameters (natural units). Defaults: the
// paper's sweep ranges (sec. 5.2) widened to cover every Table 3 value.
struct AntennaBounds {
    double zeta_lo = 1e-7, zeta_hi = 1e-2;
    double alpha_lo = 0.05, alpha_hi = 1.95;
    double gamma_lo = 1e-4, gamma_hi = 5.0;
    double lambda_lo = 0.05, lambda_hi = 1.95;
};

enum class Derivatives { Analytic, Automatic };

struct AntennaFitOptions {
    FrfWeighting weighting = FrfWeighting::InverseOmega;
    Derivatives derivatives = Derivatives::Analytic;
    AntennaBounds bounds;
    int starts = 8;             // multi-start count (>= 1)
    unsigned seed = 1;          // start generator seed: same seed, same result
    int max_iterations = 200;   // per start
    double function_tolerance = 1e-14;
    double parameter_tolerance = 1e-12;
    bool covariance = true;
    AntennaLink link;           // Table 1 constants
};

struct AntennaFitResult {
    AntennaStructure structure = AntennaStructure::VI;
    FrfWeighting weighting = FrfWeighting::InverseOmega;
    std::vector<std::string> names;    // free parameter names
    std::vector<double> params;        // free parameters, natural units
    std::vector<double> std_dev;       // from the covariance (empty if unavailable)
    Eigen::MatrixXd covariance;        // natural units (empty if unavailable)
    AntennaDamping<double> damping{};  // all four, fixed ones included
    double cost = 0.0;                 // J of eq. (26) with the chosen weights
    double mse = 0.0, wmse = 0.0;      // eqs. (28), (29) at the optimum
    bool converged = false;            // the best start's Ceres termination was CONVERGENCE
    int best_start = 0;                // index of the winning start
    int iterations = 0;                // LM iterations summed over all starts
    std::vector<double> start_costs;   // final J of every start
    std::string summary;               // Ceres BriefReport of the best start
    std::string full_report;           // Ceres FullReport of the best start
};

// The multi-start points of `fit_antenna` in its optimisation variables
// (log zeta, log gamma, alpha, lambda; free parameters of `structure` only):
// starts[0] is the centre of the box, the others uniform draws from a
// mt19937_64 seeded with `seed`. Exposed so a reference solver can start
// from exactly the same points (tests/bench/bench_ident).
std::vector<std::vector<double>> antenna_starts(AntennaStructure structure, const AntennaBounds& bounds, int starts,
                                                unsigned seed);
// Box of the optimisation variables, same order.
void antenna_box(AntennaStructure structure, const AntennaBounds& bounds, std::vector<double>& lo,
                 std::vector<double>& hi);

// Fits one structure. Throws std::invalid_argument for invalid data/options.
// `on_start(i, J)` (optional) is called after each start.
AntennaFitResult fit_antenna(const Frf& data, AntennaStructure structure, const AntennaFitOptions& opt,
                             const std::function<void(int, double)>& on_start = nullptr);

// G(j w) of eq. (25) (corrected beta^4) and dG/d(zeta, alpha, gamma, lambda)
// in one pass: the kernel of the analytic-derivative fit. It evaluates the
// same formula as the model (models/antenna.hpp), written with real
// sincos/exp so one pass costs about one model evaluation; the tests check
// G against the model to 1e-12 and the gradient against automatic
// derivatives of the model template. With I = 1 + zeta s^alpha,
// X = (rho/EI) s^2 + gamma s^lambda, u = beta^4 = -X/I, x = beta L,
// N = sin x cosh x - cos x sinh x, D = 1 + cos x cosh x, H = beta N/D:
//   G = -EI I H,   dG = -EI (dI H + I H'(beta) beta/(4u) du),
//   H'(beta) = N/D + beta L (2 sin x sinh x D + N^2)/D^2   (N' = 2 sin x sinh x, D' = -N)
//   du = -(dX + u dI)/I,  d s^a/da = s^a (ln w + j pi/2).
// G depends on beta^4 only (notes 000 sec. 2.6), so beta = sqrt(sqrt(u)).
// `grad` may be null (value only).
std::complex<double> antenna_frf_with_gradient(const AntennaLink& link, const AntennaDamping<double>& d, double w,
                                               std::array<std::complex<double>, 4>* grad);

// J of eq. (26) for given damping.
double antenna_cost(const Frf& data, const AntennaDamping<double>& d, FrfWeighting weighting,
                    const AntennaLink& link = AntennaLink());

}  // namespace ident
}  // namespace fracdesign
