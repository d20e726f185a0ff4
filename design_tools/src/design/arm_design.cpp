// arm_design.cpp - the design chain for an arm document (design/arm_design.hpp).
#include "fracdesign/design/arm_design.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <unsupported/Eigen/MatrixFunctions>

#include "fracdesign/design/riccati.hpp"
#include "fracdesign/io/signal_csv.hpp"

namespace fracdesign::design {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string fmt(double v)
{
    char b[40];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

std::string rho(double v)
{
    char b[40];
    std::snprintf(b, sizeof b, "%.9f", v);
    return b;
}

std::vector<double> below(std::vector<double> f, double fmax)
{
    f.erase(std::remove_if(f.begin(), f.end(), [&](double x) { return x > fmax; }), f.end());
    return f;
}

nlohmann::json mat(const Eigen::MatrixXd& M)
{
    nlohmann::json j = nlohmann::json::array();
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
        std::vector<double> row(static_cast<size_t>(M.cols()));
        for (Eigen::Index k = 0; k < M.cols(); ++k) row[static_cast<size_t>(k)] = M(i, k);
        j.push_back(row);
    }
    return j;
}

}  // namespace

ArmReduction choose_reduction(const ArmDocument& a, int extra_modes)
{
    if (extra_modes < 0) throw std::invalid_argument("choose_reduction: extra_modes must be >= 0");
    ArmReduction r;
    const int N = a.design.N;
    const double nyq_hz = 0.5 / a.T;
    const ArmBuild full = build_arm_from_document(a, N, false, {});
    r.full_states = static_cast<int>(full.arm.J.rows());
    r.full_hz = below(full.arm.state_space().natural_frequencies_hz(1e-3), nyq_hz);
    if (r.full_hz.empty()) throw ArmDesignError("arm: the full arm has no flexible mode below Nyquist " + fmt(nyq_hz) + " Hz");
    r.bandwidth_hz = a.design.bandwidth_hz > 0 ? a.design.bandwidth_hz : r.full_hz.front();
    const std::vector<double> beam_hz = clamped_free_frequencies_hz(full.beam, -1);
    const double wb = 2.0 * kPi * r.bandwidth_hz;
    size_t by_rule = 0;  // the rule's count: modes up to reduce_multiple x w_b, at least 2
    for (double f : beam_hz) {
        if (by_rule >= 2 && 2.0 * kPi * f > a.design.reduce_multiple * wb) break;
        ++by_rule;
    }
    const size_t m = std::min({by_rule + static_cast<size_t>(extra_modes), beam_hz.size(), static_cast<size_t>(kArmShiftsMax - 1)});
    for (size_t i = 0; i < m; ++i) r.beam_modes_rad_s.push_back(2.0 * kPi * beam_hz[i]);
    r.extra_modes = static_cast<int>(m) - static_cast<int>(std::min(by_rule, m));
    if (r.beam_modes_rad_s.size() < 2) throw ArmDesignError("arm: the beam at N = " + std::to_string(N) + " has fewer than 2 modes");
    r.shifts.push_back(0.5 * r.beam_modes_rad_s.front());
    r.shifts.insert(r.shifts.end(), r.beam_modes_rad_s.begin(), r.beam_modes_rad_s.end());
    if (static_cast<int>(4 * r.shifts.size()) > 4 * N)
        throw ArmDesignError("arm: design.N = " + std::to_string(N) + " is too small for " + std::to_string(r.shifts.size()) +
                             " Krylov shifts (4 per shift must not exceed 4 N): raise design.N");
    const ArmBuild red = build_arm_from_document(a, N, true, r.shifts);
    r.reduced_states = static_cast<int>(red.arm.J.rows());
    const std::vector<double> red_hz = below(red.arm.state_space().natural_frequencies_hz(1e-3), nyq_hz);
    for (double f : red_hz) {
        ArmModeCompare c;
        c.reduced_hz = f;
        c.full_hz = *std::min_element(r.full_hz.begin(), r.full_hz.end(),
                                      [&](double x, double y) { return std::fabs(x - f) < std::fabs(y - f); });
        c.rel_error = std::fabs(f - c.full_hz) / c.full_hz;
        r.retained.push_back(c);
    }
    // every full mode at or below the bandwidth must be retained within the bound
    for (double f : r.full_hz) {
        if (f > r.bandwidth_hz * (1.0 + 1e-9) && f != r.full_hz.front()) continue;
        double best = 1e300;
        for (double g : red_hz) best = std::min(best, std::fabs(g - f) / f);
        r.max_error_below_bandwidth = std::max(r.max_error_below_bandwidth, best);
        if (!(best <= a.design.mode_error_max))
            throw ArmDesignError("arm: the Krylov reduction (shifts " + fmt(r.shifts.front()) + ".." + fmt(r.shifts.back()) +
                                 " rad/s) misses the full arm's mode at " + fmt(f) + " Hz (below the bandwidth " +
                                 fmt(r.bandwidth_hz) + " Hz) by " + fmt(100.0 * best) + " %, more than design.mode_error_max = " +
                                 fmt(100.0 * a.design.mode_error_max) + " %: raise design.reduce_multiple or design.N");
    }
    return r;
}

std::array<double, 3> arm_measurement_covariance(const ArmDocument& a)
{
    if (a.design.s_o > 0) return {a.design.s_o, a.design.s_o, a.design.s_o};
    std::array<double, 3> s{1.0, 1.0, 1.0};  // Table 8.8: S_o = I_3
    if (a.encoder_noise > 0) {
        s[0] = a.encoder_noise * a.encoder_noise;
        s[1] = 2.0 * s[0] / (a.T * a.T);  // theta_M' as the encoder's difference quotient over T
    }
    if (a.imu_noise > 0) s[2] = a.imu_noise * a.imu_noise;
    return s;
}

