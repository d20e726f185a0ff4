// cmd_traj.cpp - `fracdesign traj`: seed 004 sin^2 point-to-point trajectory with the
// rigid-body feedforward and the delay time shift of the torque (Sec. 4.1, 4.2, 8.6).
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/design/arm_design.hpp"
#include "fracdesign/design/armctrl.hpp"
#include "fracdesign/design/ibffc.hpp"
#include "fracdesign/design/lqg.hpp"
#include "fracdesign/design/trajectory.hpp"
#include "fracdesign/models/arm.hpp"

namespace fracdesign {
namespace {

// Inversion-based feedforward: stable inversion of the arm (ibffc.hpp) for q'(t) as the tip velocity.
int run_ibffc(const Args& args, const design::SinSquaredPtp& p, double dt, long di, long dout)
{
    TimoshenkoParams beam = wang_steel_beam();
    // The thesis gives no beam damping (notes 004b 1.2); default r_t = 0.5 N s/m^2, r_r = 0.
    beam.r_t = args.num("rt", 0.5);
    beam.r_r = args.num("rr", 0.0);
    try {
        beam.validate();
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    const double pre = args.num("pre", 2.0), t_end = args.num("t-end", p.t_end() + 2.5);
    if (!(pre >= 0.0)) throw UsageError("--pre must be >= 0");
    const StateSpace plant = design::arm_measured_model(build_arm(beam, wang_drive(), ArmOptions()).arm);
    const auto r = design::stable_inversion(plant, dt, [&](double t) { return p.eval(t)[1]; }, -pre, t_end);
    if (args.has("out")) {
        std::ofstream f(args.str("out"));
        if (!f) throw std::runtime_error("cannot write '" + args.str("out") + "'");
        f.precision(12);
        f << "t,psi_dot_L_des,tau_M,theta_M,theta_M_dot,tau_M_sent,psi_dot_L_imu_ref,psi_dot_L_model\n";
        const long n = static_cast<long>(r.t.size());
        for (long k = 0; k < n; ++k)
            f << r.t[k] << "," << r.y_des[k] << "," << r.u[k] << "," << r.theta_M[k] << "," << r.theta_M_dot[k] << ","
              << r.u[std::min(k + di, n - 1)] << "," << r.y_des[std::max(k - dout, 0L)] << "," << r.y_sim[k] << "\n";
    }
    double tau_max = 0.0;
    for (double u : r.u) tau_max = std::max(tau_max, std::fabs(u));
    nlohmann::json j = {{"schema", "frac.design.ibffc"}, {"version", 1},
                        {"source", "seed 004 Sec. 4.3, App. E/F (stable inversion of the sampled arm)"},
                        {"t_a", p.t_a()}, {"t_e", p.t_end()}, {"dt", dt}, {"di", di}, {"r_t", beam.r_t},
                        {"r_r", beam.r_r}, {"samples", r.t.size()}, {"modes_forward", r.n_forward},
                        {"modes_backward", r.n_backward}, {"tau_M_max", tau_max}, {"tracking_rel_rms", r.rel_rms}};
    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("ibFFC (seed 004 stable inversion): horizon [%g, %g] s, dt = %g s, %d modes forward, %d backward\n",
                    -pre, t_end, dt, r.n_forward, r.n_backward);
        std::printf("  max |tau_M*| = %.4g N m; model driven by tau_M* tracks psi'(L)* to %.2e relative RMS\n", tau_max,
                    r.rel_rms);
        if (args.has("out")) std::printf("  written to %s\n", args.str("out").c_str());
    }
    return 0;
}

// `traj --arm ARM.json --move ...`: the rigid-body and the inverse-model feedforward of the arm
// document for the move, sampled at the document's T (design/arm_design.hpp), as one CSV.
int run_traj_arm(const Args& args)
{
    for (const char* k : {"qs", "qe", "qd-max", "qdd-max", "ts", "te", "dt", "Il", "di", "do", "rt", "rr", "ibffc"})
        if (args.has(k)) throw UsageError(std::string("--") + k + " does not go with --arm: the arm document and --move give it");
    ArmDocument a;
    try {
        a = read_arm_file(args.str("arm"));
    } catch (const ArmDocumentError& e) {
        throw UsageError(e.what());
    }
    if (args.has("move") == args.has("move-csv")) throw UsageError("--arm needs one of --move SPEC or --move-csv FILE");
    std::unique_ptr<design::Move> mv;
    try {
        mv = std::make_unique<design::Move>(args.has("move") ? design::Move::parse(args.str("move"))
                                                              : design::Move::from_csv(args.str("move-csv")));
    } catch (const std::exception& e) {
        throw UsageError(e.what());
    }
    const double pre = args.num("pre", 2.0), post = args.num("post", 2.0);
    if (!(pre >= 0.0) || !(post >= 0.0)) throw UsageError("--pre and --post must be >= 0");
    design::ArmReduction red;
    try {
        red = design::choose_reduction(a);
    } catch (const design::ArmDesignError& e) {
        std::cerr << "fracdesign traj: " << e.what() << "\n";
        return 1;
    }
    const StateSpace plant = arm_document_measured(a, build_arm_from_document(a, a.design.N, true, red.shifts));
    const double T = a.T, t0 = std::max(0.0, mv->t_start() - pre), t1 = mv->t_end() + post;
    const auto r = design::stable_inversion(plant, T, [&](double t) { return mv->eval(t)[1]; }, t0, t1);
    const double Il = a.rigid_link_inertia();
    double rb_max = 0.0, ib_max = 0.0;
    std::ostringstream f;
    f.precision(12);
    f << "t,q,qd,qdd,rb_theta_M,rb_theta_M_dot,rb_tau_M,ib_theta_M,ib_theta_M_dot,ib_tau_M,psi_dot_des\n";
    for (size_t k = 0; k < r.t.size(); ++k) {
        const auto q = mv->eval(r.t[k]);
        const auto rb = design::rigid_body_feedforward(q, a.drive.I_M, Il, a.drive.c_s);
        rb_max = std::max(rb_max, std::fabs(rb[3]));
        ib_max = std::max(ib_max, std::fabs(r.u[k]));
        f << r.t[k] << "," << q[0] << "," << q[1] << "," << q[2] << "," << rb[0] << "," << rb[1] << "," << rb[3] << ","
          << r.theta_M[k] + mv->q_start() << "," << r.theta_M_dot[k] << "," << r.u[k] << "," << r.y_des[k] << "\n";
    }
    if (args.has("out")) write_file(args.str("out"), f.str());
    nlohmann::json j = {{"schema", "frac.design.traj"}, {"version", 1}, {"arm", a.name}, {"move", mv->describe()},
                        {"dt", T}, {"samples", r.t.size()}, {"I_l", Il}, {"rigid_tau_M_max", rb_max},
                        {"inverse_tau_M_max", ib_max}, {"inverse_tracking_rel_rms", r.rel_rms},
                        {"torque_peak", a.torque_peak}};
    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("feedforward for arm '%s', move %s, dt = %g s, %zu samples\n", a.name.c_str(), mv->describe().c_str(), T,
                    r.t.size());
        std::printf("  rigid body (I_l = %.5g kg m^2): max |tau_M*| = %.4g N m; inverse model: max |tau_M*| = %.4g N m, "
                    "model tracks the IMU rate to %.2e relative RMS\n", Il, rb_max, ib_max, r.rel_rms);
        if (args.has("out")) std::printf("  written to %s\n", args.str("out").c_str());
    }
    return 0;
}

int run_traj(const std::vector<std::string>& argv)
{
    Args args(argv, {"json", "ibffc"});
    args.check_known({"json", "qs", "qe", "qd-max", "qdd-max", "ts", "te", "dt", "t-end", "Il", "di", "do", "out", "ibffc",
                      "rt", "rr", "pre", "arm", "move", "move-csv", "post"});
    if (args.has("arm")) return run_traj_arm(args);
    for (const char* k : {"move", "move-csv", "post"})
        if (args.has(k)) throw UsageError(std::string("--") + k + " only with --arm ARM.json");
    constexpr double kPi = 3.14159265358979323846;
    // Defaults: Table 8.5 (q_s = 0, q_e = pi/2, qd_m = pi/2, qdd_m = 2 pi, t_s = 0.5 s, t_e = 2 s).
    design::PtpSpec s{args.num("qs", 0.0), args.num("qe", kPi / 2), args.num("qd-max", kPi / 2),
                      args.num("qdd-max", 2 * kPi), args.num("ts", 0.5), args.num("te", 2.0)};
    const double dt = args.num("dt", 1.2e-3);
    const long di = args.integer("di", 0), dout = args.integer("do", 0);
    if (!(dt > 0.0) || di < 0 || dout < 0) throw UsageError("need --dt > 0 and --di, --do >= 0");
    std::unique_ptr<design::SinSquaredPtp> p;
    try {
        p = std::make_unique<design::SinSquaredPtp>(s);
    } catch (const std::invalid_argument& e) {
        std::cerr << "fracdesign traj: infeasible trajectory: " << e.what() << "\n";
        return 1;
    }
    const double t_end = args.num("t-end", p->t_end() + 0.5);
    // Rigid-body feedforward (4.14)-(4.17): drive of Table 8.2 (I_M = n^2 I_m, notes 004a) and a
    // rigid link I_l = I_h + I_b; the thesis gives no I_b, default rho((L + r_h)^3 - r_h^3)/3 + I_h
    // of the Table 8.3 beam (notes 004b section 3; design::wang_rigid_link_inertia).
    const DriveParams dr = wang_drive();
    const double Il = args.num("Il", design::wang_rigid_link_inertia());
    if (!(Il > 0.0)) throw UsageError("--Il must be > 0");
    const long n = static_cast<long>(std::floor(t_end / dt)) + 1;
    std::vector<std::array<double, 5>> q(n);
    std::vector<std::array<double, 4>> ff(n);
    for (long k = 0; k < n; ++k) {
        q[k] = p->eval(k * dt);
        ff[k] = design::rigid_body_feedforward(q[k], dr.I_M, Il, dr.c_s);
    }
    if (args.has("ibffc")) return run_ibffc(args, *p, dt, di, dout);
    if (args.has("out")) {
        std::ofstream f(args.str("out"));
        if (!f) throw std::runtime_error("cannot write '" + args.str("out") + "'");
        f.precision(12);
        // tau_M_bar*[k] = tau_M*[k + d_i]: the torque is sent d_i samples early (Sec. 8.6).
        // qd_imu_ref[k] = qd[k - d_o]: the IMU reference is delayed like the measurement (Sec. 8.6).
        f << "t,q,qd,qdd,q3,q4,theta_M,theta_M_dot,theta_M_ddot,tau_M,tau_M_sent,qd_imu_ref\n";
        for (long k = 0; k < n; ++k) {
            const long ks = std::min(k + di, n - 1);
            f << k * dt;
            for (double v : q[k]) f << "," << v;
            for (double v : ff[k]) f << "," << v;
            f << "," << ff[ks][3] << "," << q[std::max(k - dout, 0L)][1] << "\n";
        }
    }
    double tau_max = 0.0;
    for (const auto& v : ff) tau_max = std::max(tau_max, std::fabs(v[3]));
    nlohmann::json j = {{"schema", "frac.design.traj"}, {"version", 1},
                        {"source", "seed 004 (4.1)-(4.7) corrected, (4.14)-(4.17), Sec. 8.6"},
                        {"t_a", p->t_a()}, {"t_e", p->t_end()}, {"qd_cruise", p->qd_cruise()},
                        {"samples", n}, {"dt", dt}, {"di", di}, {"I_l", Il}, {"tau_M_max", tau_max}};
    if (args.has("out")) j["out"] = args.str("out");
    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("sin^2 PTP (seed 004): q %g -> %g rad, t_a = %g s, ends at %g s, cruise %g rad/s\n", s.q_s, s.q_e,
                    p->t_a(), p->t_end(), p->qd_cruise());
        std::printf("  rigid-body feedforward (I_M = %g, I_l = %g kg m^2, c_s = %g N m/rad): max |tau_M*| = %.4g N m\n",
                    dr.I_M, Il, dr.c_s, tau_max);
        std::printf("  %ld samples at dt = %g s%s%s\n", n, dt, di ? ", torque column shifted by d_i samples" : "",
                    args.has("out") ? (", written to " + args.str("out")).c_str() : "");
    }
    return 0;
}

