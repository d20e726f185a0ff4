// main.cpp - the `gap-bench` executable: the gap diagnosis of fracdesign
// scored against hidden effects (issues 10 and 17; logic in gap_bench.cpp and
// the family files). Options are parsed with fracdesign's Args
// (design_tools/src/cli/args.cpp, compiled in), errors follow fracdesign's
// rules: one line on stderr, exit 2 for usage, 1 for a failed run.
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>

#include "fracbench/families.hpp"
#include "fracbench/gap_bench.hpp"
#include "fracdesign/cli.hpp"

namespace {

using fracdesign::Args;
using fracdesign::UsageError;

int run_gap_bench(const std::vector<std::string>& argv)
{
    Args args(argv, {"json", "require-goals"});
    args.check_known({"family", "cases", "seed", "json", "out", "replay", "duration", "noise", "require-goals", "require-accuracy"});
    fracbench::BenchOptions opt;
    opt.family = args.str("family", opt.family);
    try {
        fracbench::family(opt.family);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string(e.what()).substr(std::string("gap-bench: ").size()));
    }
    const long cases = args.integer("cases", opt.cases), seed = args.integer("seed", long(opt.seed));
    const long replay = args.integer("replay", -1);
    if (cases < 1 || cases > 100000) throw UsageError("--cases must be in 1..100000");
    if (seed < 0) throw UsageError("--seed must be >= 0");
    if (args.has("replay") && (replay < 0 || replay >= cases))
        throw UsageError("--replay must name a case id in 0..cases-1 (ids are printed in the table)");
    opt.cases = int(cases);
    opt.seed = std::uint64_t(seed);
    opt.only_case = int(replay);
    opt.duration = args.num("duration", opt.duration);
    if (!(opt.duration >= 0.5 && opt.duration <= 60)) throw UsageError("--duration must be in [0.5, 60] s");
    opt.gyro_noise = args.num("noise", opt.gyro_noise);
    if (!(opt.gyro_noise >= 0)) throw UsageError("--noise must be >= 0");
    opt.out_dir = args.str("out", "");
    const double require_accuracy = args.num("require-accuracy", 0.0);
    if (!(require_accuracy >= 0 && require_accuracy <= 1)) throw UsageError("--require-accuracy must be a fraction in [0, 1]");
    const bool json = args.has("json");
    if (!json)
        std::cout << "gap-bench: family " << opt.family << ", " << (replay >= 0 ? "replaying case " + std::to_string(replay) : std::to_string(cases) + " cases")
                  << ", seed " << seed
                  << (opt.family == "twomass" ? ", " + std::to_string(opt.duration) + " s each, gyro noise " + std::to_string(opt.gyro_noise) + " rad/s" : std::string())
                  << "\n"
                  << "  case  truth                                  -> top-1 verdict\n";
    const nlohmann::json j = fracbench::run_bench(opt, json ? nullptr : &std::cout);
    // --require-goals: exit 1 when a goal of issues 10/17 is missed (for CI).
    const auto& g = j["goals"];
    const bool all_met = g["accuracy_met"].get<bool>() && g["param_error_met"].get<bool>() && g["shrink_met"].get<bool>();
    // --require-accuracy A: exit 1 when top-1 is below A (a family's measured floor, docs/gap.md).
    const bool accuracy_met = j["score"]["accuracy"].is_number() && j["score"]["accuracy"].get<double>() >= require_accuracy;
    const int status = (args.has("require-goals") && !all_met) || (args.has("require-accuracy") && !accuracy_met) ? 1 : 0;
    if (json) {
        std::cout << j.dump(2) << "\n";
        return status;
    }
    const auto& s = j["score"];
    auto pct = [](const nlohmann::json& x) {
        char b[32];
        if (x.is_null()) return std::string("-");
        std::snprintf(b, sizeof b, "%.1f %%", 100 * x.get<double>());
        return std::string(b);
    };
    std::cout << "top-1 accuracy " << pct(s["accuracy"]) << " (" << s["correct"] << "/" << s["cases"]
              << "; two-effect cases " << s["two_effect_correct"] << "/" << s["two_effect_cases"]
              << "; named a proved equivalent stating the truth as look-alike (ok=) " << s["look_alike_correct"] << ")\n"
              << "median parameter error " << pct(s["median_param_error"]) << " over " << s["param_cases"]
              << " found effects with a mapped parameter\n"
              << "median shrink when found " << pct(s["median_shrink_found"]) << " over " << s["found_cases"] << " cases\n";
    const auto& labels = j["confusion"]["labels"];
    const auto& M = j["confusion"]["rows_truth_cols_top1"];
    std::cout << "confusion (rows truth, columns top-1; one-effect and none cases):\n";
    std::cout << "  " << std::string(20, ' ');
    for (size_t c = 0; c < labels.size(); ++c) std::printf("%3zu", c);
    std::cout << std::flush;
    std::printf("\n");
    for (size_t r = 0; r < labels.size(); ++r) {
        std::printf("  %2zu %-17s", r, labels[r].get<std::string>().c_str());
        for (size_t c = 0; c < labels.size(); ++c) {
            const int n = M[r][c].get<int>();
            if (n) std::printf("%3d", n);
            else std::printf("  .");
        }
        std::printf("\n");
    }
    std::fflush(stdout);
    std::cout << "per effect (one-effect and none cases): cases, top-1 correct, median parameter error\n";
    for (const auto& kv : j["per_effect"].items()) {
        const auto& e = kv.value();
        std::printf("  %-20s %3d  %3d  %6s  %s\n", kv.key().c_str(), e["cases"].get<int>(), e["correct"].get<int>(),
                    pct(e["accuracy"]).c_str(), pct(e["median_param_error"]).c_str());
    }
    std::fflush(stdout);
    std::cout << "goals: accuracy >= 90 % " << (g["accuracy_met"].get<bool>() ? "met" : "NOT met")
              << "; median parameter error <= 10 % " << (g["param_error_met"].get<bool>() ? "met" : "NOT met")
              << "; median shrink when found >= 80 % " << (g["shrink_met"].get<bool>() ? "met" : "NOT met") << "\n";
    if (args.has("require-accuracy"))
        std::cout << "required top-1 accuracy >= " << pct(nlohmann::json(require_accuracy)) << ": " << (accuracy_met ? "met" : "NOT met") << "\n";
    if (!opt.out_dir.empty()) std::cout << "case files (scenario, signals, nominal, truth, result): " << opt.out_dir << "/case_NNN\n";
    return status;
}