LqgParams arm_lqg_params(const ArmDocument& a)
{
    const ArmDesignSection& s = a.design;
    LqgParams p = LqgParams::exp_d();
    p.T = a.T;
    p.di = a.di;
    p.dout = a.dout;
    const double scale = std::pow(a.torque_rated / kWangRatedTorque, 2);  // Bryson: rated torque as the torque scale
    p.n_low = s.n_low;
    p.q_low = s.q_low > 0 ? s.q_low : 5e3 * scale;
    p.q_high = s.q_high > 0 ? s.q_high : 1e-2 * scale;
    p.q_delay = s.q_delay;
    p.s_c = s.s_c > 0 ? s.s_c : 1.0;
    p.qo_drive = s.qo_drive;
    p.qo_beam = s.qo_beam;
    p.qo_delay = s.qo_delay;
    p.qo_dist = s.qo_dist;
    p.s_o = arm_measurement_covariance(a);
    return p;
}

double arm_rho_max(double T) { return std::exp(-kArmDecayMin * T); }

namespace {

// One step of the ladder: reduction with `extra` modes beyond the rule, the weights scaled by `back_off`,
// design and both checks. A model or Riccati failure is the step's note; `out` is filled when designed.
ArmLqgStep try_step(const ArmDocument& a, const StateSpace& full, int extra, double back_off, ArmLqg& out,
                    std::exception_ptr& riccati)
{
    ArmLqgStep st;
    st.extra_modes = extra;
    st.back_off = back_off;
    st.rule = back_off < 1.0 ? "weights x " + fmt(back_off) + " (q_low, q_high, Qo), " + std::to_string(extra) + " extra modes"
              : extra > 0   ? std::to_string(extra) + " extra mode" + (extra > 1 ? "s" : "") + " in the design model"
                            : "default";
    try {
        ArmLqg r;
        r.full = full;
        if (a.design.reduce) {
            r.reduction = choose_reduction(a, extra);
            if (extra > 0 && r.reduction.extra_modes < extra) {
                st.note = "no further beam mode to retain (at most " + std::to_string(kArmShiftsMax - 1) + ")";
                return st;
            }
            r.reduced = arm_document_measured(a, build_arm_from_document(a, a.design.N, true, r.reduction.shifts));
        } else {
            r.reduced = full;
        }
        st.reduced_states = static_cast<int>(r.reduced.nx());
        if (extra > 0 && st.reduced_states > kArmctrlLqgNmax) {
            st.note = "the design model would have " + std::to_string(st.reduced_states) + " states, more than the PLC's LQG holds (" +
                      std::to_string(kArmctrlLqgNmax) + ")";
            return st;
        }
        LqgParams p = arm_lqg_params(a);
        if (p.n_low > r.reduced.nx())
            throw ArmDesignError("arm: design.lqg.n_low = " + std::to_string(p.n_low) + " exceeds the model order " +
                                 std::to_string(r.reduced.nx()));
        for (double* w : {&p.q_low, &p.q_high, &p.qo_drive, &p.qo_beam, &p.qo_delay, &p.qo_dist}) *w *= back_off;
        r.lqg = design_lqg(r.reduced, p);
        r.check_reduced = check_closed_loop(r.lqg, r.reduced, a.di, a.dout);
        r.check_unreduced = check_closed_loop(r.lqg, r.full, a.di, a.dout);
        st.designed = true;
        st.rho_reduced = r.check_reduced.spectral_radius;
        st.rho_unreduced = r.check_unreduced.spectral_radius;
        st.modulus_unreduced = r.check_unreduced.modulus_margin;
        st.accepted = st.rho_unreduced <= arm_rho_max(a.T) && st.modulus_unreduced >= kArmModulusMin;
        out = std::move(r);
    } catch (const ArmDesignError& e) {
        if (extra == 0 && back_off == 1.0) throw;  // the document's own reduction or n_low refused: a document fault
        st.note = e.what();
    } catch (const RiccatiError& e) {
        st.note = std::string("Riccati: ") + e.what();
        if (!riccati) riccati = std::current_exception();
    } catch (const std::runtime_error& e) {
        st.note = e.what();  // e.g. the Krylov basis losing rank with more shifts
    }
    return st;
}

}  // namespace

ArmLqg design_arm_lqg(const ArmDocument& a)
{
    const StateSpace full = arm_document_measured(a, build_arm_from_document(a, a.design.N, false, {}));
    std::vector<ArmLqgStep> steps;
    std::vector<ArmLqg> designs;  // designs[i] belongs to steps[index[i]]
    std::vector<size_t> index;
    std::exception_ptr riccati;  // the first Riccati failure, rethrown when no step designs
    auto run = [&](int extra, double back_off) {
        ArmLqg r;
        steps.push_back(try_step(a, full, extra, back_off, r, riccati));
        if (steps.back().designed) {
            designs.push_back(std::move(r));
            index.push_back(steps.size() - 1);
        }
        return steps.back();
    };
    ArmLqgStep st = run(0, 1.0);
    // 1. more retained modes, one beam mode per step, while the model grows and fits the PLC
    int largest = 0;
    for (int extra = 1; !st.accepted && a.design.reduce; ++extra) {
        st = run(extra, 1.0);
        if (!st.designed) break;
        largest = extra;
    }
    // 2. back-off of the default weights on the largest model
    const ArmDesignSection& s = a.design;
    const bool default_weights = !(s.q_low > 0 || s.q_high > 0 || s.s_c > 0);
    for (double f : kArmBackOff) {
        if (st.accepted || !default_weights) break;
        st = run(largest, f);
    }
    if (designs.empty()) {
        if (riccati) std::rethrow_exception(riccati);
        throw ArmDesignError("arm: no step of the LQG rule gave a design: " + steps.front().note);
    }
    // the first accepted step, else the most stable design (the caller refuses it)
    size_t pick = 0;
    for (size_t i = 0; i < designs.size(); ++i) {
        if (steps[index[i]].accepted) {
            pick = i;
            break;
        }
        if (designs[i].check_unreduced.spectral_radius < designs[pick].check_unreduced.spectral_radius) pick = i;
    }
    ArmLqg out = std::move(designs[pick]);
    out.accepted_step = steps[index[pick]].accepted ? static_cast<int>(index[pick]) : -1;
    out.steps = std::move(steps);
    out.rho_max = arm_rho_max(a.T);
    return out;
}

