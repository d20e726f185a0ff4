// effects.hpp - the library of candidate unmodelled effects and the replay of
// the nominal model augmented with them.
//
// Each effect is a parametric augmentation of the nominal model (docs/gap.md
// gives the equations). Parameters are physical (force in the units of the
// model's force input, velocity in those of its velocity output, outputs in
// their own units). The fixed effect names are the ones of issue 10.
#pragma once
#include <Eigen/Dense>
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
// Effects acting through the velocity (friction, fractional damping) need gap.velocity in the model.
bool needs_velocity(Effect e);

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

// Effects that can act in a declared coupling (backlash, fractional_damping).
bool coupling_capable(Effect e);

// Parameter names of an effect; `outputs` are the compared outputs (per-channel parameters).
std::vector<std::string> param_names(Effect e, const std::vector<std::string>& outputs);

// The data a replay runs on: the nominal model, the exogenous signals taken
// from the record, the initial state, and the compared outputs.
struct ReplaySetup {
    const NominalModel* model = nullptr;
    Eigen::MatrixXd exo;               // samples x (plant inputs) open loop, or x (references + additive) closed loop
    Eigen::VectorXd x0;                // initial plant state
    Eigen::VectorXd xc0;               // initial controller state
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
