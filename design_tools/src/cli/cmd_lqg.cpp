// cmd_lqg.cpp - `fracdesign lqg`: seed 004 state-difference LQG with delays (Exp. C / D).
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/design/lqg.hpp"

namespace fracdesign {
namespace {

int run_lqg(const std::vector<std::string>& argv)
{
    Args args(argv, {"json"});
    args.check_known({"json", "exp", "T", "di", "do", "rt", "rr", "out", "plant-di", "plant-do"});
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
                      "                      [--plant-di N] [--plant-do N] [--out DESIGN.json] [--json]\n\n"
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