std::string arm_lqg_refusal(const ArmDocument& a, const ArmLqg& r)
{
    std::string tried;
    for (const ArmLqgStep& st : r.steps)
        if (st.designed) tried += (tried.empty() ? "" : "; ") + st.rule + ": " + rho(st.rho_unreduced) + ", " + fmt(st.modulus_unreduced);
    return "arm: the LQG loop on the unreduced arm with d_i = " + std::to_string(a.di) + ", d_o = " + std::to_string(a.dout) +
           " has no step of the spillover rule with spectral radius <= " + rho(r.rho_max) + " and min|1+L| >= " +
           fmt(kArmModulusMin) + " (" + tried + "): give design.lqg weights";
}

nlohmann::json arm_lqg_rule_json(const ArmLqg& r)
{
    nlohmann::json steps = nlohmann::json::array();
    for (const ArmLqgStep& st : r.steps) {
        nlohmann::json j = {{"rule", st.rule}, {"extra_modes", st.extra_modes}, {"back_off", st.back_off},
                            {"designed", st.designed}, {"accepted", st.accepted}};
        if (st.designed) {
            j["reduced_states"] = st.reduced_states;
            j["spectral_radius_reduced"] = st.rho_reduced;
            j["spectral_radius_unreduced"] = st.rho_unreduced;
            j["modulus_margin_unreduced"] = st.modulus_unreduced;
        } else {
            j["note"] = st.note;
        }
        steps.push_back(j);
    }
    return {{"criterion", "on the unreduced arm with the document's delays: spectral radius <= exp(-kArmDecayMin T), "
                          "kArmDecayMin = 1e-6 1/s, and min|1+L| >= 0.25 (docs/arm_format.md)"},
            {"rho_max", r.rho_max},
            {"modulus_min", kArmModulusMin},
            {"accepted", r.accepted()},
            {"accepted_rule", r.accepted() ? nlohmann::json(r.steps[static_cast<size_t>(r.accepted_step)].rule) : nlohmann::json(nullptr)},
            {"stability_margin", 1.0 - r.check_unreduced.spectral_radius},
            {"steps", steps}};
}

// ---- the move ----

Move::Move(double q0, const std::vector<Segment>& segs) : q0_(q0)
{
    if (!std::isfinite(q0)) throw std::invalid_argument("move: start angle must be finite");
    if (segs.empty()) throw std::invalid_argument("move: at least one segment");
    double q = q0, t = -1e300;
    for (size_t i = 0; i < segs.size(); ++i) {
        const Segment& s = segs[i];
        const std::string w = "move segment " + std::to_string(i + 1) + ": ";
        if (!(std::isfinite(s.duration) && s.duration > 0.0))
            throw std::invalid_argument(w + "duration " + fmt(s.duration) + " s: allowed > 0");
        if (!(std::isfinite(s.t_start) && s.t_start >= 0.0))
            throw std::invalid_argument(w + "start time " + fmt(s.t_start) + " s: allowed >= 0");
        if (s.t_start < t) throw std::invalid_argument(w + "starts at " + fmt(s.t_start) + " s, before the previous segment ends at " + fmt(t) + " s");
        if (!std::isfinite(s.q_end) || s.q_end == q) throw std::invalid_argument(w + "end angle " + fmt(s.q_end) + " rad: must differ from its start " + fmt(q) + " rad");
        const double se = std::fabs(s.q_end - q);
        const double qd = 1.5 * se / s.duration, qdd = 9.0 * se / (s.duration * s.duration);
        ptp_.emplace_back(PtpSpec{q, s.q_end, qd * (1.0 + 1e-12), qdd, s.t_start, s.t_start + s.duration});
        q = s.q_end;
        t = s.t_start + s.duration;
    }
    t0_ = segs.front().t_start;
    t1_ = t;
}

Move Move::parse(const std::string& spec)
{
    // "Q0:Q1@T0+DUR,Q2@T1+DUR..."
    const size_t colon = spec.find(':');
    auto bad = [&](const std::string& why) {
        throw std::invalid_argument("--move '" + spec + "': " + why + " (format Q0:Q1@T0+DUR[,Q2@T1+DUR...], rad and s)");
    };
    if (colon == std::string::npos) bad("no ':' after the start angle");
    auto number = [&](const std::string& t) {
        try {
            size_t k = 0;
            const double v = std::stod(t, &k);
            if (k != t.size()) bad("'" + t + "' is not a number");
            return v;
        } catch (const std::exception&) {
            bad("'" + t + "' is not a number");
        }
        return 0.0;
    };
    const double q0 = number(spec.substr(0, colon));
    std::vector<Segment> segs;
    std::stringstream ss(spec.substr(colon + 1));
    std::string item;
    while (std::getline(ss, item, ',')) {
        const size_t at = item.find('@'), plus = item.find('+', at == std::string::npos ? 0 : at);
        if (at == std::string::npos || plus == std::string::npos) bad("segment '" + item + "' is not Q@T+DUR");
        segs.push_back({number(item.substr(0, at)), number(item.substr(at + 1, plus - at - 1)), number(item.substr(plus + 1))});
    }
    return Move(q0, segs);
}

