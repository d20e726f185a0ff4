// effects.hpp - the library of candidate unmodelled effects and the replay of
// the nominal model augmented with them.
//
// Each effect is a parametric augmentation of the nominal model (docs/gap.md
// gives the equations). Parameters are physical (force in the units of the
// model's force input, velocity in those of its velocity output, outputs in
// their own units). The fixed effect names are the ones of issue 10.
#pragma once
#include <Eigen/Dense>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fracdesign/gap/mode_shift.hpp"
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
    quantization,
    mode_shift
};

const std::vector<Effect>& all_effects();
std::string effect_name(Effect e);
Effect effect_from_name(const std::string& name);  // std::invalid_argument if unknown

// Where an effect acts. Backlash and fractional damping act at the force
// input (a play on u, c D^alpha of the velocity output to ground) or, when
// the model declares them (gap.coupling), in one of its springs or flexible
// modes: a play in the deflection, c D^alpha of the deflection in parallel
// with the spring (Kelvin-Voigt). The unmodelled mode acts in series at the
// force input (between the actuator and the plant), at the outputs (a
// force-driven resonance the sensors see), or in one sensor's reading (a
// second-order sensor: the mount's transmissibility of the true output
// where the sensor sits on a compliant mount, its own low-pass where the
// sensor's dynamics are second order, or between the two). The mode shift acts on one resonant mode of the
// nominal plant (mode_shift.hpp), one site per mode. The gear site
// (gear_site below) is a compliant gear behind the motor-side sensors of a
// rigid nominal that declares no coupling: a share r of the inertia (the
// load) on a spring of contact frequency f and damping zeta, with a play of
// width w in it (backlash) or without (unmodelled_mode).
enum class Site { force_input, coupling, output, mode, sensor, gear };
struct EffectInstance {
    Effect kind;
    std::vector<double> params;  // physical values, in the order of param_names()
    Site site = Site::force_input;
    int coupling = 0;            // Site::coupling: index into NominalModel::couplings;
                                 // Site::mode: index into resonant_plant_modes();
                                 // Site::sensor: index into the compared outputs
};
// Two different effects that hold the same term: stribeck_friction contains
// coulomb_friction (its Fc sgn(v) at Fs = Fc), so a set with both counts the
// Coulomb level twice and the split between them is not identified. The
// forward selection never adds one to a set holding the other.
bool same_term(Effect a, Effect b);
// The same, with the sites: also fractional_damping to ground (Site::
// force_input, c D^(alpha-1) v) and viscous_friction (Fv v, its alpha = 1
// end): the sum Fv v + c D^(alpha-1) v of two nearby orders fits any damping
// between them with a large Fv and a c of opposite sign, neither identified
// (an outside-style servo record of viscous friction and a dead zone came
// out Fv 0.040 (true 0.0055) with c = -0.037 at alpha's 0.95 bound). In a
// declared coupling (Kelvin-Voigt) the damping is another term. At the gear
// site, backlash and unmodelled_mode are one gear (with and without its play).
bool same_term(Effect a, Site sa, Effect b, Site sb);
// The site's name in result.json: "force_input", "output", "coupling",
// "mode", "sensor" or "gear".
std::string site_name(Site s);
// How the CLI and the report say where an effect of result.json acts
// (effect name, site name, coupling name): "" at the force input, else
// e.g. " (in the coupling 'gear')", " (at the outputs)", " (in series at
// the force input)" for the mode, " (the nominal's mode at 12.3 Hz, zeta
// 0.02)" for a mode shift (result.json's coupling field names the mode),
// " (in the reading of sensor 'tip_rate')" for the mode at a sensor.
std::string site_phrase(const std::string& effect, const std::string& site, const std::string& coupling);

