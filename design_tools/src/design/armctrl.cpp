// armctrl.cpp - ArmCtrl parameter tables for seed 004 Exp. A-D (armctrl.hpp).
#include "fracdesign/design/armctrl.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fracdesign/models/arm.hpp"

namespace fracdesign::design {
namespace {

// ArmCtrl.h: ARMCTRL_FF_MAX samples per feedforward row, ARMCTRL_LQG_NMAX plant states and
// n_bar + 1 <= FRAC_MAT_MAX (frac/mat.h, default 64). The test checks these against the headers.
constexpr long kFfMax = 4096;
constexpr long kLqgNMax = 32;
constexpr long kMatMax = 64;

// Table 8.6 (Exp. A and B): PD (5.1) and the linear friction model (5.2) with sgn ~ tanh(k x).
constexpr double kKp = 320.0, kKd = 200.0;
constexpr double kB1 = 3.04, kB0 = 7.684, kTanh = 60.0;

std::string fmt(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

}  // namespace

void ArmctrlSpec::validate() const
{
    auto bad = [](const std::string& w) { throw std::invalid_argument(w); };
    if (exp < 'A' || exp > 'D') bad(std::string("--exp must be A, B, C or D (got '") + exp + "')");
    if (N < kArmctrlNMin || N > kArmctrlNMax)
        bad("--N (beam collocation points) must lie in [" + std::to_string(kArmctrlNMin) + ", " +
            std::to_string(kArmctrlNMax) + "] (got " + std::to_string(N) + ")");
    if (!(std::isfinite(r_t) && r_t >= 0.0)) bad("--rt must be finite and >= 0");
    if (!(std::isfinite(r_r) && r_r >= 0.0)) bad("--rr must be finite and >= 0");
    if (di < -1) bad("--di must be >= 0 (got " + std::to_string(di) + ")");
    if (dout < -1) bad("--do must be >= 0 (got " + std::to_string(dout) + ")");
    if (exp != 'D' && (di > 0 || dout > 0))
        bad(std::string("--di/--do set the delay model of Exp. D; Exp. ") + exp +
            (exp == 'C' ? " has no delay model (d_i = d_o = 0, Table 8.7)" : " has no LQG"));
    if (!(std::isfinite(T) && T > 0.0)) bad("cycle time T must be finite and > 0");
    if (!(std::isfinite(torque_limit) && torque_limit > 0.0)) bad("--torque-limit must be finite and > 0");
    if (wd_stale < 1) bad("watchdog stale cycles must be >= 1");
    if (!(std::isfinite(wd_ramp) && wd_ramp > 0.0)) bad("watchdog ramp rate must be finite and > 0");
    if (!(std::isfinite(pre) && pre >= 0.0)) bad("--pre must be finite and >= 0");
    if (!(std::isfinite(post) && post >= 0.0)) bad("--post must be finite and >= 0");
}

double wang_rigid_link_inertia()
{
    const DriveParams dr = wang_drive();
    const TimoshenkoParams b = wang_steel_beam();
    return b.rho * (std::pow(b.L + dr.r_h, 3) - std::pow(dr.r_h, 3)) / 3.0 + dr.I_h;
}

StateSpace wang_arm_measured(int N, double r_t, double r_r, bool reduce)
{
    TimoshenkoParams beam = wang_steel_beam();
    beam.r_t = r_t;
    beam.r_r = r_r;
    beam.validate();
    ArmOptions o;
    o.N = N;
    o.reduce = reduce;
    return arm_measured_model(build_arm(beam, wang_drive(), o).arm);
}

void armctrl_take_lqg(ArmctrlDesign& d, const LqgDesign& g)
{
    const long n = g.plant.nx();
    const ArmctrlSpec& s = d.spec;
    // frac/lqg.h takes the plant part of (7.18): A' = top-left of A_bar, B' = the block that feeds
    // xi_1 (d_i > 0) or B_bar's plant rows (d_i = 0), C' with the IMU row from the beta chain input.
    d.A = g.Ad.topLeftCorner(n, n);
    d.B = s.di > 0 ? Eigen::MatrixXd(g.Ad.block(0, n, n, 1)) : Eigen::MatrixXd(g.Bd.topRows(n));
    d.C = Eigen::MatrixXd(3, n);
    d.C.topRows(2) = g.Cd.block(0, 0, 2, n);
    d.C.row(2) = s.dout > 0 ? Eigen::RowVectorXd(g.Ad.block(n + s.di + s.dout - 1, 0, 1, n))
                            : Eigen::RowVectorXd(g.Cd.block(2, 0, 1, n));
    d.K = g.K;
    d.L = g.Le;
}

ArmctrlDesign design_armctrl(const ArmctrlSpec& spec_in)
{
    spec_in.validate();
    ArmctrlDesign d;
    d.spec = spec_in;
    ArmctrlSpec& s = d.spec;
    if (s.exp == 'D') {
        if (s.di < 0) s.di = 4;  // Table 8.8
        if (s.dout < 0) s.dout = 3;
    } else {
        s.di = 0;
        s.dout = 0;
    }
    d.variant = s.exp - 'A';
    const double T = s.T;
    const SinSquaredPtp ptp(s.traj);
    // Sec. 8.6: torque row played d_i cycles early, IMU reference row d_o cycles late.
    d.lead = {0, 0, -static_cast<long>(s.dout), static_cast<long>(s.di)};
    // Table grid: one sample per cycle, sample 0 at table time -d_o T so that the lagged IMU row
    // is inside the table from cycle 0 on; cycle 0 of the counter is table time 0.
    const long k0 = -static_cast<long>(s.dout);
    const long k1 = static_cast<long>(std::ceil((ptp.t_end() + s.post) / T - 1e-9));
    const long n_ff = k1 - k0 + 1;
    if (n_ff > kFfMax)
        throw std::invalid_argument("the feedforward table would need " + std::to_string(n_ff) + " samples (> " +
                                    std::to_string(kFfMax) + ", ARMCTRL_FF_MAX): shorten --post or the motion");
    if (n_ff < 2) throw std::invalid_argument("the feedforward table needs at least 2 samples");
    d.t0 = k0 * T;
    d.dt = T;
    d.t_motion_start = s.traj.t_s;
    d.t_motion_end = ptp.t_end();
    if (!(d.t0 <= d.t_motion_start)) throw std::invalid_argument("the motion must not start before the table (t_s >= 0)");
    for (auto& r : d.ff) r.assign(static_cast<size_t>(n_ff), 0.0);

    if (s.exp == 'A') {
        // rbFFC (4.14)-(4.17), (4.16) with I_l (notes 004b erratum), dpsi_L* = q' of the rigid link.
        const DriveParams dr = wang_drive();
        d.I_l = wang_rigid_link_inertia();
        for (long k = 0; k < n_ff; ++k) {
            const auto q = ptp.eval((k0 + k) * T);
            const auto f = rigid_body_feedforward(q, dr.I_M, d.I_l, dr.c_s);
            d.ff[0][k] = f[0];
            d.ff[1][k] = f[1];
            d.ff[2][k] = q[1];
            d.ff[3][k] = f[3];
        }
    } else {
        // ibFFC: stable inversion of the sampled arm (ibffc.hpp) for psi'(L)* = q'(t), computed from
        // t_s - pre (or the table start, if earlier) so the pre-actuation builds up from rest.
        const StateSpace plant = wang_arm_measured(s.N, s.r_t, s.r_r, true);
        const long ki = std::min(k0, static_cast<long>(std::floor((s.traj.t_s - s.pre) / T)));
        const auto r = stable_inversion(plant, T, [&](double t) { return ptp.eval(t)[1]; }, ki * T, (k1 + 0.5) * T);
        if (static_cast<long>(r.t.size()) < k1 - ki + 1) throw std::runtime_error("stable inversion horizon too short");
        const long off = k0 - ki;
        for (long k = 0; k < off; ++k) d.head_tau_max = std::max(d.head_tau_max, std::fabs(r.u[k]));
        for (long k = 0; k < n_ff; ++k) {
            d.ff[0][k] = r.theta_M[off + k] + s.traj.q_s;  // x = 0 is rest at angle 0; shift to q_s
            d.ff[1][k] = r.theta_M_dot[off + k];
            d.ff[2][k] = r.y_des[off + k];
            d.ff[3][k] = r.u[off + k];
        }
        d.ibffc = r;
    }
    for (double u : d.ff[3]) d.tau_max = std::max(d.tau_max, std::fabs(u));
    // The playback holds sample 0 before the Start edge (and the leads read at most d_i samples in):
    // the feedforward must be at rest there.
    double head = 0.0;
    for (long k = 0; k <= std::min<long>(n_ff - 1, -k0 + s.di); ++k) head = std::max(head, std::fabs(d.ff[3][k]));
    d.start_tau = head;
    if (head > kArmctrlRestTol * d.tau_max)
        throw std::runtime_error("the feedforward is not at rest where the playback starts (|tau_M*| = " + fmt(head) +
                                 " N m at t <= " + fmt((s.di) * T) + " s, more than " + fmt(kArmctrlRestTol) +
                                 " of the peak): the pre-actuation needs more than t_s = " + fmt(s.traj.t_s) +
                                 " s; start the motion later");
    d.pre_actuation_start = d.t_motion_end;
    for (long k = 0; k < n_ff; ++k)
        if (std::fabs(d.ff[3][k]) > 1e-3 * d.tau_max) {
            d.pre_actuation_start = d.t0 + k * T;
            break;
        }
    for (const auto& row : d.ff) d.tail_step = std::max(d.tail_step, std::fabs(row[n_ff - 1] - row[n_ff - 2]));

    if (s.exp == 'C' || s.exp == 'D') {
        LqgParams p = s.exp == 'C' ? LqgParams::exp_c() : LqgParams::exp_d();
        p.T = T;
        p.di = s.di;
        p.dout = s.dout;
        const StateSpace reduced = wang_arm_measured(s.N, s.r_t, s.r_r, true);
        const long n = reduced.nx(), nb = n + s.di + s.dout;
        if (n > kLqgNMax) throw std::invalid_argument("plant order " + std::to_string(n) + " > ARMCTRL_LQG_NMAX");
        if (nb + 1 > kMatMax)
            throw std::invalid_argument("n + d_i + d_o + 1 = " + std::to_string(nb + 1) +
                                        " exceeds the PLC's FRAC_MAT_MAX = 64: smaller --di/--do");
        d.lqg = design_lqg(reduced, p);
        const LqgDesign& g = *d.lqg;
        // Checked on the plant with the rig's delays (Table 8.8), also for Exp. C, whose controller has
        // no delay model: the delays belong to the plant.
        d.check_reduced = check_closed_loop(g, reduced, kRigDi, kRigDo);
        d.check_unreduced = check_closed_loop(g, wang_arm_measured(s.N, s.r_t, s.r_r, false), kRigDi, kRigDo);
        armctrl_take_lqg(d, g);
    }

    d.kp = kKp;
    d.kd = kKd;
    d.fr_b1 = kB1;
    d.fr_b0 = kB0;
    d.fr_k = kTanh;
    armctrl_fill_table(d, std::string("seed 004 (Wang) Exp. ") + s.exp + ": Table 8.5 trajectory, " +
                              (s.exp == 'A' ? "rbFFC (4.14)-(4.17), PD + friction Table 8.6"
                               : s.exp == 'B' ? "ibFFC (stable inversion Sec. 4.3), PD + friction Table 8.6"
                               : s.exp == 'C' ? "ibFFC, LQG Table 8.7 (no delay model)"
                                              : "ibFFC, LQG Table 8.8 with d_i, d_o and the Sec. 8.6 shifts"));
    return d;
}

void armctrl_fill_table(ArmctrlDesign& d, const std::string& source)
{
    const ArmctrlSpec& s = d.spec;
    const double T = s.T;
    const long n_ff = static_cast<long>(d.ff[0].size());
    tables::ParamTable& t = d.table;
    t = tables::ParamTable();
    t.name = "armctrl";
    t.meta = {{"source", source},
              {"experiment", std::string(1, s.exp)},
              {"collocation_points", s.N},
              {"r_t", s.r_t},
              {"r_r", s.r_r},
              {"generator", "fracdesign armctrl"}};
    t.add("variant", static_cast<double>(d.variant), "0..3 = Exp. A..D (Table 8.1)");
    t.add("ts", T, "cycle time T [s]");
    Eigen::MatrixXd F(4, n_ff);
    for (int r = 0; r < 4; ++r)
        for (long k = 0; k < n_ff; ++k) F(r, k) = d.ff[r][k];
    t.add("ff", F, "feedforward rows theta_M* [rad], theta_M*' [rad/s], psi'(L)* [rad/s], tau_M* [N m]");
    Eigen::MatrixXd grid(1, 4);
    grid << d.t0, d.dt, d.t_motion_start, d.t_motion_end;
    t.add("ff_grid", grid, "table time of sample 0, sample time, motion start, motion end [s]");
    Eigen::MatrixXd lead(1, 4);
    lead << d.lead[0], d.lead[1], d.lead[2], d.lead[3];
    t.add("ff_lead", lead, "lead (+) / lag (-) per row [cycles] (Sec. 8.6)");
    t.add("torque_limit", s.torque_limit, "|tau| limit [N m] (thesis gap; drive peak about 251 N m)");
    Eigen::MatrixXd wd(1, 2);
    wd << s.wd_stale, s.wd_ramp;
    t.add("watchdog", wd, "max stale cycles, ramp rate [N m/s]");
    if (s.exp == 'A' || s.exp == 'B') {
        Eigen::MatrixXd pd(1, 2), fr(1, 3);
        pd << d.kp, d.kd;
        fr << d.fr_b1, d.fr_b0, d.fr_k;
        t.add("pd", pd, "K_P [N m/rad], K_D [N m s/rad] (Table 8.6)");
        t.add("friction", fr, "b_1 [N m s/rad], b_0 [N m], k (linear model (5.2), Table 8.6)");
    } else {
        Eigen::MatrixXd dims(1, 5);
        dims << static_cast<double>(d.A.rows()), s.di, 0.0, 0.0, s.dout;
        t.add("lqg_dims", dims, "n, d_i, d_o of theta_M, theta_M', psi'(L) [cycles]");
        t.add("A", d.A, "ZOH plant A' (7.3)");
        t.add("B", d.B, "ZOH plant B' (7.3)");
        t.add("C", d.C, "C' rows theta_M, theta_M', psi'(L)");
        t.add("K", d.K, "state feedback K_bar (7.24)");
        t.add("L", d.L, "predictor gain L_e (7.27)");
    }
    t.validate();
}

}  // namespace fracdesign::design
