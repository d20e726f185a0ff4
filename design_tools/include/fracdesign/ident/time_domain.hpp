// time_domain.hpp - output-error identification with the simulation inside
// the Ceres cost: the fractional process of seed 001 and a servo axis with
// friction, in open or closed loop.
//
// Output error: the model is simulated on the recorded input(s) and the
// residuals are simulated minus measured output, sample by sample; Ceres
// differentiates through the whole simulation with ceres::Jet (automatic
// derivatives). A fit that does not reach Ceres' CONVERGENCE says so
// (`converged` false) and carries the Ceres reports.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "fracdesign/ident/servo.hpp"
#include "fracdesign/models/foprocess.hpp"

namespace fracdesign {
namespace ident {

// ---- fractional process, seed 001 eq. (1): G(s) = K e^{-tau s}/(T s^lambda + 1)

// Step response / forced response by the implicit Grunwald-Letnikov scheme
// (zero initial conditions, so GL = Riemann-Liouville = Caputo):
//   T h^-lambda sum_{j=0}^{k} w_j y_{k-j} + y_k = K u(t_k - tau),
//   w_0 = 1, w_j = w_{j-1} (1 - (lambda + 1)/j)     (Podlubny 1999, eq. 7.25)
// u(t - tau) by linear interpolation between samples, u = 0 for t < 0.
// O(n^2) time, full memory (no short-memory truncation). Templated for
// ceres::Jet: th = [K, T, lambda, tau]. It is the scheme libfrac's
// frac_foprocess runs with the GL operator at full memory (what the PLC and
// the HIL rig run); test_ident_fo_matches_libfrac holds the two equal.
inline double scalar_part(double x) { return x; }
template <class J>
double scalar_part(const J& x)  // ceres::Jet: the value part
{
    return x.a;
}

template <class T>
std::vector<T> simulate_fo_process(const T* th, const std::vector<double>& u, double h)
{
    using std::pow;
    const std::size_t n = u.size();
    std::vector<T> y(n), w(n);
    w[0] = T(1.0);
    for (std::size_t j = 1; j < n; ++j) w[j] = w[j - 1] * (T(1.0) - (th[2] + T(1.0)) / double(j));
    const T c = th[1] * pow(T(h), -th[2]);
    const T lead = c + T(1.0);
    const T d = th[3] / h;  // delay in samples
    // The integer part of the delay is taken on the value; the fractional
    // part carries the derivative with respect to tau.
    for (std::size_t k = 0; k < n; ++k) {
        const T pos = T(double(k)) - d;
        const double base = std::floor(scalar_part(pos));
        T ud = T(0.0);
        if (base >= -1.0) {
            const T frac = pos - T(base);
            const long i = long(base);
            const double u0 = i >= 0 ? u[std::size_t(i)] : 0.0;
            const double u1 = std::size_t(i + 1) < n ? u[std::size_t(i + 1)] : u0;
            ud = (T(1.0) - frac) * u0 + frac * u1;
        }
        T hist = T(0.0);
        for (std::size_t j = 1; j <= k; ++j) hist += w[j] * y[k - j];
        y[k] = (th[0] * ud - c * hist) / lead;
    }
    return y;
}

struct ProcessFitOptions {
    std::array<double, 4> initial = {1.0, 1.0, 1.5, 0.0};  // K, T, lambda, tau
    std::array<double, 4> lower = {-1e6, 1e-9, 0.05, 0.0};
    std::array<double, 4> upper = {1e6, 1e9, 2.0, 1e3};
    int max_iterations = 100;
    std::function<void(int, double)> on_iteration;  // optional: (iteration, sum of squared residuals)
};

struct ProcessFitResult {
    FoProcess process;            // K, T, lambda, tau
    std::array<double, 4> std_dev{};  // from ceres::Covariance scaled by the residual variance (0 if unavailable)
    double rms_error = 0.0;       // rms of simulated - measured output
    double fit_percent = 0.0;     // 100 (1 - ||y - yhat||/||y - mean y||)
    bool converged = false;
    std::string summary, full_report;
};

// Fits (K, T, lambda, tau) to the response y of the process to u (both
// sampled every h s). Throws std::invalid_argument for mismatched lengths,
// non-finite samples, fewer than 20 samples, h <= 0, or an input that never
// moves (nothing to identify).
ProcessFitResult fit_fo_process(const std::vector<double>& u, const std::vector<double>& y, double h,
                                const ProcessFitOptions& opt = ProcessFitOptions());

// ---- servo axis (model and controller in servo.hpp)

struct ServoRecord {
    double dt = 0.0;
    bool closed_loop = false;
    std::vector<double> force;      // open loop: applied force, N
    std::vector<double> qr, u_add;  // closed loop: reference (m), signal added after saturation (V, may be empty)
    ServoController controller;     // closed loop: the known controller
    std::vector<double> q;          // measured position, m
    std::vector<double> u;          // closed loop: recorded controller output (V); empty = fit on q only
};

struct ServoFitOptions {
    std::array<double, kServoParams> initial = {1.0, 0.0, 0.0, 0.0, 0.0, 0.01};
    std::array<double, kServoParams> lower = {1e-6, 0.0, 0.0, -1e6, 0.0, 1e-6};
    std::array<double, kServoParams> upper = {1e9, 1e9, 1e9, 1e6, 1e9, 1e3};
    bool stribeck = false;  // false: Fs = 0 and vs held fixed (the EMPS reference model)
    int substeps = 4;       // RK4 sub-steps per sample
    int max_iterations = 100;
    std::size_t skip = 50;  // samples not in the cost (start-up transient, EMPS n_border)
    std::function<void(int, double)> on_iteration;  // optional: (iteration, sum of squared residuals)
};

struct ServoFitResult {
    std::array<double, kServoParams> theta{};
    std::array<double, kServoParams> std_dev{};  // 0 for fixed or unavailable
    double q_error_percent = 0.0;  // 100 ||q - q_sim||/||q|| after skip
    double u_error_percent = 0.0;  // same for u (closed loop with u only)
    bool converged = false;
    std::string summary, full_report;
};

// Residuals: (q_sim - q)/rms(q), and in closed loop with u given also
// (u_sim - u)/rms(u), each sample after `skip`. Throws std::invalid_argument
// for inconsistent lengths, non-finite samples, a record shorter than
// skip + 20 samples, dt <= 0, or an initial guess outside the bounds.
ServoFitResult fit_servo(const ServoRecord& rec, const ServoFitOptions& opt = ServoFitOptions());

}  // namespace ident
}  // namespace fracdesign
