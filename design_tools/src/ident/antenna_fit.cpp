// antenna_fit.cpp - Ceres fit of the seed 000 antenna damping (see antenna_fit.hpp).
#include "fracdesign/ident/antenna_fit.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <complex>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>

namespace fracdesign {
namespace ident {

const char* weighting_name(FrfWeighting w) { return w == FrfWeighting::Constant ? "const" : "1/w"; }

const char* structure_name(AntennaStructure s)
{
    static const char* const n[] = {"I", "II", "III", "IV", "V", "VI"};
    return n[int(s) - 1];
}

AntennaStructure parse_structure(const std::string& s)
{
    for (int i = 1; i <= 6; ++i)
        if (s == structure_name(AntennaStructure(i))) return AntennaStructure(i);
    throw std::invalid_argument("unknown antenna structure '" + s + "' (expected I, II, III, IV, V or VI)");
}

void Frf::validate() const
{
    if (w.size() != G.size())
        throw std::invalid_argument("FRF: " + std::to_string(w.size()) + " frequencies but " +
                                    std::to_string(G.size()) + " values");
    if (w.size() < 8) throw std::invalid_argument("FRF: too short (" + std::to_string(w.size()) + " points, need >= 8)");
    for (std::size_t p = 0; p < w.size(); ++p) {
        if (!std::isfinite(w[p]) || !(w[p] > 0.0))
            throw std::invalid_argument("FRF: frequency " + std::to_string(p) + " is not a positive number");
        if (p && !(w[p] > w[p - 1]))
            throw std::invalid_argument("FRF: frequencies not increasing at point " + std::to_string(p));
        if (!std::isfinite(G[p].real()) || !std::isfinite(G[p].imag()))
            throw std::invalid_argument("FRF: non-finite value at point " + std::to_string(p));
    }
}

std::vector<double> frf_weights(const std::vector<double>& w, FrfWeighting weighting)
{
    std::vector<double> W(w.size());
    if (weighting == FrfWeighting::Constant) {
        for (auto& v : W) v = 1.0 / double(w.size());
        return W;
    }
    double s = 0.0;
    for (double x : w) s += 1.0 / x;
    for (std::size_t p = 0; p < w.size(); ++p) W[p] = (1.0 / w[p]) / s;
    return W;
}

std::vector<double> haro_grid(int k0, int k1)
{
    if (k0 < 1 || k1 < k0) throw std::invalid_argument("haro_grid: need 1 <= k0 <= k1");
    std::vector<double> w;
    for (int k = k0; k <= k1; ++k) w.push_back(k * 2.0 * M_PI * 1000.0 / 160000.0);
    return w;
}

double antenna_cost(const Frf& data, const AntennaDamping<double>& d, FrfWeighting weighting,
                    const AntennaLink& link)
{
    const auto W = frf_weights(data.w, weighting);
    double J = 0.0;
    for (std::size_t p = 0; p < data.w.size(); ++p) J += W[p] * std::norm(data.G[p] - antenna_frf(link, d, data.w[p]));
    return J;
}

namespace {

// Principal square root with real arithmetic (z != 0).
Cx<double> cx_sqrt(const Cx<double>& z)
{
    const double r = std::hypot(z.re, z.im);
    const double t = std::sqrt(0.5 * (r + std::fabs(z.re)));
    if (z.re >= 0.0) return {t, z.im / (2.0 * t)};
    return {std::fabs(z.im) / (2.0 * t), std::copysign(t, z.im)};
}

// The frequency-independent factors of (j w)^alpha and (j w)^lambda.
struct KernelConsts {
    double ca, sa, cl, sl;  // cos/sin(pi alpha/2), cos/sin(pi lambda/2)
    explicit KernelConsts(const AntennaDamping<double>& d)
        : ca(std::cos(0.5 * M_PI * d.alpha)), sa(std::sin(0.5 * M_PI * d.alpha)),
          cl(std::cos(0.5 * M_PI * d.lambda)), sl(std::sin(0.5 * M_PI * d.lambda))
    {
    }
};

// antenna_frf_with_gradient with lw = ln w and the constants precomputed.
std::complex<double> frf_kernel(const AntennaLink& link, const AntennaDamping<double>& d, const KernelConsts& kc,
                                double w, double lw, std::array<std::complex<double>, 4>* grad)
{
    // Cx (models/antenna.hpp) multiplies and divides with the textbook
    // formulas; std::complex<double> would call the C99 Annex G routines
    // (__muldc3/__divdc3) on every operation, several times slower here.
    using C = Cx<double>;
    const double EI = link.EI();
    const double ma = std::exp(d.alpha * lw), ml = std::exp(d.lambda * lw);
    const C sa(ma * kc.ca, ma * kc.sa);
    const C sl(ml * kc.cl, ml * kc.sl);
    const C one(1.0, 0.0);
    const C I = one + d.zeta * sa;
    const C X = C(-(link.rho / EI) * w * w, 0.0) + d.gamma * sl;
    const C u = -1.0 * (X / I);
    const C beta = cx_sqrt(cx_sqrt(u));
    const C x = link.L * beta;
    // sin, cos, sinh, cosh of x = a + j b from sin/cos/exp of a and b
    const double a = x.re, b = x.im;
    const double sa_ = std::sin(a), ca = std::cos(a), sb = std::sin(b), cb = std::cos(b);
    const double ea = std::exp(a), eb = std::exp(b);
    const double sha = 0.5 * (ea - 1.0 / ea), cha = 0.5 * (ea + 1.0 / ea);
    const double shb = 0.5 * (eb - 1.0 / eb), chb = 0.5 * (eb + 1.0 / eb);
    const C sx(sa_ * chb, ca * shb), cx(ca * chb, -sa_ * shb);
    const C shx(sha * cb, cha * sb), chx(cha * cb, sha * sb);
    const C N = sx * chx - cx * shx, D = one + cx * chx;
    const C ND = N / D;
    const C H = beta * ND;
    if (grad) {
        const C ell(lw, 0.5 * M_PI);  // d/da (j w)^a = (j w)^a ell
        const C dH = ND + (link.L * beta) * ((2.0 * (sx * shx) + ND * N) / D);
        const C k = (I * dH) * beta / (4.0 * u);
        const C zero;
        // (dI, dX) for zeta, alpha, gamma, lambda
        const C dI[4] = {sa, d.zeta * (sa * ell), zero, zero};
        const C dX[4] = {zero, zero, sl, d.gamma * (sl * ell)};
        for (int i = 0; i < 4; ++i) {
            const C g = -EI * (dI[i] * H - k * (dX[i] + u * dI[i]) / I);
            (*grad)[std::size_t(i)] = {g.re, g.im};
        }
    }
    const C G = -EI * (I * H);
    return {G.re, G.im};
}

}  // namespace

std::complex<double> antenna_frf_with_gradient(const AntennaLink& link, const AntennaDamping<double>& d, double w,
                                               std::array<std::complex<double>, 4>* grad)
{
    return frf_kernel(link, d, KernelConsts(d), w, std::log(w), grad);
}

namespace {

bool is_log_param(const char* name) { return !std::strcmp(name, "zeta") || !std::strcmp(name, "gamma"); }

// The 2N weighted real/imaginary residuals for N free parameters x (zeta and
// gamma as logarithms).
template <int N>
struct FrfResidual {
    const Frf* data;
    std::vector<double> sqw;
    AntennaStructure structure;
    AntennaLink link;
    bool log_param[N];

