// diagnosis.cpp - diagnose(): the nominal against the record, then where /
// which / how far (see diagnosis.hpp, stages.hpp, docs/gap.md).
#include "fracdesign/gap/diagnosis.hpp"

#include <chrono>

#include "stages.hpp"

namespace fracdesign {
namespace gap {

GapResult diagnose(const NominalModel& model, const Signals& data, const Signals* validate, const GapOptions& opt)
{
    const auto t_start = std::chrono::steady_clock::now();
    GapResult R;
    // The nominal replayed on the checked record, split into fit and
    // held-out rows; the fits' context from it.
    Baseline B = baseline(model, data, validate, opt, R);
    FitContext ctx = fit_context(B, data, R);
    // Friction's smooth sign tanh(v / eps) in every later replay: eps = 1 %
    // of the nominal's rms velocity (ReplaySetup::eps_velocity).
    B.fit_setup.eps_velocity = 0.01 * ctx.Sv;
    if (validate) B.eval_setup_v.eps_velocity = B.fit_setup.eps_velocity;
    const Evaluator E = held_out(B, data, R);

    where(B, model, data, R);
    // mode_shift's starts: each checked mode's measured peak.
    for (const ModeCheck& mc : R.modes) ctx.mode_checks.push_back({mc.f_hz, mc.measured_peak_hz});

    // Which: every candidate alone.
    FitProblem base_problem;
    base_problem.setup = &B.fit_setup;
    base_problem.y = B.ymeas.topRows(R.fit_samples);
    base_problem.sigma = B.noise_sd.empty() ? B.sigma : B.noise_sd;  // gap.noise: residuals in units of the sensor's noise
    const std::vector<std::pair<FitReport, EffectSetup>> singles = which(model, opt, ctx, B, base_problem, E, R);

    // How far: forward selection from the ranked singles.
    how_far(singles, base_problem, E, opt, R);

    report_traces(B, data, R);
    R.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    return R;
}

}  // namespace gap
}  // namespace fracdesign
