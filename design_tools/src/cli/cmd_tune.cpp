// cmd_tune.cpp - `fracdesign tune fopi|fopd ...`: seed 001 closed-form
// FO-PI^alpha / FO-PD^mu tuning with the feasibility tests and bands.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/design/fopi_fopd.hpp"

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

int run_tune(const std::vector<std::string>& argv)
{
    Args args(argv, {"json"});
    if (args.positional().size() != 1) throw UsageError("expected one design kind: fopi, fopd or collocated");
    const std::string kind = args.positional()[0];
    if (kind == "fopi") return run_fo(FoKind::PI, args);
    if (kind == "fopd") return run_fo(FoKind::PD, args);
    throw UsageError("unknown design kind '" + kind + "' (fopi, fopd)");
}

CommandRegistrar reg({"tune", "closed-form fractional controller tuning (seed 001 FO-PI/FO-PD)",
                      "usage: fracdesign tune fopi --T T|--w0 W0 --lambda L [--K K] [--tau TAU]\n"
                      "                            --wc WC --phim PHIM --alpha A [--band-lo W --band-hi W] [--json]\n"
                      "       fracdesign tune fopd ... --mu MU ...\n\n"
                      "Plant G(s) = K e^{-tau s} / (1 + T s^lambda), 1 < lambda <= 2 (seed 001; --w0 sets\n"
                      "T = 1/w0^2 as in eq. (51)). Tunes C = Kp + Ki s^-alpha (fopi, eq. (15)-(16)) or\n"
                      "C^ = Kp + Kd s^mu with positive feedback delta = 1/K (fopd, eq. (31)-(34), erratum E3)\n"
                      "for crossover WC (rad/s) and phase margin PHIM (rad), normalised with\n"
                      "tau_n = tau/T^(1/lambda) (erratum E1). Reports the delay limit (17), the exact\n"
                      "low-frequency condition (18) (PI), the numerical RHFC (22)/(35), the PD stability\n"
                      "condition K_p + delta > 0, and the feasible crossover band at PHIM (searched on\n"
                      "w_cn in [0.01, 10] unless --band-lo/--band-hi, rad/s, are given).\n"
                      "Exit status 1 when the specification is infeasible (reason and band on stderr).\n",
                      run_tune});

}  // namespace
}  // namespace fracdesign