    template <typename T>
    bool operator()(const T* x, T* r) const
    {
        using std::exp;
        T p[4];
        for (int i = 0; i < N; ++i) p[i] = log_param[i] ? exp(x[i]) : x[i];
        const AntennaDamping<T> d = antenna_damping<T>(structure, p);
        for (std::size_t k = 0; k < data->w.size(); ++k) {
            const Cx<T> g = antenna_frf<T>(link, d, T(data->w[k]));
            r[2 * k] = sqw[k] * (data->G[k].real() - g.re);
            r[2 * k + 1] = sqw[k] * (data->G[k].imag() - g.im);
        }
        return true;
    }
};

// The same residuals with the analytic Jacobian of antenna_frf_with_gradient
// (value and gradient in one pass).
class FrfResidualAnalytic : public ceres::CostFunction {
public:
    FrfResidualAnalytic(const Frf& data, const std::vector<double>& W, AntennaStructure s, const AntennaLink& link)
        : data_(data), structure_(s), link_(link), n_(antenna_free_count(s))
    {
        for (double v : W) sqw_.push_back(std::sqrt(v));
        for (double w : data.w) lw_.push_back(std::log(w));
        const char* const* names = antenna_free_names(s);
        // index of each free parameter in (zeta, alpha, gamma, lambda)
        for (int i = 0; i < n_; ++i) {
            const std::string nm = names[i];
            slot_[i] = nm == "zeta" ? 0 : nm == "alpha" ? 1 : nm == "gamma" ? 2 : 3;
            log_[i] = is_log_param(names[i]);
        }
        set_num_residuals(int(2 * data.w.size()));
        mutable_parameter_block_sizes()->push_back(n_);
    }

