// where.cpp - where the gap lies: frequency bands of the nominal residual,
// the nominal's modes against the measured spectrum, time windows with their
// operating condition; and the fits' context the data give (scales,
// quantization steps, residual peaks) (see stages.hpp, docs/gap.md).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "stages.hpp"

namespace fracdesign {
namespace gap {

namespace {

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

// rms(u) in the friction input's units (FitContext::Sf): a friction torque
// at a separate input (gap.friction_input, e.g. a voltage-driven motor with
// a disturbance-torque input) moves the machine as much as the drive's rms
// command when it equals Su times the ratio of the velocity each input
// gives, from rest, kFrictionScaleHorizon samples after a unit step on it
// (the plant's open-loop matrices; the horizon lets an actuator lag, e.g.
// a motor's electrical pole, settle into the rate). Su itself when friction
// acts at the force input, or where either response is zero.
constexpr int kFrictionScaleHorizon = 50;

double friction_scale(const NominalModel& m, double Su)
{
    if (m.friction_input == m.force_input || m.velocity < 0) return Su;
    auto velocity_after_step = [&](int input) {
        Eigen::VectorXd x = Eigen::VectorXd::Zero(m.A.rows());
        for (int k = 0; k < kFrictionScaleHorizon; ++k) x = m.A * x + m.B.col(input);
        return std::fabs(m.C.row(m.velocity).dot(x));
    };
    const double gu = velocity_after_step(m.force_input), gf = velocity_after_step(m.friction_input);
    const double r = gu / gf;
    return std::isfinite(r) && r > 0 ? Su * r : Su;
}

}  // namespace

FitContext fit_context(const Baseline& B, const Signals& data, const GapResult& R)
{
    const std::vector<std::string>& outs = B.outs;
    const Eigen::MatrixXd& ymeas = B.ymeas;
    const ReplayTrace& nom = B.nom;
    const std::vector<double>& sigma = B.sigma;
    const Eigen::MatrixXd& resn = B.resn;
    FitContext ctx;
    ctx.Ts = data.Ts;
    ctx.fit_samples = R.fit_samples;
    ctx.fit_seconds = double(R.fit_samples) * data.Ts;
    ctx.Su = std::max(rms(nom.u.head(R.fit_samples)), 1e-12);
    ctx.Sv = std::max(rms(nom.v.head(R.fit_samples)), 1e-12);
    ctx.Sf = friction_scale(*B.fit_setup.model, ctx.Su);
    ctx.umax = std::max(nom.u.head(R.fit_samples).cwiseAbs().maxCoeff(), 1e-12);
    const NominalModel& model = *B.fit_setup.model;
    const GearSite gear = gear_site(model);
    if (gear.ok) ctx.Sp = std::fabs(gear.kappa * ctx.Ts * ctx.Sv / model.C(model.velocity, gear.j));
    for (size_t c = 0; c < outs.size(); ++c) {
        const Eigen::VectorXd yc = ymeas.col(Eigen::Index(c)).head(R.fit_samples);
        ctx.Sy.push_back(sigma[c]);
        double q = std::numeric_limits<double>::infinity();
        for (Eigen::Index k = 1; k < R.fit_samples; ++k) {
            const double d = std::fabs(yc(k) - yc(k - 1));
            if (d > 1e-12 * sigma[c]) q = std::min(q, d);
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
        // A step finer than the white part of the residual is dithered by
        // the noise: the reading's cell then says nothing the noise does not.
        // White level: sigma_w = rms(r(k) - (r(k-1) + r(k+1))/2) / sqrt(1.5)
        // of the nominal residual (a quantization error of step q alone gives
        // sigma_w = q/sqrt(12)); the step is used when q >= 2 sigma_w, i.e.
        // q >= 2.45 x the noise std. A held output (gap.output_hold) repeats
        // each reading, its noise too: r is then taken at the readings only.
        const NominalModel& model = *B.fit_setup.model;
        Eigen::Index every = 1, phase = 0;
        for (size_t j = 0; j < model.holds.size(); ++j)
            if (model.holds[j].output == B.fit_setup.compared[c]) every = model.holds[j].every, phase = B.fit_setup.hold_phase[j];
        double hf = 0;
        Eigen::Index nhf = 0;
        for (Eigen::Index k = phase + every; k + every < R.fit_samples; k += every, ++nhf) {
            const double d =
                resn(k, Eigen::Index(c)) - 0.5 * (resn(k - every, Eigen::Index(c)) + resn(k + every, Eigen::Index(c)));
            hf += d * d;
        }
        const double sigma_w = sigma[c] * std::sqrt(hf / double(std::max<Eigen::Index>(1, nhf)) / 1.5);
        ctx.white_sd.push_back(sigma_w);
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
    return ctx;
}

void where(const Baseline& B, const NominalModel& model, const Signals& data, GapResult& R)
{
    const std::vector<std::string>& outs = B.outs;
    const Eigen::Index N = B.N;
    const Eigen::MatrixXd& ymeas = B.ymeas;
    const ReplayTrace& nom = B.nom;
    const std::vector<double>& sigma = B.sigma;
    const Eigen::MatrixXd& resn = B.resn;
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
    // Where: time windows with their operating condition.
    {
        Eigen::VectorXd r = resn.rowwise().norm() / std::sqrt(double(outs.size()));
        const double cl_limit = model.closed_loop ? std::min(model.loop.saturation, model.loop.controller->output_limit())
                                                  : std::numeric_limits<double>::infinity();
        const double limit = std::isfinite(cl_limit) ? cl_limit : nom.u.cwiseAbs().maxCoeff();
        R.windows = flag_windows(r, nom, data.Ts, data.t0, limit);
    }
}

}  // namespace gap
}  // namespace fracdesign
