// cmd_tune.cpp - `fracdesign tune fopi|fopd ...`: seed 001 closed-form
// FO-PI^alpha / FO-PD^mu tuning with the feasibility tests and bands.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/design/collocated.hpp"
#include "fracdesign/design/fopi_fopd.hpp"
#include "fracdesign/model_json.hpp"

namespace fracdesign {
namespace {

using design::FoKind;

std::string band_text(const std::vector<std::pair<double, double>>& bands)
{
    if (bands.empty()) return "none";
    std::string s;
    char buf[96];
    for (size_t i = 0; i < bands.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%s[%.6g, %.6g]", i ? ", " : "", bands[i].first, bands[i].second);
        s += buf;
    }
    return s + " rad/s";
}

int run_fo(FoKind kind, const Args& args)
{
    const bool pi = kind == FoKind::PI;
    args.check_known({"json", "K", "T", "w0", "lambda", "tau", "wc", "phim", pi ? "alpha" : "mu", "band-lo", "band-hi"});
    if (!args.has("T") && !args.has("w0")) throw UsageError("missing required option --T (or --w0)");
    for (const std::string r : {"lambda", "wc", "phim", pi ? "alpha" : "mu"})
        if (!args.has(r)) throw UsageError("missing required option --" + r);
    design::GharabPlant p;
    p.K = args.num("K", 1.0);
    if (args.has("T") && args.has("w0")) throw UsageError("give either --T or --w0, not both");
    if (args.has("w0")) {
        const double w0 = args.num("w0", 0.0);
        if (!(w0 > 0.0)) throw UsageError("--w0 must be > 0");
        p.T = 1.0 / (w0 * w0);  // seed 001 eq. (51): T = 1/w_0^2
    } else {
        p.T = args.num("T", 0.0);
    }
    p.lambda = args.num("lambda", 0.0);
    p.tau = args.num("tau", 0.0);
    design::FoSpec s;
    s.wc = args.num("wc", 0.0);
    s.phim = args.num("phim", 0.0);
    s.order = args.num(pi ? "alpha" : "mu", 0.0);
    design::FoDesign d;
    try {
        d = design::tune_fo(kind, p, s);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    // Default search range for the feasible band: w_cn in [0.01, 10].
    const double lo = args.num("band-lo", 0.01 / d.Tl), hi = args.num("band-hi", 10.0 / d.Tl);
    const auto bands = design::feasible_bands(kind, p, s, lo, hi);
    nlohmann::json j = design::to_json(d);
    j["feasible_band"] = {{"phim", s.phim}, {"search", {lo, hi}}, {"bands", nlohmann::json::array()}};
    for (const auto& b : bands) j["feasible_band"]["bands"].push_back({b.first, b.second});

    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("%s tuning (seed 001), plant K=%g T=%g lambda=%g tau=%g\n", pi ? "FO-PI^alpha" : "FO-PD^mu", p.K,
                    p.T, p.lambda, p.tau);
        std::printf("  spec: w_c = %g rad/s, phi_m = %g rad, %s = %g\n", s.wc, s.phim, pi ? "alpha" : "mu", s.order);
        std::printf("  normalised: w_cn = %.7g, tau_n = %.7g, phi_mn = %.7g, K_pn = %.7g, %s = %.7g\n", d.wcn,
                    d.taun, d.phimn, d.Kpn, pi ? "K_in" : "K_dn", pi ? d.Kin : d.Kdn);
        if (pi)
            std::printf("  C(s) = %.7g + %.7g s^-%g\n", d.Kp, d.Ki, s.order);
        else
            std::printf("  C^(s) = %.7g + %.7g s^%g; with delta = %.7g: C(s) = %.7g + %.7g s^%g, u = C e + delta y\n",
                        d.Kp, d.Kd, s.order, d.delta, d.Kp + d.delta, d.Kd, s.order);
        for (const auto& t : d.tests) std::printf("  [%s] %s: %s\n", t.pass ? "ok" : "FAIL", t.name.c_str(), t.detail.c_str());
        std::printf("  feasible crossover band at phi_m = %g: %s\n", s.phim, band_text(bands).c_str());
    }
    if (!d.feasible()) {
        std::cerr << "fracdesign tune " << (pi ? "fopi" : "fopd") << ": infeasible specification: " << d.reason()
                  << "; feasible w_c at phi_m = " << s.phim << ": " << band_text(bands) << "\n";
        return 1;
    }
    return 0;
}

// The collocated arm to design for: --model PLANT.json (kind "collocated") or the paper's robot,
// with --m2 / --m2-lo / --m2-hi overriding the nominal tip mass and its range (in the arm's unit).
CollocatedArm collocated_arm(const Args& args)
{
    CollocatedArm arm = feliu_robot_arm();
    if (args.has("model")) {
        const ModelSpec m = read_model_file(args.str("model"));  // ModelFormatError names the field
        const auto* c = std::get_if<CollocatedModelSpec>(&m);
        if (!c)
            throw ModelFormatError("kind", "is \"" + model_kind(m) + "\"; tune collocated needs a \"collocated\" model");
        arm = c->arm;
        if (!c->damped) arm.rayleigh_a = arm.rayleigh_b = 0.0;  // "damped": false designs on the undamped plant
    }
    arm.m2_nominal = args.num("m2", arm.m2_nominal);
    arm.m2_min = args.num("m2-lo", arm.m2_min);
    arm.m2_max = args.num("m2-hi", arm.m2_max);
    // A range given on the command line must still hold the nominal mass (and vice versa).
    try {
        arm.validate();
    } catch (const CollocatedArmError& e) {
        const bool cli = (e.field.find("m2") != std::string::npos) && (args.has("m2") || args.has("m2-lo") || args.has("m2-hi"));
        if (cli) throw UsageError("options --m2/--m2-lo/--m2-hi: " + e.field + " " + e.problem);
        throw;
    }
    return arm;
}

int run_collocated(const Args& args)
{
    args.check_known({"json", "model", "phi0", "wc0", "m2", "alpha", "m2-lo", "m2-hi", "exact", "prefilter",
                      "prefilter-start"});
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    const double phi0_deg = args.num("phi0", 0.0), wc0 = args.num("wc0", 0.0);
    if (!args.has("phi0") || !args.has("wc0")) throw UsageError("missing required option --phi0 (deg) or --wc0 (rad/s)");
    if (!(phi0_deg > 0.0 && phi0_deg <= 90.0))
        throw UsageError("option --phi0: is " + std::to_string(phi0_deg) + ", must lie in (0, 90] degrees (Theorem 5)");
    const CollocatedArm arm = collocated_arm(args);
    const char* unit = arm.mass_unit();
    const CollocatedPlant nominal = arm.plant(arm.m2_nominal);
    design::FdDesign d;
    try {
        d = design::design_fd(nominal, phi0_deg * kDeg, wc0, args.num("alpha", 0.0), !args.has("exact"));
    } catch (const std::invalid_argument& e) {
        std::cerr << "fracdesign tune collocated: infeasible specification: " << e.what() << "\n";
        return 1;
    }
    const auto L = [&](double w) { return design::loop_fd(d, nominal, w, true); };
    const auto c = design::modal_crossovers(L, nominal, d.theorem_case);
    const auto all = design::crossovers(L, 1e-3 * nominal.a1, 1e4 * nominal.a2,
                                        static_cast<int>(800.0 * std::log10(1e7 * nominal.a2 / nominal.a1)));
    const auto range = design::crossover_range(d, arm, arm.m2_min, arm.m2_max);
    const double eps = nominal.eps;
    const auto stab = design::loop_fd_nyquist(d, nominal, true);
    nlohmann::json j = design::to_json(d);
    j["plant"] = model_to_json(CollocatedModelSpec{arm, true});
    j["nominal_loop"] = {{"wc1", c.first.w}, {"pm1_deg", c.first.pm_deg}, {"wc2", c.second.w}, {"pm2_deg", c.second.pm_deg},
                         {"crossovers", nlohmann::json::array()},
                         {"nyquist", {{"stable", stab.stable}, {"encirclements", stab.encirclements},
                                      {"min_distance", stab.min_distance}, {"w_min", stab.w_min}}}};
    for (const auto& x : all) j["nominal_loop"]["crossovers"].push_back({{"w", x.w}, {"pm_deg", x.pm_deg}});
    j["crossover_range"] = {{"m2", {arm.m2_min, arm.m2_max}}, {"m2_unit", unit}, {"wc", {range.first, range.second}}};
    design::PrefilterResult pf;
    if (args.has("prefilter")) {
        design::Prefilter start;
        if (args.has("prefilter-start")) {
            const auto v = args.nums("prefilter-start");
            if (v.size() != 3) throw UsageError("--prefilter-start needs fn,fd,beta");
            start = design::Prefilter{v[0], v[1], v[2]};
        }
        try {
            pf = design::optimise_prefilter(L, nominal, 1.0, 0.3, args.has("prefilter-start") ? &start : nullptr);
        } catch (const std::invalid_argument& e) {
            throw UsageError(e.what());
        }
        const double bw = design::bandwidth_3db([&](double w) { return design::closed_loop_tip(L, pf.F, nominal, w); });
        j["prefilter"] = {{"form", "F(s) = (1 + fn s^beta)/(1 + fd s)"}, {"fn", pf.F.fn}, {"fd", pf.F.fd},
                          {"beta", pf.F.beta}, {"band_0p3db", pf.band}, {"bandwidth_3db", bw},
                          {"evaluations", pf.evaluations}};
    }
    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    const bool c1 = d.theorem_case == 1;
    std::printf("collocated fractional damping (seed 002, Theorem 5 case %d: w_c0 %s), %s, nominal m2 = %g %s\n",
                d.theorem_case, c1 ? "in (a1, z1)" : "< a1",
                arm.form == CollocatedArm::Form::Printed ? "the paper's robot" : "two-lumped-mass arm", arm.m2_nominal, unit);
    std::printf("  a1 = %.4f, z1 = %.4f, a2 = %.4f rad/s, b = %.6g, eps = %g s\n", nominal.a1, nominal.z1, nominal.a2,
                nominal.b, eps);
    std::printf("  alpha = %.6g (exact %.6g), Kc = %.6g; C(s) = Kc (1 + %g s)%s s^(alpha-2)\n", d.alpha, d.alpha_exact,
                d.Kc, d.q_approx ? 2.0 * eps : eps, d.q_approx ? "" : "^2");
    std::printf("  nominal loop: w_c1 = %.4f rad/s, PM1 = %.2f deg (%s); w_c2 = %.4f rad/s, PM2 = %.2f deg (%s)\n",
                c.first.w, c.first.pm_deg, c1 ? "in (a1, z1)" : "in (0, a1)", c.second.w, c.second.pm_deg,
                c1 ? "above a2" : "in (z1, a2)");
    if (!c1)
        std::printf("  (case 2: PM = -phi0 in the (-360, 0] convention, the crossing is %g deg above -1; Theorem 5.2)\n",
                    phi0_deg);
    std::printf("  all crossovers:");
    for (const auto& x : all) std::printf(" %.4f (%.2f deg)", x.w, x.pm_deg);
    std::printf("\n  closed loop (nominal, %s): %s\n", nominal.zeta1 > 0.0 ? "damped" : "undamped", stab.detail.c_str());
    std::printf("  robust crossover range over m2 in [%g, %g] %s: [%.4f, %.4f] rad/s\n", arm.m2_min, arm.m2_max, unit,
                range.first, range.second);
    if (args.has("prefilter"))
        std::printf("  prefilter F = (1 + %.4g s^%.4g)/(1 + %.4g s): +-0.3 dB band %.4f rad/s, -3 dB bandwidth %.4f rad/s\n",
                    pf.F.fn, pf.F.beta, pf.F.fd, pf.band, j["prefilter"]["bandwidth_3db"].get<double>());
    return 0;
}

int run_tune(const std::vector<std::string>& argv)
{
    Args args(argv, {"json", "exact", "prefilter"});
    if (args.positional().size() != 1) throw UsageError("expected one design kind: fopi, fopd or collocated");
    const std::string kind = args.positional()[0];
    if (kind == "fopi") return run_fo(FoKind::PI, args);
    if (kind == "fopd") return run_fo(FoKind::PD, args);
    if (kind == "collocated") return run_collocated(args);
    throw UsageError("unknown design kind '" + kind + "' (fopi, fopd, collocated)");
}

CommandRegistrar reg({"tune", "fractional controller tuning (seed 001 FO-PI/FO-PD, seed 002 collocated)",
                      "usage: fracdesign tune fopi --T T|--w0 W0 --lambda L [--K K] [--tau TAU]\n"
                      "                            --wc WC --phim PHIM --alpha A [--band-lo W --band-hi W] [--json]\n"
                      "       fracdesign tune fopd ... --mu MU ...\n\n"
                      "Plant G(s) = K e^{-tau s} / (1 + T s^lambda), 1 < lambda <= 2 (seed 001; --w0 sets\n"
                      "T = 1/w0^2 as in eq. (51)). Tunes C = Kp + Ki s^-alpha (fopi, eq. (15)-(16)) or\n"
                      "C^ = Kp + Kd s^mu with positive feedback delta = 1/K (fopd, eq. (31)-(34), erratum E3)\n"
                      "for crossover WC (rad/s) and phase margin PHIM (rad), normalised with\n"
                      "tau_n = tau/T^(1/lambda) (erratum E1). Reports the delay limit (17) (phi_m > 0), the\n"
                      "exact low-frequency condition (18) (PI), the RHFC (22)/(35) from the largest slope of\n"
                      "|L| beyond w_c, the PD stability condition K_p + delta > 0, the closed-loop verdict of\n"
                      "the argument principle on the loop with the delay (nyquist), and the feasible crossover\n"
                      "bands at PHIM (searched on w_cn in [0.01, 10] unless --band-lo/--band-hi, rad/s, are\n"
                      "given; edges refined to 1e-10 relative).\n"
                      "Exit status 1 when the specification is infeasible (reason and band on stderr).\n\n"
                      "       fracdesign tune collocated --phi0 DEG --wc0 W [--model PLANT.json] [--m2 M]\n"
                      "                                  [--alpha A] [--m2-lo M --m2-hi M] [--exact] [--prefilter]\n"
                      "                                  [--prefilter-start FN,FD,BETA] [--json]\n\n"
                      "Seed 002 collocated base-moment loop of a two-lumped-mass arm: the paper's robot, or the\n"
                      "arm of --model PLANT.json (a frac.model document of kind \"collocated\": m2_lb for the\n"
                      "printed robot, or link {L, EI}, masses {m1, x1, m2, m2_range}, moment_gain, inner_loop\n"
                      "{eps}, damping {rayleigh_a, rayleigh_b}; docs/model_format.md). --m2 sets the nominal tip\n"
                      "mass and --m2-lo/--m2-hi its range (lb for the robot, kg for a physical arm; they must\n"
                      "hold the nominal mass). alpha = 2 phi0/pi when a1 < w_c0 < z1 (Theorem 5 case 1) or\n"
                      "2 - 2 phi0/pi when w_c0 < a1 (case 2), Kc = 1/(w_c0^alpha |P(j w_c0)|) at the nominal\n"
                      "mass; --alpha overrides alpha (the paper rounds to 0.8); --exact keeps (1 + eps s)^2\n"
                      "instead of 1 + 2 eps s. Reports every crossover of the nominal loop, the two the case\n"
                      "names (case 1: in (a1, z1) and the highest above a2; case 2: in (0, a1) and in (z1, a2),\n"
                      "where PM = -phi0 means the crossing is phi0 above -1), the closed-loop verdict of the\n"
                      "argument principle, and the mode-1 crossover range over the tip masses, searched where\n"
                      "the case puts it. --prefilter optimises F = (1 + fn s^beta)/(1 + fd s) for the widest\n"
                      "+-0.3 dB band of |H| (notes 002 section 8; --prefilter-start adds a starting point).\n"
                      "A w_c0 not covered by Theorem 5 is reported infeasible with the ranges (exit 1); a bad\n"
                      "document field exits 1 naming the field, its value and the allowed range.\n",
                      run_tune});

}  // namespace
}  // namespace fracdesign
