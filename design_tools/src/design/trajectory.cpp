// trajectory.cpp - sin^2 point-to-point profile and rigid-body feedforward (seed 004 Ch. 4).
#include "fracdesign/design/trajectory.hpp"

#include <cmath>
#include <string>

namespace fracdesign::design {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

SinSquaredPtp::SinSquaredPtp(const PtpSpec& s) : spec_(s)
{
    auto bad = [](const std::string& w) { throw std::invalid_argument(w); };
    if (!std::isfinite(s.q_s) || !std::isfinite(s.q_e)) bad("q_s, q_e must be finite");
    if (!(std::isfinite(s.qd_max) && s.qd_max > 0.0)) bad("qd_max must be finite and > 0");
    if (!(std::isfinite(s.qdd_max) && s.qdd_max > 0.0)) bad("qdd_max must be finite and > 0");
    if (!std::isfinite(s.t_s) || !std::isfinite(s.t_e)) bad("t_s, t_e must be finite");
    se_ = std::fabs(s.q_e - s.q_s);
    if (se_ == 0.0) bad("q_e equals q_s: no motion to plan");
    dir_ = s.q_e > s.q_s ? 1.0 : -1.0;
    double qdm = s.qd_max, ta = 2.0 * qdm / s.qdd_max;  // (4.1)
    // Accelerating and braking cover qd_m t_a; a shorter distance never reaches qd_max:
    // the cruise phase vanishes and qd_m = sqrt(s_e qdd_m / 2).
    if (se_ < qdm * ta) {
        qdm = std::sqrt(se_ * s.qdd_max / 2.0);
        ta = 2.0 * qdm / s.qdd_max;
    }
    const double te_min = se_ / qdm + ta;  // (4.3)
    double te = te_min;
    if (s.t_e != 0.0) {
        const double req = s.t_e - s.t_s;
        if (req < te_min * (1.0 - 1e-12))
            bad("requested end time " + std::to_string(s.t_e) + " s is before the minimum " +
                std::to_string(s.t_s + te_min) + " s allowed by qd_max and qdd_max (4.3)");
        if (req > te_min) {
            // (4.4): keep qdd_m, lower qd_m so that the motion takes exactly t_e.
            const double a = s.qdd_max;
            qdm = 0.5 * (a * req / 2.0 - std::sqrt(a * a * req * req / 4.0 - 2.0 * a * se_));
            ta = 2.0 * qdm / a;  // (4.1)
            te = req;
        }
    }
    qdm_ = qdm;
    ta_ = ta;
    te_ = te;
}

std::array<double, 5> SinSquaredPtp::eval(double t) const
{
    // a = qdd_m of the (possibly lowered) profile, from (4.1): qdd_m = 2 qd_m / t_a
    const double tau = t - spec_.t_s, ta = ta_, tb = te_ - ta_, a = 2.0 * qdm_ / ta_;
    const double w = 2.0 * kPi / ta;
    std::array<double, 5> q{0, 0, 0, 0, 0};
    if (tau <= 0.0) {
        q[0] = 0.0;
    } else if (tau < ta) {  // (4.5), corrected: qdd_m factors
        q[0] = a * (tau * tau / 4.0 + ta * ta / (8.0 * kPi * kPi) * (std::cos(w * tau) - 1.0));
        q[1] = a * (tau / 2.0 - ta / (4.0 * kPi) * std::sin(w * tau));
        q[2] = a * std::pow(std::sin(kPi * tau / ta), 2);
        q[3] = a * kPi / ta * std::sin(w * tau);
        q[4] = a * 2.0 * kPi * kPi / (ta * ta) * std::cos(w * tau);
    } else if (tau < tb) {  // (4.6)
        q[0] = qdm_ * (tau - ta / 2.0);
        q[1] = qdm_;
    } else if (tau < te_) {  // (4.7), corrected braking acceleration
        const double u = tau - tb;
        q[0] = 0.5 * a * (te_ * (tau + ta) - 0.5 * (tau * tau + te_ * te_ + 2.0 * ta * ta) +
                          ta * ta / (4.0 * kPi * kPi) * (1.0 - std::cos(w * u)));
        q[1] = qdm_ - a * (u / 2.0 - ta / (4.0 * kPi) * std::sin(w * u));
        q[2] = -a * std::pow(std::sin(kPi * u / ta), 2);
        q[3] = -a * kPi / ta * std::sin(w * u);
        q[4] = -a * 2.0 * kPi * kPi / (ta * ta) * std::cos(w * u);
    } else {
        q[0] = se_;
    }
    for (double& v : q) v *= dir_;
    q[0] += spec_.q_s;
    return q;
}

std::array<double, 4> rigid_body_feedforward(const std::array<double, 5>& q, double I_M, double I_l, double c_s)
{
    if (!(I_M > 0.0 && I_l > 0.0 && c_s > 0.0)) throw std::invalid_argument("I_M, I_l and c_s must be > 0");
    const double k = I_l / c_s;
    const double th = k * q[2] + q[0];    // (4.14)
    const double thd = k * q[3] + q[1];   // (4.16), I_l (thesis prints I_M)
    const double thdd = k * q[4] + q[2];  // (4.17)
    return {th, thd, thdd, I_M * thdd + c_s * (th - q[0])};  // (4.15)
}

}  // namespace fracdesign::design