Move Move::from_csv(const std::string& path)
{
    const io::SignalTable tab = io::read_signal_csv(path);
    const std::vector<double>* q = nullptr;
    for (size_t i = 0; i < tab.names.size(); ++i)
        if (tab.names[i] == "q") q = &tab.columns[i];
    if (!q) throw std::invalid_argument("--move-csv " + path + ": needs a column 'q' (tip angle, rad)");
    if (tab.t.size() < 8) throw std::invalid_argument("--move-csv " + path + ": needs at least 8 rows");
    Move m;
    m.csv_t_ = tab.t;
    m.csv_q_ = *q;
    m.q0_ = q->front();
    m.t0_ = tab.t.front();
    m.t1_ = tab.t.back();
    return m;
}

std::array<double, 5> Move::eval(double t) const
{
    std::array<double, 5> r{q0_, 0, 0, 0, 0};
    if (!csv_t_.empty()) {
        // linear interpolation of q and of the 5-point central differences at the samples
        const double h = (csv_t_.back() - csv_t_.front()) / static_cast<double>(csv_t_.size() - 1);
        const long n = static_cast<long>(csv_t_.size());
        auto qk = [&](long k) { return csv_q_[static_cast<size_t>(std::clamp(k, 0L, n - 1))]; };
        auto deriv = [&](long k, int order) {
            // repeated 5-point first derivative (O(h^4)), held constant outside the record
            std::function<double(long, int)> d = [&](long j, int o) -> double {
                if (j <= 0 || j >= n - 1) return o == 0 ? qk(j) : 0.0;
                if (o == 0) return qk(j);
                return (d(j - 2, o - 1) - 8.0 * d(j - 1, o - 1) + 8.0 * d(j + 1, o - 1) - d(j + 2, o - 1)) / (12.0 * h);
            };
            return d(k, order);
        };
        const double x = (t - csv_t_.front()) / h;
        const long k = static_cast<long>(std::floor(x));
        const double f = x - k;
        for (int o = 0; o < 5; ++o) r[static_cast<size_t>(o)] = (1.0 - f) * deriv(k, o) + f * deriv(k + 1, o);
        return r;
    }
    double q = q0_;
    for (const SinSquaredPtp& p : ptp_) {
        const auto e = p.eval(t);
        r[0] += e[0] - q;  // each segment's own start angle is subtracted: the segments add up
        for (int o = 1; o < 5; ++o) r[static_cast<size_t>(o)] += e[static_cast<size_t>(o)];
        q = p.eval(p.t_end() + 1.0)[0];
    }
    return r;
}

std::string Move::describe() const
{
    if (!csv_t_.empty()) return "CSV tip reference, " + std::to_string(csv_t_.size()) + " samples";
    std::string s = fmt(q0_) + " rad";
    for (const SinSquaredPtp& p : ptp_) s += " -> " + fmt(p.eval(p.t_end() + 1.0)[0]) + " rad (" + fmt(p.t_end() - p.duration()) + ".." + fmt(p.t_end()) + " s)";
    return s;
}

// ---- ArmCtrl ----

