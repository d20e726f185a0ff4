// cmd_ident.cpp - `fracdesign ident frf|process|servo`: identification from
// measured data (frequency domain: the seed 000 antenna; time domain: the
// seed 001 fractional process and servo axes with friction, IDIM-LS and
// output error). Human summary on stdout, --json for a machine-readable
// result, errors on stderr with a non-zero exit; a fit that did not converge
// prints the Ceres report on stderr and exits with status 3.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/ident/antenna_fit.hpp"
#include "fracdesign/ident/emps.hpp"
#include "fracdesign/ident/progress.hpp"
#include "fracdesign/ident/time_domain.hpp"
#include "fracdesign/io/frf_csv.hpp"
#include "fracdesign/io/signal_csv.hpp"
#include "fracdesign/welch.hpp"

namespace fracdesign {
namespace {

using nlohmann::json;

constexpr int kNotConverged = 3;

bool show_progress(const Args& a) { return a.has("progress") || (!a.has("no-progress") && ident::stderr_is_terminal()); }

void report_not_converged(const std::string& what, const std::string& full_report)
{
    std::cerr << "fracdesign ident: " << what << " did NOT converge; Ceres report:\n" << full_report << "\n";
}

// ---------------------------------------------------------------- frf
// FRF from time data: Welch H1 estimate (welch.hpp) of --out over --in, with
// MATLAB's segmentation of --segments Hamming windows overlapping by
// --overlap (seed 000 Sec. 5.1: 8 segments, 0.15, nfft 160000 at 1 kHz).
io::FrfTable welch_frf(const Args& a)
{
    const io::SignalTable t = io::read_signal_csv(a.str("time"));
    const auto& x = t.column(a.str("in", "theta_m"));
    const auto& y = t.column(a.str("out", "torque"));
    const long segments = a.integer("segments", 8), nfft = a.integer("nfft", 0);
    if (segments < 1) throw UsageError("--segments must be >= 1");
    if (nfft < 0) throw UsageError("--nfft must be >= 0");
    WelchOptions wo = welch_matlab_segments(x.size(), int(segments), a.num("overlap", 0.15), int(nfft), 1.0 / t.dt);
    if (wo.nfft < wo.nperseg) wo.nfft = wo.nperseg;
    const WelchResult r = welch_tfestimate(x, y, wo);
    io::FrfTable f;
    for (std::size_t k = 1; k < r.f.size(); ++k) {  // DC has no place in a 1/w weighting
        f.w.push_back(2.0 * M_PI * r.f[k]);
        f.G.push_back(r.Txy[k]);
    }
    return f;
}

int run_frf(const Args& a)
{
    a.check_known({"json", "progress", "no-progress", "frf", "time", "in", "out", "segments", "overlap", "nfft",
                   "structure", "weighting", "starts", "seed", "wmin", "wmax", "max-iter"});
    if (a.has("frf") == a.has("time")) throw UsageError("give exactly one of --frf FILE or --time FILE");
    std::vector<AntennaStructure> structures;
    const std::string s = a.str("structure", "all");
    if (s == "all")
        for (int i = 1; i <= 6; ++i) structures.push_back(AntennaStructure(i));
    else
        structures.push_back(ident::parse_structure(s));
    std::vector<ident::FrfWeighting> weightings;
    const std::string w = a.str("weighting", "both");
    if (w == "const" || w == "both") weightings.push_back(ident::FrfWeighting::Constant);
    if (w == "1/w" || w == "both") weightings.push_back(ident::FrfWeighting::InverseOmega);
    if (weightings.empty()) throw UsageError("--weighting must be const, 1/w or both");
    const long starts = a.integer("starts", 8), seed = a.integer("seed", 1), iters = a.integer("max-iter", 200);
    if (starts < 1) throw UsageError("--starts must be >= 1");
    if (seed < 0) throw UsageError("--seed must be >= 0");
    const io::FrfTable t = a.has("frf") ? io::read_frf_csv(a.str("frf")) : welch_frf(a);
    const double wmin = a.num("wmin", 0.0), wmax = a.num("wmax", INFINITY);
    ident::Frf data;
    for (std::size_t k = 0; k < t.w.size(); ++k)
        if (t.w[k] >= wmin && t.w[k] <= wmax) {
            data.w.push_back(t.w[k]);
            data.G.push_back(t.G[k]);
        }
    const int total = int(structures.size() * weightings.size() * std::size_t(starts));
    ident::Progress prog(show_progress(a), "ident frf", total);
    json out = {{"schema", "frac.ident.frf"}, {"version", 1}, {"points", data.w.size()}, {"fits", json::array()}};
    int done = 0, failed = 0;
    if (!a.has("json"))
        std::cout << "antenna FRF fit (seed 000 eq. 25), " << data.w.size() << " points, " << starts
                  << " starts, seed " << seed << "\n"
                  << "type weights  parameters (+- std)                                     J           MSE         WMSE\n";
    for (AntennaStructure st : structures)
        for (ident::FrfWeighting wt : weightings) {
            ident::AntennaFitOptions o;
            o.weighting = wt;
            o.starts = int(starts);
            o.seed = unsigned(seed);
            o.max_iterations = int(iters);
            const std::string label = std::string(ident::structure_name(st)) + " " + ident::weighting_name(wt);
            const auto r = ident::fit_antenna(data, st, o, [&](int i, double J) {
                char m[96];
                std::snprintf(m, sizeof m, "%s start %d J = %.4g", label.c_str(), i + 1, J);
                prog.update(++done, m);
            });
            if (!r.converged) {
                ++failed;
                report_not_converged("fit " + label, r.full_report);
            }
            json p;
            std::string line;
            for (std::size_t i = 0; i < r.params.size(); ++i) {
                p[r.names[i]] = r.params[i];
                char buf[80];
                if (i < r.std_dev.size()) {
                    p[r.names[i] + "_std"] = r.std_dev[i];
                    std::snprintf(buf, sizeof buf, "%s=%.6g(%.2g) ", r.names[i].c_str(), r.params[i], r.std_dev[i]);
                } else {
                    std::snprintf(buf, sizeof buf, "%s=%.6g ", r.names[i].c_str(), r.params[i]);
                }
                line += buf;
            }
            out["fits"].push_back({{"structure", ident::structure_name(st)}, {"weighting", ident::weighting_name(wt)},
                                   {"params", p}, {"J", r.cost}, {"mse", r.mse}, {"wmse", r.wmse},
                                   {"converged", r.converged}, {"best_start", r.best_start},
                                   {"start_costs", r.start_costs}, {"summary", r.summary}});
            if (!a.has("json")) {
                char buf[256];
                std::snprintf(buf, sizeof buf, "%-4s %-6s  %-55s %-11.5g %-11.5g %-11.5g%s\n", ident::structure_name(st),
                              ident::weighting_name(wt), line.c_str(), r.cost, r.mse, r.wmse,
                              r.converged ? "" : "  NOT CONVERGED");
                std::cout << buf;
            }
        }
    if (a.has("json")) std::cout << out.dump(2) << "\n";
    return failed ? kNotConverged : 0;
}

// ---------------------------------------------------------------- process
int run_process(const Args& a)
{
    a.check_known({"json", "progress", "no-progress", "csv", "in", "out", "init", "max-iter"});
    io::SignalCsvOptions co;
    co.min_rows = 20;
    const io::SignalTable t = io::read_signal_csv(a.str("csv"), co);
    const auto& u = t.column(a.str("in", "u"));
    const auto& y = t.column(a.str("out", "y"));
    ident::ProcessFitOptions o;
    if (a.has("init")) {
        const auto v = a.nums("init");
        if (v.size() != 4) throw UsageError("--init needs K,T,lambda,tau");
        for (int i = 0; i < 4; ++i) o.initial[std::size_t(i)] = v[std::size_t(i)];
    }
    o.max_iterations = int(a.integer("max-iter", 100));
    ident::Progress prog(show_progress(a), "ident process: iteration", o.max_iterations);
    o.on_iteration = [&prog](int it, double J) {
        char m[64];
        std::snprintf(m, sizeof m, "sum of squares %.6g", J);
        prog.update(it, m);
    };
    const auto r = ident::fit_fo_process(u, y, t.dt, o);
    if (!r.converged) report_not_converged("process fit", r.full_report);
    if (a.has("json")) {
        json j = {{"schema", "frac.ident.process"}, {"version", 1},
                  {"model", "K exp(-tau s)/(T s^lambda + 1)"},
                  {"K", r.process.K}, {"T", r.process.T}, {"lambda", r.process.lambda}, {"tau", r.process.tau},
                  {"std", r.std_dev}, {"rms_error", r.rms_error}, {"fit_percent", r.fit_percent},
                  {"converged", r.converged}, {"summary", r.summary}};
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("fractional process K e^{-tau s}/(T s^lambda + 1) (seed 001 eq. 1), %zu samples, dt %.6g s\n"
                    "  K      = %.8g (+- %.2g)\n  T      = %.8g s^lambda (+- %.2g)\n"
                    "  lambda = %.8g (+- %.2g)\n  tau    = %.8g s (+- %.2g)\n"
                    "  rms error %.4g, fit %.3f %%, %s\n",
                    t.size(), t.dt, r.process.K, r.std_dev[0], r.process.T, r.std_dev[1], r.process.lambda,
                    r.std_dev[2], r.process.tau, r.std_dev[3], r.rms_error, r.fit_percent,
                    r.converged ? "converged" : "NOT CONVERGED");
    }
    return r.converged ? 0 : kNotConverged;
}

// ---------------------------------------------------------------- servo
int run_servo(const Args& a)
{
    a.check_known({"json", "progress", "no-progress", "mat", "csv", "q", "force", "closed-loop", "qr", "u", "u-add",
                   "kp", "kv", "gtau", "u-max", "delay", "method", "stribeck", "init", "skip", "max-iter",
                   "substeps"});
    ident::ServoRecord rec;
    if (a.has("mat") == a.has("csv")) throw UsageError("give exactly one of --mat FILE or --csv FILE");
    if (a.has("mat")) {
        const ident::EmpsRecord e = ident::load_emps_mat(a.str("mat"));
        rec.dt = e.dt;
        rec.closed_loop = true;
        rec.q = e.qm;
        rec.qr = e.qg;
        rec.u = e.vir;
        rec.u_add = e.pulses;
        rec.controller = e.controller;
    } else {
        const io::SignalTable t = io::read_signal_csv(a.str("csv"));
        rec.dt = t.dt;
        rec.q = t.column(a.str("q"));
        rec.closed_loop = a.has("closed-loop");
        if (rec.closed_loop) {
            rec.qr = t.column(a.str("qr"));
            rec.u = t.column(a.str("u"));
            if (a.has("u-add")) rec.u_add = t.column(a.str("u-add"));
            rec.controller.kp = a.num("kp", NAN);
            rec.controller.kv = a.num("kv", NAN);
            if (!a.has("kp") || !a.has("kv")) throw UsageError("--closed-loop needs --kp and --kv");
        } else {
            rec.force = t.column(a.str("force"));
        }
        rec.controller.gtau = a.num("gtau", 1.0);
    }
    rec.controller.u_max = a.num("u-max", rec.controller.u_max);
    rec.controller.delay = int(a.integer("delay", rec.controller.delay));
    const std::string method = a.str("method", "both");
    if (method != "idim" && method != "oe" && method != "both") throw UsageError("--method must be idim, oe or both");
    // Force for IDIM-LS: the recorded command (which includes any added
    // signal, see servo.hpp) through the drive gain in closed loop, or the
    // recorded force in open loop.
    std::vector<double> F = rec.force;
    if (rec.closed_loop) {
        F.resize(rec.u.size());
        for (std::size_t k = 0; k < F.size(); ++k) F[k] = rec.controller.gtau * rec.u[k];
    }
    json out = {{"schema", "frac.ident.servo"}, {"version", 1}, {"samples", rec.q.size()}, {"dt", rec.dt},
                {"closed_loop", rec.closed_loop}, {"param_names", {"M", "Fv", "Fc", "offset", "Fs", "vs"}}};
    ident::Progress prog(show_progress(a), "ident servo", method == "both" ? 2 : 1);
    int step = 0, rc = 0;
    ident::ServoFitOptions o;
    if (method != "oe") {
        const ident::IdimResult id = ident::idim_ls_servo(rec.q, F, rec.dt);
        prog.update(++step, "IDIM-LS done");
        out["idim"] = {{"theta", {id.theta(0), id.theta(1), id.theta(2), id.theta(3)}},
                       {"std", {id.std_dev(0), id.std_dev(1), id.std_dev(2), id.std_dev(3)}},
                       {"cond", id.cond}, {"force_rel_error_percent", id.rel_error}, {"rows", id.rows}};
        if (!a.has("json"))
            std::printf("IDIM-LS (EMPS description sec. 3.4), %zu rows after decimation, cond %.2f\n"
                        "  M = %.6g (+- %.2g) kg, Fv = %.6g (+- %.2g) N s/m, Fc = %.6g (+- %.2g) N, offset = %.6g "
                        "(+- %.2g) N\n  force relative error %.3f %%\n",
                        id.rows, id.cond, id.theta(0), id.std_dev(0), id.theta(1), id.std_dev(1), id.theta(2),
                        id.std_dev(2), id.theta(3), id.std_dev(3), id.rel_error);
        for (int i = 0; i < 4; ++i) o.initial[std::size_t(i)] = id.theta(i);
        if (!(o.initial[0] > 0.0)) throw std::runtime_error("IDIM-LS gives a non-positive mass: check the units of q and F");
        o.initial[1] = std::max(o.initial[1], 0.0);
        o.initial[2] = std::max(o.initial[2], 0.0);
    }
    if (method != "idim") {
        if (a.has("init")) {
            const auto v = a.nums("init");
            if (v.size() != 6) throw UsageError("--init needs M,Fv,Fc,offset,Fs,vs");
            for (std::size_t i = 0; i < 6; ++i) o.initial[i] = v[i];
        } else if (method == "oe") {
            throw UsageError("--method oe needs --init M,Fv,Fc,offset,Fs,vs (or use --method both)");
        }
        o.stribeck = a.has("stribeck");
        if (o.stribeck && !a.has("init")) {
            o.initial[4] = 0.1 * o.initial[2];
            o.initial[5] = 0.01;
        }
        o.skip = std::size_t(a.integer("skip", 50));
        o.max_iterations = int(a.integer("max-iter", 100));
        o.substeps = int(a.integer("substeps", 4));
        o.on_iteration = [&prog, step](int it, double J) {  // shown as the step in progress
            char m[64];
            std::snprintf(m, sizeof m, "output error: iteration %d, sum of squares %.6g", it, J);
            prog.update(step + 1, m);
        };
        const ident::ServoFitResult r = ident::fit_servo(rec, o);
        prog.update(++step, "output-error fit done");
        if (!r.converged) {
            report_not_converged("servo output-error fit", r.full_report);
            rc = kNotConverged;
        }
        out["oe"] = {{"theta", r.theta}, {"std", r.std_dev}, {"q_error_percent", r.q_error_percent},
                     {"u_error_percent", r.u_error_percent}, {"converged", r.converged}, {"summary", r.summary}};
        if (!a.has("json")) {
            std::printf("output error (%s loop, simulation in the cost), %s\n", rec.closed_loop ? "closed" : "open",
                        r.converged ? "converged" : "NOT CONVERGED");
            for (int i = 0; i < ident::kServoParams; ++i)
                std::printf("  %-6s = %.6g (+- %.2g)\n", ident::kServoParamNames[i], r.theta[std::size_t(i)],
                            r.std_dev[std::size_t(i)]);
            std::printf("  position error %.5f %%", r.q_error_percent);
            if (r.u_error_percent > 0.0) std::printf(", control error %.3f %%", r.u_error_percent);
            std::printf("\n");
        }
    }
    if (a.has("json")) std::cout << out.dump(2) << "\n";
    return rc;
}

int run_ident(const std::vector<std::string>& argv)
{
    Args a(argv, {"json", "progress", "no-progress", "closed-loop", "stribeck"});
    if (a.positional().size() != 1) throw UsageError("expected one mode: frf, process or servo (see --help)");
    const std::string mode = a.positional()[0];
    if (mode == "frf") return run_frf(a);
    if (mode == "process") return run_process(a);
    if (mode == "servo") return run_servo(a);
    throw UsageError("unknown mode '" + mode + "' (expected frf, process or servo)");
}

CommandRegistrar reg(
    {"ident", "identify model parameters from data (antenna FRF, fractional process, servo friction)",
     "usage: fracdesign ident frf (--frf FILE.csv | --time FILE.csv [--in theta_m] [--out torque]\n"
     "                            [--segments 8] [--overlap 0.15] [--nfft N])\n"
     "                            [--structure I..VI|all] [--weighting const|1/w|both]\n"
     "                            [--starts 8] [--seed 1] [--wmin W] [--wmax W] [--max-iter 200]\n"
     "       fracdesign ident process --csv FILE.csv [--in u] [--out y] [--init K,T,lambda,tau]\n"
     "       fracdesign ident servo (--mat EMPS.mat | --csv FILE.csv --q COL (--force COL |\n"
     "                              --closed-loop --qr COL --u COL --kp KP --kv KV [--u-add COL]))\n"
     "                              [--gtau G] [--u-max 10] [--delay 1] [--method idim|oe|both]\n"
     "                              [--stribeck] [--init M,Fv,Fc,offset,Fs,vs] [--skip 50]\n"
     "       common: [--json] [--progress | --no-progress]\n\n"
     "frf: fits the damping (zeta, alpha, gamma, lambda) of the seed 000 antenna, eq. (25), to an FRF\n"
     "  CSV (columns f_hz or w_rad_s, re, im), or to the Welch H1 estimate from a signal CSV (t in s),\n"
     "  with Ceres: residuals sqrt(W_p) (Re, Im)(G_exp - G), analytic derivatives,\n"
     "  weights 1/N or 1/w normalised (eq. 27), bounds, multi-start from a seeded generator, covariance.\n"
     "process: fits K, T, lambda, tau of K e^{-tau s}/(T s^lambda + 1) (seed 001) by output error,\n"
     "  simulating the Grunwald-Letnikov scheme inside the cost; signal CSV with t in s.\n"
     "servo: IDIM-LS (filtered derivatives, parallel decimation, linear LS for M, Fv, Fc, offset) and/or\n"
     "  output error with the simulation in the cost (open loop from the force, or closed loop with the\n"
     "  known EMPS-type P/PD controller, one-sample delay, saturation); --stribeck adds Fs, vs.\n"
     "  --method both (default) starts the output-error fit from the IDIM-LS estimate.\n\n"
     "Same --seed, same result. Progress goes to stderr when it is a terminal or with --progress.\n"
     "Exit status: 0 ok, 1 error, 2 usage, 3 a fit did not converge (Ceres report on stderr).\n",
     run_ident});

}  // namespace
}  // namespace fracdesign
