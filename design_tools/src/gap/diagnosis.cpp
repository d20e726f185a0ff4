// diagnosis.cpp - where / which / how far (see diagnosis.hpp, docs/gap.md).
#include "fracdesign/gap/diagnosis.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <unsupported/Eigen/FFT>

#include "fracdesign/welch.hpp"

namespace fracdesign {
namespace gap {

double total_gap(const std::vector<double>& nrmse, const std::vector<double>& weight)
{
    double s = 0, w = 0;
    for (size_t c = 0; c < nrmse.size(); ++c) {
        const double wc = c < weight.size() ? weight[c] : 1.0;
        s += wc * nrmse[c] * nrmse[c];
        w += wc;
    }
    return nrmse.empty() ? 0.0 : std::sqrt(s / w);
}

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

double rms(const Eigen::VectorXd& v) { return v.size() ? std::sqrt(v.squaredNorm() / double(v.size())) : 0.0; }

// nrmse per column: rms(y - yhat) / scale, scale = std of the output over the
// whole record the rows come from (a held-out tail that sits in steady state
// would make its own std a meaningless yardstick).
std::vector<double> nrmse(const Eigen::MatrixXd& y, const Eigen::MatrixXd& yhat, const std::vector<double>& scale)
{
    std::vector<double> out;
    for (Eigen::Index c = 0; c < y.cols(); ++c) {
        const double e = std::sqrt((y.col(c) - yhat.col(c)).squaredNorm() / double(y.rows()));
        out.push_back(scale[size_t(c)] > 0 ? e / scale[size_t(c)] : kNaN);
    }
    return out;
}

// ---- frequency bands ------------------------------------------------------

std::vector<std::pair<double, double>> band_edges(double Ts)
{
    const double nyq = 0.5 / Ts;
    std::vector<std::pair<double, double>> b;
    double lo = 0.0, hi = 0.1;
    while (lo < nyq) {
        b.push_back({lo, std::min(hi, nyq)});
        lo = hi;
        hi *= 10.0;
    }
    return b;
}

// Power of two >= n: records are zero-padded before the FFT (a prime length
// would fall back to an O(n^2) transform; padding keeps Parseval's total).
Eigen::Index fft_length(Eigen::Index n)
{
    Eigen::Index p = 1;
    while (p < n) p *= 2;
    return p;
}

// Energy of each column of x in each band (Parseval: sum over bins |X_k|^2 / N = sum |x|^2).
Eigen::MatrixXd band_energy(const Eigen::MatrixXd& x, double Ts, const std::vector<std::pair<double, double>>& bands)
{
    Eigen::FFT<double> fft;
    const Eigen::Index N = fft_length(x.rows());
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(Eigen::Index(bands.size()), x.cols());
    for (Eigen::Index c = 0; c < x.cols(); ++c) {
        std::vector<double> in(x.col(c).data(), x.col(c).data() + x.rows());
        in.resize(size_t(N), 0.0);
        std::vector<std::complex<double>> X;
        fft.fwd(X, in);
        for (Eigen::Index k = 0; k < N; ++k) {
            const double f = double(std::min(k, N - k)) / (double(N) * Ts);
            for (size_t b = 0; b < bands.size(); ++b)
                if (f >= bands[b].first && (f < bands[b].second || b + 1 == bands.size())) {
                    E(Eigen::Index(b), c) += std::norm(X[size_t(k)]) / double(N);
                    break;
                }
        }
    }
    return E;
}

// Per band, per output: sqrt(band residual energy / n) / scale, so that the
// squares over the bands add up to nrmse^2.
std::vector<std::vector<double>> band_nrmse(const Eigen::MatrixXd& y, const Eigen::MatrixXd& yhat, double Ts,
                                            const std::vector<double>& scale)
{
    const auto bands = band_edges(Ts);
    const Eigen::MatrixXd E = band_energy(y - yhat, Ts, bands);
    std::vector<std::vector<double>> out(bands.size());
    for (size_t b = 0; b < bands.size(); ++b)
        for (Eigen::Index c = 0; c < y.cols(); ++c) {
            const double den = double(y.rows()) * scale[size_t(c)] * scale[size_t(c)];
            out[b].push_back(den > 0 ? std::sqrt(E(Eigen::Index(b), c) / den) : kNaN);
        }
    return out;
}

// Smoothed periodogram (5-bin moving average) of one signal, one-sided, on
// the zero-padded length fft_length(x.size()): the project's spectrum
// estimator (welch_psd) with one rectangular segment of the whole record.
std::vector<double> smoothed_spectrum(const Eigen::VectorXd& x)
{
    WelchOptions o;
    o.fs = 1.0;
    o.nperseg = int(x.size());
    o.noverlap = 0;
    o.nfft = int(fft_length(x.size()));
    o.window.assign(size_t(x.size()), 1.0);
    const std::vector<double> P = welch_psd(std::vector<double>(x.data(), x.data() + x.size()), o).P;
    const size_t H = P.size();
    std::vector<double> S(H, 0.0);
    for (size_t k = 0; k < H; ++k) {
        int cnt = 0;
        for (long j = long(k) - 2; j <= long(k) + 2; ++j)
            if (j >= 0 && j < long(H)) {
                S[k] += P[size_t(j)];
                ++cnt;
            }
        S[k] /= cnt;
    }
    return S;
}

// ---- fitting ---------------------------------------------------------------

struct FitProblem {
    const ReplaySetup* setup;
    Eigen::MatrixXd y;                 // measured fit rows
    std::vector<double> sigma;         // per output normalization
    std::vector<EffectSetup> effects;
    std::vector<double> base;          // full normalized vector
    std::vector<int> free_idx;         // indices into base optimized by Ceres