ArmctrlForArm design_armctrl_for_arm(const ArmDocument& a, const Move& mv, FfKind kind, double post)
{
    if (!(std::isfinite(post) && post >= 0.0)) throw std::invalid_argument("--post must be finite and >= 0");
    ArmctrlForArm out;
    out.lqg = design_arm_lqg(a);
    if (!out.lqg.accepted()) throw ArmDesignError(arm_lqg_refusal(a, out.lqg));
    ArmctrlDesign& d = out.d;
    ArmctrlSpec& s = d.spec;
    s.exp = (a.di > 0 || a.dout > 0) ? 'D' : 'C';
    s.N = a.design.N;
    s.r_t = a.beam.r_t;
    s.r_r = a.beam.r_r;
    s.di = a.di;
    s.dout = a.dout;
    s.T = a.T;
    s.torque_limit = a.torque_peak;
    s.wd_ramp = a.torque_peak / 0.01;  // the limit to 0 in 10 ms (issue 9 fault reaction)
    // an IMU whose readings arrive d_o cycles late may also come that rarely (docs/arm_format.md)
    s.wd_stale = std::max(2, a.dout);
    d.variant = s.exp - 'A';
    const double T = a.T;
    if (mv.t_start() < 0.0) throw std::invalid_argument("the move must not start before 0 s");
    d.lead = {0, 0, -static_cast<long>(s.dout), static_cast<long>(s.di)};
    const long k0 = -static_cast<long>(s.dout);
    const long k1 = static_cast<long>(std::ceil((mv.t_end() + post) / T - 1e-9));
    const long n_ff = k1 - k0 + 1;
    if (n_ff > 4096)
        throw std::invalid_argument("the feedforward table would need " + std::to_string(n_ff) +
                                    " samples (> 4096, ARMCTRL_FF_MAX): shorten --post or the move");
    d.t0 = k0 * T;
    d.dt = T;
    d.t_motion_start = mv.t_start();
    d.t_motion_end = mv.t_end();
    for (auto& r : d.ff) r.assign(static_cast<size_t>(n_ff), 0.0);
    if (kind == FfKind::Rigid) {
        d.I_l = a.rigid_link_inertia();
        for (long k = 0; k < n_ff; ++k) {
            const auto q = mv.eval((k0 + k) * T);
            const auto f = rigid_body_feedforward(q, a.drive.I_M, d.I_l, a.drive.c_s);
            d.ff[0][static_cast<size_t>(k)] = f[0];
            d.ff[1][static_cast<size_t>(k)] = f[1];
            d.ff[2][static_cast<size_t>(k)] = q[1];
            d.ff[3][static_cast<size_t>(k)] = f[3];
        }
    } else {
        const long ki = std::min(k0, static_cast<long>(std::floor((mv.t_start() - 2.0) / T)));
        const auto r = stable_inversion(out.lqg.reduced, T, [&](double t) { return mv.eval(t)[1]; }, ki * T, (k1 + 0.5) * T);
        if (static_cast<long>(r.t.size()) < k1 - ki + 1) throw std::runtime_error("stable inversion horizon too short");
        const long off = k0 - ki;
        for (long k = 0; k < off; ++k) d.head_tau_max = std::max(d.head_tau_max, std::fabs(r.u[static_cast<size_t>(k)]));
        for (long k = 0; k < n_ff; ++k) {
            const size_t i = static_cast<size_t>(off + k);
            d.ff[0][static_cast<size_t>(k)] = r.theta_M[i] + mv.q_start();
            d.ff[1][static_cast<size_t>(k)] = r.theta_M_dot[i];
            d.ff[2][static_cast<size_t>(k)] = r.y_des[i];
            d.ff[3][static_cast<size_t>(k)] = r.u[i];
        }
        d.ibffc = r;
    }
    for (double u : d.ff[3]) d.tau_max = std::max(d.tau_max, std::fabs(u));
    if (d.tau_max > a.torque_peak)
        throw ArmDesignError("arm: the move's feedforward needs " + fmt(d.tau_max) + " N m, more than drive.torque_peak = " +
                             fmt(a.torque_peak) + " N m: slow the move");
    double head = 0.0;
    for (long k = 0; k <= std::min<long>(n_ff - 1, -k0 + s.di); ++k) head = std::max(head, std::fabs(d.ff[3][static_cast<size_t>(k)]));
    d.start_tau = head;
    if (head > kArmctrlRestTol * d.tau_max) {
        // The lead the pre-actuation needs: the first sample of the inversion
        // (from ki, up to 2 s before the move) above the rest tolerance.
        double lead = mv.t_start() - d.t0;
        bool bound = false;
        if (kind != FfKind::Rigid) {
            const std::vector<double>& u = d.ibffc->u;
            size_t i = 0;
            while (i < u.size() && std::fabs(u[i]) <= kArmctrlRestTol * d.tau_max) ++i;
            bound = i == 0;
            lead = mv.t_start() - d.ibffc->t[std::min(i, u.size() - 1)];
        }
        throw MoveStartTooEarly("the feedforward is not at rest where the playback starts (|tau_M*| = " + fmt(head) +
                                    " N m, more than " + fmt(kArmctrlRestTol) + " x its peak " + fmt(d.tau_max) +
                                    " N m): the pre-actuation needs " + (bound ? "more than " : "") + fmt(lead) +
                                    " s before the move, which starts at " + fmt(mv.t_start()) + " s; start the move later",
                                lead);
    }
    d.pre_actuation_start = d.t_motion_end;
    for (long k = 0; k < n_ff; ++k)
        if (std::fabs(d.ff[3][static_cast<size_t>(k)]) > 1e-3 * d.tau_max) {
            d.pre_actuation_start = d.t0 + k * T;
            break;
        }
    for (const auto& row : d.ff) d.tail_step = std::max(d.tail_step, std::fabs(row[static_cast<size_t>(n_ff - 1)] - row[static_cast<size_t>(n_ff - 2)]));
    const long n = out.lqg.reduced.nx(), nb = n + s.di + s.dout;
    if (n > 32) throw ArmDesignError("arm: plant order " + std::to_string(n) + " > ARMCTRL_LQG_NMAX = 32: fewer shifts (design.reduce_multiple)");
    if (nb + 1 > 64) throw ArmDesignError("arm: n + d_i + d_o + 1 = " + std::to_string(nb + 1) + " exceeds the PLC's FRAC_MAT_MAX = 64");
    d.lqg = out.lqg.lqg;
    d.check_reduced = out.lqg.check_reduced;
    d.check_unreduced = out.lqg.check_unreduced;
    armctrl_take_lqg(d, out.lqg.lqg);
    armctrl_fill_table(d, "arm document '" + a.name + "': " + (kind == FfKind::Rigid ? "rbFFC (4.14)-(4.17)" : "ibFFC (stable inversion)") +
                              ", LQG with d_i, d_o (7.18)-(7.27), move " + mv.describe());
    d.table.meta["arm"] = a.name;
    d.table.meta["feedforward"] = kind == FfKind::Rigid ? "rigid" : "inverse";
    return out;
}

// ---- HIL plant table, gap nominal, scenario ----

tables::ParamTable arm_plant_table_for(const ArmDocument& a, double h)
{
    if (!std::isfinite(h) || !(h > 0.0) || h > 0.1) throw std::invalid_argument("--h " + fmt(h) + " s: allowed (0, 0.1] s");
    const ArmBuild b = build_arm_from_document(a, a.design.N, false, {});
    const StateSpace c = b.arm.state_space();
    const Eigen::Index n = c.nx();
    Eigen::MatrixXd C(4, n);
    C.row(0) = Eigen::RowVectorXd::Unit(n, 0);
    C.row(1) = c.C.row(0);
    C.row(2) = arm_angle_row(b, a.imu_position);
    C.row(3) = arm_document_measured(a, b).C.row(2);
    const double scale = C.row(3).cwiseAbs().maxCoeff() + 1.0;
    const double res = (C.row(2) * c.A - C.row(3)).cwiseAbs().maxCoeff() / scale;
    const double feed = std::fabs((C.row(2) * c.B.col(0))(0, 0)) / scale;
    if (!(res < 1e-8) || !(feed < 1e-9))
        throw std::runtime_error("plant table: the IMU angle row is not the integral of its rate (residual " + fmt(res) + ", " +
                                 fmt(feed) + ")");
    StateSpace one = c;
    one.B = c.B.col(0);
    one.C = C;
    one.D = Eigen::MatrixXd::Zero(4, 1);
    one.inputs = {c.inputs[0]};
    one.outputs = {"theta_M [rad]", "theta_M_dot [rad/s]", "psi(z_imu) [rad]", "psi_dot(z_imu) [rad/s]"};
    tables::ParamTable t;
    t.name = "arm_plant";
    t.meta = {{"source", "arm document '" + a.name + "': full pseudo-spectral arm (3.103) with payload, fracdesign model --arm"},
              {"N", b.beam.N}, {"h", h}, {"I_M", a.drive.I_M}, {"imu_position", a.imu_position}};
    Eigen::MatrixXd dims(1, 3);
    dims << static_cast<double>(n), static_cast<double>(b.beam.N), static_cast<double>(n - 4 - 4 * b.beam.N);
    t.add("plant_dims", dims, "n states, N collocation points, payload states");
    add_arm_plant_steps(t, one, h);
    t.add("C", C, "theta_M [rad], theta_M' [rad/s], psi(z_imu) [rad], psi'(z_imu) [rad/s]");
    t.validate();
    return t;
}

