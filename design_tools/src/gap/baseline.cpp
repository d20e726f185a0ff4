// baseline.cpp - the nominal model against the record: the inputs checked,
// the fit / held-out split, the nominal replay and its residuals (see
// stages.hpp, docs/gap.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stages.hpp"

namespace fracdesign {
namespace gap {

namespace {

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

// The residual the sensors' noise alone leaves in a closed loop, per compared
// output (rms over each row range [first, first + n) of setup's record, per
// draw; the ranges from the same draws, one replay per draw): the
// controller reads each sensor's noise, so the plant moves with it (through
// the loop's complementary sensitivity, and the limits when it rides them); a
// record of the exact nominal differs from the noise-free replay by that
// motion as well as by the noise itself. The replay is run with white
// Gaussian noise of the stated std on every sensor gap.noise names (added
// before the reading's hold, as the sensor adds it), kLoopNoiseDraws draws
// with fixed seeds, and compared with the noise-free replay `clean`. Open
// loop this is the stated std itself (the noise does not feed back).
// `series`, when given, receives each draw's residual over the last range
// (rows x compared outputs): the null draws of noise_reach (how_far.cpp).
using RowRange = std::pair<Eigen::Index, Eigen::Index>;  // first row, count

// Draw d of white Gaussian noise, rows x sd.size(), column i of std sd[i];
// fixed seeds: the floor is a property of the record.
Eigen::MatrixXd white_draw(int d, Eigen::Index rows, const std::vector<double>& sd)
{
    std::mt19937_64 gen(0x6e6f697365ULL + std::uint64_t(d));
    std::normal_distribution<double> g(0.0, 1.0);
    Eigen::MatrixXd w(rows, Eigen::Index(sd.size()));
    for (Eigen::Index i = 0; i < w.cols(); ++i)
        for (Eigen::Index k = 0; k < rows; ++k) w(k, i) = sd[size_t(i)] * g(gen);
    return w;
}

std::vector<Eigen::MatrixXd> loop_noise_draws(const NominalModel& model, const ReplaySetup& setup, const ReplayTrace& clean,
                                              const std::vector<RowRange>& ranges, std::vector<Eigen::MatrixXd>* series = nullptr)
{
    Eigen::Index rows = 0;
    for (const RowRange& r : ranges) rows = std::max(rows, r.first + r.second);
    const Eigen::Index ny = model.C.rows();
    std::vector<double> sd(size_t(ny), 0.0);
    for (Eigen::Index i = 0; i < ny; ++i) {
        const auto it = model.noise.find(model.outputs[size_t(i)]);
        if (it != model.noise.end()) sd[size_t(i)] = it->second;
    }
    const Eigen::Index ncmp = Eigen::Index(setup.compared.size());
    std::vector<Eigen::MatrixXd> out(ranges.size(), Eigen::MatrixXd(kLoopNoiseDraws, ncmp));
    for (int d = 0; d < kLoopNoiseDraws; ++d) {
        const Eigen::MatrixXd w = white_draw(d, rows, sd);
        const ReplayTrace tr = replay(setup, {}, rows, &w);
        for (size_t r = 0; r < ranges.size(); ++r) {
            const auto [first, n] = ranges[r];
            const Eigen::MatrixXd res = tr.y.middleRows(first, n) - clean.y.middleRows(first, n);
            out[r].row(d) = (res.colwise().squaredNorm() / double(n)).cwiseSqrt();
            if (series && r + 1 == ranges.size()) series->push_back(res);
        }
    }
    for (const Eigen::MatrixXd& o : out)
        for (Eigen::Index c = 0; c < ncmp; ++c) {
            const double lim = 1e6 * std::max(sd[size_t(setup.compared[size_t(c)])], 1e-300);
            if (!o.col(c).allFinite() || o.col(c).maxCoeff() > lim)
                throw std::runtime_error("model gap.noise: the closed loop replayed with the stated sensor noise runs away (output '" +
                                         model.outputs[size_t(setup.compared[size_t(c)])] +
                                         "'): the noise floor cannot be computed; check the noise std against the loop's limits");
        }
    return out;
}

// Per output: the rms over the draws.
std::vector<double> draws_rms(const Eigen::MatrixXd& draws)
{
    std::vector<double> r;
    for (Eigen::Index c = 0; c < draws.cols(); ++c) r.push_back(rms(draws.col(c)));
    return r;
}

}  // namespace

Baseline baseline(const NominalModel& model, const Signals& data, const Signals* validate, const GapOptions& opt,
                  GapResult& R, bool feed_measured)
{
    Baseline B;
    R.model_name = model.name;
    R.realization = model.realization;
    R.data_source = data.source;
    R.Ts = data.Ts;
    if (validate && std::fabs(validate->Ts - data.Ts) > 1e-3 * data.Ts)
        throw std::runtime_error("the validation record's sample time differs from the data's");
    if (!(opt.holdout > 0 && opt.holdout < 1)) throw std::runtime_error("held-out fraction must be in (0, 1)");
    std::vector<std::string>& outs = B.outs;
    outs = opt.outputs;
    if (outs.empty())
        for (const std::string& o : model.outputs)
            if (data.has(o)) outs.push_back(o);
    if (outs.empty())
        throw std::runtime_error("model/data mismatch: none of the model outputs is a column of " + data.source);
    R.outputs = outs;
    R.units = model_units(model, outs);
    // gap.noise: every compared output needs its sensor's std.
    std::vector<double>& noise_sd = B.noise_sd;
    if (!model.noise.empty())
        for (const std::string& o : outs) {
            const auto it = model.noise.find(o);
            if (it == model.noise.end())
                throw std::runtime_error("model gap.noise: states no std for the compared output '" + o +
                                         "'; give one for every compared output, or leave gap.noise out");
            noise_sd.push_back(it->second);
        }
    for (const Coupling& c : model.couplings) R.coupling_names.push_back(c.name);
    B.fit_setup = make_replay_setup(model, data, opt.inputs, outs, feed_measured);
    for (const PlantMode& pm : B.fit_setup.plant_modes) R.mode_names.push_back(plant_mode_name(pm));
    B.validated = validate != nullptr;
    if (validate) B.eval_setup_v = make_replay_setup(model, *validate, opt.inputs, outs, feed_measured);
    const Eigen::Index N = B.N = data.samples();
    R.fit_samples = validate ? N : Eigen::Index(std::floor((1.0 - opt.holdout) * double(N)));
    R.eval_first = validate ? 0 : R.fit_samples;
    R.eval_samples = validate ? validate->samples() : N - R.fit_samples;
    R.eval_source = validate ? validate->source : data.source + " (last " + std::to_string(int(opt.holdout * 100 + 0.5)) + " %)";
    if (R.fit_samples < 20 || R.eval_samples < 20) throw std::runtime_error("record too short to split into fit and held-out parts");

    Eigen::MatrixXd& ymeas = B.ymeas;
    ymeas.resize(N, Eigen::Index(outs.size()));
    for (size_t c = 0; c < outs.size(); ++c) ymeas.col(Eigen::Index(c)) = data.col(outs[c]);
    B.evsig = validate ? validate : &data;
    const Signals& evsig = *B.evsig;
    Eigen::MatrixXd& yeval = B.yeval;
    yeval.resize(R.eval_samples, Eigen::Index(outs.size()));
    for (size_t c = 0; c < outs.size(); ++c)
        yeval.col(Eigen::Index(c)) = evsig.col(outs[c]).segment(R.eval_first, R.eval_samples);

    // Every compared channel must vary, and its statistics must be finite:
    // the gap is relative to the output's own variation.
    for (const Signals* rec : {&data, B.evsig})
        for (const std::string& o : outs) check_channel(*rec, o);

    // Nominal replay and its residuals; a replay that diverges or leaves the
    // data's range by orders of magnitude is refused (no verdict is honest on it).
    B.nom = replay(B.fit_setup, {});
    const ReplayTrace& nom = B.nom;
    check_nominal_replay(model, nom, ymeas, outs, data.source);
    // The noise floor (gap.noise) in a closed loop: the noise-only residual,
    // over the fit rows (the fits' residual scale) and the evaluated rows.
    B.eval_noise_sd = noise_sd;
    if (!noise_sd.empty() && model.closed_loop && !feed_measured) {
        // Without a validation record both row ranges come from the same draws of the whole record.
        if (validate) {
            noise_sd = draws_rms(loop_noise_draws(model, B.fit_setup, nom, {{0, R.fit_samples}})[0]);
            B.eval_noise_draws = loop_noise_draws(model, B.eval_setup_v, replay(B.eval_setup_v, {}), {{0, R.eval_samples}},
                                                  &B.eval_noise_residual)[0];
        } else {
            const std::vector<Eigen::MatrixXd> d = loop_noise_draws(
                model, B.fit_setup, nom, {{0, R.fit_samples}, {R.eval_first, R.eval_samples}}, &B.eval_noise_residual);
            noise_sd = draws_rms(d[0]);
            B.eval_noise_draws = d[1];
        }
        B.eval_noise_sd = draws_rms(B.eval_noise_draws);
    } else if (!noise_sd.empty()) {
        // Open loop (or the controller fed the measured outputs) the
        // noise-only residual is the stated white noise itself.
        for (int d = 0; d < kLoopNoiseDraws; ++d) B.eval_noise_residual.push_back(white_draw(d, R.eval_samples, noise_sd));
    }
    // Each coupling's scale (FitContext::Sq, set per site by which()).
    std::vector<double>& coupling_Sq = B.coupling_Sq;
    for (size_t i = 0; i < model.couplings.size(); ++i)
        coupling_Sq.push_back(rms(nom.twists.col(Eigen::Index(i)).head(R.fit_samples)));
    // Each output's std over the fit rows, and the nominal residual in it.
    std::vector<double>& sigma = B.sigma;
    Eigen::MatrixXd& resn = B.resn;
    resn.resize(N, Eigen::Index(outs.size()));
    for (size_t c = 0; c < outs.size(); ++c) {
        const Eigen::VectorXd yc = ymeas.col(Eigen::Index(c)).head(R.fit_samples);
        const double sd = std::sqrt((yc.array() - yc.mean()).square().mean());
        sigma.push_back(sd > 0 ? sd : 1.0);
        resn.col(Eigen::Index(c)) = (ymeas.col(Eigen::Index(c)) - nom.y.col(Eigen::Index(c))) / sigma.back();
    }
    return B;
}

}  // namespace gap
}  // namespace fracdesign