    std::vector<EffectInstance> instances(const std::vector<double>& theta) const
    {
        std::vector<EffectInstance> out;
        size_t k = 0;
        for (const EffectSetup& e : effects) {
            EffectInstance in{e.kind, {}, e.site, e.coupling};
            for (const ParamSpec& p : e.spec) in.params.push_back(p.scale * theta[k++]);
            out.push_back(in);
        }
        return out;
    }
    void residuals(const std::vector<double>& theta, double* r) const
    {
        const ReplayTrace tr = replay(*setup, instances(theta), y.rows());
        const Eigen::Index N = y.rows();
        for (Eigen::Index c = 0; c < y.cols(); ++c)
            for (Eigen::Index k = 0; k < N; ++k) {
                const double e = (y(k, c) - tr.y(k, c)) / sigma[size_t(c)];
                r[c * N + k] = std::isfinite(e) ? std::min(std::max(e, -1e6), 1e6) : 1e6;  // diverged replays stay finite
            }
    }
    double cost(const std::vector<double>& theta) const
    {
        std::vector<double> r(size_t(y.size()));
        residuals(theta, r.data());
        double s = 0;
        for (double e : r) s += e * e;
        return 0.5 * s;
    }
};

struct ReplayCost {
    const FitProblem* P;
    bool operator()(double const* const* params, double* residuals) const
    {
        std::vector<double> theta = P->base;
        for (size_t i = 0; i < P->free_idx.size(); ++i) theta[size_t(P->free_idx[i])] = params[0][i];
        P->residuals(theta, residuals);
        return true;
    }
};

struct FitOutcome {
    std::vector<double> theta;
    std::vector<double> stddev;  // normalized, per entry of theta (NaN for fixed)
    double cost = std::numeric_limits<double>::infinity();
    std::string brief;
};

// Least squares on the free parameters from theta0 (Levenberg-Marquardt,
// forward numeric differences, one replay per parameter: the replay holds
// clamp and rounding maps that automatic derivatives would differentiate
// piecewise only, and each replay is a loop over the whole record).
FitOutcome refine(FitProblem& P, const std::vector<double>& theta0, int max_iter)
{
    FitOutcome out;
    out.theta = theta0;
    out.stddev.assign(theta0.size(), kNaN);
    P.free_idx.clear();
    size_t k = 0;
    for (const EffectSetup& e : P.effects)
        for (const ParamSpec& p : e.spec) {
            if (!p.fixed) P.free_idx.push_back(int(k));
            ++k;
        }
    P.base = theta0;
    if (P.free_idx.empty()) {
        out.cost = P.cost(theta0);
        out.brief = "no continuous parameters: grid value evaluated";
        return out;
    }
    std::vector<double> x;
    for (int i : P.free_idx) x.push_back(theta0[size_t(i)]);
    ceres::Problem problem;
    auto* cf = new ceres::DynamicNumericDiffCostFunction<ReplayCost, ceres::FORWARD>(new ReplayCost{&P});
    cf->AddParameterBlock(int(x.size()));
    cf->SetNumResiduals(int(P.y.size()));
    problem.AddResidualBlock(cf, nullptr, x.data());
    std::vector<ParamSpec> specs;
    for (const EffectSetup& e : P.effects)
        for (const ParamSpec& p : e.spec) specs.push_back(p);
    for (size_t i = 0; i < P.free_idx.size(); ++i) {
        const ParamSpec& p = specs[size_t(P.free_idx[i])];
        x[i] = std::min(std::max(x[i], p.lo), p.hi);
        problem.SetParameterLowerBound(x.data(), int(i), p.lo);
        problem.SetParameterUpperBound(x.data(), int(i), p.hi);
    }
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = max_iter;
    so.function_tolerance = 1e-9;
    so.num_threads = 1;
    so.logging_type = ceres::SILENT;
    ceres::Solver::Summary sum;
    ceres::Solve(so, &problem, &sum);
    out.brief = sum.BriefReport();
    for (size_t i = 0; i < P.free_idx.size(); ++i) out.theta[size_t(P.free_idx[i])] = x[i];
    out.cost = sum.final_cost;
    // Parameter std from the Gauss-Newton covariance sigma^2 (J'J)^+ with the
    // residual variance sigma^2 = 2 cost / (m - p); residuals are correlated
    // in time, so this is optimistic.
    double cost = 0;
    ceres::CRSMatrix J;
    problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, &J);
    const size_t p = x.size();
    Eigen::MatrixXd JtJ = Eigen::MatrixXd::Zero(Eigen::Index(p), Eigen::Index(p));
    for (int r = 0; r < J.num_rows; ++r)
        for (int a = J.rows[size_t(r)]; a < J.rows[size_t(r) + 1]; ++a)
            for (int b = J.rows[size_t(r)]; b < J.rows[size_t(r) + 1]; ++b)
                JtJ(J.cols[size_t(a)], J.cols[size_t(b)]) += J.values[size_t(a)] * J.values[size_t(b)];
    const Eigen::MatrixXd C = JtJ.completeOrthogonalDecomposition().pseudoInverse();
    const double s2 = 2.0 * cost / std::max(1.0, double(P.y.size()) - double(p));
    for (size_t i = 0; i < p; ++i)
        out.stddev[size_t(P.free_idx[i])] = C(Eigen::Index(i), Eigen::Index(i)) > 0 ? std::sqrt(C(Eigen::Index(i), Eigen::Index(i)) * s2) : kNaN;
    return out;
}

// Fits the effect set: earlier effects start at `init`, the last one from each
// of its starts (screened by cost first when it is a grid); returns the best.
FitOutcome fit_set(FitProblem& P, const std::vector<double>& init, int max_iter)
{
    const EffectSetup& last = P.effects.back();
    std::vector<std::vector<double>> starts;
    for (const std::vector<double>& st : last.starts) {
        std::vector<double> th = init;
        th.insert(th.end(), st.begin(), st.end());
        starts.push_back(th);
    }
    if (last.screen && starts.size() > 3) {
        std::vector<std::pair<double, size_t>> c;
        for (size_t i = 0; i < starts.size(); ++i) c.push_back({P.cost(starts[i]), i});
        std::sort(c.begin(), c.end());
        std::vector<std::vector<double>> keep;
        for (size_t i = 0; i < 3; ++i) keep.push_back(starts[c[i].second]);
        starts = keep;
    }
    FitOutcome best;
    for (const std::vector<double>& st : starts) {
        FitOutcome o = refine(P, st, max_iter);
        if (o.cost < best.cost) best = o;
    }
    return best;
}

struct Evaluator {
    const ReplaySetup* eval;
    Eigen::MatrixXd y_eval;  // measured held-out rows
    Eigen::Index first, n;
    double gap_before;
    double Ts;
    std::vector<double> scale;  // std of each output over the whole evaluated record
    std::vector<double> weight; // channel weights of the aggregate gap (empty: equal)

