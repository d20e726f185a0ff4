// gap_bench.hpp - `gap-bench`: the gap diagnosis of fracdesign scored against
// hidden truth (issues 10 and 17, docs/gap.md "gap-bench").
//
// The bench is its own layer on top of design_tools and hil (ARCHITECTURE.md):
// it links fracdesign_core for the diagnosis and the model APIs and hil_core for
// the rig; neither of those knows the bench.
//
// Each case of a plant family draws the family's plant parameters, an effect
// (none, one, sometimes two) and its size from a seeded generator, simulates
// the plant with that effect switched on (the seed 004 two-mass drive on the
// lockstep HIL rig; the other families with their own simulators,
// fracbench/families.hpp), hands the diagnosis only the nominal model document
// and the record, and scores its verdict against the truth: top-1 effect,
// confusion matrix, per-effect accuracy, relative error of the recovered
// parameters, shrink.
#pragma once
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fracdesign/gap/diagnosis.hpp"

namespace fracbench {

using fracdesign::gap::GapResult;
using fracdesign::gap::Signals;

// A diagnosis parameter the injected effect maps to, with its true value.
struct TruthParam {
    std::string name;  // the diagnosis's parameter name (param_names())
    double value;
};

struct TruthEffect {
    std::string effect;                                      // effect name (effect_name())
    std::vector<std::pair<std::string, std::string>> rig;    // rig / simulator keys set for the injection
    std::vector<TruthParam> params;                          // mapped parameters (empty: label only)
    // Injections of other labels that give this case's record (the family
    // simulated them: noise-free, every compared output within
    // kEquivalentNoiseMultiple of its noise std, visibility.hpp), e.g. a
    // drive delay and the same delay of every in-loop sensor. A verdict
    // naming one is right when it states this effect as its look-alike
    // (docs/gap.md "Look-alikes the bench proves"). Their rig keys are empty.
    std::vector<TruthEffect> equivalents;
};

struct BenchCase {
    int id = 0;
    std::string family = "twomass"; // the plant family (families.hpp)
    std::uint64_t seed = 0;         // the case's seed (bench seed and id); noise seeds derive from it
    std::vector<TruthEffect> truth; // empty: none
    std::string scenario;           // the plant, controller and injection, as "key = value" lines
    std::map<std::string, double> plant;  // the drawn plant parameters (families other than twomass)
};

// What the scoring needs from one case.
struct CaseOutcome {
    std::vector<TruthEffect> truth;                 // empty: none
    std::vector<std::string> verdict;               // verdict effects, in selection order (empty: none)
    std::vector<std::map<std::string, double>> verdict_params;  // per verdict effect: name -> value
    double shrink = 0.0;                            // verdict shrink
    std::vector<std::string> look_alikes;           // the verdict's confidence.look_alikes (effect names)
};

struct CaseScore {
    std::string truth_label;   // the effect name, "none", or "a+b" for two effects
    std::string top1;          // the verdict's first effect or "none"
    bool correct = false;      // top1 is the truth (one of the two, for two effects), or a proved equivalent stating it
    bool by_look_alike = false;  // correct through an equivalent whose look-alike the verdict states
    double param_error;        // mean relative error of the mapped parameters of the found effect (NaN: none)
    double shrink = 0.0;
};

// Per true label (one-effect and none cases): how often it came out first,
// and the median parameter error of those found.
struct LabelScore {
    int cases = 0, correct = 0;
    double median_param_error;
};

struct BenchScore {
    std::vector<std::string> labels;           // the 13 effect names and "none"
    std::vector<std::vector<int>> confusion;   // [truth][top-1], cases with one effect or none
    int cases = 0, correct = 0;
    int two_effect_cases = 0, two_effect_correct = 0;
    int look_alike_correct = 0;                // correct cases that named a proved equivalent (CaseScore::by_look_alike)
    double accuracy = 0.0;                     // correct / cases (all cases)
    double median_param_error;                 // over cases with a found effect that has mapped parameters
    int param_cases = 0;
    double median_shrink_found;                // over cases whose (non-none) true effect was found
    int found_cases = 0;
    std::map<std::string, LabelScore> per_label;  // one-effect and none cases, by true label
    std::vector<CaseScore> per_case;
};

// The labels in matrix order: all_effects() names, then "none".
std::vector<std::string> bench_labels();
// Scores the outcomes (pure: the unit tests feed it synthetic answers).
BenchScore score_bench(const std::vector<CaseOutcome>& cases);
// The "score", "confusion", "per_effect" and "goals" sections of the bench
// document for S (run_bench's, and a sharded bench's: python/src/bind_bench.cpp).
nlohmann::json score_json(const BenchScore& S);
// The scoring's view of one case entry of the bench document ("truth",
// "verdict", "shrink"; null numbers read as NaN).
CaseOutcome outcome_from_json(const nlohmann::json& case_entry);

struct BenchOptions {
    std::string family = "twomass";  // families.hpp: family_names()
    int cases = 28;
    std::uint64_t seed = 1;
    double duration = 2.4;      // simulated seconds per case (twomass; the other families scale their own)
    double gyro_noise = 0.005;  // twomass: IMU rate noise std per sample [rad/s] in every case
    double two_effect_prob = 0.15;
    int only_case = -1;         // >= 0: run (replay) that case alone
    std::string out_dir;        // non-empty: write each case's files there
    int max_iterations = 30;    // Ceres iterations per start
};

// The twomass case draw (deterministic in opt.seed and id). `cmd_peak` is the
// peak torque command of the effect-free run (saturation limits are drawn as
// a fraction of it).
BenchCase draw_case(const BenchOptions& opt, int id, double cmd_peak);

struct CaseRun {
    BenchCase draw;
    Signals data;
    nlohmann::json nominal;     // the nominal model document the diagnosis gets
    GapResult result;
    CaseOutcome outcome;
    std::map<std::string, std::string> files;  // more case files a family writes with --out (name -> bytes)
};

// Runs the rig for the twomass case `c` and diagnoses the record.
CaseRun run_case(const BenchOptions& opt, const BenchCase& c);
// The nominal model document of the twomass family (two-mass plant, drive
// delay, the bench's PD loop) at the rig's cycle.
nlohmann::json bench_nominal_doc();
// Peak |torque command| of the effect-free twomass run.
double bench_cmd_peak(const BenchOptions& opt);

// Diagnoses `data` against `nominal` (outputs compared: `outputs`) and fills
// the run's result and outcome; the step every family shares.
void diagnose_case(const BenchOptions& opt, const std::vector<std::string>& outputs, CaseRun& run);

// Runs every case of opt.family (or opt.only_case), writes the case files
// when opt.out_dir is set, and returns the whole bench as JSON (cases with
// their draws, score, confusion matrix, per-effect accuracy, goals).
// `progress` gets one line per case.
nlohmann::json run_bench(const BenchOptions& opt, std::ostream* progress);

// A value as the scenario text writes it (%.17g: reads back exactly).
std::string format_value(double x);
// The "key = value" line of a scenario text.
std::string scenario_line(const std::string& key, double value);

}  // namespace fracbench
