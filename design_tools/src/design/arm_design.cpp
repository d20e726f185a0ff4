// arm_design.cpp - the design chain for an arm document (design/arm_design.hpp).
#include "fracdesign/design/arm_design.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

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

ArmReduction choose_reduction(const ArmDocument& a)
{
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
    for (double f : beam_hz) {
        const double w = 2.0 * kPi * f;
        if (r.beam_modes_rad_s.size() >= 2 && w > a.design.reduce_multiple * wb) break;
        if (static_cast<int>(r.beam_modes_rad_s.size()) >= kArmShiftsMax - 1) break;
        r.beam_modes_rad_s.push_back(w);
    }
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
    p.s_o = s.s_o;
    return p;
}

ArmLqg design_arm_lqg(const ArmDocument& a)
{
    ArmLqg r;
    const int N = a.design.N;
    if (a.design.reduce) {
        r.reduction = choose_reduction(a);
        r.reduced = arm_document_measured(a, build_arm_from_document(a, N, true, r.reduction.shifts));
    }
    r.full = arm_document_measured(a, build_arm_from_document(a, N, false, {}));
    if (!a.design.reduce) r.reduced = r.full;
    const LqgParams p = arm_lqg_params(a);
    if (p.n_low > r.reduced.nx())
        throw ArmDesignError("arm: design.lqg.n_low = " + std::to_string(p.n_low) + " exceeds the model order " +
                             std::to_string(r.reduced.nx()));
    r.lqg = design_lqg(r.reduced, p);
    r.check_reduced = check_closed_loop(r.lqg, r.reduced, a.di, a.dout);
    r.check_unreduced = check_closed_loop(r.lqg, r.full, a.di, a.dout);
    return r;
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
    if (!(out.lqg.check_unreduced.spectral_radius < 1.0))
        throw ArmDesignError("arm: the LQG loop on the unreduced arm with d_i = " + std::to_string(a.di) + ", d_o = " +
                             std::to_string(a.dout) + " is unstable (spectral radius " +
                             fmt(out.lqg.check_unreduced.spectral_radius) + "): give design.lqg weights");
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
    if (head > kArmctrlRestTol * d.tau_max)
        throw std::runtime_error("the feedforward is not at rest where the playback starts (|tau_M*| = " + fmt(head) +
                                 " N m): the pre-actuation needs more than the move's start " + fmt(mv.t_start()) +
                                 " s; start the move later");
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
    const StateSpace d = c2d_zoh(one, h);
    tables::ParamTable t;
    t.name = "arm_plant";
    t.meta = {{"source", "arm document '" + a.name + "': full pseudo-spectral arm (3.103) with payload, fracdesign model --arm"},
              {"N", b.beam.N}, {"h", h}, {"I_M", a.drive.I_M}, {"imu_position", a.imu_position}};
    Eigen::MatrixXd dims(1, 3);
    dims << static_cast<double>(n), static_cast<double>(b.beam.N), static_cast<double>(n - 4 - 4 * b.beam.N);
    t.add("plant_dims", dims, "n states, N collocation points, payload states");
    t.add("h", h, "step of Ad, Bd [s]");
    t.add("Ad", d.A, "exact ZOH of Ac at h");
    t.add("Bd", d.B, "exact ZOH of Bc at h; input net driven-side torque [N m]");
    t.add("C", C, "theta_M [rad], theta_M' [rad/s], psi(z_imu) [rad], psi'(z_imu) [rad/s]");
    t.add("Ac", c.A, "continuous");
    t.add("Bc", one.B, "continuous");
    t.validate();
    return t;
}

int arm_imu_reading_cycles(const ArmDocument& a) { return 2 * std::max(1, a.dout - 1); }

