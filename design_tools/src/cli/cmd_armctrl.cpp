// cmd_armctrl.cpp - `fracdesign armctrl`: the parameter table of the PLC program ArmCtrl for
// seed 004 Exp. A-D (design/armctrl.hpp), written with the emitters of `fracdesign table`.
#include <cstdio>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/design/arm_design.hpp"
#include "fracdesign/design/armctrl.hpp"
#include "fracdesign/tables/ptable.hpp"

namespace fracdesign {
namespace {

int to_int(const Args& args, const char* key, long def, long lo, long hi, const std::string& what)
{
    const long v = args.integer(key, def);
    if (v < lo || v > hi)
        throw UsageError(std::string("--") + key + " " + what + " (got " + std::to_string(v) + ")");
    return static_cast<int>(v);
}

design::Move move_from_args(const Args& args)
{
    if (args.has("move") == args.has("move-csv")) throw UsageError("--arm needs one of --move SPEC or --move-csv FILE");
    try {
        return args.has("move") ? design::Move::parse(args.str("move")) : design::Move::from_csv(args.str("move-csv"));
    } catch (const std::exception& e) {
        throw UsageError(e.what());
    }
}

// `armctrl --arm ARM.json --move ...`: the ArmCtrl table of the arm document (design/arm_design.hpp).
int run_armctrl_arm(const Args& args)
{
    for (const char* k : {"exp", "N", "rt", "rr", "di", "do", "torque-limit"})
        if (args.has(k)) throw UsageError(std::string("--") + k + " does not go with --arm: the arm document gives it");
    ArmDocument a;
    try {
        a = read_arm_file(args.str("arm"));
    } catch (const ArmDocumentError& e) {
        throw UsageError(e.what());
    }
    const design::Move mv = move_from_args(args);
    const std::string ffs = args.str("ff", "inverse");
    if (ffs != "inverse" && ffs != "rigid") throw UsageError("--ff must be inverse or rigid (got '" + ffs + "')");
    const std::string format = args.str("format", "bin"), out = args.str("out");
    if (!tables::is_emit_format(format)) throw UsageError("--format must be json, c, var or bin");
    design::ArmctrlForArm r;
    try {
        r = design::design_armctrl_for_arm(a, mv, ffs == "rigid" ? design::FfKind::Rigid : design::FfKind::Inverse,
                                           args.num("post", 2.0));
    } catch (const design::RiccatiError& e) {
        std::cerr << "fracdesign armctrl: Riccati equation has no stabilising solution: " << e.what() << "\n";
        return 1;
    } catch (const design::ArmDesignError& e) {
        std::cerr << "fracdesign armctrl: " << e.what() << "\n";
        return 1;
    } catch (const std::runtime_error& e) {
        std::cerr << "fracdesign armctrl: " << e.what() << "\n";
        return 1;
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    design::ArmctrlDesign& d = r.d;
    if (args.has("real")) {
        try {
            d.table.real = tables::real_type_from_string(args.str("real"));
        } catch (const tables::TableError&) {
            throw UsageError("--real must be float64 or float32");
        }
    }
    const std::string data = tables::emit(d.table, format);
    write_file(out, data);
    const long n_ff = static_cast<long>(d.ff[0].size());
    nlohmann::json j = {{"schema", "frac.armctrl"}, {"version", 1}, {"arm", a.name}, {"experiment", std::string(1, d.spec.exp)},
                        {"variant", d.variant}, {"feedforward", ffs}, {"move", mv.describe()}, {"format", format},
                        {"out", out}, {"bytes", data.size()}, {"ts", a.T}, {"di", a.di}, {"do", a.dout},
                        {"ff_samples", n_ff}, {"ff_grid", {d.t0, d.dt, d.t_motion_start, d.t_motion_end}},
                        {"tau_M_max", d.tau_max}, {"torque_peak", a.torque_peak}, {"pre_actuation_start", d.pre_actuation_start},
                        {"lqg", {{"n", d.A.rows()}, {"n_bar", d.K.cols()}, {"check_reduced", design::to_json(d.check_reduced)},
                                 {"check_unreduced", design::to_json(d.check_unreduced)},
                                 {"spillover_rule", design::arm_lqg_rule_json(r.lqg)}}}};
    if (d.ibffc) j["ibffc"] = {{"tracking_rel_rms", d.ibffc->rel_rms}, {"modes_forward", d.ibffc->n_forward}, {"modes_backward", d.ibffc->n_backward}};
    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("ArmCtrl table for arm '%s' (variant %c, %s feedforward): move %s\n", a.name.c_str(), d.spec.exp,
                    ffs.c_str(), mv.describe().c_str());
        std::printf("  feedforward: %ld samples, max |tau_M*| = %.4g N m (peak %.4g), torque from %.4g s\n", n_ff, d.tau_max,
                    a.torque_peak, d.pre_actuation_start);
        for (const auto& [name, c] : {std::pair<const char*, design::LoopCheck>{"reduced", d.check_reduced}, {"unreduced", d.check_unreduced}})
            std::printf("  LQG closed loop on the %s arm, d_i = %d, d_o = %d: spectral radius %.9f (%s), GM %.2f dB, PM %.2f deg\n",
                        name, c.plant_di, c.plant_do, c.spectral_radius, c.spectral_radius < 1.0 ? "stable" : "UNSTABLE",
                        c.gain_margin_db, c.phase_margin_deg);
        std::printf("  LQG spillover rule: %s (design model %ld states, unreduced spectral radius <= %.9f)\n",
                    r.lqg.steps[static_cast<size_t>(r.lqg.accepted_step)].rule.c_str(), long(d.A.rows()), r.lqg.rho_max);
        std::printf("  table '%s' -> %s [%s, %zu bytes]\n", d.table.name.c_str(), out.c_str(), format.c_str(), data.size());
    }
    return 0;
}

int run_armctrl(const std::vector<std::string>& argv)
{
    Args args(argv, {"json"});
    args.check_known({"json", "exp", "N", "rt", "rr", "di", "do", "format", "real", "out", "torque-limit", "post", "arm", "move",
                      "move-csv", "ff"});
    if (!args.positional().empty()) throw UsageError("unexpected argument '" + args.positional()[0] + "'");
    if (args.has("arm")) return run_armctrl_arm(args);
    for (const char* k : {"move", "move-csv", "ff"})
        if (args.has(k)) throw UsageError(std::string("--") + k + " only with --arm ARM.json");
    design::ArmctrlSpec s;
    const std::string exp = args.str("exp");
    if (exp.size() != 1 || exp[0] < 'A' || exp[0] > 'D') throw UsageError("--exp must be A, B, C or D (got '" + exp + "')");
    s.exp = exp[0];
    s.N = to_int(args, "N", s.N, design::kArmctrlNMin, design::kArmctrlNMax,
                 "(beam collocation points) must lie in [" + std::to_string(design::kArmctrlNMin) + ", " +
                     std::to_string(design::kArmctrlNMax) + "]");
    s.r_t = args.num("rt", s.r_t);
    s.r_r = args.num("rr", s.r_r);
    if (args.has("di")) s.di = to_int(args, "di", 0, 0, 47, "must be >= 0 and fit the PLC (n + d_i + d_o < 64)");
    if (args.has("do")) s.dout = to_int(args, "do", 0, 0, 47, "must be >= 0 and fit the PLC (n + d_i + d_o < 64)");
    s.torque_limit = args.num("torque-limit", s.torque_limit);
    s.post = args.num("post", s.post);
    const std::string format = args.str("format", "bin"), out = args.str("out");
    if (!tables::is_emit_format(format)) throw UsageError("--format must be json, c, var or bin");
    try {
        s.validate();
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    design::ArmctrlDesign d;
    try {
        d = design::design_armctrl(s);
    } catch (const design::RiccatiError& e) {
        std::cerr << "fracdesign armctrl: Riccati equation has no stabilising solution: " << e.what() << "\n";
        return 1;
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    if (args.has("real")) {
        try {
            d.table.real = tables::real_type_from_string(args.str("real"));
        } catch (const tables::TableError& e) {
            throw UsageError("--real must be float64 or float32");
        }
    }
    const std::string data = tables::emit(d.table, format);
    write_file(out, data);
    const size_t bytes = data.size();
    const auto& sp = d.spec;
    const long n_ff = static_cast<long>(d.ff[0].size());
    nlohmann::json j = {{"schema", "frac.armctrl"},
                        {"version", 1},
                        {"experiment", std::string(1, sp.exp)},
                        {"variant", d.variant},
                        {"table", d.table.name},
                        {"format", format},
                        {"real", tables::to_string(d.table.real)},
                        {"out", out},
                        {"bytes", bytes},
                        {"entries", d.table.entries.size()},
                        {"N", sp.N},
                        {"r_t", sp.r_t},
                        {"r_r", sp.r_r},
                        {"ts", sp.T},
                        {"di", sp.di},
                        {"do", sp.dout},
                        {"ff_samples", n_ff},
                        {"ff_grid", {d.t0, d.dt, d.t_motion_start, d.t_motion_end}},
                        {"ff_lead", d.lead},
                        {"tau_M_max", d.tau_max},
                        {"pre_actuation_start", d.pre_actuation_start},
                        {"tail_step", d.tail_step}};
    if (d.ibffc) {
        j["ibffc"] = {{"tracking_rel_rms", d.ibffc->rel_rms}, {"modes_forward", d.ibffc->n_forward},
                      {"modes_backward", d.ibffc->n_backward}, {"head_tau_max", d.head_tau_max},
                      {"tau_M_at_rest", d.start_tau}};
    }
    if (d.lqg) {
        j["lqg"] = {{"n", d.A.rows()},
                    {"n_bar", d.K.cols()},
                    {"controller_residual", d.lqg->ctrl.residual},
                    {"observer_residual", d.lqg->obs.residual},
                    {"check_reduced", design::to_json(d.check_reduced)},
                    {"check_unreduced", design::to_json(d.check_unreduced)}};
    }
    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("ArmCtrl table, seed 004 Exp. %c (variant %d): %s\n", sp.exp, d.variant,
                    d.table.meta["source"].get<std::string>().c_str());
        std::printf("  feedforward: %ld samples, T0 = %g s, dt = %g s, motion %g..%g s, lead (%ld, %ld, %ld, %ld); "
                    "max |tau_M*| = %.4g N m, torque from %.4g s\n",
                    n_ff, d.t0, d.dt, d.t_motion_start, d.t_motion_end, d.lead[0], d.lead[1], d.lead[2], d.lead[3],
                    d.tau_max, d.pre_actuation_start);
        if (d.ibffc)
            std::printf("  ibFFC (N = %d, r_t = %g, r_r = %g): model tracks psi'(L)* to %.2e relative RMS\n", sp.N, sp.r_t,
                        sp.r_r, d.ibffc->rel_rms);
        if (d.lqg)
            for (const auto& [name, c] : {std::pair<const char*, design::LoopCheck>{"reduced", d.check_reduced},
                                          {"unreduced", d.check_unreduced}})
                std::printf("  LQG closed loop on the %s arm with the rig's delays d_i = %d, d_o = %d (%d states): "
                            "spectral radius %.9f (%s), GM %.2f dB, PM %.2f deg, min|1+L| %.3f\n",
                            name, c.plant_di, c.plant_do, c.plant_states, c.spectral_radius,
                            c.spectral_radius < 1.0 ? "stable" : "UNSTABLE", c.gain_margin_db, c.phase_margin_deg,
                            c.modulus_margin);
        std::printf("  table '%s' (%zu entries, %s) -> %s [%s, %zu bytes]\n", d.table.name.c_str(),
                    d.table.entries.size(), tables::to_string(d.table.real).c_str(), out.c_str(), format.c_str(), bytes);
    }
    return 0;
}

CommandRegistrar reg({"armctrl", "parameter table of the PLC program ArmCtrl for seed 004 Exp. A-D",
                      "usage: fracdesign armctrl --arm ARM.json --move SPEC|--move-csv FILE --out FILE\n"
                      "                          [--ff inverse|rigid] [--post S] [--format ...] [--json]\n"
                      "       fracdesign armctrl --exp A|B|C|D --out FILE [--format json|c|var|bin]\n"
                      "                          [--real float64|float32] [--N 9] [--rt R --rr R]\n"
                      "                          [--di 4 --do 3] [--torque-limit 250] [--post S] [--json]\n\n"
                      "--arm: the table for the arm document (docs/arm_format.md): LQG with the document's\n"
                      "delays (variant D; C without delays), feedforward by stable inversion (--ff inverse,\n"
                      "default) or rigid-body (4.14)-(4.17) (--ff rigid) for the move: --move\n"
                      "Q0:Q1@T0+DUR[,Q2@T1+DUR...] (sin^2 segments, rad and s, e.g. 0:1.0@0.5+1.5) or\n"
                      "--move-csv FILE (columns t, q: the tip reference). Refused (exit 1, cause named) when\n"
                      "the unreduced loop is unstable or the feedforward exceeds drive.torque_peak.\n\n"
                      "Designs the controller of one experiment of seed 004 (Table 8.1) and writes the\n"
                      "table ArmCtrl loads (plc_blocks/programs/ArmCtrl.h; docs/armctrl_tables.md):\n"
                      "  A  rigid-body feedforward (4.14)-(4.17) + PD 320/200 + linear friction (Table 8.6)\n"
                      "  B  inversion-based feedforward (stable inversion) + PD + friction (Table 8.6)\n"
                      "  C  ibFFC + state-difference LQG, Table 8.7, no delay model (d_i = d_o = 0)\n"
                      "  D  ibFFC + LQG with delays, Table 8.8 (T = 1.2 ms, d_i = 4, d_o = 3), torque\n"
                      "     row led by d_i and IMU reference row lagged by d_o cycles (Sec. 8.6)\n"
                      "Trajectory: Table 8.5 (sin^2 PTP 0 -> pi/2 rad, 0.5 s to 2 s in the run-time\n"
                      "counter's time). The feedforward table (one sample per 1.2 ms cycle, up to\n"
                      "t_e + POST, default 2.5 s) starts at rest and holds the ibFFC pre-actuation before\n"
                      "0.5 s. LQG matrices: A', B', C' (ZOH plant), K, L_e exactly as `fracdesign lqg`\n"
                      "designs them, in libfrac's frac_lqg convention. --N: beam collocation points\n"
                      "(5..24, default 9, Table 8.4); --rt/--rr: beam damping (thesis gives none;\n"
                      "default 0.5, 0). --di/--do only for Exp. D. Formats as `fracdesign table emit`\n"
                      "(default bin: the FRPT data object). Exit status 2 on a bad option, 1 when\n"
                      "the design fails (cause named).\n",
                      run_armctrl});

}  // namespace
}  // namespace fracdesign