// The parameters' units come from the model document's optional gap.units
// (signal name -> unit); a unit the document does not give is written
// "[name]" after the signal it is the unit of.
struct Units {
    std::string u = "[u]";        // the force input
    std::string v = "[v]";        // the velocity output
    std::string q = "[q]";        // the deflection of the coupling an effect acts in
    std::string p = "[p]";        // the position state (the gear site's play)
    std::vector<std::string> qs;  // each coupling's deflection (model order)
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
    // >= 0: this parameter is the negative of the effect's parameter
    // `mirror` (a symmetric restriction: lower = -upper), neither fitted nor
    // counted as a fitted parameter; its std and identification are the
    // mirrored one's.
    int mirror = -1;
    // A nested restriction's parameter held at its start value (Coulomb
    // friction without offset): fixed, and not counted as fitted.
    bool held = false;
    // The normalized value at which this parameter does nothing (a dead
    // zone's edge at 0, a limit beyond the command's reach), or NaN. An
    // effect with two or more such parameters acts through each on its own
    // part of the signal (the two edges of a dead zone or a saturation: the
    // command above the upper one, below the lower one); the fit searches
    // each alone, the others at this value, before the joint refine
    // (fit.cpp coordinate_starts).
    double neutral = std::numeric_limits<double>::quiet_NaN();
};
// The fit set-up of one effect at one site: parameter scales and bounds, start values.
struct EffectSetup {
    Effect kind;
    Site site = Site::force_input;
    int coupling = 0;                          // Site::coupling: which one
    std::vector<ParamSpec> spec;
    std::vector<std::vector<double>> starts;  // normalized start vectors
    bool screen = false;                      // rank starts by cost, refine the best three
    // Normalized starts from another pass's fit of this effect at this site
    // (diagnosis.cpp: the loop-feedback pass's verdict); refined besides the
    // screened ones, never screened out.
    std::vector<std::vector<double>> seeded = {};
};
// The data scales that effects' bounds and starts are taken from.
struct FitContext {
    double Ts = 0, Su = 1, Sv = 1, umax = 1, fit_seconds = 0;
    // The friction's scale: Su in the friction input's units (gap.friction_input;
    // Su itself when friction acts at the force input). where.cpp friction_scale.
    double Sf = 1;
    // The coupling a set-up is for: rms nominal deflection, stiffness, slowest
    // oscillation of its block [rad/s] (0: none), index.
    double Sq = 0, kq = 0, wq = 0;
    int coupling = 0;
    std::vector<double> Sy;                 // std of each compared output
    std::vector<double> quant_step;         // lattice step of each compared output (0: not quantized)
    // White level of each compared output's nominal residual [its unit]:
    // rms(r(k) - (r(k-1) + r(k+1))/2)/sqrt(1.5) over the fit rows (at the
    // readings of a held output), the noise std when the residual is white.
    std::vector<double> white_sd;
    std::vector<double> residual_peaks_hz;  // largest peaks of the nominal residual spectrum
    long fit_samples = 0;
    // The nominal plant mode a set-up is for (Site::mode, index in
    // `coupling`): its frequency [Hz] and damping; and the where stage's
    // mode checks (diagnosis.hpp ModeCheck): (f checked, measured peak) [Hz].
    double mode_f_hz = 0, mode_zeta = 0;
    std::vector<std::pair<double, double>> mode_checks;
    // The gear site's length scale (GearSite): how far the position state
    // moves in one sample at the rms velocity, kappa Ts Sv / C[v][j]; 0 when
    // the nominal has no gear site.
    double Sp = 0;
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
    double bl = -1, gain = 1;                                 // play on the force input (< 0: none), gain
    double dz_lo = 0, dz_hi = 0;                              // dead zone edges (lower <= 0 <= upper; 0, 0: none)
    double sat_lo = 0, sat_hi = 0;                            // limits (lower < 0 < upper; 0, 0: none)
    bool fractional = false;
    double fc = 0, alpha = 0.5;                               // c D^alpha of the velocity to ground
    int coupling = 0;                 // set by replay() before each apply: the instance's coupling
    int bl_coupling = -1;             // coupling holding the play (-1: none)
    double cbl = -1;                  // its play (< 0: none)
    int frac_coupling = -1;           // coupling holding c D^alpha of its deflection (-1: none)
    double cfc = 0, calpha = 0.5;
    bool mode = false;                // the mode at the outputs
    bool series_mode = false;         // the mode in series at the force input
    int sensor_mode = -1;             // model output whose reading passes through the mode at its sensor (-1: none)
    double sensor_zero = 1.0;         // that mode's zero share: 1 a compliant mount, 0 the sensor's own low-pass
    double f_hz = 1, zeta = 0.1;
    bool gear = false;                // the gear site (gear_site): its play, load share, frequency, damping
    double gear_w = 0, gear_r = 0.5, gear_f = 100, gear_zeta = 0.1;
    std::vector<double> mode_gain, offset, step;              // per model output
    Eigen::MatrixXd A, B;             // the plant with a nominal mode moved (mode_shift; empty: the nominal's)
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
    // Optional: nested restrictions of setup() at a site (fewer parameters,
    // the same names, e.g. the symmetric dead zone lower = -upper inside the
    // asymmetric one). Each is fitted as a variant of its own, like the
    // sites: the best score is the effect's candidate, so the full model
    // must beat its restriction on held-out data by the penalty of its extra
    // parameters (docs/gap.md, "Nested restrictions").
    std::vector<EffectSetup> (*nested)(const FitContext& c, Site site) = nullptr;
};
const EffectDescriptor& descriptor(Effect e);

