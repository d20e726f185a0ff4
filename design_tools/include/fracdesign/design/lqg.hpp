// lqg.hpp - seed 004 (Wang, PhD thesis) state-difference LQG with an integrating
// friction-disturbance state and input/output delays (Ch. 6-7, Exp. C and D).
//
// Plant: the arm (models/arm.hpp) with input tau_M and the measured outputs of the
// thesis (footnote 23) y = [theta_M, theta_M', psi'(L)]; the IMU channel psi'(L) is the
// one delayed by d_o samples, the torque path by d_i samples (7.1)-(7.2).
// Design, all in the difference coordinates e = x* - x (6.36), (7.19):
//  1. ZOH at T (7.3)-(7.7);
//  2. delay augmentation n -> n + d_i + d_o (7.18): x_bar = [x; xi; beta], the torque
//     delay line xi with the fictitious friction input E_xi = [0 .. 0 -1]' (7.10)-(7.11)
//     and the IMU delay line beta (7.14)-(7.15) (indices d_o throughout, notes 004b 7.4);
//     without delays the friction enters at the torque input, E = -B' (e_z = -tau_f, so
//     +e_z_hat in the control compensates it);
//  3. controller: dlqr on (A_bar, B_bar) with Q_bar = blockdiag(Q_c, Q_c^xi_beta), R = S_c
//     (7.22)-(7.24); Q_c from modal weights (8.2)-(8.5), see modal_basis;
//  4. observer: the integrating disturbance e_s[k+1] = e_s[k] (7.25, a_s = 1: the printed 0
//     in (7.26) is the erratum the notes list), A_e = [[A_bar, E_bar], [0, 1]],
//     C_e = [C_bar, 0]; predictor Kalman gain L_e = A_e P C_e' (S_o + C_e P C_e')^-1 from the
//     dual DARE (7.27);
//  5. control law (7.21): u = u* + K e_x_hat - e_z_hat, i.e. e_u = -K e_x_hat + e_z_hat.
#pragma once
#include <Eigen/Dense>
#include <array>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "fracdesign/design/riccati.hpp"
#include "fracdesign/models/arm.hpp"

