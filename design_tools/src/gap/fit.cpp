// fit.cpp - the fit of an effect set on the fit rows (Ceres) and its
// FitReport on held-out data: gap, shrink, score, parameter std and the
// parameters the data do not identify (see stages.hpp, docs/gap.md).
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "stages.hpp"

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

namespace {

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

}  // namespace

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
            if (!p.fixed && p.mirror < 0) P.free_idx.push_back(int(k));
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
    // Forward differences of relative step 1e-6 (Ceres' default), at least
    // sqrt(eps) of a closed loop's controller arithmetic (controller.hpp).
    ceres::NumericDiffOptions nd;
    const NominalModel& nm = *P.setup->model;
    if (nm.closed_loop && nm.loop.controller)
        nd.relative_step_size = std::max(nd.relative_step_size, std::sqrt(nm.loop.controller->arithmetic_epsilon()));
    auto* cf = new ceres::DynamicNumericDiffCostFunction<ReplayCost, ceres::FORWARD>(new ReplayCost{&P}, ceres::TAKE_OWNERSHIP, nd);
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

namespace {

// The starts of the set's last effect (after the earlier ones at `init`),
// screened by cost to the best three when it is a grid; then its seeded ones.
std::vector<std::vector<double>> screened_starts(const FitProblem& P, const std::vector<double>& init, size_t keep_n = 3)
{
    const EffectSetup& last = P.effects.back();
    const auto after_init = [&init](const std::vector<double>& st) {
        std::vector<double> th = init;
        th.insert(th.end(), st.begin(), st.end());
        return th;
    };
    std::vector<std::vector<double>> starts;
    for (const std::vector<double>& st : last.starts) starts.push_back(after_init(st));
    if (last.screen && starts.size() > keep_n) {
        std::vector<std::pair<double, size_t>> c;
        for (size_t i = 0; i < starts.size(); ++i) c.push_back({P.cost(starts[i]), i});
        std::sort(c.begin(), c.end());
        std::vector<std::vector<double>> keep;
        for (size_t i = 0; i < keep_n; ++i) keep.push_back(starts[c[i].second]);
        starts = keep;
    }
    for (const std::vector<double>& st : last.seeded) starts.push_back(after_init(st));
    return starts;
}

// The grid's values of one coordinate, with three geometric steps between
// neighbours of one sign (a 2-per-octave grid becomes 8 per octave).
std::vector<double> densified(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    std::vector<double> out;
    for (size_t i = 0; i < v.size(); ++i) {
        out.push_back(v[i]);
        if (i + 1 < v.size() && v[i] * v[i + 1] > 0)
            for (int t = 1; t < 4; ++t) out.push_back(v[i] * std::pow(v[i + 1] / v[i], t / 4.0));
    }
    return out;
}

// Starts from a coordinate search, for a last effect with two or more
// parameters that each act on their own part of the signal
// (ParamSpec::neutral: the edges of a dead zone or a saturation). The joint
// grid misses the true pair when the cost is a narrow valley in each edge:
// in a loop a limit set too tight costs more than none (the loop saturates
// where the machine did not, and a lightly damped arm rings), so on a grid
// of two per octave every pair is either off the valley or leaves one edge
// out of reach, where the cost is flat in it and the solver cannot move
// it (an outside arm's -0.56/+0.44 limits: the best pair refined to a
// lower of -0.49 and an upper of 0.56, above the command, with no held-out
// gain). Each coordinate alone, the others at their neutral value, is a
// one-dimensional search on the grid made 4 times finer and refined; the
// start of the joint refine is every coordinate at its own optimum, and
// each coordinate's optimum alone (the record may reach one edge only).
std::vector<std::vector<double>> coordinate_starts(const FitProblem& P, const std::vector<double>& init, int max_iter)
{
    const EffectSetup& last = P.effects.back();
    std::vector<size_t> sep;
    for (size_t j = 0; j < last.spec.size(); ++j)
        if (std::isfinite(last.spec[j].neutral) && !last.spec[j].fixed && last.spec[j].mirror < 0) sep.push_back(j);
    if (sep.size() < 2 || last.starts.empty()) return {};
    // The earlier effects at init, the last one's separable parameters at
    // their neutral values (its others at its first start).
    std::vector<double> off = init;
    off.insert(off.end(), last.starts.front().begin(), last.starts.front().end());
    const size_t n0 = init.size();
    for (size_t j : sep) off[n0 + j] = last.spec[j].neutral;
    std::vector<double> joint = off;
    std::vector<std::vector<double>> out(1);  // out[0]: the joint start, set below
    for (size_t j : sep) {
        FitProblem Q = P;
        for (size_t k : sep)
            if (k != j) Q.effects.back().spec[k].fixed = true;
        std::vector<double> values;
        for (const std::vector<double>& st : last.starts) values.push_back(st[j]);
        std::vector<double> th = off;
        double best = std::numeric_limits<double>::infinity();
        std::vector<double> start = th;
        for (double v : densified(values)) {
            th[n0 + j] = v;
            const double c = Q.cost(th);
            if (c < best) {
                best = c;
                start = th;
            }
        }
        joint[n0 + j] = refine(Q, start, max_iter).theta[n0 + j];
        std::vector<double> alone = off;
        alone[n0 + j] = joint[n0 + j];
        out.push_back(alone);
    }
    out[0] = joint;
    return out;
}

FitOutcome refine_best(FitProblem& P, const std::vector<std::vector<double>>& starts, int max_iter)
{
    FitOutcome best;
    for (const std::vector<double>& st : starts) {
        FitOutcome o = refine(P, st, max_iter);
        if (o.cost < best.cost) best = o;
    }
    return best;
}

}  // namespace