// Effects acting through the velocity (friction, fractional damping) need gap.velocity in the model.
bool needs_velocity(Effect e);
// Effects that can act in a declared coupling (backlash, fractional_damping).
bool coupling_capable(Effect e);
// Parameter names of an effect at a site; `outputs` are the compared outputs (per-channel parameters).
std::vector<std::string> param_names(Effect e, const std::vector<std::string>& outputs, Site site = Site::force_input);
// The sites the diagnosis tries for an effect on this model (coupling: once per declared coupling;
// mode: once per entry of resonant_plant_modes, `plant_modes` of them (ReplaySetup::plant_modes);
// sensor: once per compared output).
std::vector<std::pair<Site, int>> effect_sites(Effect e, const NominalModel& m, size_t compared_outputs, size_t plant_modes);
// `u` with the deflection unit of coupling `coupling`.
Units units_at(const Units& u, int coupling);
// Units of the model's signals as the replay's parameters see them.
Units model_units(const NominalModel& m, const std::vector<std::string>& outputs);

// The gear site of a nominal (gear.cpp, docs/gap.md "The gear site"): a
// continuous generator (NominalModel::Ac) whose velocity output
// (gap.velocity) reads one state j, a position state p with p' = kappa x_j
// and nothing else, and no declared coupling (a declared one holds its own
// play). `ok` false, with `why`, where the nominal has no such body.
struct GearSite {
    bool ok = false;
    std::string why;
    int p = -1, j = -1;   // position and velocity states
    double kappa = 0;     // p' = kappa x_j
    int position_output = -1;  // a model output reading p alone (its unit is the play's), or -1
};
GearSite gear_site(const NominalModel& m);

// A play of width w in a deflection q = twist . z of a linear block held
// over `substeps` sub-steps: z+ = Phi z + drive + torque D, D = -k clamp(q,
// -w/2, w/2) at the sub-step's mid deflection (an implicit trapezoid solved
// by fixed-point iteration; it contracts while |twist . torque| k / 2 < 1).
// A coupling's play (replay.cpp) and the gear site's (gear.cpp) step this way.
void play_substeps(Eigen::VectorXd& z, const Eigen::VectorXd& drive, const Eigen::MatrixXd& Phi,
                   const Eigen::VectorXd& torque, const Eigen::RowVectorXd& twist, double k, double w, int substeps);