const char* const kHelp =
    "usage: gap-bench [--family twomass|servo|foprocess|arm] [--cases N] [--seed S] [--json]\n"
    "                 [--out DIR] [--replay CASE_ID] [--duration 2.4] [--noise 0.005]\n"
    "                 [--require-goals] [--require-accuracy A]\n\n"
    "For each case of the family draws the plant's parameters (servo, foprocess, arm), an\n"
    "effect (each of the family's labels equally often, in shuffled rounds; sometimes\n"
    "a second effect) and its size, and simulates the record with it switched on:\n"
    "  twomass    seed 004 two-mass drive on the lockstep HIL rig (in-process), drive\n"
    "             with 4-cycle delay, IMU, the bench's PD loop (--duration, --noise)\n"
    "  servo      rigid servo axis, PD with filtered difference, +-10 V clip\n"
    "  foprocess  y = K e^{-tau s} / (1 + T s^lambda) u in open loop, with delay\n"
    "  arm        a drawn arm document (frac.arm, around docs/examples/arm_b) on the\n"
    "             HIL rig, ArmCtrl from the document, its open-loop gap nominal\n"
    "gives fracdesign's gap diagnosis only the nominal model document and the record,\n"
    "and scores the verdict: top-1 accuracy, per-effect accuracy, confusion matrix,\n"
    "relative error of the recovered parameters, shrink.\n"
    "A case depends only on --family, --seed, its id, --duration and --noise:\n"
    "--replay CASE_ID reruns one case of the same bench (same result). --out DIR\n"
    "writes per case DIR/case_NNN/{scenario.txt, signals.csv, nominal.json,\n"
    "truth.json, result.json}, so `fracdesign gap --model nominal.json --data\n"
    "signals.csv` repeats the diagnosis. Defaults: family twomass, 28 cases, seed 1.\n"
    "--json prints everything (draws, scenario text, verdicts, score, confusion\n"
    "matrix, per-effect accuracy). --require-goals exits 1 when a goal is missed\n"
    "(accuracy >= 90 %, median parameter error <= 10 %, median shrink >= 80 %);\n"
    "--require-accuracy A exits 1 when the top-1 accuracy is below A (0..1).\n"
    "See docs/gap.md.\n";

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    for (const auto& a : args)
        if (a == "--help" || a == "-h") {
            std::cout << kHelp;
            return 0;
        }
    try {
        return run_gap_bench(args);
    } catch (const UsageError& e) {
        std::cerr << "gap-bench: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "gap-bench: error: " << e.what() << "\n";
        return 1;
    }
}
