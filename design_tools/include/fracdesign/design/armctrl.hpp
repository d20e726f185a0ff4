// armctrl.hpp - the parameter table of the PLC program ArmCtrl (plc_blocks/programs/ArmCtrl.h)
// for seed 004 (M. Wang, PhD thesis) Exp. A-D (Table 8.1):
//   A  rigid-body feedforward (4.14)-(4.17) + PD (5.1) + linear friction (5.2), Table 8.6;
//   B  inversion-based feedforward (Sec. 4.3, ibffc.hpp) + PD + friction, Table 8.6;
//   C  ibFFC + state-difference LQG with the friction state (6.45), Table 8.7, no delay model;
//   D  ibFFC + LQG with the delay model (7.18)-(7.27), Table 8.8, and the feedforward time shifts of
//      Sec. 8.6: torque sent d_i cycles early (lead +d_i), IMU reference delayed d_o cycles (lead -d_o).
// Trajectory: the sin^2 PTP of Table 8.5 (trajectory.hpp) in the run-time counter's time (the counter
// starts at 0 on the Start edge; the motion nominally runs from t_s = 0.5 s to t_e = 2 s).
//
// Table layout (ArmCtrl.h, above armctrl_params_from_table), name "armctrl", in this order:
//   variant 1x1, ts 1x1, ff 4xN (theta_M*, theta_M*', psi'(L)*, tau_M*), ff_grid 1x4 (T0, Dt, motion
//   start, motion end), ff_lead 1x4, torque_limit 1x1, watchdog 1x2; A/B: pd 1x2, friction 1x3;
//   C/D: lqg_dims 1x5 (n, d_i, d_o of theta_M, theta_M', psi'(L) = 0, 0, d_o), A nxn, B nx1, C 3xn
//   (the ZOH plant A', B', C' (7.3)-(7.7)), K 1xn_bar (7.24), L (n_bar+1)x3 (7.27), which is the
//   convention of libfrac's frac_lqg_step (frac/lqg.h) and the design of `fracdesign lqg`
//   (design_lqg, the same code).
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fracdesign/design/ibffc.hpp"
#include "fracdesign/design/lqg.hpp"
#include "fracdesign/design/trajectory.hpp"
#include "fracdesign/tables/ptable.hpp"

namespace fracdesign::design {

struct ArmctrlSpec {
    char exp = 'A';           // 'A'..'D'
    int N = 9;                // beam collocation points (Table 8.4), kArmctrlNMin..kArmctrlNMax
    double r_t = 0.5, r_r = 0.0;  // beam damping (not given by the thesis; notes 004b 1.2), project choice
    int di = -1, dout = -1;   // Exp. D delays [cycles]; -1: Table 8.8 (4, 3). Exp. C: 0 (no delay model)
    double T = 1.2e-3;        // cycle time [s] (Table 8.8, Ch. 2)
    double torque_limit = 250.0;  // |tau| [N m]: thesis [GAP]; the drive's peak is about 251 N m
    int wd_stale = 2;             // watchdog: max stale cycles
    double wd_ramp = 25000.0;     // watchdog: ramp to zero [N m/s]: the 250 N m limit to 0 in 10 ms (issue 9 fault reaction)
    double pre = 2.0, post = 2.5; // stable inversion horizon before t_s and after t_e [s] (thesis [GAP])
    PtpSpec traj{0.0, 1.5707963267948966, 1.5707963267948966, 6.283185307179586, 0.5, 2.0};  // Table 8.5
    // Validates; throws std::invalid_argument with a message naming the option.
    void validate() const;
};

// N = 4 gives a 16-state beam, which the 3-shift Krylov reduction to 12 states (Table 8.4) cannot span.
constexpr int kArmctrlNMin = 5, kArmctrlNMax = 24;
// |tau_M*| / max|tau_M*| accepted as "at rest" where the playback starts (cycle 0 and the leads): the
// backward-in-time part of the stable inversion decays like exp(25.9 (t - t_s)) (the real zero pair
// +-25.9 rad/s of the inverse dynamics, notes 004b 4.2), about 1e-6 of the peak at t_s - 0.5 s.
constexpr double kArmctrlRestTol = 1e-5;

struct ArmctrlDesign {
    ArmctrlSpec spec;
    int variant = 0;
    double t0 = 0.0, dt = 0.0, t_motion_start = 0.0, t_motion_end = 0.0;
    std::array<long, 4> lead{0, 0, 0, 0};
    std::array<std::vector<double>, 4> ff;  // rows theta_M*, theta_M*', psi'(L)*, tau_M* on t0 + k dt
    double tau_max = 0.0;
    double pre_actuation_start = 0.0;  // first table time with |tau_M*| > 1e-3 max|tau_M*| [s]
    double head_tau_max = 0.0;         // max |tau_M*| of the inversion before the table's first sample
    double start_tau = 0.0;            // max |tau_M*| played at rest (cycle 0, with the leads)
    double tail_step = 0.0;            // max over rows of |last - second-to-last sample| (rest at the end)
    // Exp. B-D: the stable inversion (tracking check through the sampled model)
    std::optional<IbffcResult> ibffc;
    // Exp. C/D: the LQG design and the entries taken from it
    std::optional<LqgDesign> lqg;
    LoopCheck check_reduced, check_unreduced;
    Eigen::MatrixXd A, B, C, K, L;
    double I_l = 0.0;  // Exp. A rigid link inertia [kg m^2]
    double kp = 0.0, kd = 0.0;                // Exp. A/B PD (5.1)
    double fr_b1 = 0.0, fr_b0 = 0.0, fr_k = 0.0;  // Exp. A/B friction compensation (5.2)
    tables::ParamTable table;
};

// Builds d.table (entries in the order of ArmCtrl.h) from the filled design: spec (exp, T, torque limit,
// watchdog), ff rows and grid, leads, and the PD/friction (A/B) or LQG matrices (C/D); meta "source".
void armctrl_fill_table(ArmctrlDesign& d, const std::string& source);
// The LQG entries of the table from a design (frac/lqg.h's convention): A', B', C' of (7.18), K, L_e.
void armctrl_take_lqg(ArmctrlDesign& d, const LqgDesign& g);

// Rigid link inertia I_l = I_h + I_b with I_b = rho((L + r_h)^3 - r_h^3)/3 of the Table 8.3 beam
// (the thesis gives no I_b; notes 004b section 3).
double wang_rigid_link_inertia();

// The measured arm model (arm_measured_model) of the steel beam with damping r_t, r_r and N points.
StateSpace wang_arm_measured(int N, double r_t, double r_r, bool reduce);

// Designs everything and builds the table. Throws std::invalid_argument for a bad spec, RiccatiError
// when a Riccati equation has no stabilising solution, std::runtime_error when the feedforward does not
// start at rest at the table's first sample (pre-actuation longer than t_s allows).
ArmctrlDesign design_armctrl(const ArmctrlSpec& spec);

}  // namespace fracdesign::design
