// arm_design.hpp - the whole design chain for an arm document (models/arm_document.hpp,
// docs/arm_format.md): reduced model with automatic Krylov shifts, LQG with delays and friction state,
// the move's feedforward, and the ArmCtrl, HIL plant and gap nominal documents of that arm.
//
// Reduction rule (seed 004 Sec. 3.5 generalised; the thesis's shifts 16, 18.43, 115.6 rad/s sit at its
// beam's clamped-free modes 18.44 and 115.5 rad/s and below the first):
//   bandwidth w_b = design.bandwidth_hz (default: the first flexible mode of the full arm);
//   m = number of clamped-free modes w_i of the full PS beam with w_i <= design.reduce_multiple x w_b
//       (default 8), at least 2, at most kArmShiftsMax - 1;
//   shifts = {w_1 / 2, w_1, ..., w_m} (real, rad/s): 4 (m + 1) beam states.
// Each retained flexible mode of the reduced arm is compared with the nearest mode of the full arm;
// a reduction whose relative error on a mode at or below the bandwidth exceeds design.mode_error_max
// (default 1 %) is refused (ArmDesignError naming the mode).
//
// LQG default weights (Table 8.8 scaled to the arm by Bryson's rule with the rated torque as the
// torque scale): S_c = 1, q_low = 5e3 (tau_rated / 95.7 N m)^2, q_high = 1e-2 (tau_rated / 95.7 N m)^2
// on the first n_low = 4 modal coordinates (rigid-body pair and first flexible mode) and the rest; Kalman
// process weights of Table 8.8; measurement covariance S_o from the sensors' noise
// (arm_measurement_covariance). Explicit design.lqg values replace them. The loop is checked on the
// UNREDUCED arm with the document's delays (and on the reduced one).
//
// Spillover ladder (design_arm_lqg): a design is accepted when the unreduced loop's spectral radius is
// at most rho_max = exp(-kArmDecayMin T) and its modulus margin at least kArmModulusMin. Steps,
// in this order, the first accepted one wins:
//   0. the reduction rule and the weights above;
//   1. one more clamped-free beam mode in the Krylov design model per step (shift at that mode), while
//      the beam has one, the Krylov basis keeps its rank and the model fits kArmctrlLqgNmax states: an
//      unmodelled, lightly damped mode (often one above Nyquist, aliased) is what the loop destabilises;
//   2. only with the default weights: q_low, q_high and the Kalman Q_o scaled by each of kArmBackOff on
//      the largest model of step 1 (slower controller and observer, less gain where the model is wrong).
// None accepted: the most stable design is returned with accepted_step = -1 and callers refuse it.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fracdesign/design/armctrl.hpp"
#include "fracdesign/design/lqg.hpp"
#include "fracdesign/design/trajectory.hpp"
#include "fracdesign/models/arm_document.hpp"
#include "fracdesign/tables/ptable.hpp"

