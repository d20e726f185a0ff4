// nominal.hpp - the nominal model the gap diagnosis replays on recorded data.
//
// Internally every nominal model is a discrete-time LTI plant at the data's
// sample time, x(k+1) = A x(k) + B u(k), y(k) = C x(k) + D u(k), with named
// inputs and outputs, plus, for closed-loop records, the known controller:
//   w(k)  = [r(k); y_m(k)]          references from the data, measured model outputs
//   xc(k+1) = Ac xc(k) + Bc w(k),   c(k) = Cc xc(k) + Dc w(k)
//   u(k)  = clamp(c(k - delay), min, max) + a(k) additive data columns (e.g. injected pulses)
// The plant is any rational model of the project's model format
// (fracdesign/model_json.hpp, e.g. kind "statespace"); the "gap" extension
// section of the document gives the loop and the friction hook-up
// (docs/gap.md).
#pragma once
#include <Eigen/Dense>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fracdesign/gap/controller.hpp"
#include "fracdesign/models/lti.hpp"

namespace fracdesign {
namespace gap {

struct ClosedLoop {
    std::vector<std::string> references;  // data columns, the controller's reference inputs
    std::vector<int> measured;            // model output indices fed back to the controller
    // The controller at its document parameters; each replay runs its own
    // clone (controller.hpp). Inputs [references; measured], outputs = plant inputs.
    std::shared_ptr<const Controller> controller;
    int delay_samples = 0;                // pure delay between controller and plant (computation delay)
    // Limits on the plant inputs, [saturation_min, saturation_max]
    // (gap.closed_loop.saturation: a number L for [-L, L] or {"min", "max"});
    // saturation = max(|min|, |max|), the scale of the saturation candidate.
    double saturation = std::numeric_limits<double>::infinity();
    double saturation_min = -std::numeric_limits<double>::infinity();
    double saturation_max = std::numeric_limits<double>::infinity();
    // Data columns added to the plant inputs after the saturation, the i-th to
    // plant input i; a column absent from a record counts as zero there.
    std::vector<std::string> additive;
};

// A spring inside the plant (e.g. a gear between motor and link) on which
// backlash and fractional damping may act instead of at the force input
// (docs/gap.md "coupling"): its deflection is twist . x, its nominal torque
// stiffness * (twist . x), and an extra spring torque D held over one sample
// moves the state by torque * D (x(k+1) = A x + B u + torque D).
//
// A play in the spring makes contact within a sample (a stiff spring hits
// in a fraction of a 1 ms sample), so the replay sub-steps the block of
// plant states the spring belongs to (`states`, default all): from the
// block's discrete matrix Phi = A[S,S] it takes the generator
// Ac = log(Phi)/Ts and splits each sample into `substeps` exact steps of
// Phi_m = e^{Ac Ts/m}, with the sample's forcing (inputs and the other
// states, known only through x(k+1) - Phi x(k)) held constant over it.
// Without correction the sub-steps end exactly at the nominal x(k+1).
//
// A coupling is declared either by its spring (twist, torque, stiffness) or,
// on a continuous modal model, by a flexible mode's coordinates
// ("modal": {"position": i, "rate": j}, docs/gap.md): twist e_i, torque
// -e_j (unit modal mass), stiffness -A(j, i) = w^2. gap.coupling is one
// such object or a list of them (coupling.cpp).
struct Coupling {
    std::string name;
    std::string unit;          // unit of the deflection (gap.coupling.unit; empty: not given)
    Eigen::RowVectorXd twist;  // 1 x n, deflection from the plant state
    Eigen::VectorXd torque;    // n, discrete at Ts: the state change per unit of extra spring torque over one sample
    Eigen::VectorXd torque_c;  // n, the continuous plant's column of the torque (empty for a discrete plant)
    double stiffness = 0.0;    // nominal spring rate, torque per unit deflection
    std::vector<int> states;   // S: the sub-stepped block (twist and torque vanish outside it)
    int substeps = 8;          // m
    Eigen::MatrixXd Phi, Phi_m, Gamma_m, Gamma_inv;  // A[S,S], e^{Ac Ts/m}, int_0^{Ts/m} e^{Ac s} ds, (int_0^Ts ..)^-1
    Eigen::VectorXd torque_m;  // Gamma_m Gamma^-1 torque[S]: one sub-step of a unit extra spring torque
    Eigen::RowVectorXd twist_s;  // twist[S]
    double w_slow = 0.0;       // slowest oscillatory eigenfrequency of the block's generator Ac [rad/s] (0: none)
};

// Reads gap.coupling (an object or a list of objects) of a plant whose
// continuous matrices are Ac (empty for a discrete plant) into couplings
// with their sub-step matrices; std::runtime_error naming the entry and
// field on a malformed one (coupling.cpp).
std::vector<Coupling> read_couplings(const nlohmann::json& spec, const Eigen::MatrixXd& A, const Eigen::MatrixXd& Ac,
                                     double Ts);
// Grunwald-Letnikov memory for c D^alpha of a coupling's deflection: at
// least `base` samples and 20/(w_slow Ts), so that the truncated operator's
// error at the block's slowest mode, (L Ts w)^-(1+alpha)/|Gamma(-alpha)|
// (fo_gl.h), stays below 0.4 % for every alpha in (0, 1); at most `cap`.
int coupling_gl_memory(const Coupling& c, double Ts, int base, long cap);

struct Mode {
    double f_hz;  // natural frequency
    double zeta;  // damping ratio
};

struct NominalModel {
    std::string name;
    double Ts = 0.0;
    Eigen::MatrixXd A, B, C, D;  // discrete at Ts
    // The plant's generator x' = Ac x + Bc u: the document's when its plant
    // is continuous, else log(A)/Ts and Bc = G^-1 B when A has one
    // (discrete_generator); empty without. The series mode's exact hold
    // (replay.cpp series_mode_hold), a fractional input delay's exact hold,
    // a mode moved by a coupling's spring (mode_shift.cpp).
    Eigen::MatrixXd Ac, Bc;
    std::vector<std::string> inputs, outputs;
    bool closed_loop = false;
    ClosedLoop loop;
    int velocity = -1;     // model output used as the friction velocity (-1: none)
    int force_input = 0;   // plant input where dead zone, backlash, gain and saturation act
    // Plant input where friction acts (gap.friction_input; default force_input): a torque
    // on the moving part held over the sample, e.g. where the actuator's own dynamics (a
    // current loop, a torque ramp) lie between force_input and the shaft. Zero in the
    // record (open loop: need not be a column) and from the controller (closed loop).
    int friction_input = 0;
    // gap.friction: the friction the user knows (an arm document's, seed 004 (5.2)), part of the
    // nominal: viscous v + coulomb s(v) on friction_input at the velocity gap.velocity, s(v) =
    // tanh(tanh_k v) when tanh_k > 0 (libfrac's linear model, the HIL plant's), else the dry
    // stick-slip sign of the friction effects. The friction effects fit what lies beyond it.
    struct KnownFriction {
        double viscous = 0.0, coulomb = 0.0, tanh_k = 0.0;
    } friction;
    std::vector<Coupling> couplings;  // gap.coupling (none, one or several springs / flexible modes)
    std::map<std::string, std::string> units;  // gap.units: signal name -> unit (optional, for the report)