void add_arm_plant_steps(tables::ParamTable& t, const StateSpace& one, double h)
{
    const StateSpace d = c2d_zoh(one, h);
    const FohDiscretisation f = c2d_foh(one, h);
    t.add("h", h, "step of Ad, Bd [s]");
    t.add("Ad", d.A, "exact ZOH of Ac at h");
    t.add("Bd", d.B, "exact ZOH of Bc at h; input net driven-side torque [N m]");
    t.add("Bd1", Eigen::MatrixXd(0.5 * h * (f.B_now - f.B_prev)),
          "exact response over h to the torque's ramp about its mid-step value, per unit slope [N m/s]");
    t.add("Ac", one.A, "continuous");
    t.add("Bc", one.B, "continuous");
}

int arm_imu_reading_cycles(const ArmDocument& a) { return 2 * std::max(1, a.dout - 1); }

namespace {

// The document's friction (seed 004 (5.2): b1 v + b0 tanh(k v) on the motor, as the rig's plant applies
// it) as the nominal's gap.friction, so the replay runs what the rig runs; an arm without known friction
// gets none. The gap's friction effects then fit what lies beyond it.
// The viscous part is linear and goes into the plant itself (with_viscous: exact in continuous time, as
// the rig integrates it), the Coulomb part into gap.friction (the replay holds it over the cycle).
nlohmann::json with_friction(const ArmDocument& a, nlohmann::json gap)
{
    if (a.friction.known && a.friction.b0 != 0.0) gap["friction"] = {{"coulomb", a.friction.b0}, {"tanh_k", a.friction.k}};
    return gap;
}

// The document's viscous friction b1 on the motor, the plant's torque input 0 and motor velocity row
// vrow: A - b1 B(:, 0) vrow.
void with_viscous(const ArmDocument& a, StateSpace& m, Eigen::Index vrow)
{
    if (a.friction.known && a.friction.b1 != 0.0) m.A -= a.friction.b1 * m.B.col(0) * m.C.row(vrow);
}

std::string friction_words(const ArmDocument& a)
{
    if (!a.friction.known || (a.friction.b1 == 0.0 && a.friction.b0 == 0.0)) return "no friction";
    return "the document's friction " + fmt(a.friction.b1) + " v + " + fmt(a.friction.b0) + " tanh(" + fmt(a.friction.k) +
           " v) N m on the motor (the viscous part in the plant, the Coulomb part as gap.friction)";
}

// The rig's IMU reading of the link rate, one model for every gap nominal of the arm (open and closed loop).
// The reading (hil/imu.c, r = arm_imu_reading_cycles acquisitions at T/2 between samples, sent r
// acquisitions later) is psi'(t_{k-q}) with the age q = h .. 2h - 1 cycles, h = r/2, running through
// the hold (measured on the rig: imu_rate[k] equals tip_velocity[k - q] to the gyro's wire step).
// Periodically time-varying for h > 1; the LTI map nearest to it for every input is the mean over
// the phases, imu_rate[k] = (1/h) sum_{q=h}^{2h-1} psi'(t_{k-q}) (mean age (3h - 1)/2 cycles).
// The discrete plant (A, B) of n0 states, whose link rate at t_k is rate_row x[k], gets the states
// imu_past[q][k] = psi'(t_{k-q}), q = 1 .. L = 2h - 1 (imu_past[1][k+1] = rate_row x[k],
// imu_past[q+1][k+1] = imu_past[q][k]); returns the output row of the mean reading over the enlarged
// state and appends the states' names.
struct ImuReadingRow {
    Eigen::RowVectorXd mean;    // (1/h) sum_{q=h}^{2h-1} imu_past[q]
    Eigen::RowVectorXd sample;  // imu_past[h]: the reading as it arrives (its youngest age)
    Eigen::Index h;           // cycles between readings (and the youngest age)
    std::string ages;         // the ages in words, for the nominal's description
};

ImuReadingRow append_imu_reading(const ArmDocument& a, const Eigen::RowVectorXd& rate_row, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                 std::vector<std::string>& states)
{
    const Eigen::Index n0 = A.rows(), h = arm_imu_reading_cycles(a) / 2, L = 2 * h - 1, N = n0 + L;
    Eigen::MatrixXd A2 = Eigen::MatrixXd::Zero(N, N), B2 = Eigen::MatrixXd::Zero(N, B.cols());
    A2.topLeftCorner(n0, n0) = A;
    B2.topRows(n0) = B;
    A2.block(n0, 0, 1, n0) = rate_row;
    for (Eigen::Index q = 1; q < L; ++q) A2(n0 + q, n0 + q - 1) = 1.0;
    A = A2;
    B = B2;
    ImuReadingRow r;
    r.h = h;
    r.mean = Eigen::RowVectorXd::Zero(N);
    for (Eigen::Index q = h; q <= L; ++q) r.mean(n0 + q - 1) = 1.0 / static_cast<double>(h);
    r.sample = Eigen::RowVectorXd::Unit(N, n0 + h - 1);
    for (Eigen::Index q = 1; q <= L; ++q) states.push_back("imu_past[" + std::to_string(q) + "]");
    r.ages = h == 1 ? "1 cycle old" : "the mean of psi' " + std::to_string(h) + " .. " + std::to_string(L) + " cycles old";
    return r;
}

}  // namespace