std::vector<Eigen::Index> growing_windows(const std::vector<double>& energy, Eigen::Index min_rows, double share)
{
    const Eigen::Index N = Eigen::Index(energy.size());
    double total = 0;
    for (double e : energy) total += e;
    std::vector<Eigen::Index> w;
    if (!(total > 0) || N < 2 * min_rows) return w;
    Eigen::Index n = N;
    double cum = 0;
    for (Eigen::Index k = 0; k < N; ++k) {
        cum += energy[size_t(k)];
        if (cum >= share * total) {
            n = k + 1;
            break;
        }
    }
    n = std::max(n, min_rows);
    for (; n < N; n = Eigen::Index(std::ceil(double(n) * kWindowGrowth))) w.push_back(n);
    return w;
}

// Continuation in record length. A replay that oscillates on its own (a
// loop destabilised by the effect, riding its clip in a limit cycle; a
// lightly damped loop ringing through the record) has a cost that is rough
// in the oscillation's frequency: over the record its phase drifts by many
// cycles for a small frequency error, so that no start of a grid lies in
// the basin of the true value. On a short prefix the drift is small and the
// cost smooth; the estimate from a window is the start on a window 1.5
// times as long, whose basin it lies in, and so on up to the whole record
// (the growing-horizon relative of multiple shooting: H. U. Voss, J.
// Timmer, J. Kurths, "Nonlinear dynamical system identification from
// uncertain and indirect measurements", Int. J. Bifurcation and Chaos
// 14(6), 2004, sec. 3; H. G. Bock, "Recent advances in parameter
// identification techniques for ODE", 1983). Two paths, each from its own
// first window (kFirstWindowShares): where the nominal's misfit begins
// (1/1024 of its residual energy: for a loop that grows into a limit cycle,
// within the growth, before the clip is reached; a window ending after a
// few cycles of the limit cycle was already rough in f on the bench's servo
// records), and where it holds 1/16 of that energy (a loop whose reference
// ramps in shows too little of the misfit in its first cycles to place the
// effect: tracked from there, an outside-style arm's series mode ended at
// 22.5 Hz for 23.8). The lower final cost wins.
FitOutcome fit_continued(FitProblem& P, const std::vector<double>& init, int max_iter)
{
    // The nominal's (the earlier effects' at init) residual energy per sample.
    FitProblem before = P;
    before.effects.pop_back();
    const Eigen::Index N = P.y.rows();
    std::vector<double> r(size_t(P.y.size()));
    before.residuals(init, r.data());
    std::vector<double> energy(size_t(N), 0.0);
    for (Eigen::Index c = 0; c < P.y.cols(); ++c)
        for (Eigen::Index k = 0; k < N; ++k) energy[size_t(k)] += r[size_t(c * N + k)] * r[size_t(c * N + k)];
    FitOutcome best;
    Eigen::Index last_first = -1;
    for (const double share : kFirstWindowShares) {
        const std::vector<Eigen::Index> windows = growing_windows(energy, std::max<Eigen::Index>(N / kMinWindowDiv, 1), share);
        if (windows.empty() || windows[0] == last_first) continue;
        last_first = windows[0];
        FitProblem Pw = P;
        Pw.y = P.y.topRows(windows[0]);
        std::vector<FitOutcome> os;
        for (const std::vector<double>& st : screened_starts(Pw, init)) os.push_back(refine(Pw, st, max_iter));
        // Each of the (up to three) refined starts is carried through the
        // windows: on a short window a wrong basin may still cost less.
        for (size_t j = 1; j < windows.size(); ++j) {
            Pw.y = P.y.topRows(windows[j]);
            for (FitOutcome& o : os) o = refine(Pw, o.theta, max_iter);
        }
        for (const FitOutcome& o : os) {
            FitOutcome f = refine(P, o.theta, max_iter);
            if (f.cost < best.cost) best = f;
        }
    }
    return best;
}

double white_cost(const FitProblem& P, const std::vector<double>& white_sd)
{
    double white = 0;
    for (size_t c = 0; c < white_sd.size() && c < P.sigma.size(); ++c)
        white += 0.5 * double(P.y.rows()) * std::pow(white_sd[c] / P.sigma[c], 2);
    return white;
}

// Fits the effect set: earlier effects start at `init`, the last one from each
// of its starts (screened by cost first when it is a grid); returns the best.
FitOutcome fit_set(FitProblem& P, const std::vector<double>& init, int max_iter)
{
    std::vector<std::vector<double>> starts = screened_starts(P, init);
    for (std::vector<double>& st : coordinate_starts(P, init, max_iter)) starts.push_back(std::move(st));
    return refine_best(P, starts, max_iter);
}