CommandRegistrar reg({"traj", "sin^2 point-to-point trajectory and rigid-body feedforward (seed 004)",
                      "usage: fracdesign traj --arm ARM.json --move SPEC|--move-csv FILE [--pre S] [--post S]\n"
                      "                       [--out FILE.csv] [--json]\n"
                      "       fracdesign traj [--qs Q] [--qe Q] [--qd-max V] [--qdd-max A] [--ts T] [--te T]\n"
                      "                       [--dt DT] [--t-end T] [--Il I] [--di N] [--do N] [--out FILE.csv] [--json]\n"
                      "                       [--ibffc [--rt R] [--rr R] [--pre S]]\n\n"
                      "--arm: rigid-body (4.14)-(4.17) and inverse-model (stable inversion of the reduced\n"
                      "arm) feedforward of the arm document (docs/arm_format.md) for the move, at its T.\n\n"
                      "Plans the sin^2 PTP of seed 004 (4.1)-(4.7) (corrected: qdd_m in (4.5), braking\n"
                      "sin^2(pi (t - t_b)/t_a) in (4.7)); defaults are Table 8.5. --te 0 moves as fast as\n"
                      "qd_max and qdd_max allow; an end time shorter than that is refused (exit 1). Samples\n"
                      "q..q^(4) and the rigid-body feedforward theta_M*, theta_M*', theta_M*'', tau_M*\n"
                      "(4.14)-(4.17) every DT up to --t-end; --di N adds tau_M_sent[k] = tau_M*[k + N]\n"
                      "(torque sent N samples early for the input delay, Sec. 8.6) and --do N the IMU\n"
                      "reference qd_imu_ref[k] = qd*[k - N] (compared with the delayed measurement).\n"
                      "--ibffc: inversion-based feedforward instead: stable inversion of the ZOH arm\n"
                      "(tau_M -> psi'(L), 16 states) for psi'(L)* = q'(t), modes |lambda| <= 1 forward and\n"
                      "|lambda| > 1 backward in time over [-PRE, t-end] (--pre, default 2 s): CSV columns\n"
                      "tau_M*, theta_M*, theta_M*', tau_M_sent; --rt/--rr set the beam damping\n"
                      "(not given by the thesis; default 0.5, 0).\n",
                      run_traj});

}  // namespace
}  // namespace fracdesign