nlohmann::json arm_gap_nominal(const ArmDocument& a)
{
    const ArmBuild b = build_arm_from_document(a, a.design.N, false, {});
    StateSpace m = arm_document_measured(a, b);
    with_viscous(a, m, 1);
    m.C = m.C.bottomRows(2).eval();  // theta_M', psi'(z_imu)
    m.D = Eigen::MatrixXd::Zero(2, 1);
    m.outputs = {"motor_velocity", "imu_rate"};
    // The rig's drive ramps the shaft torque over [t_k, t_{k+1}] from torque_actual[k-1] to
    // torque_actual[k] (hil/drive.c, RIG_TORQUE): first-order hold, exact, with the previous torque as a
    // state. motor_velocity[k] = theta_M'(t_k) (the drive's TPDO at SYNC k).
    const FohDiscretisation d = c2d_foh(m, a.T);
    const Eigen::Index n = d.Ad.rows();
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 1, n + 1), B = Eigen::MatrixXd::Zero(n + 1, 1);
    A.topLeftCorner(n, n) = d.Ad;
    A.block(0, n, n, 1) = d.B_prev;
    B.topRows(n) = d.B_now;
    B(n, 0) = 1.0;  // torque_prev[k+1] = torque_actual[k]
    Eigen::RowVectorXd rate = Eigen::RowVectorXd::Zero(n + 1);
    rate.head(n) = m.C.row(1);
    std::vector<std::string> states = m.states;
    states.push_back("torque_prev");
    const ImuReadingRow imu = append_imu_reading(a, rate, A, B, states);
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(2, A.rows());
    C.block(0, 0, 1, n) = m.C.row(0);
    C.row(1) = imu.mean;
    const std::string hs = std::to_string(imu.h);
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "arm_nominal_" + a.name},
            {"description", "gap nominal of the arm document '" + a.name + "' (fracdesign model --arm --gap-nominal): the full arm (N = " +
                                std::to_string(b.beam.N) + ", " + std::to_string(n) + " states) the controller was designed and checked on, "
                                "open loop from the drive's torque_actual to motor_velocity and imu_rate, first-order hold at T "
                                "(the drive's torque ramps from the previous torque_actual to this one, state torque_prev), imu_rate " +
                                imu.ages + " (the rig's IMU reading every " + hs + " cycles, sent " + hs +
                                " cycles after its sample, as an LTI map), " + friction_words(a)},
            {"time", "discrete"},
            {"Ts", a.T},
            {"A", mat(A)},
            {"B", mat(B)},
            {"C", mat(C)},
            {"D", mat(Eigen::MatrixXd::Zero(2, 1))},
            {"inputs", {"torque_actual"}},
            {"outputs", {"motor_velocity", "imu_rate"}},
            {"states", states},
            {"gap", with_friction(a, {{"velocity", "motor_velocity"}, {"force_input", "torque_actual"}})}};
}

