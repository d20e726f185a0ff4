// which.cpp - which effect causes the gap: every candidate at each of its
// sites on the model, fitted alone on the fit rows (the fits run in
// parallel), scored on the held-out rows and ranked, with the nested
// Coulomb / Stribeck rule (see stages.hpp, docs/gap.md).
#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "stages.hpp"

namespace fracdesign {
namespace gap {

namespace {

// Another pass's fitted values of this effect at this site as a start
// (normalized, inside the bounds): a parameter set from the data (a grid) or
// held by a nested restriction keeps the set-up's first start. A fit whose
// cost is rough in its parameters (a series mode in a loop that cycles at
// the clip: its grid's best starts lie in other basins) then also starts
// where the other replay found the effect.
void seed(EffectSetup& es, const std::vector<EffectInstance>& seeds)
{
    for (const EffectInstance& s : seeds) {
        if (!same_place(s, es) || s.params.size() != es.spec.size() || es.starts.empty()) continue;
        std::vector<double> th = es.starts.front();
        for (size_t j = 0; j < th.size(); ++j) {
            const ParamSpec& p = es.spec[j];
            if (p.fixed || p.held || p.mirror >= 0 || !std::isfinite(s.params[j]) || p.scale == 0) continue;
            th[j] = std::min(std::max(s.params[j] / p.scale, p.lo), p.hi);
        }
        es.seeded.push_back(th);
    }
}

}  // namespace

FitReport none_candidate(const GapResult& R)
{
    FitReport none;
    none.gap_after = R.gap_before;
    none.gap = R.gap_before_total;
    none.band_nrmse = R.band_nrmse_before;
    none.solver = "nominal model";
    none.fit_cost = R.fit_cost_nominal;
    return none;
}

std::vector<std::pair<FitReport, EffectSetup>> which(const NominalModel& model, const GapOptions& opt,
                                                     const FitContext& ctx, const Baseline& B,
                                                     const FitProblem& base_problem, const Evaluator& E, GapResult& R,
                                                     const std::vector<EffectInstance>& seeds)
{
    const std::vector<double>& coupling_Sq = B.coupling_Sq;
    // The single fits are independent: they run on opt.threads workers
    // (each job's result lands in its own slot, so the outcome does not
    // depend on the thread count or the order the jobs finish in).
    struct Job {
        size_t effect;
        EffectSetup setup;
    };
    std::vector<Job> jobs, sensor_variants;
    for (size_t ie = 0; ie < opt.effects.size(); ++ie) {
        const Effect e = opt.effects[ie];
        // The effect at each of its sites on this model (effect_sites: the
        // force input, the outputs, each declared coupling): each variant is
        // fitted, the one with the better score is the effect's candidate.
        std::vector<EffectSetup> variants;
        for (const std::pair<Site, int>& site : effect_sites(e, model, B.outs.size(), B.fit_setup.plant_modes.size())) {
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
                cc.mode_f_hz = B.fit_setup.plant_modes[size_t(site.second)].f_hz;
                cc.mode_zeta = B.fit_setup.plant_modes[size_t(site.second)].zeta;
                cc.coupling = site.second;
                variants.push_back(descriptor(e).setup(cc, Site::mode));
            } else if (site.first == Site::sensor) {
                // The mode in one compared output's reading (its index in
                // `coupling`): fitted after the first pass, and only where a
                // mode at another site found a resonance (below).
                FitContext cc = ctx;
                cc.coupling = site.second;
                sensor_variants.push_back({ie, descriptor(e).setup(cc, Site::sensor)});
                seed(sensor_variants.back().setup, seeds);
            } else if (needs_velocity(e) && model.velocity < 0) {
                R.skipped.push_back(effect_name(e) + (model.couplings.empty() ? "" : " at the force input") +
                                    ": the model names no velocity output (gap.velocity)");
            } else {
                variants.push_back(descriptor(e).setup(ctx, site.first));
                // And its nested restrictions (EffectDescriptor::nested), fitted as variants of their own.
                if (descriptor(e).nested)
                    for (const EffectSetup& v : descriptor(e).nested(ctx, site.first)) variants.push_back(v);
            }
        }
        for (EffectSetup& es : variants) {
            seed(es, seeds);
            if (es.starts.empty()) {
                R.skipped.push_back(effect_name(e) + (e == Effect::quantization
                                                           ? ": no output's data lie on a lattice coarser than its noise"
                                                           : ": no start value from the data"));
                continue;
            }
            jobs.push_back({ie, es});
        }
    }
    // Runs fit(i) for each listed job on the workers (run_jobs); progress per job.
    const auto run_pool = [&](const std::vector<size_t>& todo, const char* what, auto fit) {
        size_t done = 0;
        std::mutex mu;
        run_jobs(todo.size(), opt.threads, [&](size_t n) {
            const size_t i = todo[n];
            fit(i);
            if (!opt.progress) return;
            std::lock_guard<std::mutex> lk(mu);
            ++done;
            const EffectSetup& js = jobs[i].setup;
            const std::string name = effect_name(js.kind);
            opt.progress("gap: " + std::string(what) + " " + std::to_string(done) + "/" + std::to_string(todo.size()) +
                         " candidates: " + name + site_phrase(name, site_name(js.site), site_subject(R, js.site, js.coupling)));
        });
    };
    // First pass: every candidate from its starts.
    std::vector<FitOutcome> outcome(jobs.size());
    std::vector<FitReport> job_report(jobs.size());
    std::vector<size_t> all(jobs.size());
    for (size_t i = 0; i < jobs.size(); ++i) all[i] = i;
    run_pool(all, "fitted", [&](size_t i) {
        FitProblem P = base_problem;
        P.effects = {jobs[i].setup};
        outcome[i] = fit_set(P, {}, opt.max_iterations);
        job_report[i] = make_report(P, outcome[i], E, opt.param_penalty);
    });
    // Second pass (stages.hpp kStructuredMisfit, kExplainedShare):
    // continuation in record length for the candidates that explained
    // little, when the nominal's misfit is structured and no first-pass fit
    // explained the larger part of it on the held-out rows. Held out, not
    // on the fit rows: a fit caught in a wrong basin of a rough cost (a
    // lightly damped loop's mode 1 % off) may lower the fit cost and still
    // replay the held-out rows worse than the nominal.
    FitProblem nominal = base_problem;
    nominal.effects.clear();
    const double base_cost = nominal.cost({});
    const double white = white_cost(base_problem, B.noise_sd.empty() ? ctx.white_sd : B.noise_sd);
    R.fit_cost_nominal = base_cost;
    R.fit_cost_white = white;
    // The held-out gap's white part, in the fit rows' proportion.
    const double g2 = R.gap_before_total * R.gap_before_total;
    const double w2 = base_cost > 0 ? g2 * std::min(1.0, white / base_cost) : 0.0;
    double best2 = g2;
    for (const FitReport& r : job_report)
        if (std::isfinite(r.gap)) best2 = std::min(best2, r.gap * r.gap);
    std::vector<size_t> weak;
    if (structured_misfit(base_cost, white) &&
        best2 - w2 > (1.0 - kExplainedShare) * (g2 - w2))
        for (size_t i = 0; i < jobs.size(); ++i)
            if (!(outcome[i].cost < (1.0 - kContinuationGain) * base_cost) || !(job_report[i].shrink >= opt.margin))
                weak.push_back(i);
    R.continued = weak.size();