nlohmann::json arm_gap_nominal(const ArmDocument& a)
{
    const ArmBuild b = build_arm_from_document(a, a.design.N, false, {});
    StateSpace m = arm_document_measured(a, b);
    m.C = m.C.bottomRows(2).eval();  // theta_M', psi'(z_imu)
    m.D = Eigen::MatrixXd::Zero(2, 1);
    m.outputs = {"motor_velocity", "imu_rate"};
    // The rig's drive ramps the shaft torque over [t_k, t_{k+1}] from torque_actual[k-1] to
    // torque_actual[k] (hil/drive.c, RIG_TORQUE): first-order hold, exact, with the previous torque as a
    // state. motor_velocity[k] = theta_M'(t_k) (the drive's TPDO at SYNC k).
    const FohDiscretisation d = c2d_foh(m, a.T);
    // The IMU reading (hil/imu.c, r = arm_imu_reading_cycles acquisitions at T/2 between samples, sent r
    // acquisitions later) is psi'(t_{k-q}) with the age q = h .. 2h - 1 cycles, h = r/2, running through
    // the hold (measured on the rig: imu_rate[k] equals tip_velocity[k - q] to the gyro's wire step).
    // Periodically time-varying for h > 1; the LTI map nearest to it for every input is the mean over
    // the phases, imu_rate[k] = (1/h) sum_{q=h}^{2h-1} psi'(t_{k-q}) (mean age (3h - 1)/2 cycles).
    const Eigen::Index n = d.Ad.rows(), h = arm_imu_reading_cycles(a) / 2, L = 2 * h - 1, N = n + 1 + L;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N, N), B = Eigen::MatrixXd::Zero(N, 1), C = Eigen::MatrixXd::Zero(2, N);
    A.topLeftCorner(n, n) = d.Ad;
    A.block(0, n, n, 1) = d.B_prev;
    B.topRows(n) = d.B_now;
    B(n, 0) = 1.0;  // torque_prev[k+1] = torque_actual[k]
    // imu_past[q][k] = psi'(t_{k-q}): imu_past[1][k+1] = C_imu x[k], imu_past[q+1][k+1] = imu_past[q][k]
    A.block(n + 1, 0, 1, n) = m.C.row(1);
    for (Eigen::Index q = 1; q < L; ++q) A(n + 1 + q, n + q) = 1.0;
    C.block(0, 0, 1, n) = m.C.row(0);
    for (Eigen::Index q = h; q <= L; ++q) C(1, n + q) = 1.0 / static_cast<double>(h);
    std::vector<std::string> states = m.states;
    states.push_back("torque_prev");
    for (Eigen::Index q = 1; q <= L; ++q) states.push_back("imu_past[" + std::to_string(q) + "]");
    const std::string ages = h == 1 ? "1 cycle" : "the mean of psi' " + std::to_string(h) + " .. " + std::to_string(L) + " cycles old";
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "arm_nominal_" + a.name},
            {"description", "gap nominal of the arm document '" + a.name + "' (fracdesign model --arm --gap-nominal): the full arm (N = " +
                                std::to_string(b.beam.N) + ", " + std::to_string(n) + " states) the controller was designed and checked on, "
                                "open loop from the drive's torque_actual to motor_velocity and imu_rate, first-order hold at T "
                                "(the drive's torque ramps from the previous torque_actual to this one, state torque_prev), imu_rate " +
                                ages + " (the rig's IMU reading every " + std::to_string(h) + " cycles, sent " + std::to_string(h) +
                                " cycles after its sample, as an LTI map), no friction"},
            {"time", "discrete"},
            {"Ts", a.T},
            {"A", mat(A)},
            {"B", mat(B)},
            {"C", mat(C)},
            {"D", mat(Eigen::MatrixXd::Zero(2, 1))},
            {"inputs", {"torque_actual"}},
            {"outputs", {"motor_velocity", "imu_rate"}},
            {"states", states},
            {"gap", {{"velocity", "motor_velocity"}, {"force_input", "torque_actual"}}}};
}

std::string arm_hil_scenario(const ArmDocument& a, const std::string& plant_table, const std::string& ctrl_table, double duration)
{
    // The IMU node reads every r/2 cycles and sends r acquisitions (r/2 cycles) later: seen r/2 .. r/2 + 1
    // cycles old, i.e. d_o = r/2 + 1 (the thesis's r = 4 for d_o = 3). r must lie in 2..8.
    const int r = arm_imu_reading_cycles(a);
    if (a.dout > 5)
        throw std::invalid_argument("the HIL IMU node models d_o <= 5 samples (imu.reading_cycles <= 8); the document has " +
                                    std::to_string(a.dout));
    long bits = 0;
    while ((1L << bits) < a.encoder_counts) ++bits;
    if ((1L << bits) != a.encoder_counts || bits > 20)
        throw std::invalid_argument("the HIL drive counts 2^bits per revolution, bits <= 20; sensors.encoder_counts_per_rev = " +
                                    std::to_string(a.encoder_counts));
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
