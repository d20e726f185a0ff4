// cmd_model.cpp - `fracdesign model <beam|arm|antenna|collocated|foprocess> [params] [--json]`:
// builds one of the seeds' models (or reads it with --model FILE), prints its frequencies,
// poles/zeros or frequency responses, and with --save FILE writes it in the JSON model format.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/design/arm_design.hpp"
#include "fracdesign/design/riccati.hpp"
#include "fracdesign/model_json.hpp"
#include "fracdesign/tables/ptable.hpp"

namespace fracdesign {
namespace {

using nlohmann::json;

std::vector<double> freq_list(const Args& a, std::vector<double> def)
{
    if (!a.has("w")) return def;
    std::vector<double> w = a.nums("w");
    for (double v : w)
        if (!(v > 0)) throw UsageError("option --w: frequencies must be > 0 rad/s");
    return w;
}

json cx(std::complex<double> z) { return json::array({z.real(), z.imag()}); }

void print_list(const char* label, const std::vector<double>& v, const char* unit)
{
    std::printf("%s:", label);
    for (double x : v) std::printf(" %.6f", x);
    std::printf(" %s\n", unit);
}

ModelSpec spec_from_args(const std::string& kind, const Args& a)
{
    if (kind == "beam" || kind == "arm") {
        TimoshenkoParams b = wang_steel_beam();
        b.L = a.num("L", b.L);
        b.r_t = a.num("r_t", 0.0);
        b.r_r = a.num("r_r", 0.0);
        const long N = a.integer("N", 9);
        if (N < 2 || N > 200) throw UsageError("option --N: must be in [2, 200]");
        const std::string c = a.str("collocation", "gl");
        if (c != "gl" && c != "eq") throw UsageError("option --collocation: must be gl or eq");
        const Collocation col = c == "gl" ? Collocation::GaussLegendre : Collocation::Equidistant;
        if (kind == "beam") return BeamModelSpec{b, static_cast<int>(N), col};
        ArmModelSpec s;
        s.beam = b;
        s.drive = wang_drive();
        s.drive.I_M = a.num("I_M", s.drive.I_M);
        s.options.N = static_cast<int>(N);
        s.options.collocation = col;
        s.options.reduce = !a.has("full");
        if (a.has("shifts")) s.options.shifts = a.nums("shifts");
        return s;
    }
    if (kind == "antenna") {
        AntennaModelSpec s;
        s.structure = antenna_structure_from_name(a.str("structure", "VI"));
        const AntennaDamping<double> nom = s.structure == AntennaStructure::III ? haro_nominal_III() : haro_nominal_VI();
        // free parameters default to the Table 5 nominal values (III or VI), fixed ones come from Table 2
        const int nf = antenna_free_count(s.structure);
        const char* const* fn = antenna_free_names(s.structure);
        for (const char* p : {"zeta", "alpha", "gamma", "lambda"}) {
            bool is_free = false;
            for (int i = 0; i < nf; ++i) is_free = is_free || std::string(fn[i]) == p;
            if (a.has(p) && !is_free)
                throw UsageError(std::string("option --") + p + ": structure " + antenna_structure_name(s.structure) +
                                 " fixes this parameter (seed 000 Table 2)");
        }
        double free[4];
        for (int i = 0; i < nf; ++i) {
            const std::string n = fn[i];
            const double d = n == "zeta" ? nom.zeta : n == "alpha" ? nom.alpha : n == "gamma" ? nom.gamma : nom.lambda;
            free[i] = a.num(n, d);
        }
        s.damping = antenna_damping(s.structure, free);
        return s;
    }
    if (kind == "collocated") return CollocatedModelSpec{a.num("m2", kFeliuM2Nominal), !a.has("undamped")};
    if (kind == "foprocess") {
        FoProcessModelSpec s{feliu_benftima_robot()};
        s.process.K = a.num("K", s.process.K);
        s.process.T = a.num("T", s.process.T);
        s.process.lambda = a.num("lambda", s.process.lambda);
        s.process.tau = a.num("tau", s.process.tau);
        s.process.validate();
        return s;
    }
    throw UsageError("unknown model kind '" + kind + "' (beam, arm, antenna, collocated, foprocess)");
}

json summarize(const ModelSpec& m, const Args& a, bool print)
{
    json r;
    const int modes = static_cast<int>(a.integer("modes", 5));
    if (modes < 1) throw UsageError("option --modes: must be >= 1");
    if (auto* b = std::get_if<BeamModelSpec>(&m)) {
        const PsBeam beam = build_ps_beam(b->beam, b->N, b->collocation);
        const std::vector<double> f = clamped_free_frequencies_hz(beam, modes);
        const std::vector<double> ex = exact_clamped_free_frequencies_hz(b->beam, modes);
        r = {{"states", 4 * b->N}, {"clamped_free_hz", f}, {"exact_hz", ex}, {"feedthrough_sign", beam.sigma}};
        if (print) {
            std::printf("PS Timoshenko beam, N = %d (%d states), feedthrough sign %+g\n", b->N, 4 * b->N, beam.sigma);
            print_list("clamped-free frequencies", f, "Hz");
            print_list("exact (App. C)          ", ex, "Hz");
        }
    } else if (auto* s = std::get_if<ArmModelSpec>(&m)) {
        const ArmModel arm = build_arm(s->beam, s->drive, s->options);
        std::vector<double> f = arm.arm.state_space().natural_frequencies_hz(1e-3);
        if (static_cast<int>(f.size()) > modes) f.resize(static_cast<size_t>(modes));
        r = {{"states", arm.arm.J.rows()}, {"flexible_modes_hz", f}, {"inputs", arm.arm.inputs}, {"outputs", arm.arm.outputs}};
        if (print) {
            std::printf("arm (drive + %s beam), %ld states\n", s->options.reduce ? "Krylov-reduced" : "full",
                        static_cast<long>(arm.arm.J.rows()));
            print_list("flexible modes", f, "Hz");
        }
    } else if (auto* n = std::get_if<AntennaModelSpec>(&m)) {
        const std::vector<double> p = antenna_undamped_poles(n->link, 3), z = antenna_undamped_zeros(n->link, 2);
        r = {{"undamped_poles_rad_s", p}, {"undamped_zeros_rad_s", z}};
        json fr = json::array();
        for (double w : freq_list(a, {1, 10, 30, 100}))
            fr.push_back({{"w", w}, {"G", cx(antenna_frf(n->link, n->damping, w))}});
        r["frf"] = fr;
        if (print) {
            std::printf("antenna, structure %s: zeta %g alpha %g gamma %g lambda %g\n", antenna_structure_name(n->structure).c_str(),
                        n->damping.zeta, n->damping.alpha, n->damping.gamma, n->damping.lambda);
            print_list("undamped poles", p, "rad/s");
            print_list("undamped zeros", z, "rad/s");
            for (const auto& e : fr)
                std::printf("G(j%g) = %.7g %+.7gj N m/rad\n", e["w"].get<double>(), e["G"][0].get<double>(), e["G"][1].get<double>());
        }
    } else if (auto* c = std::get_if<CollocatedModelSpec>(&m)) {
        const CollocatedPlant p = c->arm.plant(c->arm.m2_nominal);
        r = {{"a1", p.a1}, {"z1", p.z1}, {"a2", p.a2}, {"b", p.b}, {"k1", p.k1}, {"k2", p.k2},
             {"zeta1", p.zeta1}, {"zeta2", p.zeta2}, {"xi1", p.xi1}, {"eps", p.eps},
             {"G2_numerator", {p.g2_s2, p.g2_0}}};
        json fr = json::array();
        for (double w : freq_list(a, {1, 10, 40})) fr.push_back({{"w", w}, {"P", cx(collocated_P(p, w, c->damped))}});
        r["frf"] = fr;
        if (print) {
            std::printf("collocated plant (seed 002, %s), m2 = %g %s, %s\n",
                        c->arm.form == CollocatedArm::Form::Printed ? "the paper's robot" : "two-lumped-mass arm",
                        p.m2, c->arm.mass_unit(), c->damped ? "Rayleigh damped" : "undamped");
            std::printf("a1 = %.4f  z1 = %.4f  a2 = %.4f rad/s, b = %g, k1 = %.5f, k2 = %.5f\n", p.a1, p.z1, p.a2, p.b, p.k1, p.k2);
            std::printf("zeta1 = %.5f  zeta2 = %.5f  xi1 = %.5f\n", p.zeta1, p.zeta2, p.xi1);
            for (const auto& e : fr)
                std::printf("P(j%g) = %.7g %+.7gj\n", e["w"].get<double>(), e["P"][0].get<double>(), e["P"][1].get<double>());
        }
    } else if (auto* f = std::get_if<FoProcessModelSpec>(&m)) {
        const FoProcess& p = f->process;
        r = {{"time_scale_s", p.time_scale()}, {"tau_n", p.normalised_delay()}};
        json fr = json::array();
        for (double w : freq_list(a, {1, 5.8434, 10})) fr.push_back({{"w", w}, {"G", cx(p.frf(w))}});
        r["frf"] = fr;
        if (print) {
            std::printf("FO process K e^{-tau s}/(T s^lambda + 1): K %g T %g lambda %g tau %g\n", p.K, p.T, p.lambda, p.tau);
            std::printf("T^(1/lambda) = %.7f s, tau_n = %.6f\n", p.time_scale(), p.normalised_delay());
            for (const auto& e : fr)
                std::printf("G(j%g) = %.7g %+.7gj\n", e["w"].get<double>(), e["G"][0].get<double>(), e["G"][1].get<double>());
        }
    } else {
        const StateSpace& s = std::get<StateSpace>(m);
        const Eigen::VectorXcd p = s.poles();
        json pj = json::array();
        for (Eigen::Index i = 0; i < p.size(); ++i) pj.push_back(cx(p[i]));
        r = {{"states", s.nx()}, {"inputs", s.inputs}, {"outputs", s.outputs}, {"poles", pj}};
        if (print) {
            std::printf("state space: %ld states, %ld inputs, %ld outputs, %s\n", static_cast<long>(s.nx()),
                        static_cast<long>(s.nu()), static_cast<long>(s.ny()), s.continuous() ? "continuous" : "discrete");
            for (Eigen::Index i = 0; i < p.size(); ++i) std::printf("pole %.6g %+.6gj\n", p[i].real(), p[i].imag());
        }
    }
    return r;
}

// --save-plant: the full-order arm (3.103) as the HIL bench's plant table (docs/hil.md, "The arm
// plant"): input the net torque on the driven side of the gear, outputs C = [theta_M; theta_M';
// psi_L; psi_L'], continuous (Ac, Bc) and its exact ZOH (Ad, Bd) at step h (c2d_zoh, (7.3)-(7.7)).
// The tip angle is not a port output of (3.103): psi_L = psi(0) + int_0^L eps_r dz with psi(0) =
// theta_h (the beam clamped in the hub, u_b^0 = y_a2) and eps_r = dpsi/dz on the flow basis, whose
// integrals are the column sums of M (3.70) (the effort basis sums to 1). Its derivative must be the
// port output psi'(L) and the torque must not act on it directly: both are checked here.
tables::ParamTable arm_plant_table(const ArmModelSpec& s, double h)
{
    if (s.options.reduce)
        throw UsageError("--save-plant: needs the full-order arm (--full); the Krylov-reduced beam has no tip angle");
    if (!std::isfinite(h) || !(h > 0.0) || h > 0.1) throw UsageError("option --h: must be in (0, 0.1] s");
    const ArmModel arm = build_arm(s.beam, s.drive, s.options);
    const StateSpace c = arm.arm.state_space();
    const Eigen::Index n = c.nx(), N = arm.beam.N;
    if (n != 4 + 4 * N) throw std::logic_error("--save-plant: the full arm must have 4 + 4 N states");
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(4, n);
    C(0, 0) = 1.0;              // theta_M, drive state 0 (3.35)
    C.row(1) = c.C.row(0);      // theta_M' = p_M / I_M
    C(2, 1) = 1.0;              // theta_h = psi(0)
    C.block(2, 4 + 3 * N, 1, N) = arm.beam.M.colwise().sum();  // + int eps_r dz (beam block eps_r)
    C.row(3) = c.C.row(2);      // psi'(L) (port output, (3.103))
    const double scale = C.row(3).cwiseAbs().maxCoeff() + 1.0;
    const double res = (C.row(2) * c.A - C.row(3)).cwiseAbs().maxCoeff() / scale;
    const double feed = std::fabs((C.row(2) * c.B.col(0))(0, 0)) / scale;
    if (!(res < 1e-9) || !(feed < 1e-9))
        throw std::runtime_error("--save-plant: the tip angle row is not the integral of psi'(L) (residual " +
                                 std::to_string(res) + ", " + std::to_string(feed) + ")");
    StateSpace one = c;
    one.B = c.B.col(0);
    one.C = C;
    one.D = Eigen::MatrixXd::Zero(4, 1);
    one.inputs = {c.inputs[0]};
    one.outputs = {"theta_M [rad]", "theta_M_dot [rad/s]", "psi_L [rad]", "psi_L_dot [rad/s]"};
    tables::ParamTable t;
    t.name = "arm_plant";
    t.meta = {{"source", "seed 004 (3.103), full pseudo-spectral arm, fracdesign model arm --save-plant"},
              {"N", N}, {"h", h}, {"I_M", s.drive.I_M}};
    Eigen::MatrixXd dims(1, 2);
    dims << static_cast<double>(n), static_cast<double>(N);
    t.add("plant_dims", dims, "n states, N collocation points");
    design::add_arm_plant_steps(t, one, h);
    t.add("C", C, "theta_M [rad], theta_M' [rad/s], psi_L [rad], psi_L' [rad/s]");
    t.validate();
    return t;
}

// `model --arm ARM.json`: the arm document's full and reduced models, and its HIL plant table, gap
// nominal and rig scenario. Every output is composed first and written only when all were made.
int run_model_arm(const Args& a)
{
    for (const char* k : {"model", "save", "save-ss", "N", "collocation", "L", "r_t", "r_r", "I_M", "full", "shifts"})
        if (a.has(k)) throw UsageError(std::string("--") + k + " does not go with --arm: the arm document gives it");
    if (!a.positional().empty() && a.positional()[0] != "arm") throw UsageError("--arm builds an arm, not '" + a.positional()[0] + "'");
    ArmDocument doc;
    try {
        doc = read_arm_file(a.str("arm"));
    } catch (const ArmDocumentError& e) {
        throw UsageError(e.what());
    }
    if (a.has("h") && !a.has("save-plant")) throw UsageError("option --h: only with --save-plant");
    std::vector<std::pair<std::string, std::string>> files;
    double h = 0.0;
    if (a.has("save-plant")) {
        // the rig integrates half cycles: default h = T / 8 (4 steps per half cycle)
        h = a.num("h", doc.T / 8.0);
        try {
            files.emplace_back(a.str("save-plant"), tables::emit(design::arm_plant_table_for(doc, h), "bin"));
        } catch (const std::invalid_argument& e) {
            throw UsageError(e.what());
        }
    }
    if (a.has("closed-loop") && !a.has("gap-nominal")) throw UsageError("option --closed-loop TABLE: only with --gap-nominal FILE");
    if (a.has("gap-nominal")) {
        nlohmann::json nom;
        try {
            nom = a.has("closed-loop") ? design::arm_gap_nominal_closed(doc, a.str("closed-loop")) : design::arm_gap_nominal(doc);
        } catch (const std::invalid_argument& e) {
            throw UsageError(e.what());
        }
        files.emplace_back(a.str("gap-nominal"), nom.dump(1) + "\n");
    }
    if (a.has("save-scenario")) {
        const double dur = a.num("duration", 4.0);
        if (!(dur > 0.0 && dur <= 600.0)) throw UsageError("option --duration: allowed (0, 600] s");
        try {
            files.emplace_back(a.str("save-scenario"),
                               design::arm_hil_scenario(doc, a.str("plant-table", "plant.bin"), a.str("ctrl-table", "ctrl.bin"), dur));
        } catch (const ArmDocumentError& e) {
            throw UsageError(e.what());
        } catch (const std::invalid_argument& e) {
            throw UsageError(e.what());
        }
    }
    design::ArmReduction red;
    try {
        red = design::choose_reduction(doc);
    } catch (const design::ArmDesignError& e) {
        std::cerr << "fracdesign model: " << e.what() << "\n";
        return 1;
    }
    for (const auto& f : files) write_file(f.first, f.second);
    json modes = json::array();
    for (const auto& m : red.retained) modes.push_back({{"full_hz", m.full_hz}, {"reduced_hz", m.reduced_hz}, {"rel_error", m.rel_error}});
    const json r = {{"schema", "frac.arm.model"}, {"version", 1}, {"arm", doc.name}, {"N", doc.design.N},
                    {"full_states", red.full_states}, {"reduced_states", red.reduced_states},
                    {"bandwidth_hz", red.bandwidth_hz}, {"shifts_rad_s", red.shifts}, {"full_modes_hz", red.full_hz},
                    {"retained", modes}, {"max_error_below_bandwidth", red.max_error_below_bandwidth},
                    {"rigid_link_inertia", doc.rigid_link_inertia()}};
    if (a.has("json")) {
        std::cout << r.dump(2) << "\n";
    } else {
        std::printf("arm '%s': full model N = %d, %d states; reduced %d states (bandwidth %.4g Hz, shifts", doc.name.c_str(),
                    doc.design.N, red.full_states, red.reduced_states, red.bandwidth_hz);
        for (double x : red.shifts) std::printf(" %.4g", x);
        std::printf(" rad/s)\n");
        for (const auto& m : red.retained)
            std::printf("  mode full %.5f Hz, reduced %.5f Hz, error %.3e\n", m.full_hz, m.reduced_hz, m.rel_error);
        for (const auto& f : files) std::printf("  written: %s\n", f.first.c_str());
    }
    return 0;
}

int run_model(const std::vector<std::string>& argv)
{
    Args a(argv, {"json", "full", "undamped"});
    a.check_known({"json", "arm", "gap-nominal", "closed-loop", "save-scenario", "plant-table", "ctrl-table", "duration", "model", "save", "save-ss", "save-plant", "h", "modes", "w", "N", "collocation", "L", "r_t", "r_r", "I_M", "full", "shifts",
                   "structure", "zeta", "alpha", "gamma", "lambda", "m2", "undamped", "K", "T", "tau"});
    if (a.has("arm")) return run_model_arm(a);
    for (const char* k : {"gap-nominal", "closed-loop", "save-scenario", "plant-table", "ctrl-table", "duration"})
        if (a.has(k)) throw UsageError(std::string("--") + k + " only with --arm ARM.json");
    ModelSpec m;
    if (a.has("model")) {
        m = read_model_file(a.str("model"));
        if (!a.positional().empty() && a.positional()[0] != model_kind(m))
            throw UsageError("the model file holds a '" + model_kind(m) + "' model, not '" + a.positional()[0] + "'");
    } else {
        if (a.positional().size() != 1) throw UsageError("expected one model kind: beam, arm, antenna, collocated, foprocess");
        try {
            // the round trip through the JSON format applies its validation (one line naming the field)
            m = model_from_json(model_to_json(spec_from_args(a.positional()[0], a)));
        } catch (const std::invalid_argument& e) {
            throw UsageError(e.what());
        }
    }
    if (a.has("save-ss")) {
        try {
            write_model_file(a.str("save-ss"), model_state_space(m));
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string("--save-ss: ") + e.what());
        }
    }
    if (a.has("save-plant")) {
        const ArmModelSpec* arm = std::get_if<ArmModelSpec>(&m);
        if (!arm) throw UsageError("--save-plant: only for the arm model");
        const tables::ParamTable t = arm_plant_table(*arm, a.num("h", 1.2e-3 / 8));
        write_file(a.str("save-plant"), tables::emit(t, "bin"));
    } else if (a.has("h")) {
        throw UsageError("option --h: only with --save-plant");
    }
    const bool js = a.has("json");
    const json result = summarize(m, a, !js);
    if (a.has("save")) write_model_file(a.str("save"), m);
    if (js) std::cout << json{{"schema", "frac.model.summary"}, {"version", 1}, {"model", model_to_json(m)}, {"result", result}}.dump(2) << "\n";
    return 0;
}

CommandRegistrar reg({"model", "build a seed model and print its frequencies, poles/zeros or responses",
                      "usage: fracdesign model <beam|arm|antenna|collocated|foprocess> [params] [--json]\n"
                      "       fracdesign model --model FILE [--json]\n"
                      "       fracdesign model --arm ARM.json [--save-plant FILE.bin [--h S]]\n"
                      "                        [--gap-nominal FILE.json [--closed-loop CTRL.bin]]\n"
                      "                        [--save-scenario FILE.txt [--plant-table F] [--ctrl-table F] [--duration S]] [--json]\n\n"
                      "  --arm ARM.json  the arm document (docs/arm_format.md): full model at design.N and the\n"
                      "                reduced one with automatic shifts (each retained mode vs the full arm);\n"
                      "                --save-plant: its HIL plant table (default h = T/8); --gap-nominal: the gap\n"
                      "                diagnosis's nominal (open loop torque_actual -> motor_velocity, imu_rate);\n"
                      "                with --closed-loop CTRL.bin the closed loop of ArmCtrl from that table\n"
                      "                (path relative to the nominal; replayed by gap-plc, docs/gap.md) and the\n"
                      "                drive (delay, limit, current loop) -> motor_angle, motor_velocity, imu_rate;\n"
                      "                --save-scenario: hil_bench scenario lines for the arm\n\n"
                      "  beam        PS Timoshenko beam (seed 004): --N 9 --collocation gl|eq --L --r_t --r_r --modes 5\n"
                      "  arm         drive + beam (3.103): --N 9 --full (no Krylov reduction) --shifts 16,18.43,115.6\n"
                      "              --I_M 5.8624 (load side, n^2 I_m)\n"
                      "  antenna     eq. (25) of seed 000: --structure I..VI --zeta --alpha --gamma --lambda\n"
                      "              (free parameters default to Table 5 nominal values) --w 1,10,30,100\n"
                      "  collocated  seed 002 plant P(s): --m2 0.12 (lb) --undamped --w 1,10,40\n"
                      "  foprocess   seed 001 K e^{-tau s}/(T s^lambda+1): --K --T --lambda --tau --w ...\n\n"
                      "  --model FILE  read a JSON model (docs/model_format.md) instead of parameters\n"
                      "  --save FILE   write the model as JSON\n"
                      "  --save-ss FILE  write its LTI state space (kind statespace; rational models only)\n"
                      "  --save-plant FILE.bin  arm --full only: the HIL bench's plant table (FRPT): plant_dims (n, N),\n"
                      "                h, Ad, Bd (exact ZOH at h), C (theta_M, theta_M', psi_L, psi_L'), Ac, Bc;\n"
                      "                input: net torque on the driven side [N m] (docs/hil.md)\n"
                      "  --h SECONDS   step of --save-plant (default 1.5e-4 = 1.2 ms / 8)\n"
                      "  --json        machine-readable result {schema, version, model, result}\n",
                      run_model});

}  // namespace
}  // namespace fracdesign