    if (!weak.empty())
        run_pool(weak, "continued", [&](size_t i) {
            FitProblem P = base_problem;
            P.effects = {jobs[i].setup};
            const FitOutcome c = fit_continued(P, {}, opt.max_iterations);
            if (c.cost < outcome[i].cost) {
                outcome[i] = c;
                job_report[i] = make_report(P, c, E, opt.param_penalty);
            }
        });
    // The mode in a sensor's reading (unmodelled_mode at Site::sensor, one
    // variant per compared output: a second-order sensor, from a compliant
    // mount's transmissibility, m = 1, to the sensor's own low-pass, m = 0)
    // is seen in part by other candidates, placed differently: a resonance
    // by the mode at the outputs or in series and by a nominal mode moved
    // (mode_shift), the lag 2 zeta / w a low-pass makes below its resonance
    // by a delay of that output. Where none of them lowers the held-out gap
    // by the selection margin, the record holds no sensor mode to place and
    // the sensor variants are not fitted (they would cost one replay per
    // start and output and find nothing). Otherwise each is fitted, without
    // the log grid and without the continuation, from the located resonance:
    // those candidates' fitted frequency and damping (f_hz, zeta: the first
    // two parameters of both effects), for a delay d of its output the
    // low-pass of that lag, f = zeta / (pi d) at zeta 0.1, 0.3 and 0.5, and
    // the residual's peaks; each at both ends of m.
    {
        std::vector<std::vector<double>> found;  // physical (f_hz, zeta) of the resonant candidates that found one
        std::vector<std::vector<double>> lags;   // per compared output: the delays of output_delay fits that lower the gap
        for (size_t i = 0; i < jobs.size(); ++i) {
            const EffectSetup& js = jobs[i].setup;
            if (!(job_report[i].shrink >= opt.margin)) continue;
            if (js.kind == Effect::output_delay) {
                lags.resize(std::max(lags.size(), js.spec.size()));
                for (size_t c = 0; c < js.spec.size() && c < outcome[i].theta.size(); ++c)
                    if (outcome[i].theta[c] > 0) lags[c].push_back(js.spec[c].scale * outcome[i].theta[c]);
                continue;
            }
            if (!((js.kind == Effect::unmodelled_mode && js.site != Site::sensor) || js.kind == Effect::mode_shift) ||
                outcome[i].theta.size() < 2 || js.spec.size() < 2)
                continue;
            found.push_back({js.spec[0].scale * outcome[i].theta[0], js.spec[1].scale * outcome[i].theta[1]});
        }
        std::vector<size_t> todo;
        bool led = false;  // some variant had a located resonance or lag to start from
        for (Job j : sensor_variants) {
            const size_t c = size_t(j.setup.coupling);
            const bool lagged = c < lags.size() && !lags[c].empty();
            if (found.empty() && !lagged) continue;
            led = true;
            std::vector<std::vector<double>> fz = found;  // physical (f_hz, zeta)
            if (lagged)
                for (double d : lags[c])
                    for (double z : {0.1, 0.3, 0.5}) fz.push_back({z / (M_PI * d), z});
            // Starts in the variant's normalized units (ParamSpec::scale), the
            // frequency inside its band, each at both ends of m, ahead of the
            // descriptor's own (the residual's peaks).
            const ParamSpec &sf = j.setup.spec[0], &sz = j.setup.spec[1];
            const auto clamp = [](double v, const ParamSpec& p) { return std::min(p.hi, std::max(p.lo, v / p.scale)); };
            std::vector<std::vector<double>> st;
            for (const std::vector<double>& p : fz) {
                if (p[0] / sf.scale < sf.lo || p[0] / sf.scale > sf.hi) continue;
                for (double m : {1.0, 0.0}) st.push_back({p[0] / sf.scale, clamp(p[1], sz), m});
            }
            st.insert(st.end(), j.setup.starts.begin(), j.setup.starts.end());
            if (st.empty()) continue;
            j.setup.starts = st;
            todo.push_back(jobs.size());
            jobs.push_back(j);
        }
        if (todo.empty() && !sensor_variants.empty())
            R.skipped.push_back(
                led ? "unmodelled_mode in a sensor's reading: the located resonances and lags lie outside the band "
                      "the record resolves and the residual has no peak inside it, so there is no sensor mode to place"
                    : "unmodelled_mode in a sensor's reading: no mode at the outputs or in series, no mode_shift and "
                      "no delay of an output lowers the held-out gap by the margin, so there is no sensor mode to "
                      "place");
        outcome.resize(jobs.size());
        job_report.resize(jobs.size());
        if (!todo.empty())
            run_pool(todo, "fitted", [&](size_t i) {
                FitProblem P = base_problem;
                P.effects = {jobs[i].setup};
                outcome[i] = fit_set(P, {}, opt.max_iterations);
                job_report[i] = make_report(P, outcome[i], E, opt.param_penalty);
            });
    }
    // A Stribeck fit whose curve does not fall (Fs <= Fc: the replay reads
    // it as Fs = Fc, effects.cpp) is a Coulomb friction without offset. When
    // it fits better than the Coulomb candidate at the same site, that fit
    // found a basin the Coulomb starts missed: Coulomb is refined from
    // (Fc, offset 0) there, so the contained model is never scored worse
    // than its own restriction of the container and the nested rule below
    // compares like with like.
    for (size_t is = 0; is < jobs.size(); ++is) {
        const EffectSetup& ss = jobs[is].setup;
        const std::vector<double>& ts = outcome[is].theta;
        if (ss.kind != Effect::stribeck_friction || ts.size() < 2 || !(ts[1] <= ts[0])) continue;
        for (size_t ic = 0; ic < jobs.size(); ++ic) {
            const EffectSetup& cs = jobs[ic].setup;
            if (cs.kind != Effect::coulomb_friction || cs.site != ss.site || cs.spec.size() != 2 ||
                !(outcome[is].cost < outcome[ic].cost) || cs.spec[0].scale != ss.spec[0].scale)
                continue;
            FitProblem P = base_problem;
            P.effects = {cs};
            const FitOutcome c = refine(P, {ts[0], 0.0}, opt.max_iterations);
            if (c.cost < outcome[ic].cost) {
                outcome[ic] = c;
                job_report[ic] = make_report(P, c, E, opt.param_penalty);
            }
        }
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
    R.candidates.push_back(none_candidate(R));
    std::stable_sort(R.candidates.begin(), R.candidates.end(),
                     [](const FitReport& a, const FitReport& b) { return a.score > b.score; });
    std::sort(singles.begin(), singles.end(),
              [](const std::pair<FitReport, EffectSetup>& a, const std::pair<FitReport, EffectSetup>& b) {
                  return a.first.score > b.first.score;
              });
    // Nested effects (stages.hpp nested_rule).
    for (const std::pair<Effect, Effect>& n : kNestedPairs) {
        nested_rule(R.candidates, [](const FitReport& f) -> const FitReport& { return f; }, n.first, n.second, opt.margin);
        nested_rule(singles, [](const std::pair<FitReport, EffectSetup>& p) -> const FitReport& { return p.first; }, n.first,
                    n.second, opt.margin);
    }
    return singles;
}

}  // namespace gap
}  // namespace fracdesign
