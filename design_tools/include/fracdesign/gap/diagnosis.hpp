// diagnosis.hpp - the sim-to-real gap diagnosis: where the gap lies, which
// unmodelled effect causes it, how far it shrinks (issue 10, docs/gap.md).
//
//  replay the nominal model on the recorded inputs (open or closed loop)
//  -> residuals -> where (channel, band, mode, time window + operating condition)
//  -> which (each effect fitted with Ceres on the fit part, scored on the
//     held-out part with a parameter penalty; forward selection with a margin)
//  -> how far (nrmse per channel and band before/after, parameters with std).
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "fracdesign/gap/effects.hpp"
#include "fracdesign/gap/nominal.hpp"
#include "fracdesign/gap/signals.hpp"

namespace fracdesign {
namespace gap {

// What the controller of a closed-loop nominal reads in the replay
// (docs/gap.md "Loop feedback"): `model`, the model's outputs (the loop is
// simulated: every effect acts through the loop as on the machine);
// `measured`, the record's columns of those outputs (the controller gives the
// command the machine's controller gave, and the plant is replayed on it: a
// limit cycle or a loop hunting on a play, a quantized sensor or a dead zone
// keeps the record's phase instead of drifting off it); `automatic`, model
// first and measured as the second pass of diagnose() (below).
enum class LoopFeedback { automatic, model, measured };
// "auto", "model" or "measured" (the CLI's --loop-feedback); std::invalid_argument
// naming the value and the allowed ones otherwise.
LoopFeedback loop_feedback_from_name(const std::string& name);

struct GapOptions {
    std::vector<std::string> inputs;    // data columns driving the model (default: the model's names)
    std::vector<std::string> outputs;   // compared outputs (default: model outputs present in the data)
    std::vector<Effect> effects = all_effects();  // candidates tried
    double holdout = 0.3;               // held-out tail fraction without a validation record
    double param_penalty = 0.005;       // score = shrink - param_penalty * (number of fitted parameters)
    double margin = 0.05;               // forward selection: relative held-out gap reduction needed to add an effect
    int max_effects = 3;                // forward selection depth
    int max_iterations = 30;            // Ceres iterations per start (half in forward selection)
    int threads = 0;                    // workers for the independent single fits (0: one per core); results do not depend on it
    LoopFeedback loop_feedback = LoopFeedback::automatic;  // closed loop: what the replayed controller reads
    std::function<void(const std::string&)> progress;  // one line per finished fit (the CLI prints them on stderr)
};

// Why the data do not identify a fitted parameter (fit.cpp
// unidentified_reason, flag_unreached_edges). The kind is what code decides
// on (stages.hpp nested_rule: alpha at its lower bound); the text is what
// the report and result.json print.
enum class Unidentified {
    identified,       // the record pins it
    lower_bound,      // the bound lies within 2 std of the estimate (or at it, without a std)
    upper_bound,
    no_std,           // the cost is flat or singular in it
    std_exceeds,      // the record cannot tell it from zero
    never_reached     // a limit or dead-zone edge the command never reaches: the record only bounds it
};
// result.json's spelling ("lower_bound", ...).
std::string unidentified_name(Unidentified u);

struct Identification {
    Unidentified why = Unidentified::identified;
    std::string text;  // the reason in words, with the figures ("" when identified)
    bool identified() const { return why == Unidentified::identified; }
};

struct FitReport {
    std::vector<EffectInstance> effects;
    std::vector<std::vector<double>> stddev;  // per effect, per parameter (NaN where not estimable)
    // Per effect, per parameter: whether the data identify it, and if not, why.
    std::vector<std::vector<Identification>> identification;
    std::vector<double> gap_after;            // nrmse per compared output, held-out
    double gap = 0.0;                         // aggregate held-out gap sqrt(mean nrmse^2)
    double shrink = 0.0;                      // 1 - gap / gap_before
    double score = 0.0;                       // shrink - penalty * fitted parameters
    double fit_cost = 0.0;                    // the fit's cost on the fit rows (least squares, 1/2 sum r^2)
    int fitted_params = 0;
    std::string solver;                       // Ceres BriefReport of the winning start
    std::vector<std::vector<double>> band_nrmse;  // per band, per output, held-out
};

struct ModeCheck {
    double f_hz, zeta;                // nominal mode
    double residual_share;            // residual energy share in [f/1.5, 1.5 f]
    double measured_peak_hz, model_peak_hz, peak_ratio;
    std::string flag;                 // "ok", "shifted", "mis-damped"
};

struct Window {
    double t0, t1;
    double rms;                       // normalized residual rms in the window
    std::string condition;
};

struct GapResult {
    std::string model_name, data_source, eval_source;
    std::string realization;                        // the nominal's fractional realization (NominalModel::realization)
    // Closed loop: what the replayed controller read ("model outputs" or
    // "measured outputs"; "" open loop) and why (diagnose(), the second pass).
    std::string loop_feedback, loop_feedback_note;
    double Ts = 0.0;
    std::vector<std::string> outputs;
    Units units;                                    // of the model's signals (gap.units)
    std::vector<std::string> coupling_names;        // the model's couplings (gap.coupling), in order
    std::vector<std::string> mode_names;            // the plant's resonant modes (mode_shift's sites), in order
    Eigen::Index fit_samples = 0, eval_first = 0, eval_samples = 0;
    std::vector<double> gap_before;                 // nrmse per output, held-out
    double gap_before_total = 0.0;
    std::vector<std::vector<double>> bands;         // [lo, hi, share] of the nominal residual energy
    std::vector<std::vector<double>> band_nrmse_before;  // per band, per output, held-out
    std::vector<ModeCheck> modes;
    std::vector<Window> windows;
    std::vector<FitReport> candidates;              // best first (includes "none" as an empty set)
    FitReport verdict;                              // forward selection result (empty effects: "none")
    // The verdict's confidence: the runner-up to its first effect (or to
    // none), their score margin, and the candidates this record cannot tell
    // apart from the first (held-out gaps within the selection margin), each
    // with the experiment that would separate them.
    struct LookAlike {
        std::string effect;
        double gap;
        std::string experiment;
    };
    struct Confidence {
        std::string first, runner_up;
        double margin = 0.0;  // score(first) - score(runner_up)
        std::vector<LookAlike> look_alikes;
        // What the verdict says about the gap (how_far.cpp verdict_status):
        // "at_noise_floor" (gap.noise stated and the gap within its limit:
        // none), "explained" (the verdict leaves the gap within the noise
        // floor's limit, or without gap.noise removes >= kExplainedShrink of
        // it), "partly_explained" (an effect found, but more of the gap is
        // left than that), "unexplained" (none, yet the gap is above the
        // stated noise floor: no candidate accounts for it), "no_candidate"
        // (none without gap.noise: the tool cannot tell noise from an effect
        // outside its list), "fit_part_only" (the start is stated and only
        // the fit rows show the effect: kFitPartShare), "beyond_noise" (the
        // gap is within the noise floor's limit, but the verdict improves it
        // beyond what the noise can: kNoiseReach); `explanation` says
        // it in a sentence with figures.
        std::string status, explanation;
        // At the noise floor: how far the best candidate's held-out
        // improvement lies beyond the noise's (how_far.cpp noise_reach), in
        // standard deviations; NaN where not tested.
        double noise_reach = std::numeric_limits<double>::quiet_NaN();
    } confidence;
    // gap.noise: the aggregate gap the sensors' noise alone leaves (the
    // held-out nrmse of a perfect model; in a closed loop with the motion the
    // noise makes through the controller), 0 when the document states no
    // noise; a gap_before_total within noise_floor_limit is `none`:
    // kNoiseFloorFactor x the floor, in a closed loop at least the one-sided
    // 99 % prediction bound of the noise-only gap from its draws.
    // noise_floor_outputs: the floor per compared output (empty: no noise).
    double noise_floor = 0.0, noise_floor_limit = 0.0;
    std::vector<double> noise_floor_outputs;
    // The nominal's cost on the fit rows and the cost its residual's white
    // level alone gives there (which.cpp; the fit-part evidence, how_far.cpp).
    double fit_cost_nominal = 0.0, fit_cost_white = 0.0;
    // Single candidates fitted a second time by continuation in record
    // length (docs/gap.md "Continuation in record length").
    size_t continued = 0;
    std::vector<std::string> skipped;               // effects not applicable, with the reason
    // Traces for the report (evaluation record): time, measured, nominal, augmented.
    Eigen::VectorXd t;
    Eigen::MatrixXd measured, nominal, augmented;
    // Nominal residual on the fit record, each output divided by its std (the "where" analysis input).
    Eigen::VectorXd where_t;
    Eigen::MatrixXd where_residual;
    double seconds = 0.0;                           // wall time of the diagnosis
};

// A gap within this factor of the noise floor (GapResult::noise_floor) is
// `none`: what an effect could add is below sqrt(1.1^2 - 1) = 0.46 of the noise.
constexpr double kNoiseFloorFactor = 1.1;

// A record whose gap lies within the noise floor's limit still has a finding
// when the best single candidate (score >= margin, every parameter
// identified) improves the held-out gap beyond what the noise alone gives
// the same change of prediction by this many standard deviations of a new
// draw (status "beyond_noise", how_far.cpp noise_reach): Student's t at one-
// sided 99.9 % for the 7 degrees of freedom of the 8 noise draws, 4.785,
// times sqrt(1 + 1/8); the stricter level pays for choosing the best of the
// candidates.
constexpr double kNoiseReach = 5.075;

// A record whose document states its start (gap.initial_state at_rest or
// given) and whose held-out rows leave no candidate a finding: a candidate
// removing at least this share of the fit rows' structured misfit (the
// nominal's cost above its white level), without worsening the held-out
// rows, is the verdict, status "fit_part_only" (how_far.cpp).
constexpr double kFitPartShare = 0.8;

// Without gap.noise a verdict that removes less than this share of the
// held-out gap is "partly_explained" (GapResult::Confidence::status).
constexpr double kExplainedShrink = 0.5;

// With LoopFeedback::automatic, a closed-loop record whose first pass (the
// controller reads the model's outputs) is not explained (status
// partly_explained, no_candidate or unexplained), with the nominal's misfit
// structured (its fit cost above kStructuredMisfit x its white cost), is
// diagnosed again with the controller reading the measured outputs. When
// that second pass names effects, the first pass runs again with its fits
// also started where the second found them, and replaces the first when its
// verdict scores higher (the same closed-loop replay, the same nominal gap).
// Then, if the first pass names nothing or a weak verdict (partly_explained,
// shrink below kExplainedShrink), the second pass is the result when its
// status is "explained", the record identifies every parameter of its
// verdict, and, after a weak verdict without a look-alike, it names the
// same effects at the same sites; else the first is, and
// GapResult::loop_feedback_note says what the other passes gave.
GapResult diagnose(const NominalModel& model, const Signals& data, const Signals* validate, const GapOptions& opt);

// result.json (schema "frac.gap", version 1; keys of issue 10 plus details).
nlohmann::json result_json(const GapResult& r);

// Aggregate gap: sqrt(mean over outputs of nrmse^2), or with channel
// weights w_c (gap.noise: w_c proportional to (std(y_c)/noise_c)^2)
// sqrt(sum w_c nrmse_c^2 / sum w_c).
double total_gap(const std::vector<double>& nrmse, const std::vector<double>& weight = {});

}  // namespace gap
}  // namespace fracdesign