nlohmann::json arm_gap_nominal_closed(const ArmDocument& a, const std::string& table)
{
    if (table.empty()) throw std::invalid_argument("--closed-loop: the ArmCtrl table file name is empty");
    const ArmBuild b = build_arm_from_document(a, a.design.N, false, {});
    StateSpace m = arm_document_measured(a, b);  // outputs theta_M, theta_M', psi'(z_imu); input tau_M
    with_viscous(a, m, 1);
    const Eigen::Index n = m.nx();
    // The drive (hil/drive.h, seed 004 Sec. 8.2): the current loop tau_a' = (c - tau_a)/tau_c with the
    // command c held over the cycle, tau_a(k+1) = e tau_a(k) + (1 - e) c(k), e = exp(-T/tau_c) (0 for
    // an ideal loop); the shaft gets the torque ramped linearly from tau_a(k) to tau_a(k+1) over the
    // cycle (first-order hold), so x(k+1) = Phi x + G0 tau_a(k) + G1 (tau_a(k+1) - tau_a(k)) / T with
    // [Phi G0 G1] the first block row of exp([[A, B, 0], [0, 0, 1], [0, 0, 0]] T).
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + 2, n + 2);
    M.topLeftCorner(n, n) = m.A;
    M.block(0, n, n, 1) = m.B.col(0);
    M(n, n + 1) = 1.0;
    const Eigen::MatrixXd E = (M * a.T).exp();
    const Eigen::MatrixXd Phi = E.topLeftCorner(n, n);
    const Eigen::VectorXd G0 = E.block(0, n, n, 1), G1 = E.block(0, n + 1, n, 1) / a.T;
    const double e = a.current_tau > 0.0 ? std::exp(-a.T / a.current_tau) : 0.0;
    // states [x; tau_a; the IMU reading's chain (append_imu_reading)]
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 1, n + 1), B = Eigen::MatrixXd::Zero(n + 1, 1);
    A.topLeftCorner(n, n) = Phi;
    A.block(0, n, n, 1) = G0 + G1 * (e - 1.0);
    B.topRows(n) = G1 * (1.0 - e);
    A(n, n) = e;
    B(n, 0) = 1.0 - e;
    Eigen::RowVectorXd rate = Eigen::RowVectorXd::Zero(n + 1);
    rate.head(n) = m.C.row(2);
    std::vector<std::string> states = m.states;
    states.push_back("torque_actual");
    // Friction acts on the shaft itself, not through the current loop and the ramp: the second input
    // friction_torque (gap.friction_input) is a torque on the motor held over the cycle, column G0
    // (zero-order hold); zero in the record and from ArmCtrl.
    B.conservativeResize(n + 1, 2);
    B.col(1).setZero();
    B.block(0, 1, n, 1) = G0;
    const ImuReadingRow imu = append_imu_reading(a, rate, A, B, states);
    // The replay holds the reading exactly (gap.output_hold: imu_rate reads imu_rate_sample every h
    // cycles at the record's phase and repeats it in between, as ArmCtrl received it); the LTI row of
    // imu_rate, the mean over the phases, is what the nominal's modes and small-signal checks see.
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(4, A.rows());
    C.block(0, 0, 2, n) = m.C.topRows(2);
    C.row(2) = imu.mean;
    C.row(3) = imu.sample;
    nlohmann::json hold = nlohmann::json::object();
    if (imu.h > 1) hold["imu_rate"] = {{"every", imu.h}, {"sample", "imu_rate_sample"}};
    const std::string hs = std::to_string(imu.h);
    const nlohmann::json controller = {
        {"kind", "armctrl"},
        {"table", table},
        {"inputs", {{"MotorAngle", "motor_angle"}, {"MotorVelocity", "motor_velocity"}, {"TipRate", "imu_rate"}}},
        {"output", "torque_cmd"}};
    nlohmann::json doc = {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "arm_closed_loop_" + a.name},
            {"description", "closed-loop gap nominal of the arm document '" + a.name + "' (fracdesign model --arm --gap-nominal --closed-loop): "
                            "ArmCtrl from the table '" + table + "' (replayed by gap-plc in the task runtime) on the full arm (N = " +
                                std::to_string(b.beam.N) + ", " + std::to_string(n) + " states), the drive's delay d_i = " +
                                std::to_string(a.di) + " cycles, peak torque limit, current loop (tau_c = " + fmt(a.current_tau) +
                                " s) and first-order hold to the shaft; imu_rate " + imu.ages + " (the rig's IMU reading every " + hs +
                                " cycles, sent " + hs + " cycles after its sample, as an LTI map); " + friction_words(a)},
            {"time", "discrete"},
            {"Ts", a.T},
            {"A", mat(A)},
            {"B", mat(B)},
            {"C", mat(C)},
            {"D", mat(Eigen::MatrixXd::Zero(4, 2))},
            {"inputs", {"torque_cmd", "friction_torque"}},
            {"outputs", {"motor_angle", "motor_velocity", "imu_rate", "imu_rate_sample"}},
            {"states", states},
            {"gap", {{"velocity", "motor_velocity"},
                     {"force_input", "torque_cmd"},
                     {"friction_input", "friction_torque"},
                     {"units", {{"torque_cmd", "N m"}, {"motor_angle", "rad"}, {"motor_velocity", "rad/s"}, {"imu_rate", "rad/s"},
                                {"imu_rate_sample", "rad/s"}, {"friction_torque", "N m"}}},
                     {"closed_loop", {{"references", nlohmann::json::array()},
                                      {"measured", {"motor_angle", "motor_velocity", "imu_rate"}},
                                      {"controller", controller},
                                      {"delay_samples", a.di},
                                      {"saturation", a.torque_peak}}}}}};
    if (!hold.empty()) doc["gap"]["output_hold"] = hold;
    doc["gap"] = with_friction(a, doc["gap"]);
    return doc;
}

std::string arm_hil_scenario(const ArmDocument& a, const std::string& plant_table, const std::string& ctrl_table, double duration)
{
    // The IMU node reads every r/2 cycles and sends r acquisitions (r/2 cycles) later: seen r/2 .. r/2 + 1
    // cycles old, i.e. d_o = r/2 + 1 (the thesis's r = 4 for d_o = 3). r = 2 (d_o - 1) must lie in 2..8
    // (hil/imu.h), so the rig models d_o = 2..5 and no other: a d_o of 0 or 1 would run with 2.
    if (a.dout < kRigImuDoMin || a.dout > kRigImuDoMax)
        throw ArmDocumentError("delays.output", "value " + std::to_string(a.dout) + ": the HIL rig's IMU node models only [" +
                                                    std::to_string(kRigImuDoMin) + ", " + std::to_string(kRigImuDoMax) +
                                                    "] samples (imu.reading_cycles = 2 (d_o - 1) in 2..8); no scenario for this arm");
    const int r = 2 * (a.dout - 1);
    int bits = 0;
    while (bits < 31 && (1L << bits) < a.encoder_counts) ++bits;
    if ((1L << bits) != a.encoder_counts || bits > kRigEncoderBitsMax)
        throw ArmDocumentError("sensors.encoder_counts_per_rev",
                               "value " + std::to_string(a.encoder_counts) + ": the HIL rig's drive counts 2^bits per revolution, "
                               "bits in [1, " + std::to_string(kRigEncoderBitsMax) + "] (2 .. " +
                               std::to_string(1L << kRigEncoderBitsMax) + ", a power of 2); no scenario for this arm");
    std::ostringstream s;
    s.precision(10);
    s << "# hil_bench scenario of the arm document '" << a.name << "' (fracdesign model --arm --save-scenario)\n"
      << "T = " << a.T << "\nduration = " << duration << "\nplant = arm\nplant.table = " << plant_table
      << "\nplant.L = " << a.imu_position + a.drive.r_h << "\nctrl.law = armctrl\nctrl.table = " << ctrl_table
      << "\ndrive.delay = " << a.di << "\ndrive.tau_current = " << a.current_tau << "\ndrive.torque_rated = " << a.torque_rated
      << "\ndrive.torque_peak = " << a.torque_peak << "\ndrive.encoder_bits = " << bits
      << "\nimu.reading_cycles = " << r << "\nimu.gyro_noise = " << a.imu_noise << "\n";
    if (a.friction.known)
        s << "plant.friction = 0\nplant.fric_b1 = " << a.friction.b1 << "\nplant.fric_b0 = " << a.friction.b0
          << "\nplant.fric_k = " << a.friction.k << "\n";
    else
        s << "plant.friction = 0\nplant.fric_b1 = 0\nplant.fric_b0 = 0\n";
    return s.str();
}

}  // namespace fracdesign::design