std::string unidentified_name(Unidentified u)
{
    switch (u) {
    case Unidentified::identified: return "identified";
    case Unidentified::lower_bound: return "lower_bound";
    case Unidentified::upper_bound: return "upper_bound";
    case Unidentified::no_std: return "no_std";
    case Unidentified::std_exceeds: return "std_exceeds";
    case Unidentified::never_reached: return "never_reached";
    }
    return "identified";
}

// Whether the data identify a fitted parameter (normalized value x, std sd),
// and if not, why: at a bound, no std (a flat or singular cost), or a std
// larger than the value (the data cannot tell it from zero).
Identification unidentified_reason(double x, double sd, const ParamSpec& p)
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
    // A std wide enough to hold both bounds names the nearer one: a mode at
    // the band's upper edge with a std of the band's width is at its upper
    // bound, not its lower.
    const bool near_lo = std::fabs(x - p.lo) <= tol, near_hi = std::fabs(x - p.hi) <= tol;
    if (near_lo && !(near_hi && std::fabs(x - p.hi) < std::fabs(x - p.lo))) {
        std::snprintf(b, sizeof b, "at its lower bound %.4g", p.lo * p.scale);
        return {Unidentified::lower_bound, b};
    }
    if (near_hi) {
        std::snprintf(b, sizeof b, "at its upper bound %.4g", p.hi * p.scale);
        return {Unidentified::upper_bound, b};
    }
    if (!std::isfinite(sd)) return {Unidentified::no_std, "no uncertainty estimate (the cost is flat in it)"};
    if (sd > std::fabs(x)) {
        std::snprintf(b, sizeof b, "std %.3g exceeds |value| %.3g", std::fabs(sd * p.scale), std::fabs(x * p.scale));
        return {Unidentified::std_exceeds, b};
    }
    return {};
}

namespace {

// A limit or dead-zone edge that the command entering them never reaches on
// the fit rows (ReplayTrace::u_static of the fitted replay) is not identified
// by the record: it only bounds the edge (e.g. a symmetric fit's mirrored
// lower limit when the command never went that far down; a true lower limit
// anywhere below the command's least value gives the same record).
void flag_unreached_edges(const FitProblem& P, FitReport& r)
{
    bool have = false;
    double lo = 0.0, hi = 0.0;
    char b[200];
    for (size_t i = 0; i < r.effects.size() && i < r.identification.size(); ++i) {
        const EffectInstance& e = r.effects[i];
        if ((e.kind != Effect::saturation && e.kind != Effect::deadzone) || e.params.size() < 2 || r.identification[i].size() < 2)
            continue;
        if (!have) {
            const ReplayTrace tr = replay(*P.setup, r.effects, P.y.rows());
            lo = tr.u_static.minCoeff();
            hi = tr.u_static.maxCoeff();
            have = true;
        }
        if (e.params[0] < lo && r.identification[i][0].identified()) {
            std::snprintf(b, sizeof b, "never reached: the command's least value on the fit rows is %.4g, so the record says only lower < %.4g",
                          lo, lo);
            r.identification[i][0] = {Unidentified::never_reached, b};
        }
        if (e.params[1] > hi && r.identification[i][1].identified()) {
            std::snprintf(b, sizeof b, "never reached: the command's largest value on the fit rows is %.4g, so the record says only upper > %.4g",
                          hi, hi);
            r.identification[i][1] = {Unidentified::never_reached, b};
        }
    }
}

}  // namespace

FitReport make_report(const FitProblem& P, const FitOutcome& o, const Evaluator& E, double penalty)
{
    FitReport r;
    r.effects = P.instances(o.theta);
    size_t k = 0;
    for (const EffectSetup& e : P.effects) {
        std::vector<double> sd;
        std::vector<Identification> why;
        const size_t first = k;
        for (const ParamSpec& p : e.spec) {
            // A mirrored parameter (ParamSpec::mirror) has the std and the identification of its source.
            const size_t src = p.mirror >= 0 ? first + size_t(p.mirror) : k;
            const ParamSpec& ps = e.spec[src - first];
            sd.push_back(ps.fixed ? kNaN : ps.scale * o.stddev[src]);
            why.push_back(ps.fixed ? Identification{} : unidentified_reason(o.theta[src], o.stddev[src], ps));
            if (p.mirror < 0 && !p.held) r.fitted_params += 1;
            ++k;
        }
        r.stddev.push_back(sd);
        r.identification.push_back(why);
    }
    flag_unreached_edges(P, r);
    const Eigen::MatrixXd yhat = E.simulate(r.effects);
    r.gap_after = nrmse(E.y_eval, yhat, E.scale);
    r.gap = total_gap(r.gap_after, E.weight);
    if (!std::isfinite(r.gap)) r.gap = std::numeric_limits<double>::infinity();
    r.shrink = E.gap_before > 0 ? 1.0 - r.gap / E.gap_before : 0.0;
    r.score = r.shrink - penalty * r.fitted_params;
    r.fit_cost = o.cost;
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

}  // namespace gap
}  // namespace fracdesign