    Eigen::MatrixXd simulate(const std::vector<EffectInstance>& eff) const
    {
        const ReplayTrace tr = replay(*eval, eff, first + n);
        return tr.y.bottomRows(n);
    }
};

// Why the data do not identify a fitted parameter (normalized value x, std
// sd), or "" when they do: at a bound (within 0.1 % of the bound range, or
// 1e-6 of an unbounded side's scale), no std (a flat or singular cost), or a
// std larger than the value (the data cannot tell it from zero).
std::string unidentified_reason(double x, double sd, const ParamSpec& p)
{
    char b[160];
    // "At a bound": the bound lies within two standard deviations of the
    // estimate (the data cannot tell the value from the bound), or within
    // 0.1 % of the parameter's scale (normalized units are the data's scale
    // of it, ParamSpec) where there is no uncertainty estimate. Not 0.1 % of
    // the range: the ranges are up to 1e3 scales wide, so that flagged arm_b's
    // Coulomb 5.93 +- 0.001 N m as "at its lower bound 0".
    double tol = std::isfinite(p.hi - p.lo) ? std::min(1e-3 * (p.hi - p.lo), 1e-3) : 1e-6;
    if (std::isfinite(sd)) tol = std::max(tol, 2.0 * std::fabs(sd));
    if (std::fabs(x - p.lo) <= tol) {
        std::snprintf(b, sizeof b, "at its lower bound %.4g", p.lo * p.scale);
        return b;
    }
    if (std::fabs(x - p.hi) <= tol) {
        std::snprintf(b, sizeof b, "at its upper bound %.4g", p.hi * p.scale);
        return b;
    }
    if (!std::isfinite(sd)) return "no uncertainty estimate (the cost is flat in it)";
    if (sd > std::fabs(x)) {
        std::snprintf(b, sizeof b, "std %.3g exceeds |value| %.3g", std::fabs(sd * p.scale), std::fabs(x * p.scale));
        return b;
    }
    return "";
}

FitReport make_report(const FitProblem& P, const FitOutcome& o, const Evaluator& E, double penalty)
{
    FitReport r;
    r.effects = P.instances(o.theta);
    size_t k = 0;
    for (const EffectSetup& e : P.effects) {
        std::vector<double> sd;
        std::vector<std::string> why;
        for (const ParamSpec& p : e.spec) {
            sd.push_back(p.fixed ? kNaN : p.scale * o.stddev[k]);
            why.push_back(p.fixed ? "" : unidentified_reason(o.theta[k], o.stddev[k], p));
            r.fitted_params += 1;
            ++k;
        }
        r.stddev.push_back(sd);
        r.unidentified.push_back(why);
    }
    const Eigen::MatrixXd yhat = E.simulate(r.effects);
    r.gap_after = nrmse(E.y_eval, yhat, E.scale);
    r.gap = total_gap(r.gap_after, E.weight);
    if (!std::isfinite(r.gap)) r.gap = std::numeric_limits<double>::infinity();
    r.shrink = E.gap_before > 0 ? 1.0 - r.gap / E.gap_before : 0.0;
    r.score = r.shrink - penalty * r.fitted_params;
    r.solver = o.brief;
    r.band_nrmse = band_nrmse(E.y_eval, yhat, E.Ts, E.scale);
    return r;
}

std::vector<double> normalized(const FitProblem& P, const std::vector<EffectInstance>& eff)
{
    std::vector<double> th;
    for (size_t i = 0; i < eff.size(); ++i)
        for (size_t j = 0; j < eff[i].params.size(); ++j) th.push_back(eff[i].params[j] / P.effects[i].spec[j].scale);
    return th;
}

// ---- where: time windows ------------------------------------------------------

std::vector<Window> flag_windows(const Eigen::VectorXd& res, const ReplayTrace& nom, double Ts, double t0,
                                 double torque_limit)
{
    const Eigen::Index N = res.size();
    const Eigen::Index W = std::max<Eigen::Index>(10, N / 40);
    std::vector<double> wr;
    for (Eigen::Index s = 0; s + W <= N; s += W) wr.push_back(rms(res.segment(s, W)));
    if (wr.empty()) return {};
    std::vector<double> sorted = wr;
    std::sort(sorted.begin(), sorted.end());
    const double med = sorted[sorted.size() / 2], q85 = sorted[sorted.size() * 85 / 100];
    const double vmax = nom.v.cwiseAbs().maxCoeff();
    Eigen::VectorXd a = Eigen::VectorXd::Zero(N);
    for (Eigen::Index k = 1; k < N; ++k) a(k) = (nom.v(k) - nom.v(k - 1)) / Ts;
    const double amax = a.cwiseAbs().maxCoeff();
    std::vector<Window> out;
    for (size_t i = 0; i < wr.size(); ++i) {
        if (!(wr[i] >= 1.25 * med && wr[i] >= q85 && wr[i] > 0)) continue;
        const Eigen::Index s = Eigen::Index(i) * W;
        std::vector<std::string> cond;
        if (vmax > 0) {
            bool reversal = false;
            for (Eigen::Index k = s; k + 1 < s + W; ++k)
                if (nom.v(k) * nom.v(k + 1) < 0) reversal = true;
            const Eigen::VectorXd seg = nom.v.segment(s, W).cwiseAbs();
            if (reversal && seg.maxCoeff() > 0.05 * vmax) cond.push_back("velocity reversal");
            std::vector<double> sv(seg.data(), seg.data() + W);
            std::nth_element(sv.begin(), sv.begin() + W / 2, sv.end());
            if (sv[size_t(W / 2)] < 0.02 * vmax) cond.push_back("standstill");
            if (amax > 0 && a.segment(s, W).cwiseAbs().maxCoeff() > 0.5 * amax) cond.push_back("high acceleration");
        }
        if (torque_limit > 0 && nom.u.segment(s, W).cwiseAbs().maxCoeff() >= 0.9 * torque_limit)
            cond.push_back("near torque limit");
        std::string c;
        for (const std::string& x : cond) c += (c.empty() ? "" : "+") + x;
        if (c.empty()) c = "steady motion";
        const double ta = t0 + double(s) * Ts, tb = t0 + double(s + W) * Ts;
        if (!out.empty() && std::fabs(out.back().t1 - ta) < 0.5 * Ts && out.back().condition == c) {
            out.back().t1 = tb;
            out.back().rms = std::max(out.back().rms, wr[i]);
        } else {
            out.push_back({ta, tb, wr[i], c});
        }
    }
    return out;
}

// A compared channel of `rec`: finite statistics and a nonzero spread, or
// one clear error naming the channel.
void check_channel(const Signals& rec, const std::string& name)
{
    const Eigen::VectorXd y = rec.col(name);
    Eigen::Index kmax = 0;
    const double amax = y.cwiseAbs().maxCoeff(&kmax);
    const double mean = y.mean(), var = (y.array() - mean).square().mean();
    char b[400];
    if (!std::isfinite(mean) || !std::isfinite(var)) {
        std::snprintf(b, sizeof b,
                      "output '%s' of %s: its statistics overflow (a sample of %.4g at t = %.6g s); values must stay "
                      "below about 1e150 in magnitude",
                      name.c_str(), rec.source.c_str(), y(kmax), rec.t0 + double(kmax) * rec.Ts);
        throw std::runtime_error(b);
    }
    if (!(var > 0) || std::sqrt(var) <= 1e-14 * std::max(amax, 1e-300)) {
        std::snprintf(b, sizeof b,
                      "output '%s' of %s is constant (%.6g over all %ld samples): the gap is relative to an output's "
                      "variation; leave it out with --outputs",
                      name.c_str(), rec.source.c_str(), y(0), long(y.size()));
        throw std::runtime_error(b);
    }
}

// Refuses a nominal whose replay on the recorded inputs is not finite or
// runs away: a residual above 1000 x the output's std is not a gap but a
// divergence (an unstable nominal, or a wrong loop sign).
void check_nominal_replay(const NominalModel& model, const ReplayTrace& nom, const Eigen::MatrixXd& ymeas,
                          const std::vector<std::string>& outs, const std::string& source)
{
    for (Eigen::Index c = 0; c < ymeas.cols(); ++c) {
        const Eigen::VectorXd y = ymeas.col(c);
        const double sd = std::sqrt((y.array() - y.mean()).square().mean());
        const bool finite = nom.y.col(c).allFinite();
        const double worst = finite ? (nom.y.col(c) - y).cwiseAbs().maxCoeff() : std::numeric_limits<double>::infinity();
        if (finite && worst <= 1e3 * sd) continue;
        Eigen::EigenSolver<Eigen::MatrixXd> es(model.A, false);
        const double rho = es.eigenvalues().cwiseAbs().maxCoeff();
        char b[500];
        std::snprintf(b, sizeof b,
                      "the nominal model's replay diverges on %s: output '%s' %s against a recorded std of %.4g (the "
                      "replay must stay within 1000 stds of the record); the plant's largest eigenvalue is |z| = %.6g "
                      "per sample%s",
                      source.c_str(), outs[size_t(c)].c_str(),
                      finite ? ("is off by " + std::to_string(worst)).c_str() : "becomes infinite or NaN", sd, rho,
                      rho > 1.0 + 1e-9 ? (model.closed_loop ? " (unstable open loop: check the loop closes it)" : " (unstable)") : "");
        throw std::runtime_error(b);
    }
}

// The verdict's confidence (GapResult::Confidence): the runner-up to the
// verdict's first effect among the single candidates (none included), the
// score margin, and the candidates that remove the same share of the
// held-out gap as the first within `margin` (shrink difference; a relative
// gap difference would separate two fits that both reach the noise floor),
// with the experiments that separate them.
// A verdict holding both unmodelled_mode and mode_shift names the added
// mode first: a mode coupled into the structure moves its neighbours
// (interlacing), so the record's shifted mode is its consequence.
void added_mode_first(FitReport& v)
{
    size_t iu = v.effects.size(), is = v.effects.size();
    for (size_t i = 0; i < v.effects.size(); ++i) {
        if (v.effects[i].kind == Effect::unmodelled_mode) iu = i;
        if (v.effects[i].kind == Effect::mode_shift) is = i;
    }
    if (iu == v.effects.size() || is > iu) return;
    auto to_front = [&](auto& vec) {
        if (iu < vec.size()) std::rotate(vec.begin(), vec.begin() + long(iu), vec.begin() + long(iu) + 1);
    };
    to_front(v.effects);
    to_front(v.stddev);
    to_front(v.unidentified);
}

GapResult::Confidence confidence_of(const std::vector<FitReport>& candidates, const FitReport& verdict, double margin)
{
    GapResult::Confidence c;
    auto name = [](const FitReport& f) { return f.effects.empty() ? std::string("none") : effect_name(f.effects[0].kind); };
    c.first = name(verdict);
    const FitReport* first = nullptr;
    for (const FitReport& f : candidates)
        if (name(f) == c.first) {
            first = &f;
            break;
        }
    if (!first) return c;
    for (const FitReport& f : candidates) {
        if (&f == first) continue;
        if (c.runner_up.empty()) {
            c.runner_up = name(f);
            c.margin = first->score - f.score;
        }
        if (f.effects.empty() || first->effects.empty()) continue;
        if (f.shrink >= first->shrink - margin) {
            const EffectDescriptor &a = descriptor(first->effects[0].kind), &b = descriptor(f.effects[0].kind);
            std::string x = std::string("to separate ") + a.name + " from " + b.name + ", record " + a.reveals;
            if (std::string(a.reveals) != b.reveals) x += std::string("; and ") + b.reveals;
            c.look_alikes.push_back({b.name, f.gap, x});
        }
    }
    return c;
}

}  // namespace

