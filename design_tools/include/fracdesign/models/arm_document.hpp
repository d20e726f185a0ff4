// arm_document.hpp - the user's arm as one JSON document (`"schema": "frac.arm"`, version 1, SI units;
// docs/arm_format.md). Everything for that arm is derived from it: the port-Hamiltonian model
// (models/arm.hpp), the reduced model, the LQG and feedforward, the PLC and HIL tables and the gap
// nominal (design/arm_design.hpp). Nothing here is specific to one arm; the seed 004 arm is the
// document docs/examples/arm_wang/arm.json.
//
// The link is the Timoshenko beam of seed 004 Sec. 3.3 given either by material and section
// (E, G or Poisson's ratio, rho, kappa; rectangular width x thickness bending about the thickness, or
// area and second moment) or directly per length (EI, GA = kappa G A, rhoA, rhoI). An Euler-Bernoulli
// link is the Timoshenko model in its shear-rigid limit (kEbShear, kEbRotary below).
// The tip payload (mass m, rotary inertia J about the tip) is bolted to the beam tip through a mount
// of stiffness k_w (translation) and k_psi (rotation): the beam's tip ports are forces (3.91), so a
// rigid mass would be a causality conflict; the mount makes it the PH system of payload_model with its
// own mode at mount_hz (default kMountPerNyquist x the Nyquist frequency, far above the controller).
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fracdesign/models/arm.hpp"
#include "fracdesign/models/timoshenko_beam.hpp"

namespace fracdesign {

constexpr const char* kArmSchema = "frac.arm";
constexpr int kArmVersion = 1;

// A bad arm document: what() is one line "arm: field 'F': value V: allowed RANGE" (or the problem).
struct ArmDocumentError : std::runtime_error {
    ArmDocumentError(const std::string& field, const std::string& problem);
    std::string field;
};

// Bounds of the document (docs/arm_format.md gives the same table).
constexpr int kArmNMin = 4, kArmNMax = 200;         // design.N, collocation points
constexpr int kArmDelayMax = 40;                     // delays.input / delays.output [samples]
constexpr double kArmTMin = 1e-5, kArmTMax = 0.1;    // sample_time [s]
// Euler-Bernoulli link as the Timoshenko model's limit: GA = kEbShear EI / L^2, rhoI = kEbRotary rhoA L^2.
// Mode i then differs from Euler-Bernoulli by about (beta_i L)^2 / (2 kEbShear) + kEbRotary (tested).
constexpr double kEbShear = 1e5, kEbRotary = 1e-7;
// Default payload mount mode: this multiple of the Nyquist frequency pi/T.
constexpr double kMountPerNyquist = 20.0;
// Damping ratio of the payload mount mode (a damper in parallel with each mount spring).
constexpr double kMountZeta = 0.05;

struct ArmFriction {
    bool known = false;
    double b1 = 0.0;   // viscous [N m s/rad] (seed 004 (5.2))
    double b0 = 0.0;   // Coulomb [N m]
    double k = 60.0;   // tanh smoothing of sgn [s/rad]
};

struct ArmDesignSection {
    int N = 9;                  // collocation points of the full model
    double bandwidth_hz = 0.0;  // controller bandwidth; 0: the first flexible mode of the full arm
    double reduce_multiple = 8.0;   // reduction keeps the beam modes up to this multiple of the bandwidth
    double mode_error_max = 0.01;   // refuse a reduction whose relative frequency error below the bandwidth is larger
    bool reduce = true;
    // LQG weights: <= 0 means "by the default rule" (docs/arm_format.md, design/arm_design.hpp)
    int n_low = 4;
    double q_low = 0.0, q_high = 0.0, q_delay = 0.0, s_c = 0.0;
    double qo_drive = 1e-4, qo_beam = 1e-4, qo_delay = 1e-4, qo_dist = 1e4;
    double s_o = 0.0;  // > 0: S_o = s_o I_3; 0: from the sensors' noise (arm_measurement_covariance)
};

struct ArmDocument {
    std::string name;
    bool timoshenko = true;
    TimoshenkoParams beam;  // per-length parameters and damping (r_t, r_r)
    double payload_mass = 0.0, payload_inertia = 0.0;  // [kg], [kg m^2] about the tip
    double mount_k_w = 0.0, mount_k_psi = 0.0;          // payload mount stiffness [N/m], [N m/rad] (derived if absent)
    DriveParams drive;                                  // I_M, I_h (hub), c_s, r_h, d_s
    double torque_rated = 0.0, torque_peak = 0.0;       // driven side [N m]
    double current_tau = 0.0;                           // current loop time constant [s]
    long encoder_counts = 1L << 20;                     // per revolution
    double imu_position = 0.0;                          // along the link from the hub end [m], (0, L]
    double imu_noise = 0.0, encoder_noise = 0.0;        // gyro [rad/s], encoder [rad] (std)
    double T = 1e-3;                                    // sample time [s]
    int di = 0, dout = 0;                               // input / IMU output delay [samples]
    ArmFriction friction;
    ArmDesignSection design;