    bool Evaluate(double const* const* x, double* r, double** jac) const override
    {
        double p[4];
        for (int i = 0; i < n_; ++i) p[i] = log_[i] ? std::exp(x[0][i]) : x[0][i];
        const AntennaDamping<double> d = antenna_damping<double>(structure_, p);
        const bool want_jac = jac && jac[0];
        const KernelConsts kc(d);
        std::array<std::complex<double>, 4> g;
        for (std::size_t k = 0; k < data_.w.size(); ++k) {
            const std::complex<double> e =
                data_.G[k] - frf_kernel(link_, d, kc, data_.w[k], lw_[k], want_jac ? &g : nullptr);
            r[2 * k] = sqw_[k] * e.real();
            r[2 * k + 1] = sqw_[k] * e.imag();
            if (want_jac) {
                for (int i = 0; i < n_; ++i) {
                    // dr/dx = -sqrt(W) dG/dtheta dtheta/dx, dtheta/dx = theta for log parameters
                    const std::complex<double> dg = g[std::size_t(slot_[i])] * (log_[i] ? p[i] : 1.0);
                    jac[0][(2 * k) * std::size_t(n_) + std::size_t(i)] = -sqw_[k] * dg.real();
                    jac[0][(2 * k + 1) * std::size_t(n_) + std::size_t(i)] = -sqw_[k] * dg.imag();
                }
            }
        }
        return true;
    }

private:
    const Frf& data_;
    std::vector<double> sqw_, lw_;
    AntennaStructure structure_;
    AntennaLink link_;
    int n_;
    int slot_[4] = {0, 0, 0, 0};
    bool log_[4] = {false, false, false, false};
};

template <int N>
ceres::CostFunction* make_cost(const Frf& data, const std::vector<double>& W, AntennaStructure s,
                               const AntennaLink& link)
{
    auto* f = new FrfResidual<N>;
    f->data = &data;
    for (double v : W) f->sqw.push_back(std::sqrt(v));
    f->structure = s;
    f->link = link;
    const char* const* names = antenna_free_names(s);
    for (int i = 0; i < N; ++i) f->log_param[i] = is_log_param(names[i]);
    return new ceres::AutoDiffCostFunction<FrfResidual<N>, ceres::DYNAMIC, N>(f, int(2 * data.w.size()));
}

void param_bounds(const char* name, const AntennaBounds& b, double& lo, double& hi)
{
    if (!std::strcmp(name, "zeta")) lo = std::log(b.zeta_lo), hi = std::log(b.zeta_hi);
    else if (!std::strcmp(name, "gamma")) lo = std::log(b.gamma_lo), hi = std::log(b.gamma_hi);
    else if (!std::strcmp(name, "alpha")) lo = b.alpha_lo, hi = b.alpha_hi;
    else lo = b.lambda_lo, hi = b.lambda_hi;
}

}  // namespace

void antenna_box(AntennaStructure structure, const AntennaBounds& bounds, std::vector<double>& lo,
                 std::vector<double>& hi)
{
    const int n = antenna_free_count(structure);
    const char* const* names = antenna_free_names(structure);
    lo.assign(std::size_t(n), 0.0);
    hi.assign(std::size_t(n), 0.0);
    for (int i = 0; i < n; ++i) param_bounds(names[i], bounds, lo[std::size_t(i)], hi[std::size_t(i)]);
}

std::vector<std::vector<double>> antenna_starts(AntennaStructure structure, const AntennaBounds& bounds, int starts,
                                                unsigned seed)
{
    std::vector<double> lo, hi;
    antenna_box(structure, bounds, lo, hi);
    // The 53-bit conversion is written out so the sequence is the same on
    // every standard library for a given seed.
    std::mt19937_64 rng(seed);
    auto uniform = [&rng]() { return double(rng() >> 11) * (1.0 / 9007199254740992.0); };
    std::vector<std::vector<double>> x(std::size_t(std::max(starts, 0)), std::vector<double>(lo.size()));
    for (std::size_t s = 0; s < x.size(); ++s)
        for (std::size_t i = 0; i < lo.size(); ++i)
            x[s][i] = s == 0 ? 0.5 * (lo[i] + hi[i]) : lo[i] + (hi[i] - lo[i]) * uniform();
    return x;
}

AntennaFitResult fit_antenna(const Frf& data, AntennaStructure structure, const AntennaFitOptions& opt,
                             const std::function<void(int, double)>& on_start)
{
    data.validate();
    opt.link.validate();
    if (opt.starts < 1) throw std::invalid_argument("antenna fit: starts must be >= 1");
    const AntennaBounds& b = opt.bounds;
    if (!(b.zeta_lo > 0 && b.zeta_lo < b.zeta_hi && b.gamma_lo > 0 && b.gamma_lo < b.gamma_hi &&
          b.alpha_lo < b.alpha_hi && b.lambda_lo < b.lambda_hi))
        throw std::invalid_argument("antenna fit: bounds must satisfy 0 < lo < hi (zeta, gamma) and lo < hi");
    const int n = antenna_free_count(structure);
    const char* const* names = antenna_free_names(structure);
    const auto W = frf_weights(data.w, opt.weighting);

    std::vector<double> lo, hi;
    antenna_box(structure, b, lo, hi);
    const std::vector<std::vector<double>> x0 = antenna_starts(structure, b, opt.starts, opt.seed);

    AntennaFitResult res;
    res.structure = structure;
    res.weighting = opt.weighting;
    double best = std::numeric_limits<double>::infinity();
    std::vector<double> xbest(n);
    for (int s = 0; s < opt.starts; ++s) {
        std::vector<double> x = x0[std::size_t(s)];
        ceres::Problem::Options popt;
        ceres::Problem problem(popt);
        ceres::CostFunction* cf = opt.derivatives == Derivatives::Analytic
                                      ? new FrfResidualAnalytic(data, W, structure, opt.link)
                                  : n == 1 ? make_cost<1>(data, W, structure, opt.link)
                                  : n == 2 ? make_cost<2>(data, W, structure, opt.link)
                                           : make_cost<4>(data, W, structure, opt.link);
        problem.AddResidualBlock(cf, nullptr, x.data());
        for (int i = 0; i < n; ++i) {
            problem.SetParameterLowerBound(x.data(), i, lo[i]);
            problem.SetParameterUpperBound(x.data(), i, hi[i]);
        }
        ceres::Solver::Options so;
        so.minimizer_type = ceres::TRUST_REGION;
        so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
        so.linear_solver_type = ceres::DENSE_QR;
        so.max_num_iterations = opt.max_iterations;
        so.function_tolerance = opt.function_tolerance;
        so.parameter_tolerance = opt.parameter_tolerance;
        so.gradient_tolerance = 1e-20;
        // With bounds, Ceres follows a rejected trust-region step by a line
        // search along the projected step that evaluates the Jacobian at every
        // trial point; on this problem it costs more evaluations than it saves.
        so.max_num_line_search_step_size_iterations = 0;
        so.num_threads = 1;
        so.logging_type = ceres::SILENT;
        ceres::Solver::Summary sum;
        ceres::Solve(so, &problem, &sum);
        const double J = 2.0 * sum.final_cost;
        res.start_costs.push_back(J);
        res.iterations += int(sum.iterations.size());
        if (J < best) {
            best = J;
            xbest = x;
            res.best_start = s;
            res.converged = sum.termination_type == ceres::CONVERGENCE;
            res.summary = sum.BriefReport();
            res.full_report = sum.FullReport();
            if (opt.covariance) {
                ceres::Covariance::Options co;
                co.algorithm_type = ceres::DENSE_SVD;
                co.null_space_rank = -1;
                co.min_reciprocal_condition_number = 1e-14;
                ceres::Covariance cov(co);
                std::vector<std::pair<const double*, const double*>> blocks = {{x.data(), x.data()}};
                res.covariance.resize(0, 0);
                if (cov.Compute(blocks, &problem)) {
                    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> C(n, n);
                    cov.GetCovarianceBlock(x.data(), x.data(), C.data());
                    // Residual variance per real residual, and the delta method
                    // for the log-parametrised entries (d exp(x)/dx = exp(x)).
                    const double s2 = J / double(2 * data.w.size() - std::size_t(n));
                    Eigen::VectorXd jac(n);
                    for (int i = 0; i < n; ++i) jac(i) = is_log_param(names[i]) ? std::exp(x[i]) : 1.0;
                    res.covariance = s2 * jac.asDiagonal() * Eigen::MatrixXd(C) * jac.asDiagonal();
                }
            }
        }
        if (on_start) on_start(s, J);
    }
    res.names.assign(names, names + n);
    res.params.resize(n);
    for (int i = 0; i < n; ++i) res.params[i] = is_log_param(names[i]) ? std::exp(xbest[i]) : xbest[i];
    res.damping = antenna_damping<double>(structure, res.params.data());
    res.cost = best;
    res.mse = antenna_cost(data, res.damping, FrfWeighting::Constant, opt.link);
    res.wmse = antenna_cost(data, res.damping, FrfWeighting::InverseOmega, opt.link);
    res.std_dev.clear();
    if (res.covariance.size())
        for (int i = 0; i < n; ++i) res.std_dev.push_back(std::sqrt(std::max(0.0, res.covariance(i, i))));
    return res;
}

}  // namespace ident
}  // namespace fracdesign