    // What the document states the user knows (docs/gap.md "What the
    // document states"; read by read_known_section, nominal_known.cpp).
    // Nominal delay of every plant input [samples]: gap.input_delay plus a
    // foprocess's dead time; the input_delay effect looks for delay beyond it.
    double input_delay = 0.0;
    enum class Start { fitted, at_rest, given };
    Start initial_state = Start::fitted;  // gap.initial_state
    Eigen::VectorXd x0_given;             // Start::given: the plant state (the document's, discretisation keeps it)
    std::map<std::string, double> noise;  // gap.noise: model output -> sensor noise std (empty: not stated)
    // gap.input_limits (open loop): per plant input, the actuator's limits
    // [lo, hi] (-inf/+inf where the document states none).
    std::vector<double> input_lo, input_hi;
    // Input i clamped to its stated limits (unchanged where none are stated).
    double limit_input(size_t i, double u) const
    {
        if (i < input_lo.size()) u = u < input_lo[i] ? input_lo[i] : u;
        if (i < input_hi.size()) u = u > input_hi[i] ? input_hi[i] : u;
        return u;
    }
    // gap.output_hold: a sensor read every `every` samples whose reading is held in between (e.g. an
    // IMU reading every h PLC cycles): at the samples k with (k - phase) mod every = 0 the output
    // `output` reads the model output `sample` (its effects applied: delay, offset, step), at the
    // others it repeats its last reading. phase -1: taken from the record (make_replay_setup).
    struct OutputHold {
        int output = -1, sample = -1, every = 1, phase = -1;
    };
    std::vector<OutputHold> holds;
    std::string realization;  // a fractional plant's rational realization: band, order, accuracy ("" if rational)