    // Rigid-link inertia about the hub axis: I_h + rhoA((L + r_h)^3 - r_h^3)/3 + rhoI L + m (L + r_h)^2 + J.
    double rigid_link_inertia() const;
};

// Reads and validates (every field: type, finiteness, range; one message naming field, value, range).
ArmDocument arm_from_json(const nlohmann::json& j);
ArmDocument read_arm_file(const std::string& path);
// Writes the document in per-length form (round trip: arm_from_json(arm_to_json(a)) == a).
nlohmann::json arm_to_json(const ArmDocument& a);

// The payload with its mount as a PH system, states [d_w, d_psi, p_m, p_J] (mount deflections, payload
// momenta), input the beam tip velocities [w'(L); psi'(L)], output the mount forces [-F_w; -M_psi]:
//   Q = diag(k_w, k_psi, 1/m, 1/J), J = [[0, I2], [-I2, 0]], B = [[-I2]; [0]].
// A payload with J = 0 (or m = 0) drops that half (2 states). Coupled by couple_payload.
PhSystem payload_model(const ArmDocument& a);

// Couples a beam (4 boundary inputs) to the payload at its tip: u_p = y_b^L, u_b^L = -y_p (power
// preserving; no algebraic loop since the payload has no feedthrough and the beam's D does not map
// u^L to y^L). The result has the beam's two hub inputs only (its tip inputs are closed) plus zero
// columns for Q_s(L), M_b(L) so couple_arm applies unchanged. Payload states follow the beam's.
PhSystem couple_payload(const PhSystem& beam, double sigma, const PhSystem& payload);

struct ArmBuild {
    PsBeam beam;          // full PS beam at N
    PhSystem beam_used;   // the beam alone, Krylov-reduced when reduced
    Eigen::MatrixXd V;    // beam state ~ V x_r (identity when full)
    bool payload = false;
    PhSystem link_used;   // beam_used (+ payload)
    PhSystem arm;         // drive (4 states) + link_used
    std::vector<double> shifts;  // Krylov shifts used [rad/s] (empty when full)
};

// The arm at N (full: reduce = false) with the given Krylov shifts for the beam (ignored when full).
ArmBuild build_arm_from_document(const ArmDocument& a, int N, bool reduce, const std::vector<double>& shifts);

// Rows c of the arm state with psi'(z) = c x and psi(z) = c x, z in (0, L]:
//  - psi'(z), the effort e_r = p_r / rho_I on the effort basis reconstructed with its hub value
//    psi'(0) = theta_h' (the closed form behind (3.87): e = P0 f + p0 u(0), [P0 | p0] = [M^T; w^e(0)^T]^-1);
//    at z = L it equals the port output psi'(L) (tested);
//  - psi(z) = theta_h + int_0^z eps_r dz (the beam clamped in the hub), eps_r on the flow basis.
// On a reduced build the full-beam row is projected, c V (Galerkin: x ~ V x_r).
Eigen::RowVectorXd arm_rate_row(const ArmBuild& b, double z);
Eigen::RowVectorXd arm_angle_row(const ArmBuild& b, double z);

// Measured model (1 input tau_M, outputs theta_M, theta_M', psi'(z_imu)). At the tip the port output
// psi'(L) = B_bL^T Q_b x_b - sigma theta_h' of the beam in use (3.92), (3.95); inside the link arm_rate_row.
StateSpace arm_document_measured(const ArmDocument& a, const ArmBuild& b);

}  // namespace fracdesign