// The data a replay runs on: the nominal model, the exogenous signals taken
// from the record, the initial state, and the compared outputs.
struct ReplaySetup {
    const NominalModel* model = nullptr;
    Eigen::MatrixXd exo;               // samples x (plant inputs) open loop, or x (references + additive) closed loop
    Eigen::VectorXd x0;                // initial plant state
    // A fitted start (gap.initial_state "fitted"): x0 = x0_fit y0, the least
    // squares map of the compared outputs' first sample (empty otherwise);
    // the replay takes sensor offsets out of y0 through it.
    Eigen::MatrixXd x0_fit;
    // The controller started at the first sample (closed loop; each replay runs a clone).
    std::shared_ptr<const Controller> controller0;
    std::vector<int> compared;         // model output index of each compared output
    // The record's compared outputs (samples x compared): a quantizing
    // sensor's reading stands for its cell, so the quantization effect
    // compares the model with the cell around the reading (docs/gap.md).
    Eigen::MatrixXd measured;
    // The record's columns of the outputs the controller reads
    // (NominalModel::loop.measured, samples x their count) when the replay
    // feeds the controller the measured outputs instead of the model's
    // (GapOptions::loop_feedback, docs/gap.md "Loop feedback"); empty: the
    // controller reads the model's outputs (a closed-loop simulation).
    Eigen::MatrixXd loop_measured;
    // Phase of each gap.output_hold (model.holds): the document's, else the residue
    // modulo `every` of the samples at which the record's column changes most often
    // (a new reading), 0 when the output is no column or never changes.
    std::vector<int> hold_phase;
    double eps_velocity = 1.0;         // sign(v) ~ tanh(v/eps) where the force input does not reach v in one step
    int fractional_memory = 256;       // Grunwald-Letnikov memory, samples (a coupling's: coupling_gl_memory)
    std::vector<PlantMode> plant_modes;  // the nominal's resonant modes, the mode_shift sites (mode_shift.hpp)

    Eigen::Index samples() const { return exo.rows(); }
};

// Builds the replay set-up for `data`: maps the model's inputs (open loop) or
// references and additive signals (closed loop) onto data columns (`inputs`
// overrides the names, in model order), checks that every compared output is
// a model output and a data column, and estimates the initial state from the
// first measured sample (least squares through the compared outputs).
// feed_measured (closed loop): the controller reads the record's columns of
// its measured outputs (ReplaySetup::loop_measured), each of which must be
// a column of `data`.
// std::runtime_error with one clear message on a mismatch.
ReplaySetup make_replay_setup(const NominalModel& m, const Signals& data, const std::vector<std::string>& inputs,
                              const std::vector<std::string>& outputs, bool feed_measured = false);

struct ReplayTrace {
    Eigen::MatrixXd y;      // samples x compared outputs, as the sensors would read them
    Eigen::VectorXd u;      // plant force input after input effects and friction
    Eigen::VectorXd u_static;  // the command entering the force input's limits and dead zone (gain x the delayed command)
    Eigen::VectorXd v;      // friction velocity (zero when the model names none)
    Eigen::VectorXd twist;  // the first coupling's deflection twist . x (zero when the model declares no coupling)
    Eigen::MatrixXd twists; // samples x couplings: each coupling's deflection
};

// Replays the nominal model with the given effects over the first `n`
// samples (all when n < 0). Each effect kind appears at most once.
// `sensor_noise` (samples x model outputs, optional): added to each sensor's
// reading before its quantization and hold, so that in a closed loop the
// controller reads it too (the closed-loop noise floor, baseline.cpp).
ReplayTrace replay(const ReplaySetup& s, const std::vector<EffectInstance>& effects, Eigen::Index n = -1,
                   const Eigen::MatrixXd* sensor_noise = nullptr);

}  // namespace gap
}  // namespace fracdesign