    int output_index(const std::string& name) const;  // -1 if absent
    // Oscillatory and real modes of the nominal (loop closed when closed_loop
    // and the controller has a small-signal state space, controller delay and
    // limits left out), as continuous-time equivalents.
    std::vector<Mode> modes() const;
};

// Builds the model from a "frac.model" document, discretising a continuous
// plant (and controller) with zero-order hold at Ts. std::runtime_error with
// one clear message for a malformed document (dimensions, names, schema,
// an irrational model kind).
// `base_dir` is where tables a controller names by a relative path are
// looked up (load_nominal_model: the document's directory).
// `record_seconds` (the data's length; 0: unknown, read as 1e5 samples)
// sets the default band of a fractional plant's realization.
NominalModel nominal_from_json(const nlohmann::json& doc, double Ts, const std::string& base_dir = ".",
                               double record_seconds = 0.0);
NominalModel load_nominal_model(const std::string& path, double Ts, double record_seconds = 0.0);

// The plant of a model document as a continuous or discrete state space:
// a rational kind's own (model_state_space), a foprocess realized by
// foprocess_realization (fracdesign/models/fo_realization.hpp) over the
// band of gap.realization or its default for (Ts, record_seconds), its
// dead time returned in *delay_s and its realization described in
// *realization. std::runtime_error naming the field on a bad document.
StateSpace plant_state_space(const nlohmann::json& doc, double Ts, double record_seconds, double* delay_s,
                             std::string* realization);
// Reads gap.input_delay, gap.initial_state, gap.noise, gap.input_limits and gap.output_hold
// into m (the plant already read), adding `plant_delay_s` (a foprocess's
// dead time) to the input delay. Each bad value: std::runtime_error with
// one line naming the field, the value and what is allowed.
void read_known_section(const nlohmann::json& gap, double plant_delay_s, NominalModel& m);

// Reads the state space (A, B, C, D) of a document object with m inputs and
// p outputs ("time": "continuous", discretised with zero-order hold at Ts,
// or "discrete" with its "Ts" equal to Ts); std::runtime_error naming
// `where` and the matrix on a malformed object.
void read_statespace(const nlohmann::json& j, Eigen::Index m, Eigen::Index p, double Ts, const std::string& where,
                     Eigen::MatrixXd& A, Eigen::MatrixXd& B, Eigen::MatrixXd& C, Eigen::MatrixXd& D);

// Zero-order-hold discretisation: Ad = e^{A Ts}, Bd = int_0^Ts e^{A s} ds B
// (design::c2d_zoh; std::invalid_argument on a non-finite entry or Ts <= 0).
void zoh(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double Ts, Eigen::MatrixXd& Ad, Eigen::MatrixXd& Bd);

// The generator of a discrete plant held at Ts: Ac = log(A)/Ts and the
// inverse of the hold integral G = int_0^Ts e^{Ac s} ds, so that a column b
// of the discrete input map is G^-1 b in continuous time. False (outputs
// untouched) when A has no real logarithm that gives it back to 1e-8 (a
// pure delay, a mode at or above Nyquist) or G is singular; `singular`, if
// given, tells the second from the first.
bool discrete_generator(const Eigen::MatrixXd& A, double Ts, Eigen::MatrixXd& Ac, Eigen::MatrixXd& G_inv,
                        bool* singular = nullptr);

}  // namespace gap
}  // namespace fracdesign
