// trajectory.hpp - seed 004 (Wang, PhD thesis) point-to-point trajectory with a
// sin^2 acceleration profile (Sec. 4.1, Table 4.1, eqs. (4.1)-(4.7)) and the
// rigid-body feedforward (Sec. 4.2, (4.14)-(4.17)).
//
// Corrections applied (notes 004b section 2.1, 3):
//  - (4.5): velocity and position of the acceleration phase carry qdd_m, not qd_m;
//  - (4.7): braking acceleration is -qdd_m sin^2(pi (t - t_b)/t_a);
//  - (4.16): the factor is I_l / c_s (the thesis prints I_M).
// The profile is C^2 in acceleration (jerk continuous); the 4th derivative jumps
// at the phase borders by +-2 pi^2 qdd_m / t_a^2.
#pragma once
#include <array>
#include <stdexcept>

namespace fracdesign::design {

struct PtpSpec {
    double q_s = 0.0;     // start position [rad]
    double q_e = 0.0;     // end position [rad]
    double qd_max = 0.0;  // maximum velocity [rad/s]
    double qdd_max = 0.0; // maximum acceleration [rad/s^2]
    double t_s = 0.0;     // start time [s] (absolute)
    double t_e = 0.0;     // requested end time [s] (absolute); 0: as fast as qd_max, qdd_max allow
};

class SinSquaredPtp {
public:
    // Throws std::invalid_argument naming the field (non-finite, qd_max or qdd_max <= 0,
    // q_e == q_s) or, when the requested duration is shorter than the minimum (4.3),
    // a message giving the minimum end time.
    explicit SinSquaredPtp(const PtpSpec& s);
    double t_a() const { return ta_; }           // acceleration time (4.1), local
    double t_b() const { return te_ - ta_; }     // braking start, local
    double duration() const { return te_; }      // t_e local (4.3)/(4.4)
    double t_end() const { return spec_.t_s + te_; }
    double qd_cruise() const { return qdm_; }
    // q and its derivatives 1..4 at absolute time t (constant q_s before t_s, q_e after).
    std::array<double, 5> eval(double t) const;

private:
    PtpSpec spec_;
    double se_ = 0.0, dir_ = 1.0, qdm_ = 0.0, ta_ = 0.0, te_ = 0.0;
};

// Rigid-body feedforward (4.14)-(4.17) for the link reference theta_l* = q(t):
// returns {theta_M*, theta_M*', theta_M*'', tau_M*}.
std::array<double, 4> rigid_body_feedforward(const std::array<double, 5>& q, double I_M, double I_l, double c_s);

}  // namespace fracdesign::design