GapResult diagnose(const NominalModel& model, const Signals& data, const Signals* validate, const GapOptions& opt)
{
    const auto t_start = std::chrono::steady_clock::now();
    GapResult R;
    R.model_name = model.name;
    R.realization = model.realization;
    R.data_source = data.source;
    R.Ts = data.Ts;
    if (validate && std::fabs(validate->Ts - data.Ts) > 1e-3 * data.Ts)
        throw std::runtime_error("the validation record's sample time differs from the data's");
    if (!(opt.holdout > 0 && opt.holdout < 1)) throw std::runtime_error("held-out fraction must be in (0, 1)");
    std::vector<std::string> outs = opt.outputs;
    if (outs.empty())
        for (const std::string& o : model.outputs)
            if (data.has(o)) outs.push_back(o);
    if (outs.empty())
        throw std::runtime_error("model/data mismatch: none of the model outputs is a column of " + data.source);
    R.outputs = outs;
    R.units = model_units(model, outs);
    // gap.noise: every compared output needs its sensor's std.
    std::vector<double> noise_sd;
    if (!model.noise.empty())
        for (const std::string& o : outs) {
            const auto it = model.noise.find(o);
            if (it == model.noise.end())
                throw std::runtime_error("model gap.noise: states no std for the compared output '" + o +
                                         "'; give one for every compared output, or leave gap.noise out");
            noise_sd.push_back(it->second);
        }
    for (const Coupling& c : model.couplings) R.coupling_names.push_back(c.name);
    ReplaySetup fit_setup = make_replay_setup(model, data, opt.inputs, outs);
    for (const PlantMode& pm : fit_setup.plant_modes) R.mode_names.push_back(plant_mode_name(pm));
    ReplaySetup eval_setup_v;
    if (validate) eval_setup_v = make_replay_setup(model, *validate, opt.inputs, outs);
    const ReplaySetup& eval_setup = validate ? eval_setup_v : fit_setup;
    const Eigen::Index N = data.samples();
    R.fit_samples = validate ? N : Eigen::Index(std::floor((1.0 - opt.holdout) * double(N)));
    R.eval_first = validate ? 0 : R.fit_samples;
    R.eval_samples = validate ? validate->samples() : N - R.fit_samples;
    R.eval_source = validate ? validate->source : data.source + " (last " + std::to_string(int(opt.holdout * 100 + 0.5)) + " %)";
    if (R.fit_samples < 20 || R.eval_samples < 20) throw std::runtime_error("record too short to split into fit and held-out parts");

    Eigen::MatrixXd ymeas(N, Eigen::Index(outs.size()));
    for (size_t c = 0; c < outs.size(); ++c) ymeas.col(Eigen::Index(c)) = data.col(outs[c]);
    const Signals& evsig = validate ? *validate : data;
    Eigen::MatrixXd yeval(R.eval_samples, Eigen::Index(outs.size()));
    for (size_t c = 0; c < outs.size(); ++c)
        yeval.col(Eigen::Index(c)) = evsig.col(outs[c]).segment(R.eval_first, R.eval_samples);

    // Every compared channel must vary, and its statistics must be finite:
    // the gap is relative to the output's own variation.
    const Signals& evrec = validate ? *validate : data;
    for (const Signals* rec : {&data, &evrec})
        for (const std::string& o : outs) check_channel(*rec, o);

    // Nominal replay and its residuals; a replay that diverges or leaves the
    // data's range by orders of magnitude is refused (no verdict is honest on it).
    const ReplayTrace nom = replay(fit_setup, {});
    check_nominal_replay(model, nom, ymeas, outs, data.source);
    FitContext ctx;
    ctx.Ts = data.Ts;
    ctx.fit_samples = R.fit_samples;
    ctx.fit_seconds = double(R.fit_samples) * data.Ts;
    ctx.Su = std::max(rms(nom.u.head(R.fit_samples)), 1e-12);
    ctx.Sv = std::max(rms(nom.v.head(R.fit_samples)), 1e-12);
    ctx.umax = std::max(nom.u.head(R.fit_samples).cwiseAbs().maxCoeff(), 1e-12);
    // Each coupling's scales (FitContext::Sq, kq, wq), set into ctx per site below.
    std::vector<double> coupling_Sq;
    for (size_t i = 0; i < model.couplings.size(); ++i)
        coupling_Sq.push_back(rms(nom.twists.col(Eigen::Index(i)).head(R.fit_samples)));
    fit_setup.eps_velocity = 0.01 * ctx.Sv;
    if (validate) eval_setup_v.eps_velocity = fit_setup.eps_velocity;
    std::vector<double> sigma;
    Eigen::MatrixXd resn(N, Eigen::Index(outs.size()));
    for (size_t c = 0; c < outs.size(); ++c) {
        const Eigen::VectorXd yc = ymeas.col(Eigen::Index(c)).head(R.fit_samples);
        const double sd = std::sqrt((yc.array() - yc.mean()).square().mean());
        sigma.push_back(sd > 0 ? sd : 1.0);
        ctx.Sy.push_back(sigma.back());
        double q = std::numeric_limits<double>::infinity();
        for (Eigen::Index k = 1; k < R.fit_samples; ++k) {
            const double d = std::fabs(yc(k) - yc(k - 1));
            if (d > 1e-12 * sigma.back()) q = std::min(q, d);
        }
        // The step: the smallest nonzero change, refined as the least-squares
        // scale of the measured values as integer multiples of it (a step
        // that the logger rounds again, e.g. to a wire resolution, is then
        // not off by that rounding).
        // Passes over |y| <= 5 q, <= 50 q, <= 500 q, then all: the multiples
        // n stay exact while the step is still off by up to 10 %.
        for (const double reach : {5.0, 50.0, 500.0, std::numeric_limits<double>::infinity()}) {
            if (!std::isfinite(q)) break;
            double num = 0, den = 0;
            for (Eigen::Index k = 0; k < R.fit_samples; ++k) {
                if (std::fabs(yc(k)) > reach * q) continue;
                const double n = std::round(yc(k) / q);
                num += n * yc(k);
                den += n * n;
            }
            if (den > 0 && std::fabs(num / den - q) < 0.5 * q) q = num / den;
        }
        resn.col(Eigen::Index(c)) = (ymeas.col(Eigen::Index(c)) - nom.y.col(Eigen::Index(c))) / sigma.back();
        // A step finer than the white part of the residual is dithered by
        // the noise: the reading's cell then says nothing the noise does not.
        // White level: sigma_w = rms(r(k) - (r(k-1) + r(k+1))/2) / sqrt(1.5)
        // of the nominal residual (a quantization error of step q alone gives
        // sigma_w = q/sqrt(12)); the step is used when q >= 2 sigma_w, i.e.
        // q >= 2.45 x the noise std.
        double hf = 0;
        for (Eigen::Index k = 1; k + 1 < R.fit_samples; ++k) {
            const double d = resn(k, Eigen::Index(c)) - 0.5 * (resn(k - 1, Eigen::Index(c)) + resn(k + 1, Eigen::Index(c)));
            hf += d * d;
        }
        const double sigma_w = sigma.back() * std::sqrt(hf / double(std::max<Eigen::Index>(1, R.fit_samples - 2)) / 1.5);
        // And the data must lie on the lattice: rms distance to it below
        // q/10 (values off any lattice give q/sqrt(12) = 0.29 q).
        double off = 0;
        for (Eigen::Index k = 0; std::isfinite(q) && k < R.fit_samples; ++k) off += std::pow(yc(k) - q * std::round(yc(k) / q), 2);
        const bool lattice = std::isfinite(q) && std::sqrt(off / double(R.fit_samples)) < 0.1 * q;
        ctx.quant_step.push_back(lattice && q >= 2 * sigma_w ? q : 0.0);
    }
    // Residual peaks (fit part), for the mode candidates' start frequencies.
    {
        Eigen::VectorXd rsum = resn.topRows(R.fit_samples).rowwise().sum();
        rsum.array() -= rsum.mean();
        const std::vector<double> S = smoothed_spectrum(rsum);
        const double df = 1.0 / (double(fft_length(R.fit_samples)) * data.Ts);
        std::vector<std::pair<double, size_t>> peaks;
        for (size_t k = 2; k + 1 < S.size(); ++k)
            if (S[k] >= S[k - 1] && S[k] >= S[k + 1]) peaks.push_back({S[k], k});
        std::sort(peaks.rbegin(), peaks.rend());
        for (size_t i = 0; i < peaks.size() && ctx.residual_peaks_hz.size() < 3; ++i) {
            const double f = double(peaks[i].second) * df;
            bool near = false;
            for (double g : ctx.residual_peaks_hz) near = near || std::fabs(f - g) < 0.2 * g;
            if (!near) ctx.residual_peaks_hz.push_back(f);
        }
    }

    Evaluator E{&eval_setup, yeval, R.eval_first, R.eval_samples, 0.0, data.Ts, {}, {}};
    for (size_t c = 0; c < outs.size(); ++c) {
        const Eigen::VectorXd yc = evsig.col(outs[c]);
        E.scale.push_back(std::sqrt((yc.array() - yc.mean()).square().mean()));
    }
    const Eigen::MatrixXd yhat_nom = E.simulate({});
    R.gap_before = nrmse(yeval, yhat_nom, E.scale);
    // gap.noise: channels weighted by (std/noise)^2 in the aggregate gap,
    // and the floor the noise alone leaves.
    if (!noise_sd.empty()) {
        std::vector<double> floor;
        for (size_t c = 0; c < outs.size(); ++c) {
            E.weight.push_back(std::pow(E.scale[c] / noise_sd[c], 2));
            floor.push_back(noise_sd[c] / E.scale[c]);
        }
        R.noise_floor = total_gap(floor, E.weight);
    }
    R.gap_before_total = total_gap(R.gap_before, E.weight);
    E.gap_before = R.gap_before_total;
    R.band_nrmse_before = band_nrmse(yeval, yhat_nom, data.Ts, E.scale);

    // Where: bands of the nominal residual (whole record, normalized outputs).
    const auto bands = band_edges(data.Ts);
    {
        Eigen::MatrixXd r0 = resn;
        const Eigen::MatrixXd Eb = band_energy(r0, data.Ts, bands);
        const double tot = Eb.sum();
        for (size_t b = 0; b < bands.size(); ++b)
            R.bands.push_back({bands[b].first, bands[b].second, tot > 0 ? Eb.row(Eigen::Index(b)).sum() / tot : 0.0});
    }
    // Where: modes of the nominal, checked against the measured spectrum.
    // Both records answer the same excitation, so where the measured
    // response has a resonance the model lacks, the ratio of their spectra
    // peaks (outputs divided by their std, spectra summed over outputs);
    // the raw spectra's peaks would mostly show the excitation's shape.
    {
        std::vector<double> Sa_sum, Sb_sum, Sr_sum;
        for (size_t c = 0; c < outs.size(); ++c) {
            Eigen::VectorXd a = ymeas.col(Eigen::Index(c)) / sigma[c], b = nom.y.col(Eigen::Index(c)) / sigma[c];
            a.array() -= a.mean();
            b.array() -= b.mean();
            const std::vector<double> Sa = smoothed_spectrum(a), Sb = smoothed_spectrum(b),
                                      Sr = smoothed_spectrum(resn.col(Eigen::Index(c)));
            if (Sa_sum.empty()) Sa_sum.assign(Sa.size(), 0.0), Sb_sum.assign(Sa.size(), 0.0), Sr_sum.assign(Sa.size(), 0.0);
            for (size_t k = 0; k < Sa.size(); ++k) Sa_sum[k] += Sa[k], Sb_sum[k] += Sb[k], Sr_sum[k] += Sr[k];
        }
        const double df = 1.0 / (double(fft_length(N)) * data.Ts);
        double tot = 0;
        for (size_t k = 1; k < Sr_sum.size(); ++k) tot += Sr_sum[k];
        for (const Mode& md : model.modes()) {
            // Resonant modes only (zeta < 1/sqrt(2): a resonance peak exists).
            if (md.zeta >= M_SQRT1_2 || md.f_hz > 0.4 / data.Ts || md.f_hz * double(N) * data.Ts < 4) continue;
            ModeCheck mc{md.f_hz, md.zeta, 0, 0, 0, 0, "ok"};
            const double flo = md.f_hz / 1.5, fhi = md.f_hz * 1.5;
            double share = 0, ps = 0, rmax = 0, ratio_at_f = kNaN, bmax = 0;
            for (size_t k = 1; k < Sa_sum.size(); ++k) bmax = std::max(bmax, Sb_sum[k]);
            for (size_t k = 1; k < Sa_sum.size(); ++k) {
                const double f = double(k) * df;
                if (f < flo || f > fhi) continue;
                share += Sr_sum[k];
                if (Sb_sum[k] > ps) { ps = Sb_sum[k]; mc.model_peak_hz = f; }
                // Bins where the model has next to no energy carry no ratio.
                if (Sb_sum[k] < 1e-6 * bmax) continue;
                const double rho = Sa_sum[k] / Sb_sum[k];
                if (rho > rmax) { rmax = rho; mc.measured_peak_hz = f; }
                if (std::fabs(f - md.f_hz) <= 0.5 * df) ratio_at_f = rho;
            }
            mc.residual_share = tot > 0 ? share / tot : 0;
            mc.peak_ratio = rmax > 0 ? rmax : kNaN;
            // Shifted: the ratio peaks > 10 % of f away from f, more than 2x
            // above its value at f (energy moved from f to the true mode);
            // mis-damped: at f the measured energy is off by more than 2x.
            const double contrast = std::isfinite(ratio_at_f) && ratio_at_f > 0 ? rmax / ratio_at_f : kNaN;
            if (std::fabs(mc.measured_peak_hz - md.f_hz) > 0.1 * md.f_hz && contrast > 2.0) mc.flag = "shifted";
            else if (ratio_at_f > 2.0 || ratio_at_f < 0.5) mc.flag = "mis-damped";
            R.modes.push_back(mc);
        }
    }
    // mode_shift's starts: each checked mode's measured peak.
    for (const ModeCheck& mc : R.modes) ctx.mode_checks.push_back({mc.f_hz, mc.measured_peak_hz});
    // Where: time windows with their operating condition.
    {
        Eigen::VectorXd r = resn.rowwise().norm() / std::sqrt(double(outs.size()));
        const double cl_limit = model.closed_loop ? std::min(model.loop.saturation, model.loop.controller->output_limit())
                                                  : std::numeric_limits<double>::infinity();
        const double limit = std::isfinite(cl_limit) ? cl_limit : nom.u.cwiseAbs().maxCoeff();
        R.windows = flag_windows(r, nom, data.Ts, data.t0, limit);
    }

    // Which: every candidate alone.
    FitProblem base_problem;
    base_problem.setup = &fit_setup;
    base_problem.y = ymeas.topRows(R.fit_samples);
    base_problem.sigma = noise_sd.empty() ? sigma : noise_sd;  // gap.noise: residuals in units of the sensor's noise
    // The single fits are independent: they run on opt.threads workers
    // (each job's result lands in its own slot, so the outcome does not
    // depend on the thread count or the order the jobs finish in).
    struct Job {
        size_t effect;
        EffectSetup setup;
    };
    std::vector<Job> jobs;
    for (size_t ie = 0; ie < opt.effects.size(); ++ie) {
        const Effect e = opt.effects[ie];
        // The effect at the force input and, for backlash and fractional
        // damping with a declared coupling, in the coupling: each variant is
        // fitted, the one with the better score is the effect's candidate.
        // The effect at each of its sites on this model (effect_sites: the
        // force input, the outputs, each declared coupling): each variant is
        // fitted, the one with the better score is the effect's candidate.
        std::vector<EffectSetup> variants;
        for (const std::pair<Site, int>& site : effect_sites(e, model)) {
            if (site.first == Site::coupling) {
                const Coupling& cp = model.couplings[size_t(site.second)];
                if (!(coupling_Sq[size_t(site.second)] > 0)) {
                    R.skipped.push_back(effect_name(e) + " in the coupling '" + cp.name + "': the nominal replay never deflects it");
                    continue;
                }
                FitContext cc = ctx;
                cc.Sq = coupling_Sq[size_t(site.second)];
                cc.kq = cp.stiffness;
                cc.wq = cp.w_slow;
                cc.coupling = site.second;
                variants.push_back(descriptor(e).setup(cc, Site::coupling));
            } else if (site.first == Site::mode) {
                // mode_shift at one resonant plant mode (FitContext::mode_f_hz, mode_zeta).
                FitContext cc = ctx;
                cc.mode_f_hz = fit_setup.plant_modes[size_t(site.second)].f_hz;
                cc.mode_zeta = fit_setup.plant_modes[size_t(site.second)].zeta;
                cc.coupling = site.second;
                variants.push_back(descriptor(e).setup(cc, Site::mode));
            } else if (needs_velocity(e) && model.velocity < 0) {
                R.skipped.push_back(effect_name(e) + (model.couplings.empty() ? "" : " at the force input") +
                                    ": the model names no velocity output (gap.velocity)");
            } else {
                variants.push_back(descriptor(e).setup(ctx, site.first));
            }
        }
        for (const EffectSetup& es : variants) {
            if (es.starts.empty()) {
                R.skipped.push_back(effect_name(e) + (e == Effect::quantization
                                                           ? ": no output's data lie on a lattice coarser than its noise"
                                                           : ": no start value from the data"));
                continue;
            }
            jobs.push_back({ie, es});
        }
    }
    std::vector<FitReport> job_report(jobs.size());
    {
        std::atomic<size_t> next{0};
        size_t done = 0;
        std::mutex mu;
        std::exception_ptr failure;
        auto work = [&]() {
            for (size_t i = next++; i < jobs.size(); i = next++) {
                try {
                    FitProblem P = base_problem;
                    P.effects = {jobs[i].setup};
                    const FitOutcome o = fit_set(P, {}, opt.max_iterations);
                    job_report[i] = make_report(P, o, E, opt.param_penalty);
                } catch (...) {
                    std::lock_guard<std::mutex> lk(mu);
                    if (!failure) failure = std::current_exception();
                }
                std::lock_guard<std::mutex> lk(mu);
                ++done;
                if (opt.progress)
                    opt.progress("gap: fitted " + std::to_string(done) + "/" + std::to_string(jobs.size()) + " candidates (" +
                                 effect_name(jobs[i].setup.kind) +
                                 (jobs[i].setup.site == Site::coupling
                                      ? " in the coupling '" + model.couplings[size_t(jobs[i].setup.coupling)].name + "'"
                                      : jobs[i].setup.site == Site::output ? " at the outputs" : "") + ")");
            }
        };
        const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
        const size_t nthreads = std::min<size_t>(jobs.size(), opt.threads > 0 ? size_t(opt.threads) : size_t(hw));
        std::vector<std::thread> pool;
        for (size_t t = 1; t < nthreads; ++t) pool.emplace_back(work);
        work();
        for (std::thread& t : pool) t.join();
        if (failure) std::rethrow_exception(failure);
    }
    std::vector<std::pair<FitReport, EffectSetup>> singles;
    for (size_t ie = 0; ie < opt.effects.size(); ++ie) {
        bool have = false;
        std::pair<FitReport, EffectSetup> best;
        for (size_t i = 0; i < jobs.size(); ++i) {
            if (jobs[i].effect != ie) continue;
            if (!have || job_report[i].score > best.first.score) best = {job_report[i], jobs[i].setup};
            have = true;
        }
        if (have) singles.push_back(best);
    }
    for (const auto& s : singles) R.candidates.push_back(s.first);
    FitReport none;
    none.gap_after = R.gap_before;
    none.gap = R.gap_before_total;
    none.band_nrmse = R.band_nrmse_before;
    none.solver = "nominal model";
    R.candidates.push_back(none);
    std::stable_sort(R.candidates.begin(), R.candidates.end(),
                     [](const FitReport& a, const FitReport& b) { return a.score > b.score; });
    std::sort(singles.begin(), singles.end(),
              [](const std::pair<FitReport, EffectSetup>& a, const std::pair<FitReport, EffectSetup>& b) {
                  return a.first.score > b.first.score;
              });
    // Nested effects: stribeck_friction contains coulomb_friction (Fs = Fc);
    // it ranks above it only when it lowers the held-out gap by the margin.
    // Likewise mode_shift (any change seen at one mode: near a mode, Kelvin-
    // Voigt damping in a spring or an added mode coupled to it moves that
    // mode's frequency and damping) ranks above fractional_damping and
    // unmodelled_mode, the mechanisms, only by the margin.
    auto nested_rule = [&](auto& list, auto report_of, Effect contained, Effect container) {
        int ic = -1, is = -1;
        for (size_t i = 0; i < list.size(); ++i) {
            const FitReport& f = report_of(list[i]);
            if (f.effects.size() != 1) continue;
            if (f.effects[0].kind == contained) ic = int(i);
            if (f.effects[0].kind == container) is = int(i);
        }
        if (ic > is && is >= 0 && report_of(list[size_t(is)]).gap > (1.0 - opt.margin) * report_of(list[size_t(ic)]).gap) {
            auto moved = list[size_t(ic)];
            list.erase(list.begin() + ic);
            list.insert(list.begin() + is, moved);
        }
    };
    for (const std::pair<Effect, Effect>& n : {std::pair<Effect, Effect>{Effect::coulomb_friction, Effect::stribeck_friction},
                                               {Effect::fractional_damping, Effect::mode_shift},
                                               {Effect::unmodelled_mode, Effect::mode_shift}}) {
        nested_rule(R.candidates, [](const FitReport& f) -> const FitReport& { return f; }, n.first, n.second);
        nested_rule(singles, [](const std::pair<FitReport, EffectSetup>& p) -> const FitReport& { return p.first; }, n.first,
                    n.second);
    }

    // Forward selection: add the best, refit all jointly, repeat while the
    // held-out gap shrinks by at least `margin` (relative) and the penalized score grows.
    R.verdict = none;
    const bool at_noise_floor = R.noise_floor > 0 && R.gap_before_total <= kNoiseFloorFactor * R.noise_floor;
    if (!at_noise_floor && !singles.empty() && singles.front().first.score >= opt.margin) {
        FitProblem cur = base_problem;
        cur.effects = {singles.front().second};
        FitReport best = singles.front().first;
        std::vector<double> theta = normalized(cur, best.effects);
        std::vector<bool> used(singles.size(), false);
        used[0] = true;
        while (int(cur.effects.size()) < opt.max_effects) {
            int pick = -1;
            FitReport pick_rep;
            std::vector<double> pick_theta;
            FitProblem pick_prob;
            int tried = 0;
            for (size_t i = 0; i < singles.size() && tried < 3; ++i) {
                if (used[i] || singles[i].first.score <= 0) continue;
                ++tried;
                // The new effect starts from its single fit, the others from the current set.
                FitProblem P = cur;
                EffectSetup es = singles[i].second;
                FitProblem solo = base_problem;
                solo.effects = {es};
                es.starts = {normalized(solo, singles[i].first.effects)};
                P.effects.push_back(es);
                const FitOutcome o = fit_set(P, theta, opt.max_iterations / 2);
                FitReport rep = make_report(P, o, E, opt.param_penalty);
                if (pick < 0 || rep.gap < pick_rep.gap) {
                    pick = int(i);
                    pick_rep = rep;
                    pick_theta = o.theta;
                    pick_prob = P;
                }
            }
            if (pick < 0 || !(pick_rep.gap <= (1.0 - opt.margin) * best.gap) || pick_rep.score <= best.score) break;
            used[size_t(pick)] = true;
            cur = pick_prob;
            theta = pick_theta;
            best = pick_rep;
        }
        R.verdict = best;
    }
    added_mode_first(R.verdict);
    R.confidence = confidence_of(R.candidates, R.verdict, opt.margin);

    // Traces for the report.
    const Eigen::Index n_tr = R.eval_first + R.eval_samples;
    const ReplayTrace aug = replay(eval_setup, R.verdict.effects, n_tr);
    const ReplayTrace nomtr = replay(eval_setup, {}, n_tr);
    R.t = Eigen::VectorXd::LinSpaced(n_tr, evsig.t0, evsig.t0 + double(n_tr - 1) * data.Ts);
    R.measured.resize(n_tr, Eigen::Index(outs.size()));
    for (size_t c = 0; c < outs.size(); ++c) R.measured.col(Eigen::Index(c)) = evsig.col(outs[c]).head(n_tr);
    R.nominal = nomtr.y;
    R.augmented = aug.y;
    R.where_t = Eigen::VectorXd::LinSpaced(N, data.t0, data.t0 + double(N - 1) * data.Ts);
    R.where_residual = resn;
    R.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    return R;
}

