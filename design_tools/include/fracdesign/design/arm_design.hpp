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
// weights of Table 8.8. Explicit design.lqg values replace them. The loop is checked on the UNREDUCED
// arm with the document's delays (and on the reduced one).
#pragma once
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

constexpr int kArmShiftsMax = 7;            // 4 x 7 = 28 beam states: the PLC's LQG holds 32
constexpr double kWangRatedTorque = 95.7;   // N m, seed 004 Table G.2 x 160 (notes 004a)

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
};

// The shifts by the rule above and the comparison; throws ArmDesignError when refused.
ArmReduction choose_reduction(const ArmDocument& a);

// The LQG parameters of the document (default rule or explicit weights), T and delays from it.
LqgParams arm_lqg_params(const ArmDocument& a);

struct ArmLqg {
    ArmReduction reduction;
    StateSpace reduced, full;  // measured models (tau_M -> theta_M, theta_M', psi'(z_imu))
    LqgDesign lqg;
    LoopCheck check_reduced, check_unreduced;  // both with the document's delays
};

// Throws ArmDesignError (reduction refused or unreduced loop unstable) or RiccatiError.
ArmLqg design_arm_lqg(const ArmDocument& a);

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

// The HIL IMU's reading period for the document's d_o, in acquisitions (T/2 each): r = 2 max(1, d_o - 1),
// a reading every r/2 cycles sent r/2 cycles after its sample (arm_hil_scenario's imu.reading_cycles).
int arm_imu_reading_cycles(const ArmDocument& a);

// The gap nominal (docs/gap.md, frac.model statespace) of the rig's record: the full arm, open loop from
// the drive's torque_actual to motor_velocity and imu_rate, first-order hold at T (the drive ramps its
// torque from the previous torque_actual, state torque_prev), imu_rate the mean of the link rate h .. 2h - 1
// cycles old, h = arm_imu_reading_cycles / 2 (the reading's ages through its hold; exact for h = 1),
// gap.velocity motor_velocity, gap.force_input torque_actual.
nlohmann::json arm_gap_nominal(const ArmDocument& a);

// hil_bench scenario lines for the arm (T, plant = arm, drive delay/limits/current loop/encoder, IMU
// reading period for d_o, noise, friction). `plant_table`, `ctrl_table`: file names; duration in s.
std::string arm_hil_scenario(const ArmDocument& a, const std::string& plant_table, const std::string& ctrl_table,
                             double duration);

}  // namespace fracdesign::design
