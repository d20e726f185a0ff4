// effects.hpp - the library of candidate unmodelled effects and the replay of
// the nominal model augmented with them.
//
// Each effect is a parametric augmentation of the nominal model (docs/gap.md
// gives the equations). Parameters are physical (force in the units of the
// model's force input, velocity in those of its velocity output, outputs in
// their own units). The fixed effect names are the ones of issue 10.
#pragma once
#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "fracdesign/gap/nominal.hpp"
#include "fracdesign/gap/signals.hpp"

namespace fracdesign {
namespace gap {

enum class Effect {
    input_delay,
    output_delay,
    coulomb_friction,
    viscous_friction,
    stribeck_friction,
    backlash,
    deadzone,
    saturation,
    fractional_damping,
    unmodelled_mode,
    gain_error,
    sensor_offset,
    quantization
};

const std::vector<Effect>& all_effects();
std::string effect_name(Effect e);
Effect effect_from_name(const std::string& name);  // std::invalid_argument if unknown

// Where an effect acts. Backlash and fractional damping act at the force
// input (a play on u, c D^alpha of the velocity output to ground) or, when
// the model declares one (gap.coupling), in its spring: a play in the
// deflection, c D^alpha of the deflection in parallel with the spring.
enum class Site { force_input, coupling };
struct EffectInstance {
    Effect kind;
    std::vector<double> params;  // physical values, in the order of param_names()
    Site site = Site::force_input;
};

// The parameters' units come from the model document's optional gap.units
// (signal name -> unit); a unit the document does not give is written
// "[name]" after the signal it is the unit of.
struct Units {
    std::string u = "[u]";        // the force input
    std::string v = "[v]";        // the velocity output
    std::string q = "[q]";        // the coupling's deflection
    std::vector<std::string> y;   // each compared output
};
struct ParamInfo {
    std::string name;
    std::string unit;
};

// One parameter of a fit, in normalized form: physical = scale * normalized.
struct ParamSpec {
    double scale;
    double lo, hi;  // normalized bounds
    bool fixed;     // set from the data (a grid), not by the solver
};
// The fit set-up of one effect at one site: parameter scales and bounds, start values.
struct EffectSetup {
    Effect kind;
    Site site = Site::force_input;
    std::vector<ParamSpec> spec;
    std::vector<std::vector<double>> starts;  // normalized start vectors
    bool screen = false;                      // rank starts by cost, refine the best three
};
// The data scales that effects' bounds and starts are taken from.
struct FitContext {
    double Ts = 0, Su = 1, Sv = 1, umax = 1, fit_seconds = 0;
    double Sq = 0, kq = 0;                  // coupling: rms nominal deflection, stiffness (0: no coupling)
    std::vector<double> Sy;                 // std of each compared output
    std::vector<double> quant_step;         // lattice step of each compared output (0: not quantized)
    std::vector<double> residual_peaks_hz;  // largest peaks of the nominal residual spectrum
    long fit_samples = 0;
};

// The replay's terms (effects.cpp, replay()): what the effects set, the
// nominal values when no effect sets them.
struct ReplayTerms {
    double din = 0;                 // input delay [samples]
    std::vector<double> dout;       // per model output delay [samples]
    int dout_max = 0;
    double Fc = 0, Foff = 0, Fv = 0;                          // Coulomb level and offset, viscous rate
    bool stribeck = false;
    double Sc = 0, Ss = 0, Svs = 1;                           // Stribeck Fc, Fs, vs
    double bl = -1, dz = 0, sat = 0, gain = 1;                // play (< 0: none), dead zone, limit (0: none), gain
    bool fractional = false;
    double fc = 0, alpha = 0.5;                               // c D^alpha of the velocity to ground
    double cbl = -1;                                          // play in the coupling (< 0: none)
    bool cfrac = false;
    double cfc = 0, calpha = 0.5;                             // c D^alpha of the coupling deflection
    bool mode = false;
    double f_hz = 1, zeta = 0.1;
    std::vector<double> mode_gain, offset, step;              // per model output
};

// The data a replay runs on (below).
struct ReplaySetup;

// One home per effect: everything the diagnosis (and the bench, through
// effect_name/param_names) knows about an effect is its descriptor.
struct EffectDescriptor {
    Effect kind;
    const char* name;               // the fixed name of issue 10
    const char* summary;            // one line: the model equation (CLI help, report)
    bool needs_velocity;            // acts through gap.velocity (skipped without it)
    std::vector<Site> sites;        // where it may act (coupling: only with gap.coupling)
    const char* reveals;            // the experiment that shows this effect apart from look-alikes
    // Parameter names and units (per-output parameters carry the output's name).
    std::vector<ParamInfo> (*params)(const std::vector<std::string>& outputs, const Units& units, Site site);
    // Scales, bounds and the start rule at a site, from the data's scales.
    EffectSetup (*setup)(const FitContext& c, Site site);
    // Its replay: sets its terms from its physical parameters.
    void (*apply)(const std::vector<double>& p, Site site, const ReplaySetup& s, ReplayTerms& t);
};
const EffectDescriptor& descriptor(Effect e);

// Effects acting through the velocity (friction, fractional damping) need gap.velocity in the model.
bool needs_velocity(Effect e);
// Effects that can act in a declared coupling (backlash, fractional_damping).
bool coupling_capable(Effect e);
// Parameter names of an effect; `outputs` are the compared outputs (per-channel parameters).
std::vector<std::string> param_names(Effect e, const std::vector<std::string>& outputs);
// Units of the model's signals as the replay's parameters see them.
Units model_units(const NominalModel& m, const std::vector<std::string>& outputs);

// The data a replay runs on: the nominal model, the exogenous signals taken
// from the record, the initial state, and the compared outputs.
struct ReplaySetup {
    const NominalModel* model = nullptr;
    Eigen::MatrixXd exo;               // samples x (plant inputs) open loop, or x (references + additive) closed loop
    Eigen::VectorXd x0;                // initial plant state
    // The controller started at the first sample (closed loop; each replay runs a clone).
    std::shared_ptr<const Controller> controller0;
    std::vector<int> compared;         // model output index of each compared output
    // The record's compared outputs (samples x compared): a quantizing
    // sensor's reading stands for its cell, so the quantization effect
    // compares the model with the cell around the reading (docs/gap.md).
    Eigen::MatrixXd measured;
    double eps_velocity = 1.0;         // sign(v) ~ tanh(v/eps) where the force input does not reach v in one step
    int fractional_memory = 256;       // Grunwald-Letnikov memory, samples

    Eigen::Index samples() const { return exo.rows(); }
};

// Builds the replay set-up for `data`: maps the model's inputs (open loop) or
// references and additive signals (closed loop) onto data columns (`inputs`
// overrides the names, in model order), checks that every compared output is
// a model output and a data column, and estimates the initial state from the
// first measured sample (least squares through the compared outputs).
// std::runtime_error with one clear message on a mismatch.
ReplaySetup make_replay_setup(const NominalModel& m, const Signals& data, const std::vector<std::string>& inputs,
                              const std::vector<std::string>& outputs);

struct ReplayTrace {
    Eigen::MatrixXd y;      // samples x compared outputs, as the sensors would read them
    Eigen::VectorXd u;      // plant force input after input effects and friction
    Eigen::VectorXd v;      // friction velocity (zero when the model names none)
    Eigen::VectorXd twist;  // coupling deflection twist . x (zero when the model declares no coupling)
};

// Replays the nominal model with the given effects over the first `n`
// samples (all when n < 0). Each effect kind appears at most once.
ReplayTrace replay(const ReplaySetup& s, const std::vector<EffectInstance>& effects, Eigen::Index n = -1);

}  // namespace gap
}  // namespace fracdesign