namespace fracdesign::design {

// Measured model of the arm: input tau_M, outputs [theta_M, theta_M', psi'(L)].
StateSpace arm_measured_model(const PhSystem& arm);

// Real modal basis V of A (modal weighting convention of this project, seed 004 (8.2)-(8.5)):
//  - modes ordered by |lambda| ascending (the rigid-body mode first, then flexible modes by
//    frequency); a complex pair sigma +- j omega with eigenvector a +- j b (unit 2-norm, as
//    MATLAB eig) contributes the columns [a, b] (real modal form);
//  - a real eigenvalue contributes its unit eigenvector; when the two smallest modes are both
//    real (the rigid-body mode damped by r_t > 0: 0 and -0.047 rad/s, nearly parallel
//    eigenvectors), the second column is made orthogonal to the first and normalised, so the
//    pair is an orthonormal basis of its invariant subspace (angle, velocity), as the Jordan
//    chain below for r_t = 0 (weights continuous in r_t; see docs/armctrl_tables.md);
//  - when the eigenvectors are (numerically) dependent — the undamped rigid-body double
//    zero eigenvalue — the two smallest modes are replaced by the Jordan chain v1 = null(A),
//    A v2 = v1 (least squares), each normalised to unit 2-norm.
// Modal coordinates sigma = V^-1 x; Q_c = V^-T Q_tilde V^-1 (8.5).
Eigen::MatrixXd modal_basis(const Eigen::MatrixXd& A);

// The delays of the thesis's rig (Sec. 7.1, Table 8.8): torque path PLC -> ACOPOS T_i = 4 T = 4.8 ms,
// IMU -> PLC T_o = 3 T = 3.6 ms. They are a property of the plant, whatever delay model the
// controller has: Exp. C (no delay model) ran on the same rig.
constexpr int kRigDi = 4, kRigDo = 3;

struct LqgParams {
    double T = 1.2e-3;  // sample time [s] (Table 8.8)
    int di = 4, dout = 3;  // input and IMU output delays [samples]
    int n_low = 4;         // modal coordinates weighted with q_low (the "first and second eigenmodes")
    double q_low = 5e3, q_high = 1e-2;  // Q_tilde_c^l, Q_tilde_c^h (Table 8.8)
    double q_delay = 0.0;               // Q_c^xi_beta = q_delay I (Table 8.8: 0)
    double s_c = 1.0;                   // S_c
    double qo_drive = 1e-4, qo_beam = 1e-4, qo_delay = 1e-4, qo_dist = 1e4;  // Kalman Q_o blocks (Table 8.8)
    // S_o = diag(s_o), the measurement covariance of (theta_M, theta_M', psi'(z)) (Table 8.8: I_3)
    std::array<double, 3> s_o{1.0, 1.0, 1.0};
    // Table 8.7 (Exp. C, no delay) and Table 8.8 (Exp. D) presets.
    static LqgParams exp_c();
    static LqgParams exp_d();
};

struct LqgDesign {
    LqgParams params;
    StateSpace plant;             // continuous measured model used for the design
    Eigen::MatrixXd Ad, Bd, Ed, Cd;  // delay-augmented discrete difference model (7.18)
    Eigen::MatrixXd Ae, Be, Ce;      // with the disturbance state (7.26), a_s = 1
    Eigen::MatrixXd Qc, Qbar, Qo, So;
    Eigen::MatrixXd K;   // 1 x (n + d_i + d_o)
    Eigen::MatrixXd Le;  // (n + d_i + d_o + 1) x 3
    RiccatiSolution ctrl, obs;
};

// Throws RiccatiError naming the cause, std::invalid_argument on bad parameters.
LqgDesign design_lqg(const StateSpace& plant, const LqgParams& p);

// Delay augmentation (7.18) of a discrete model with one input and 3 outputs (the last delayed).
void delay_augment(const Eigen::MatrixXd& Ad, const Eigen::MatrixXd& Bd, const Eigen::MatrixXd& Cd, int di, int dout,
                   Eigen::MatrixXd& A, Eigen::MatrixXd& B, Eigen::MatrixXd& E, Eigen::MatrixXd& C);

struct LoopCheck {
    double spectral_radius = 0.0;  // closed loop (plant + delays + observer-based controller)
    double critical_w = 0.0;       // |arg z| / T of the eigenvalue of largest modulus [rad/s] (aliased)
    double gain_margin_db = 0.0;   // at the plant input: smallest |20 log10 |L|| over the -180 deg
                                   // crossings (+inf if the phase never crosses -180)
    double phase_margin_deg = 0.0; // smallest over the crossovers
    double modulus_margin = 0.0;   // min |1 + L(e^{j w T})|
    int plant_states = 0;
    int plant_di = 0, plant_do = 0;  // delays of the plant the loop was closed around
};

// Closes the loop of `d` around `plant` (continuous measured model, possibly the unreduced
// arm), discretised with ZOH at T and delay-augmented with the plant's delays plant_di, plant_do
// (< 0: the design's d_i, d_o). The controller keeps its own delay model: Exp. C (no delay
// model) checked on the rig's delays is plant_di = 4, plant_do = 3 with d.params.di = do = 0.
// Margins: the loop L = -C(z) P(z) on a log grid over (0.1, pi/T) rad/s plus, for every plant
// pole with |z| > 0.9, points at its (aliased) frequency |arg z|/T and +-(1, 2, 4, 8, 16) times
// its half-power width (1 - |z|)/T, so lightly damped beam modes (zeta ~ 1e-6) are resolved.
LoopCheck check_closed_loop(const LqgDesign& d, const StateSpace& plant, int plant_di = -1, int plant_do = -1);

nlohmann::json to_json(const LqgDesign& d);
// A loop check with "stable" (spectral radius < 1); non-finite margins as null.
nlohmann::json to_json(const LoopCheck& c);

}  // namespace fracdesign::design