namespace {

nlohmann::json num(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json per_output(const std::vector<std::string>& outs, const std::vector<double>& v)
{
    nlohmann::json j = nlohmann::json::object();
    for (size_t i = 0; i < outs.size() && i < v.size(); ++i) j[outs[i]] = num(v[i]);
    return j;
}

nlohmann::json fit_json(const GapResult& R, const FitReport& f, const std::vector<std::pair<double, double>>& bands)
{
    nlohmann::json params = nlohmann::json::object(), sd = nlohmann::json::object(), units = nlohmann::json::object(),
                   unid = nlohmann::json::object();
    std::vector<std::string> names, sites, couplings;
    for (size_t i = 0; i < f.effects.size(); ++i) {
        const EffectInstance& e = f.effects[i];
        sites.push_back(site_name(e.site));
        couplings.push_back(e.site == Site::coupling && size_t(e.coupling) < R.coupling_names.size()
                                ? R.coupling_names[size_t(e.coupling)]
                                : e.site == Site::mode && size_t(e.coupling) < R.mode_names.size() ? R.mode_names[size_t(e.coupling)] : "");
        const std::vector<ParamInfo> pn =
            descriptor(e.kind).params(R.outputs, units_at(R.units, e.site == Site::coupling ? e.coupling : -1), e.site);
        const std::string prefix = f.effects.size() > 1 ? effect_name(e.kind) + "." : "";
        for (size_t j = 0; j < pn.size(); ++j) {
            params[prefix + pn[j].name] = num(e.params[j]);
            sd[prefix + pn[j].name] = num(f.stddev[i][j]);
            units[prefix + pn[j].name] = pn[j].unit;
            if (i < f.unidentified.size() && !f.unidentified[i][j].empty()) unid[prefix + pn[j].name] = f.unidentified[i][j];
        }
        names.push_back(effect_name(e.kind));
    }
nlohmann::json bj = nlohmann::json::array();
    for (size_t b = 0; b < f.band_nrmse.size() && b < bands.size(); ++b)
        bj.push_back({{"band_hz", {bands[b].first, bands[b].second}}, {"nrmse", per_output(R.outputs, f.band_nrmse[b])}});
    nlohmann::json j = {{"params", params},         {"params_std", sd},     {"gap_after", per_output(R.outputs, f.gap_after)},
                        {"gap_after_total", num(f.gap)}, {"shrink", num(f.shrink)}, {"score", num(f.score)},
                        {"fitted_params", f.fitted_params}, {"bands", bj}, {"solver", f.solver},
                        {"params_unit", units}, {"unidentified", unid}};
    if (names.empty()) {
        names.push_back("none");
        sites.push_back("");
        couplings.push_back("");
    }
    j["effects"] = names;
    j["sites"] = sites;
    j["couplings"] = couplings;  // the coupling's name for effects in a coupling, the nominal mode's for mode_shift, else ""

    return j;
}

}  // namespace

nlohmann::json result_json(const GapResult& R)
{
    const auto bands = band_edges(R.Ts);
    nlohmann::json j;
    j["schema"] = "frac.gap";
    j["version"] = 1;
    j["metric"] = "nrmse";
    j["gap_before"] = per_output(R.outputs, R.gap_before);
    nlohmann::json bj = nlohmann::json::array(), wj = nlohmann::json::array(), mj = nlohmann::json::array();
    for (const auto& b : R.bands) bj.push_back({b[0], b[1], b[2]});
    for (const Window& w : R.windows) wj.push_back({w.t0, w.t1, w.condition});
    for (const ModeCheck& m : R.modes)
        mj.push_back({{"f_hz", m.f_hz}, {"zeta", m.zeta}, {"residual_share", num(m.residual_share)},
                      {"measured_peak_hz", num(m.measured_peak_hz)}, {"model_peak_hz", num(m.model_peak_hz)},
                      {"peak_ratio", num(m.peak_ratio)}, {"flag", m.flag}});
    j["where"] = {{"outputs", R.outputs}, {"bands_hz", bj}, {"windows_s", wj}, {"modes", mj}};
    nlohmann::json cj = nlohmann::json::array();
    for (const FitReport& f : R.candidates) {
        nlohmann::json c = fit_json(R, f, bands);
        c["effect"] = c["effects"][0];
        c["site"] = c["sites"][0];
        c["coupling"] = c["couplings"][0];
        c.erase("effects");
        c.erase("sites");
        c.erase("couplings");
        cj.push_back(c);
    }
    j["candidates"] = cj;
    j["verdict"] = fit_json(R, R.verdict, bands);
    nlohmann::json la = nlohmann::json::array();
    for (const GapResult::LookAlike& l : R.confidence.look_alikes)
        la.push_back({{"effect", l.effect}, {"gap_after_total", num(l.gap)}, {"experiment", l.experiment}});
    j["verdict"]["confidence"] = {{"first", R.confidence.first}, {"runner_up", R.confidence.runner_up},
                                  {"margin", num(R.confidence.margin)}, {"look_alikes", la}};
    nlohmann::json bb = nlohmann::json::array();
    for (size_t b = 0; b < R.band_nrmse_before.size() && b < bands.size(); ++b)
        bb.push_back({{"band_hz", {bands[b].first, bands[b].second}}, {"nrmse", per_output(R.outputs, R.band_nrmse_before[b])}});
    j["gap_before_total"] = num(R.gap_before_total);
    j["gap_before_bands"] = bb;
    j["criterion"] = {{"nrmse", "rms(measured - model) on held-out data / std(measured output over its whole record)"},
                      {"gap", "sqrt(mean over outputs of nrmse^2) on held-out data"},
                      {"shrink", "1 - gap_after/gap_before"},
                      {"score", "shrink - 0.005 * fitted parameters"},
                      {"nesting", "stribeck_friction ranks above coulomb_friction, mode_shift above fractional_damping and unmodelled_mode, only if its gap is >= 5 % (relative) lower; a verdict with unmodelled_mode and mode_shift names unmodelled_mode first"},
                      {"forward_selection", "add the best-scoring effect, refit jointly, keep it while the gap falls by >= 5 % (relative) and the score rises"}};
    j["data"] = {{"model", R.model_name}, {"fit", R.data_source}, {"held_out", R.eval_source},
                 {"fit_samples", R.fit_samples}, {"held_out_samples", R.eval_samples}, {"Ts", R.Ts}};
    if (R.noise_floor > 0) {
        j["noise_floor"] = num(R.noise_floor);
        j["criterion"]["noise_floor"] = "gap.noise: a gap_before_total within 1.1 x the noise floor is none; channels weighted by (std/noise)^2";
    }
    if (!R.realization.empty()) j["data"]["realization"] = R.realization;
    j["skipped"] = R.skipped;
    j["seconds"] = R.seconds;
    return j;
}

}  // namespace gap
}  // namespace fracdesign
