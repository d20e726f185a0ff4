// time_domain.cpp - output-error fits of the fractional process and of a servo
// axis with Ceres (see time_domain.hpp).
#include "fracdesign/ident/time_domain.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <stdexcept>

namespace fracdesign {
namespace ident {
namespace {

void require_finite(const std::vector<double>& v, const char* what)
{
    for (std::size_t k = 0; k < v.size(); ++k)
        if (!std::isfinite(v[k]))
            throw std::invalid_argument(std::string(what) + ": non-finite sample at index " + std::to_string(k));
}

double rms(const std::vector<double>& v, std::size_t skip)
{
    double s = 0.0;
    for (std::size_t k = skip; k < v.size(); ++k) s += v[k] * v[k];
    return std::sqrt(s / double(v.size() - skip));
}

// Forwards Ceres' per-iteration state to an optional progress callback.
class IterationReporter : public ceres::IterationCallback {
public:
    explicit IterationReporter(const std::function<void(int, double)>& f) : f_(f) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override
    {
        f_(s.iteration, 2.0 * s.cost);
        return ceres::SOLVER_CONTINUE;
    }

private:
    const std::function<void(int, double)>& f_;
};

ceres::Solver::Options solver_options(int max_iterations)
{
    ceres::Solver::Options so;
    so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = max_iterations;
    so.function_tolerance = 1e-12;
    so.parameter_tolerance = 1e-12;
    so.num_threads = 1;
    so.logging_type = ceres::SILENT;
    return so;
}

// sqrt(diag(s^2 (J'J)^-1)) of the parameter block, s^2 = sum r^2/(m - p);
// zeros if Ceres cannot compute it (rank deficient).
template <std::size_t N>
std::array<double, N> std_devs(ceres::Problem& problem, double* x, double sum_sq, std::size_t m, int free)
{
    std::array<double, N> sd{};
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    co.null_space_rank = -1;
    ceres::Covariance cov(co);
    std::vector<std::pair<const double*, const double*>> blocks = {{x, x}};
    if (!cov.Compute(blocks, &problem)) return sd;
    std::vector<double> C(N * N);
    cov.GetCovarianceBlock(x, x, C.data());
    const double s2 = sum_sq / double(m - std::size_t(free));
    for (std::size_t i = 0; i < N; ++i) sd[i] = std::sqrt(std::max(0.0, s2 * C[i * N + i]));
    return sd;
}

struct ProcessResidual {
    const std::vector<double>* u;
    const std::vector<double>* y;
    double h;
    template <typename T>
    bool operator()(const T* th, T* r) const
    {
        const std::vector<T> ys = simulate_fo_process(th, *u, h);
        for (std::size_t k = 0; k < ys.size(); ++k) r[k] = ys[k] - (*y)[k];
        return true;
    }
};

struct ServoResidual {
    const ServoRecord* rec;
    std::size_t skip;
    int substeps;
    double q_scale, u_scale;  // 1/rms
    template <typename T>
    bool operator()(const T* th, T* r) const
    {
        std::vector<T> q, u;
        if (rec->closed_loop)
            simulate_servo_closed_loop(th, rec->controller, rec->qr, rec->u_add, rec->dt, substeps, q,
                                       rec->u.empty() ? nullptr : &u);
        else
            q = simulate_servo_open_loop(th, rec->force, rec->dt, substeps, rec->q[0]);
        const std::size_t n = rec->q.size() - skip;
        for (std::size_t k = 0; k < n; ++k) r[k] = q_scale * (q[skip + k] - rec->q[skip + k]);
        if (!u.empty())
            for (std::size_t k = 0; k < n; ++k) r[n + k] = u_scale * (u[skip + k] - rec->u[skip + k]);
        return true;
    }
};

}  // namespace

ProcessFitResult fit_fo_process(const std::vector<double>& u, const std::vector<double>& y, double h,
                                const ProcessFitOptions& opt)
{
    if (u.size() != y.size())
        throw std::invalid_argument("process fit: input has " + std::to_string(u.size()) + " samples, output " +
                                    std::to_string(y.size()));
    if (u.size() < 20) throw std::invalid_argument("process fit: record too short (" + std::to_string(u.size()) +
                                                   " samples, need >= 20)");
    if (!(h > 0.0) || !std::isfinite(h)) throw std::invalid_argument("process fit: sample time must be > 0");
    require_finite(u, "process fit: input");
    require_finite(y, "process fit: output");
    bool moves = false;
    for (double v : u) moves = moves || v != 0.0;
    if (!moves) throw std::invalid_argument("process fit: the input is identically zero (nothing to identify)");
    std::array<double, 4> x = opt.initial;
    for (int i = 0; i < 4; ++i)
        if (!(x[std::size_t(i)] >= opt.lower[std::size_t(i)] && x[std::size_t(i)] <= opt.upper[std::size_t(i)]))
            throw std::invalid_argument("process fit: initial guess outside the bounds (parameter " +
                                        std::to_string(i) + ")");
    ceres::Problem problem;
    auto* f = new ProcessResidual{&u, &y, h};
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<ProcessResidual, ceres::DYNAMIC, 4>(f, int(u.size())),
                             nullptr, x.data());
    for (int i = 0; i < 4; ++i) {
        problem.SetParameterLowerBound(x.data(), i, opt.lower[std::size_t(i)]);
        problem.SetParameterUpperBound(x.data(), i, opt.upper[std::size_t(i)]);
    }
    ceres::Solver::Summary sum;
    ceres::Solver::Options so = solver_options(opt.max_iterations);
    IterationReporter rep(opt.on_iteration);
    if (opt.on_iteration) so.callbacks.push_back(&rep);
    ceres::Solve(so, &problem, &sum);
    ProcessFitResult res;
    res.process.K = x[0];
    res.process.T = x[1];
    res.process.lambda = x[2];
    res.process.tau = x[3];
    res.converged = sum.termination_type == ceres::CONVERGENCE;
    res.summary = sum.BriefReport();
    res.full_report = sum.FullReport();
    res.std_dev = std_devs<4>(problem, x.data(), 2.0 * sum.final_cost, u.size(), 4);
    const std::vector<double> ys = simulate_fo_process(x.data(), u, h);
    double e2 = 0.0, v2 = 0.0, mean = 0.0;
    for (double v : y) mean += v / double(y.size());
    for (std::size_t k = 0; k < y.size(); ++k) {
        e2 += (ys[k] - y[k]) * (ys[k] - y[k]);
        v2 += (y[k] - mean) * (y[k] - mean);
    }
    res.rms_error = std::sqrt(e2 / double(y.size()));
    res.fit_percent = v2 > 0.0 ? 100.0 * (1.0 - std::sqrt(e2 / v2)) : 0.0;
    return res;
}

ServoFitResult fit_servo(const ServoRecord& rec, const ServoFitOptions& opt)
{
    const std::size_t n = rec.q.size();
    if (!(rec.dt > 0.0) || !std::isfinite(rec.dt)) throw std::invalid_argument("servo fit: sample time must be > 0");
    if (n < opt.skip + 20)
        throw std::invalid_argument("servo fit: record too short (" + std::to_string(n) + " samples, need >= " +
                                    std::to_string(opt.skip + 20) + ")");
    const std::vector<double>& input = rec.closed_loop ? rec.qr : rec.force;
    if (input.size() != n)
        throw std::invalid_argument(std::string("servo fit: ") + (rec.closed_loop ? "reference" : "force") +
                                    " has " + std::to_string(input.size()) + " samples, position " +
                                    std::to_string(n));
    if (rec.closed_loop && !rec.u_add.empty() && rec.u_add.size() != n)
        throw std::invalid_argument("servo fit: added signal length differs from the position");
    if (rec.closed_loop && !rec.u.empty() && rec.u.size() != n)
        throw std::invalid_argument("servo fit: recorded control length differs from the position");
    if (rec.closed_loop && rec.controller.delay < 0) throw std::invalid_argument("servo fit: negative delay");
    require_finite(rec.q, "servo fit: position");
    require_finite(input, "servo fit: input");
    require_finite(rec.u_add, "servo fit: added signal");
    require_finite(rec.u, "servo fit: control");
    std::array<double, kServoParams> x = opt.initial;
    if (!opt.stribeck) x[4] = 0.0;
    for (std::size_t i = 0; i < kServoParams; ++i)
        if (!(x[i] >= opt.lower[i] && x[i] <= opt.upper[i]))
            throw std::invalid_argument(std::string("servo fit: initial ") + kServoParamNames[i] +
                                        " outside its bounds");
    const double qr = rms(rec.q, opt.skip);
    if (!(qr > 0.0)) throw std::invalid_argument("servo fit: measured position is identically zero");
    const bool with_u = rec.closed_loop && !rec.u.empty();
    const double ur = with_u ? rms(rec.u, opt.skip) : 1.0;
    if (!(ur > 0.0)) throw std::invalid_argument("servo fit: recorded control is identically zero");
    auto* f = new ServoResidual{&rec, opt.skip, opt.substeps, 1.0 / qr, 1.0 / ur};
    const std::size_t m = (n - opt.skip) * (with_u ? 2 : 1);
    ceres::Problem problem;
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<ServoResidual, ceres::DYNAMIC, kServoParams>(f, int(m)), nullptr, x.data());
    for (int i = 0; i < kServoParams; ++i) {
        problem.SetParameterLowerBound(x.data(), i, opt.lower[std::size_t(i)]);
        problem.SetParameterUpperBound(x.data(), i, opt.upper[std::size_t(i)]);
    }
    if (!opt.stribeck) problem.SetManifold(x.data(), new ceres::SubsetManifold(kServoParams, {4, 5}));
    ceres::Solver::Summary sum;
    ceres::Solver::Options so = solver_options(opt.max_iterations);
    IterationReporter rep(opt.on_iteration);
    if (opt.on_iteration) so.callbacks.push_back(&rep);
    ceres::Solve(so, &problem, &sum);
    ServoFitResult res;
    res.theta = x;
    res.converged = sum.termination_type == ceres::CONVERGENCE;
    res.summary = sum.BriefReport();
    res.full_report = sum.FullReport();
    res.std_dev = std_devs<kServoParams>(problem, x.data(), 2.0 * sum.final_cost, m, opt.stribeck ? 6 : 4);
    std::vector<double> q, u;
    if (rec.closed_loop)
        simulate_servo_closed_loop(x.data(), rec.controller, rec.qr, rec.u_add, rec.dt, opt.substeps, q,
                                   with_u ? &u : nullptr);
    else
        q = simulate_servo_open_loop(x.data(), rec.force, rec.dt, opt.substeps, rec.q[0]);
    res.q_error_percent = relative_error_percent(rec.q, q, opt.skip);
    if (with_u) res.u_error_percent = relative_error_percent(rec.u, u, opt.skip);
    return res;
}

}  // namespace ident
}  // namespace fracdesign
