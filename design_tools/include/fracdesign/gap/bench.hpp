// bench.hpp - `fracdesign gap-bench`: the gap diagnosis scored against hidden
// truth on the HIL rig (issue 10, docs/gap.md "gap-bench").
//
// Each case draws an effect (none, one, sometimes two) and its size from a
// seeded generator, runs the lockstep rig (hil/rig.h, linked in-process) with
// that effect switched on, hands the diagnosis only the nominal model and the
// record, and scores its verdict against the truth: top-1 effect, confusion
// matrix, relative error of the recovered parameters, shrink.
#pragma once
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fracdesign/gap/diagnosis.hpp"

namespace fracdesign {
namespace gap {

// A diagnosis parameter the injected effect maps to, with its true value.
struct TruthParam {
    std::string name;  // the diagnosis's parameter name (param_names())
    double value;
};

struct TruthEffect {
    std::string effect;                                      // effect name (effect_name())
    std::vector<std::pair<std::string, std::string>> rig;    // scenario keys set on the rig
    std::vector<TruthParam> params;                          // mapped parameters (empty: label only)
};

struct BenchCase {
    int id = 0;
    std::uint64_t seed = 0;         // the case's seed (bench seed and id); rig noise seeds derive from it
    std::vector<TruthEffect> truth; // empty: none
    std::string scenario;           // the rig configuration, scenario-file text (hil_rig_config_write)
};

// What the scoring needs from one case.
struct CaseOutcome {
    std::vector<TruthEffect> truth;                 // empty: none
    std::vector<std::string> verdict;               // verdict effects, in selection order (empty: none)
    std::vector<std::map<std::string, double>> verdict_params;  // per verdict effect: name -> value
    double shrink = 0.0;                            // verdict shrink
};

struct CaseScore {
    std::string truth_label;   // the effect name, "none", or "a+b" for two effects
    std::string top1;          // the verdict's first effect or "none"
    bool correct = false;      // top1 is the truth (one of the two, for two effects)
    double param_error;        // mean relative error of the mapped parameters of the found effect (NaN: none)
    double shrink = 0.0;
};

struct BenchScore {
    std::vector<std::string> labels;           // the 13 effect names and "none"
    std::vector<std::vector<int>> confusion;   // [truth][top-1], cases with one effect or none
    int cases = 0, correct = 0;
    int two_effect_cases = 0, two_effect_correct = 0;
    double accuracy = 0.0;                     // correct / cases (all cases)
    double median_param_error;                 // over cases with a found effect that has mapped parameters
    int param_cases = 0;
    double median_shrink_found;                // over cases whose (non-none) true effect was found
    int found_cases = 0;
    std::vector<CaseScore> per_case;
};

// The labels in matrix order: all_effects() names, then "none".
std::vector<std::string> bench_labels();
// Scores the outcomes (pure: the unit tests feed it synthetic answers).
BenchScore score_bench(const std::vector<CaseOutcome>& cases);

struct BenchOptions {
    int cases = 28;
    std::uint64_t seed = 1;
    double duration = 2.4;      // simulated seconds per case
    double gyro_noise = 0.005;  // IMU rate noise std per sample [rad/s] in every case
    double two_effect_prob = 0.15;
    int only_case = -1;         // >= 0: run (replay) that case alone
    std::string out_dir;        // non-empty: write each case's files there
    int max_iterations = 30;    // Ceres iterations per start
};

// The case draw (deterministic in opt.seed and id). `cmd_peak` is the peak
// torque command of the effect-free run (saturation limits are drawn as a
// fraction of it).
BenchCase draw_case(const BenchOptions& opt, int id, double cmd_peak);

struct CaseRun {
    BenchCase draw;
    Signals data;
    nlohmann::json nominal;     // the nominal model document the diagnosis gets
    GapResult result;
    CaseOutcome outcome;
};

// Runs the rig for `c` and diagnoses the record.
CaseRun run_case(const BenchOptions& opt, const BenchCase& c);
// The nominal model document of the bench (two-mass plant, drive delay,
// the bench's PD loop) at the rig's cycle.
nlohmann::json bench_nominal_doc();
// Peak |torque command| of the effect-free run.
double bench_cmd_peak(const BenchOptions& opt);

// Runs every case (or opt.only_case), writes the case files when
// opt.out_dir is set, and returns the whole bench as JSON (cases with their
// draws, score, confusion matrix, goals). `progress` gets one line per case.
nlohmann::json run_bench(const BenchOptions& opt, std::ostream* progress);

}  // namespace gap
}  // namespace fracdesign
