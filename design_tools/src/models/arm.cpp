// arm.cpp - 2-mass drive and the drive + beam coupling of seed 004 (Sec. 3.2, 3.6).
#include "fracdesign/models/arm.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "fracdesign/models/krylov.hpp"

namespace fracdesign {

void DriveParams::validate() const
{
    auto pos = [](double v, const char* name) {
        if (!std::isfinite(v) || v <= 0) throw std::invalid_argument(std::string("drive: ") + name + " must be finite and > 0");
    };
    pos(I_M, "I_M");
    pos(I_h, "I_h");
    pos(c_s, "c_s");
    if (!std::isfinite(r_h) || r_h < 0) throw std::invalid_argument("drive: r_h must be finite and >= 0");
    if (!std::isfinite(d_s) || d_s < 0) throw std::invalid_argument("drive: d_s must be finite and >= 0");
}

DriveParams wang_drive()
{
    DriveParams d;
    d.I_M = 160.0 * 160.0 * 2.29e-4;  // (3.30) I_M = n^2 I_m, n = 160, I_m = 2.29e-4 (Table 8.2 / G.2)
    d.I_h = 1.69e-4;                  // Table 8.2
    d.c_s = 5e4;                      // Table 8.2
    d.r_h = 0.025;                    // Table 8.2
    return d;
}

PhSystem drive_model(const DriveParams& d)
{
    d.validate();
    PhSystem ph;
    ph.Q = Eigen::MatrixXd::Zero(4, 4);  // (3.34)
    ph.Q(0, 0) = ph.Q(1, 1) = d.c_s;
    ph.Q(0, 1) = ph.Q(1, 0) = -d.c_s;
    ph.Q(2, 2) = 1.0 / d.I_M;
    ph.Q(3, 3) = 1.0 / d.I_h;
    ph.J = Eigen::MatrixXd::Zero(4, 4);  // (3.35)
    ph.J.topRightCorner(2, 2).setIdentity();
    ph.J.bottomLeftCorner(2, 2) = -Eigen::Matrix2d::Identity();
    // Gear damping d_s on the twist rate theta_M' - theta_h' (co-energies 1/I_M p_M, 1/I_h p_h):
    // R_pp = d_s [[1, -1], [-1, 1]] >= 0, so the PH power balance holds with this dissipation.
    ph.R = Eigen::MatrixXd::Zero(4, 4);
    ph.R(2, 2) = ph.R(3, 3) = d.d_s;
    ph.R(2, 3) = ph.R(3, 2) = -d.d_s;
    ph.B = Eigen::MatrixXd::Zero(4, 3);
    ph.B(2, 0) = 1.0;
    ph.B(3, 1) = d.r_h;
    ph.B(3, 2) = 1.0;
    ph.D = Eigen::MatrixXd::Zero(3, 3);
    ph.inputs = {"tau_M [N m]", "-Q_h [N]", "-M_h [N m]"};
    ph.outputs = {"theta_M_dot [rad/s]", "v_h [m/s]", "theta_h_dot [rad/s]"};
    ph.states = {"theta_M [rad]", "theta_h [rad]", "p_M [N m s]", "p_h [N m s]"};
    return ph;
}

PhSystem couple_arm(const PhSystem& drive, const PhSystem& beam, double sigma)
{
    if (drive.J.rows() != 4 || drive.B.cols() != 3) throw std::invalid_argument("arm: drive must be the 4-state, 3-input model");
    if (beam.B.cols() != 4) throw std::invalid_argument("arm: beam must have the 4 boundary inputs");
    if (std::fabs(std::fabs(sigma) - 1.0) > 1e-9) throw std::invalid_argument("arm: sigma must be +1 or -1");
    const Eigen::Index na = 4, nb = beam.J.rows(), n = na + nb;
    const Eigen::MatrixXd Ba1 = drive.B.col(0), Ba2 = drive.B.rightCols(2);
    const Eigen::MatrixXd Bb0 = beam.B.leftCols(2), BbL = beam.B.rightCols(2);
    // Interconnection (3.100): u_a2 = -y_b^0, u_b^0 = y_a2, with y_b^0 = B_b0^T e_b + sigma u_b^L
    // (3.101); (3.102) prints grad H_a where grad H_b belongs and omits R_b (notes 004a erratum 10).
    PhSystem arm;
    arm.J = Eigen::MatrixXd::Zero(n, n);
    arm.J.topLeftCorner(na, na) = drive.J;
    arm.J.topRightCorner(na, nb) = -Ba2 * Bb0.transpose();
    arm.J.bottomLeftCorner(nb, na) = Bb0 * Ba2.transpose();
    arm.J.bottomRightCorner(nb, nb) = beam.J;
    arm.R = Eigen::MatrixXd::Zero(n, n);
    arm.R.topLeftCorner(na, na) = drive.R;
    arm.R.bottomRightCorner(nb, nb) = beam.R;
    arm.Q = Eigen::MatrixXd::Zero(n, n);
    arm.Q.topLeftCorner(na, na) = drive.Q;
    arm.Q.bottomRightCorner(nb, nb) = beam.Q;
    // (3.103): inputs [tau_M; Q_s(L); M_b(L)], y = B^T grad H (no feedthrough left)
    arm.B = Eigen::MatrixXd::Zero(n, 3);
    arm.B.block(0, 0, na, 1) = Ba1;
    arm.B.block(0, 1, na, 2) = -sigma * Ba2;
    arm.B.block(na, 1, nb, 2) = BbL;
    arm.D = Eigen::MatrixXd::Zero(3, 3);
    arm.inputs = {"tau_M [N m]", "Q_s(L) [N]", "M_b(L) [N m]"};
    arm.outputs = {"theta_M_dot [rad/s]", "w_dot(L) [m/s]", "psi_dot(L) [rad/s]"};
    arm.states = drive.states;
    arm.states.insert(arm.states.end(), beam.states.begin(), beam.states.end());
    return arm;
}

ArmModel build_arm(const TimoshenkoParams& beam, const DriveParams& drive, const ArmOptions& opt)
{
    ArmModel m;
    m.beam = build_ps_beam(beam, opt.N, opt.collocation);
    m.beam_used = opt.reduce ? krylov_reduce(m.beam.ph, opt.shifts) : m.beam.ph;
    m.arm = couple_arm(drive_model(drive), m.beam_used, m.beam.sigma);
    return m;
}

}  // namespace fracdesign
