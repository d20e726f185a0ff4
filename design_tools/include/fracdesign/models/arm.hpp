// arm.hpp - the single-link flexible arm of seed 004: the 2-mass drive (Sec. 3.2) coupled to the PH
// Timoshenko beam through the power-preserving interconnection (3.100)-(3.103).
//
// Drive state x_a = [theta_M; theta_h; p_M; p_h] (rad, rad, N m s, N m s), eqs. (3.29)-(3.36):
//   Q_a = [[c_s, -c_s, 0, 0], [-c_s, c_s, 0, 0], [0, 0, 1/I_M, 0], [0, 0, 0, 1/I_h]],
//   J_a = [[0, I2], [-I2, 0]], B_a = [B_a1 | B_a2] = [[0,0,0],[0,0,0],[1,0,0],[0,r_h,1]],
//   u_a = [tau_M; -Q_h; -M_h],  y_a = [theta_M'; v_h = r_h theta_h'; theta_h'].
// Arm (3.103): x = [x_a; x_b], u = [tau_M; Q_s(L); M_b(L)], y = [theta_M'; w'(L); psi'(L)]
// ((3.104) prints psi'(L) twice; the second entry is w'(L), notes 004a erratum 11). The feedthrough sign
// sigma of the beam enters the coupling (3.101): for even N the printed formula needs sigma = -1.
#pragma once
#include <vector>

#include "fracdesign/models/ph_system.hpp"
#include "fracdesign/models/timoshenko_beam.hpp"

namespace fracdesign {

struct DriveParams {
    double I_M = 0.0;  // load-side motor inertia n^2 I_m [kg m^2] (eq. (3.30))
    double I_h = 0.0;  // hub inertia [kg m^2]
    double c_s = 0.0;  // gear torsion stiffness [N m/rad]
    double r_h = 0.0;  // hub radius [m]
    double d_s = 0.0;  // gear damping [N m s/rad] on the gear's twist rate (0 in the thesis's model)
    void validate() const;  // std::invalid_argument naming the field (non-finite, I, c_s <= 0, r_h, d_s < 0)
};

// Seed 004 Table 8.2 with I_M = n^2 I_m = 160^2 * 2.29e-4 = 5.8624 kg m^2. The table prints the motor-side
// rotor inertia 2.29e-4 as I_M; only the load-side value (3.30) gives the "about 3 Hz" first mode of
// Sec. 2.1 (notes 004a, open issue 19), so the load-side value is the project's choice.
DriveParams wang_drive();

// The 4-state PH drive model (3.35).
PhSystem drive_model(const DriveParams& d);

// Couples the drive to a beam PH model (full or reduced) with feedthrough sign sigma, eq. (3.103).
PhSystem couple_arm(const PhSystem& drive, const PhSystem& beam, double sigma);

struct ArmOptions {
    int N = 9;                                     // collocation points (Table 8.4)
    Collocation collocation = Collocation::GaussLegendre;
    bool reduce = true;                            // Krylov-reduce the beam before coupling
    std::vector<double> shifts = {16.0, 18.43, 115.6};  // rad/s, Table 8.4
};

struct ArmModel {
    PsBeam beam;         // the full discretised beam
    PhSystem beam_used;  // the beam actually coupled (reduced when options.reduce)
    PhSystem arm;        // 4 + states(beam_used) states
};

ArmModel build_arm(const TimoshenkoParams& beam, const DriveParams& drive, const ArmOptions& opt);

}  // namespace fracdesign
