// cmd_lqg.cpp - `fracdesign lqg`: seed 004 state-difference LQG with delays (Exp. C / D).
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/design/arm_design.hpp"
#include "fracdesign/design/lqg.hpp"

namespace fracdesign {
namespace {

void print_check(const char* name, const design::LoopCheck& c)
{
    std::printf("  closed loop on the %s arm, plant d_i = %d, d_o = %d (%d states): spectral radius %.9f (%s, "
                "at %.1f rad/s), GM %.2f dB, PM %.2f deg, min|1+L| %.3f\n",
                name, c.plant_di, c.plant_do, c.plant_states, c.spectral_radius,
                c.spectral_radius < 1.0 ? "stable" : "UNSTABLE", c.critical_w, c.gain_margin_db, c.phase_margin_deg,
                c.modulus_margin);
}

nlohmann::json reduction_json(const design::ArmReduction& r)
{
    nlohmann::json modes = nlohmann::json::array();
    for (const auto& m : r.retained) modes.push_back({{"full_hz", m.full_hz}, {"reduced_hz", m.reduced_hz}, {"rel_error", m.rel_error}});
    return {{"rule", "shifts {w1/2, w1..wm}: clamped-free beam modes up to reduce_multiple x bandwidth (docs/arm_format.md)"},
            {"bandwidth_hz", r.bandwidth_hz}, {"shifts_rad_s", r.shifts}, {"full_states", r.full_states},
            {"reduced_states", r.reduced_states}, {"full_modes_hz", r.full_hz}, {"retained", modes},
            {"max_error_below_bandwidth", r.max_error_below_bandwidth}};
}

// `lqg --arm ARM.json`: everything from the arm document (design/arm_design.hpp).
int run_lqg_arm(const Args& args)
{
    for (const char* k : {"exp", "T", "di", "do", "rt", "rr", "plant-di", "plant-do"})
        if (args.has(k)) throw UsageError(std::string("--") + k + " does not go with --arm: the arm document gives it");
    ArmDocument a;
    try {
        a = read_arm_file(args.str("arm"));
    } catch (const ArmDocumentError& e) {
        throw UsageError(e.what());
    }
    design::ArmLqg r;
    try {
        r = design::design_arm_lqg(a);
    } catch (const design::ArmDesignError& e) {
        std::cerr << "fracdesign lqg: " << e.what() << "\n";
        return 1;
    } catch (const design::RiccatiError& e) {
        std::cerr << "fracdesign lqg: Riccati equation has no stabilising solution: " << e.what() << "\n";
        return 1;
    }
    nlohmann::json j = design::to_json(r.lqg);
    j["source"] = "arm document '" + a.name + "': seed 004 (6.36)-(6.45), (7.3)-(7.27) with the weights of docs/arm_format.md";
    j["arm"] = a.name;
    if (a.design.reduce) j["reduction"] = reduction_json(r.reduction);
    j["spillover_rule"] = design::arm_lqg_rule_json(r);
    j["check_reduced"] = design::to_json(r.check_reduced);
    j["check_unreduced"] = design::to_json(r.check_unreduced);
    if (args.has("out") && r.accepted()) write_file(args.str("out"), j.dump(2) + "\n");
    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        const design::LqgParams& p = r.lqg.params;
        std::printf("LQG for arm '%s': T = %g s, d_i = %d, d_o = %d; weights q_low %.4g, q_high %.4g (n_low %d), S_c %g; "
                    "Q_o %.3g %.3g %.3g %.3g, S_o diag %.3g %.3g %.3g\n",
                    a.name.c_str(), p.T, p.di, p.dout, p.q_low, p.q_high, p.n_low, p.s_c, p.qo_drive, p.qo_beam, p.qo_delay,
                    p.qo_dist, p.s_o[0], p.s_o[1], p.s_o[2]);
        std::printf("  spillover rule (accept: unreduced spectral radius <= %.9f, min|1+L| >= %.2f):\n", r.rho_max,
                    design::kArmModulusMin);
        for (size_t i = 0; i < r.steps.size(); ++i) {
            const design::ArmLqgStep& st = r.steps[i];
            if (st.designed)
                std::printf("    %-56s %2d states: unreduced %.9f, min|1+L| %.3f%s\n", st.rule.c_str(), st.reduced_states,
                            st.rho_unreduced, st.modulus_unreduced, static_cast<int>(i) == r.accepted_step ? "  <- accepted" : "");
            else
                std::printf("    %-56s not designed: %s\n", st.rule.c_str(), st.note.c_str());
        }
        if (a.design.reduce) {
            const auto& rd = r.reduction;
            std::printf("  reduction: bandwidth %.4g Hz, %zu shifts", rd.bandwidth_hz, rd.shifts.size());
            for (double s : rd.shifts) std::printf(" %.4g", s);
            std::printf(" rad/s: %d -> %d states\n", rd.full_states, rd.reduced_states);
            for (const auto& m : rd.retained)
                std::printf("    mode %.5f Hz (full %.5f Hz): error %.3e\n", m.reduced_hz, m.full_hz, m.rel_error);
        }
        std::printf("  K: %ld x %ld, L_e: %ld x %ld; DARE residuals %.2e (K), %.2e (L_e)\n", long(r.lqg.K.rows()),
                    long(r.lqg.K.cols()), long(r.lqg.Le.rows()), long(r.lqg.Le.cols()), r.lqg.ctrl.residual, r.lqg.obs.residual);
        print_check("reduced", r.check_reduced);
        print_check("unreduced", r.check_unreduced);
        std::printf("  stability margin 1 - rho = %.3g (bound %.3g)\n", 1.0 - r.check_unreduced.spectral_radius, 1.0 - r.rho_max);
        if (args.has("out") && r.accepted()) std::printf("  design written to %s\n", args.str("out").c_str());
    }
    if (!r.accepted()) {
        std::cerr << "fracdesign lqg: " << design::arm_lqg_refusal(a, r) << "\n";
        return 1;
    }
    return 0;
}

int run_lqg(const std::vector<std::string>& argv)
{
    Args args(argv, {"json"});
    args.check_known({"json", "exp", "T", "di", "do", "rt", "rr", "out", "plant-di", "plant-do", "arm"});
    if (args.has("arm")) return run_lqg_arm(args);
    const std::string exp = args.str("exp", "D");
    if (exp != "C" && exp != "D") throw UsageError("--exp must be C or D");
    design::LqgParams p = exp == "C" ? design::LqgParams::exp_c() : design::LqgParams::exp_d();
    p.T = args.num("T", p.T);
    p.di = static_cast<int>(args.integer("di", p.di));
    p.dout = static_cast<int>(args.integer("do", p.dout));
    TimoshenkoParams beam = wang_steel_beam();
    // The thesis gives no beam damping (notes 004b 1.2); default r_t = 0.5 N s/m^2, r_r = 0.
    beam.r_t = args.num("rt", 0.5);
    beam.r_r = args.num("rr", 0.0);
    if (!(p.T > 0.0) || p.di < 0 || p.dout < 0) throw UsageError("need --T > 0 and --di, --do >= 0");
    // The loop is checked on the plant with the rig's delays (Table 8.8), whatever the controller models.
    const int plant_di = static_cast<int>(args.integer("plant-di", design::kRigDi));
    const int plant_do = static_cast<int>(args.integer("plant-do", design::kRigDo));
    if (plant_di < 0 || plant_do < 0) throw UsageError("need --plant-di, --plant-do >= 0");
    try {
        beam.validate();
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    ArmOptions o;
    const StateSpace reduced = design::arm_measured_model(build_arm(beam, wang_drive(), o).arm);
    o.reduce = false;
    const StateSpace full = design::arm_measured_model(build_arm(beam, wang_drive(), o).arm);
    design::LqgDesign d;
    try {
        d = design::design_lqg(reduced, p);
    } catch (const design::RiccatiError& e) {
        std::cerr << "fracdesign lqg: Riccati equation has no stabilising solution: " << e.what() << "\n";
        return 1;
    }
    const auto cn = design::check_closed_loop(d, reduced);  // the design's own loop (its delay model)
    const auto cr = design::check_closed_loop(d, reduced, plant_di, plant_do);
    const auto cf = design::check_closed_loop(d, full, plant_di, plant_do);
    nlohmann::json j = design::to_json(d);
    j["beam_damping"] = {{"r_t", beam.r_t}, {"r_r", beam.r_r}};
    j["check_nominal"] = design::to_json(cn);
    j["check_reduced"] = design::to_json(cr);
    j["check_unreduced"] = design::to_json(cf);
    if (args.has("out")) {
        write_file(args.str("out"), j.dump(2) + "\n");
    }
    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("LQG (seed 004 Exp. %s): T = %g s, d_i = %d, d_o = %d, r_t = %g, r_r = %g\n", exp.c_str(), p.T, p.di,
                    p.dout, beam.r_t, beam.r_r);
        std::printf("  K: %ld x %ld, L_e: %ld x %ld; DARE residuals %.2e (K), %.2e (L_e)\n", long(d.K.rows()),
                    long(d.K.cols()), long(d.Le.rows()), long(d.Le.cols()), d.ctrl.residual, d.obs.residual);
        for (const auto& [name, c] : {std::pair<const char*, design::LoopCheck>{"reduced", cn}, {"reduced", cr},
                                      {"unreduced", cf}})
            std::printf("  closed loop on the %s arm, plant d_i = %d, d_o = %d (%d states): spectral radius %.9f (%s, "
                        "at %.1f rad/s), GM %.2f dB, PM %.2f deg, min|1+L| %.3f\n",
                        name, c.plant_di, c.plant_do, c.plant_states, c.spectral_radius,
                        c.spectral_radius < 1.0 ? "stable" : "UNSTABLE", c.critical_w, c.gain_margin_db,
                        c.phase_margin_deg, c.modulus_margin);
        if (args.has("out")) std::printf("  design written to %s (fracdesign table emit --in it)\n", args.str("out").c_str());
    }
    return cf.spectral_radius < 1.0 ? 0 : 1;
}

CommandRegistrar reg({"lqg", "state-difference LQG with delays for the flexible arm (seed 004 Exp. C/D)",
                      "usage: fracdesign lqg [--exp C|D] [--T S] [--di N] [--do N] [--rt R] [--rr R]\n"
                      "                      [--plant-di N] [--plant-do N] [--out DESIGN.json] [--json]\n"
                      "       fracdesign lqg --arm ARM.json [--out DESIGN.json] [--json]\n\n"
                      "--arm: the arm document (docs/arm_format.md) gives everything: the full model at\n"
                      "design.N, the reduced model with automatic Krylov shifts (each retained mode's\n"
                      "error printed; refused above design.mode_error_max below the bandwidth), the\n"
                      "weights (default rule scaled to the rated torque, or design.lqg; S_o from the\n"
                      "sensors' noise), T, d_i, d_o; the loop is checked on the reduced and the UNREDUCED\n"
                      "arm with those delays. Accepted: unreduced spectral radius <= exp(-1e-6 T) and\n"
                      "min|1+L| >= 0.25; else the spillover rule retains more beam modes, then (default\n"
                      "weights) backs the weights off x 0.1, 0.01, 0.001; every step is printed, the\n"
                      "first accepted wins; none: exit 1, no --out (docs/arm_format.md).\n\n"
                      "Designs K and L_e for the Krylov-reduced arm (16 states) with the weights of\n"
                      "Table 8.7 (C: no delay) or 8.8 (D: T = 1.2 ms, d_i = 4, d_o = 3): ZOH, delay\n"
                      "augmentation, modal weights (real modal form, |lambda| ascending), dlqr for K,\n"
                      "dual DARE for the predictor gain L_e of the model with the integrating friction\n"
                      "state. Checks the closed loop (stability, GM, PM, min|1+L| at the plant input,\n"
                      "lightly damped beam modes resolved at their aliased frequencies): the design's own\n"
                      "loop (reduced arm, its delay model), then the reduced and the unreduced (N = 9,\n"
                      "40 states) arm with the rig's delays --plant-di/--plant-do (default 4, 3, Table\n"
                      "8.8: the delays are the plant's, so Exp. C is checked with them too).\n"
                      "--rt/--rr: beam damping, not given by the thesis (default 0.5, 0).\n"
                      "Exit status 1 if a Riccati equation fails (cause named) or the unreduced loop is unstable.\n",
                      run_lqg});

}  // namespace
}  // namespace fracdesign