namespace fracdesign::design {

struct ArmDesignError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The inverse feedforward's pre-actuation (the backward-in-time part of the
// stable inversion, decaying like exp(sigma (t - t_s)) for the slowest
// non-minimum-phase zero sigma of the arm) is not at rest where the playback
// starts: the move must start later. `lead` [s] is how long before the move's
// start the torque first exceeds kArmctrlRestTol x its peak on the inversion's
// horizon (a lower bound when the horizon itself starts above it).
struct MoveStartTooEarly : std::runtime_error {
    MoveStartTooEarly(const std::string& what, double lead_s) : std::runtime_error(what), lead(lead_s) {}
    double lead;
};

constexpr int kArmShiftsMax = 7;            // 4 x 7 = 28 beam states: the PLC's LQG holds 32
constexpr double kWangRatedTorque = 95.7;   // N m, seed 004 Table G.2 x 160 (notes 004a)
constexpr int kArmctrlLqgNmax = 32;         // plant states the PLC's LQG holds (ARMCTRL_LQG_NMAX, ArmCtrl.h)
// Accepted loop (the stated stability margin):
//  - spectral radius <= exp(-kArmDecayMin T): the slowest closed-loop mode decays with a time constant of
//    at most 1e6 s. This floor is set by the plant, not the controller: a beam mode with no damping in
//    the model (r_r = 0 leaves the shear/rotation modes undamped, r_t = 0 all of them) that the loop
//    barely reaches keeps its eigenvalue within ~1e-8 of the unit circle (seed 004's arm: 1 - 3.8e-9 at
//    41.9 Hz) and no controller moves it far. Moduli that close to 1 are near the resolution of the
//    computed eigenvalues (n eps ||A_cl|| with ||A_cl|| up to ~1e5 in the Krylov coordinates), so the
//    floor decides "not destabilised" (the spillover failures it catches are 1 + 1e-5 .. 1 + 1e-3), and
//    the robustness margin is the second criterion:
//  - min |1 + L| >= kArmModulusMin at the plant input on the unreduced arm: a gain margin of at least
//    -20 log10(1 - 0.25) = 2.5 dB and a phase margin of at least 2 asin(0.125) = 14.4 deg, the margin
//    against the model error that is left once the loop is stable.
constexpr double kArmDecayMin = 1e-6;    // 1/s
constexpr double kArmModulusMin = 0.25;  // min |1 + L|
constexpr double kArmBackOff[] = {1e-1, 1e-2, 1e-3};
double arm_rho_max(double T);

struct ArmModeCompare {
    double full_hz = 0.0, reduced_hz = 0.0, rel_error = 0.0;
};

struct ArmReduction {
    double bandwidth_hz = 0.0;
    std::vector<double> beam_modes_rad_s;  // clamped-free beam modes used for the rule
    std::vector<double> shifts;            // rad/s
    std::vector<double> full_hz;           // flexible modes of the full arm below Nyquist
    std::vector<ArmModeCompare> retained;  // each reduced-arm flexible mode below Nyquist vs the full arm
    double max_error_below_bandwidth = 0.0;
    int full_states = 0, reduced_states = 0;
    int extra_modes = 0;  // beam modes retained beyond the rule (the spillover ladder's step 1)
};

// The shifts by the rule above (plus `extra_modes` further beam modes, as far as the beam and
// kArmShiftsMax allow: extra_modes in the result says how many) and the comparison; throws
// ArmDesignError when refused.
ArmReduction choose_reduction(const ArmDocument& a, int extra_modes = 0);

// S_o = diag(theta_M, theta_M', psi'(z_imu)) of the document: design.lqg.S_o x I_3 when given; else
// sensors.encoder_noise sigma_e gives sigma_e^2 and 2 sigma_e^2 / T^2 (the velocity as the encoder's
// difference quotient), sensors.imu_noise sigma_g gives sigma_g^2; a channel without a noise figure
// (absent or 0) keeps Table 8.8's 1 (the seed's S_o = I_3; the thesis gives no sensor noise).
std::array<double, 3> arm_measurement_covariance(const ArmDocument& a);

// The LQG parameters of the document (default rule or explicit weights), T and delays from it.
LqgParams arm_lqg_params(const ArmDocument& a);

// One step of the spillover ladder.
struct ArmLqgStep {
    std::string rule;        // "default", "2 extra modes in the design model", "weights x 0.01 (...)"
    int extra_modes = 0;     // beam modes beyond the reduction rule
    double back_off = 1.0;   // factor on q_low, q_high, Qo
    int reduced_states = 0;
    bool designed = false;   // false: `note` says why (no further mode, too many states, Riccati, Krylov rank)
    bool accepted = false;   // on the unreduced arm: spectral radius <= rho_max, min |1 + L| >= kArmModulusMin
    double rho_reduced = 0.0, rho_unreduced = 0.0, modulus_unreduced = 0.0;
    std::string note;
};

struct ArmLqg {
    ArmReduction reduction;
    StateSpace reduced, full;  // measured models (tau_M -> theta_M, theta_M', psi'(z_imu))
    LqgDesign lqg;
    LoopCheck check_reduced, check_unreduced;  // both with the document's delays
    std::vector<ArmLqgStep> steps;             // every step tried, in order
    int accepted_step = -1;                    // index into steps; -1: none accepted (this is the most stable)
    double rho_max = 1.0;
    bool accepted() const { return accepted_step >= 0; }
};

// The spillover ladder above. Throws ArmDesignError (the document's reduction refused, n_low too large)
// or RiccatiError (no step's Riccati equations solvable: the default step's cause); an unaccepted loop is
// accepted_step = -1.
ArmLqg design_arm_lqg(const ArmDocument& a);
// One line for a design none of whose steps was accepted: each step's unreduced spectral radius.
std::string arm_lqg_refusal(const ArmDocument& a, const ArmLqg& r);
// {"criterion", "rho_max", "accepted", "accepted_rule", "stability_margin" (1 - rho), "steps": [...]}.
nlohmann::json arm_lqg_rule_json(const ArmLqg& r);

// A move of the tip: consecutive sin^2 segments (seed 004 (4.1)-(4.7)); each goes from the previous
// end angle to q_end, starting at t_start and taking `duration`, with t_a = duration / 3 so that
// (4.3) gives exactly that duration (qd_m = 1.5 s_e / duration, qdd_m = 9 s_e / duration^2; Table 8.5
// is q 0 -> pi/2 from 0.5 s in 1.5 s). Or a CSV tip reference (columns t, q; uniform t, sampled finer than
// the controller) whose derivatives are taken by central differences of a 5-point stencil.
class Move {
public:
    struct Segment {
        double q_end, t_start, duration;
    };
    // "Q0:Q1@T0+DUR[,Q2@T1+DUR...]" (angles rad, times s), e.g. "0:1.0@0.5+1.5,0.2@2.5+1.0".
    static Move parse(const std::string& spec);
    static Move from_csv(const std::string& path);
    Move(double q0, const std::vector<Segment>& segs);
    double t_start() const { return t0_; }
    double t_end() const { return t1_; }
    double q_start() const { return q0_; }
    // q and its derivatives 1..4 at time t (held before and after).
    std::array<double, 5> eval(double t) const;
    std::string describe() const;

private:
    Move() = default;
    double q0_ = 0.0, t0_ = 0.0, t1_ = 0.0;
    std::vector<SinSquaredPtp> ptp_;
    std::vector<double> csv_t_, csv_q_;
};

enum class FfKind { Rigid, Inverse };

// The ArmCtrl table of variant D (LQG with delays, Sec. 8.6 shifts; variant C when d_i = d_o = 0) for
// the arm and move, feedforward rigid-body (4.14)-(4.17) on the document's rigid-link inertia or by
// stable inversion of the reduced arm (ibffc.hpp). Table layout as design_armctrl (armctrl.hpp).
struct ArmctrlForArm {
    ArmLqg lqg;
    ArmctrlDesign d;
};
ArmctrlForArm design_armctrl_for_arm(const ArmDocument& a, const Move& m, FfKind ff, double post = 2.0);

// The HIL plant table `arm_plant` of the full arm at step h (docs/hil.md): C = [theta_M; theta_M';
// psi(z_imu); psi'(z_imu)] with the checks of the seed arm's table (C_3 A = C_4, C_3 B = 0).
tables::ParamTable arm_plant_table_for(const ArmDocument& a, double h);

// The step entries of a HIL plant table (docs/hil.md) for the continuous single-input arm `one`
// at step h: h; Ad, Bd, the exact ZOH (c2d_zoh, seed 004 (7.3)-(7.7)); Bd1 = int_0^h e^{A (h - r)} B
// (r - h/2) dr, the exact response to the drive's torque ramp about its mid-step value per unit slope
// (= (h/2) (B_now - B_prev) of c2d_foh), with which the rig integrates the ramp exactly; Ac, Bc.
void add_arm_plant_steps(tables::ParamTable& t, const StateSpace& one, double h);

// The HIL IMU's reading period for the document's d_o, in acquisitions (T/2 each): r = 2 max(1, d_o - 1),
// a reading every r/2 cycles sent r/2 cycles after its sample (arm_hil_scenario's imu.reading_cycles).
int arm_imu_reading_cycles(const ArmDocument& a);

// The gap nominal (docs/gap.md, frac.model statespace) of the rig's record: the full arm, open loop from
// the drive's torque_actual to motor_velocity and imu_rate, first-order hold at T (the drive ramps its
// torque from the previous torque_actual, state torque_prev), imu_rate the mean of the link rate h .. 2h - 1
// cycles old, h = arm_imu_reading_cycles / 2 (the reading's ages through its hold; exact for h = 1),
// gap.velocity motor_velocity, gap.force_input torque_actual.
nlohmann::json arm_gap_nominal(const ArmDocument& a);

// What the HIL rig can emulate (hil/imu.h reading_cycles 1..8 with d_o = reading_cycles / 2 + 1 for even
// values; hil/drive.h encoder_bits 1..20).
constexpr int kRigImuDoMin = 2, kRigImuDoMax = 5, kRigEncoderBitsMax = 20;

// The closed-loop gap nominal: ArmCtrl from the parameter table `table` (a file name, relative to the
// nominal document) as gap.closed_loop.controller kind "armctrl" (replayed by gap-plc, which runs the
// program in the PLC task runtime; design_tools only names the table), inputs MotorAngle, MotorVelocity,
// TipRate from the model outputs motor_angle, motor_velocity, imu_rate, output torque_cmd; the drive as
// the rig's (hil/drive.h): delay d_i (delay_samples), peak torque (saturation), current loop of tau_c
// as a state (torque_actual) and a first-order hold to the shaft; the IMU as arm_gap_nominal's (its
// reading's ages as states, imu_rate their phase mean) plus gap.output_hold: imu_rate reads
// imu_rate_sample (h cycles old) every h cycles and holds it; friction on the shaft through the second
// input friction_torque (gap.friction_input, zero-order hold).
nlohmann::json arm_gap_nominal_closed(const ArmDocument& a, const std::string& table);

// hil_bench scenario lines for the arm (T, plant = arm, drive delay/limits/current loop/encoder, IMU
// reading period for d_o, noise, friction). `plant_table`, `ctrl_table`: file names; duration in s.
// Throws ArmDocumentError naming delays.output outside [kRigImuDoMin, kRigImuDoMax] or
// sensors.encoder_counts_per_rev that is not 2^bits with bits <= kRigEncoderBitsMax.
std::string arm_hil_scenario(const ArmDocument& a, const std::string& plant_table, const std::string& ctrl_table,
                             double duration);

}  // namespace fracdesign::design
