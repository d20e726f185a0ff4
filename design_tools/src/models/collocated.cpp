// collocated.cpp - the two-lumped-mass arm of seed 002, eqs. (38)-(46).
#include "fracdesign/models/collocated.hpp"

#include <cmath>
#include <stdexcept>

namespace fracdesign {

double feliu_rayleigh_zeta(double w) { return 0.5 * (0.059 / w + 2.9e-5 * w); }  // (44)

CollocatedPlant collocated_plant(double m2)
{
    if (!std::isfinite(m2) || m2 <= 0) throw std::invalid_argument("collocated plant: m2 must be finite and > 0 (lb)");
    CollocatedPlant p;
    p.m2_lb = m2;
    // (42): denominator s^4 + c2 s^2 + c0, numerator b (s^2 + z1^2)
    const double c2 = 1455.2 + 21.83 / m2, c0 = 6948.4 / m2;
    const double disc = std::sqrt(c2 * c2 - 4.0 * c0);
    const double a1s = 0.5 * (c2 - disc), a2s = 0.5 * (c2 + disc), z1s = 636.65 + 19.1 / m2;
    p.a1 = std::sqrt(a1s);
    p.a2 = std::sqrt(a2s);
    p.z1 = std::sqrt(z1s);
    p.b = 4.11;
    // partial fractions (45), Lemma 1: k1, k2 > 0 under pole-zero interlacing
    p.k1 = p.b * (z1s - a1s) / (a2s - a1s);
    p.k2 = p.b * (a2s - z1s) / (a2s - a1s);
    p.zeta1 = feliu_rayleigh_zeta(p.a1);
    p.zeta2 = feliu_rayleigh_zeta(p.a2);
    p.xi1 = feliu_rayleigh_zeta(p.z1);  // equals (k1 zeta2 a2 + k2 zeta1 a1)/(b z1) exactly (notes 002 sec. 6.4)
    return p;
}

std::complex<double> collocated_P(const CollocatedPlant& p, double w, bool damped)
{
    const std::complex<double> s(0.0, w);
    const double z1 = damped ? p.zeta1 : 0.0, z2 = damped ? p.zeta2 : 0.0;
    return p.k1 / (s * s + 2.0 * z1 * p.a1 * s + p.a1 * p.a1) + p.k2 / (s * s + 2.0 * z2 * p.a2 * s + p.a2 * p.a2);
}

StateSpace collocated_state_space(const CollocatedPlant& p, bool damped)
{
    StateSpace ss;
    ss.A = Eigen::MatrixXd::Zero(4, 4);
    ss.B = Eigen::MatrixXd::Zero(4, 1);
    ss.C = Eigen::MatrixXd::Zero(1, 4);
    ss.D = Eigen::MatrixXd::Zero(1, 1);
    const double a[2] = {p.a1, p.a2}, k[2] = {p.k1, p.k2};
    const double z[2] = {damped ? p.zeta1 : 0.0, damped ? p.zeta2 : 0.0};
    for (int i = 0; i < 2; ++i) {
        ss.A(2 * i, 2 * i + 1) = 1.0;
        ss.A(2 * i + 1, 2 * i) = -a[i] * a[i];
        ss.A(2 * i + 1, 2 * i + 1) = -2.0 * z[i] * a[i];
        ss.B(2 * i + 1, 0) = 1.0;
        ss.C(0, 2 * i) = k[i];
    }
    ss.inputs = {"u (P input; Gamma_c = s^2 G_m P theta_m*)"};
    ss.outputs = {"P output"};
    ss.states = {"q1", "q1_dot", "q2", "q2_dot"};
    return ss;
}

}  // namespace fracdesign
