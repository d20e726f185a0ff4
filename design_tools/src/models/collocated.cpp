// collocated.cpp - the two-lumped-mass arm of seed 002, eqs. (38)-(46).
#include "fracdesign/models/collocated.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

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

void CollocatedModes::validate() const
{
    auto bad = [](const std::string& m) { throw std::invalid_argument("collocated modes: " + m); };
    if (a.empty()) bad("a must not be empty");
    if (k.size() != a.size()) bad("k must have one residue per mode");
    if (zeta.size() != a.size()) bad("zeta must have one damping ratio per mode");
    for (size_t i = 0; i < a.size(); ++i) {
        if (!std::isfinite(a[i]) || a[i] <= 0) bad("a[" + std::to_string(i) + "] must be finite and > 0");
        if (!std::isfinite(k[i])) bad("k[" + std::to_string(i) + "] must be finite");
        if (!std::isfinite(zeta[i]) || zeta[i] < 0) bad("zeta[" + std::to_string(i) + "] must be finite and >= 0");
    }
}

CollocatedModes pzi_to_modes(double b, const std::vector<double>& a, const std::vector<double>& z)
{
    if (z.size() + 1 != a.size()) throw std::invalid_argument("collocated modes: z must have n - 1 zeros for n poles");
    CollocatedModes m;
    m.a = a;
    m.zeta.assign(a.size(), 0.0);
    for (size_t i = 0; i < a.size(); ++i) {
        // residue of P in the variable s^2 at s^2 = -a_i^2 (Lemma 1)
        double k = b;
        for (double zj : z) k *= zj * zj - a[i] * a[i];
        for (size_t j = 0; j < a.size(); ++j)
            if (j != i) k /= a[j] * a[j] - a[i] * a[i];
        m.k.push_back(k);
    }
    m.validate();
    return m;
}

std::complex<double> modal_P(const CollocatedModes& m, double w)
{
    const std::complex<double> s(0.0, w);
    std::complex<double> p = 0.0;
    for (size_t i = 0; i < m.a.size(); ++i) p += m.k[i] / (s * s + 2.0 * m.zeta[i] * m.a[i] * s + m.a[i] * m.a[i]);
    return p;
}

StateSpace modal_state_space(const CollocatedModes& m)
{
    m.validate();
    const Eigen::Index n = static_cast<Eigen::Index>(m.a.size());
    StateSpace ss;
    ss.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    ss.B = Eigen::MatrixXd::Zero(2 * n, 1);
    ss.C = Eigen::MatrixXd::Zero(1, 2 * n);
    ss.D = Eigen::MatrixXd::Zero(1, 1);
    for (Eigen::Index i = 0; i < n; ++i) {
        const size_t u = static_cast<size_t>(i);
        ss.A(2 * i, 2 * i + 1) = 1.0;
        ss.A(2 * i + 1, 2 * i) = -m.a[u] * m.a[u];
        ss.A(2 * i + 1, 2 * i + 1) = -2.0 * m.zeta[u] * m.a[u];
        ss.B(2 * i + 1, 0) = 1.0;
        ss.C(0, 2 * i) = m.k[u];
        ss.states.push_back("q" + std::to_string(i + 1));
        ss.states.push_back("q" + std::to_string(i + 1) + "_dot");
    }
    ss.inputs = {"u (P input)"};
    ss.outputs = {"P output"};
    return ss;
}

CollocatedModes collocated_modes(const CollocatedPlant& p, bool damped)
{
    CollocatedModes m;
    m.a = {p.a1, p.a2};
    m.k = {p.k1, p.k2};
    m.zeta = {damped ? p.zeta1 : 0.0, damped ? p.zeta2 : 0.0};
    return m;
}

std::complex<double> collocated_P(const CollocatedPlant& p, double w, bool damped)
{
    return modal_P(collocated_modes(p, damped), w);
}

StateSpace collocated_state_space(const CollocatedPlant& p, bool damped)
{
    StateSpace ss = modal_state_space(collocated_modes(p, damped));
    ss.inputs = {"u (P input; Gamma_c = Ghat P theta_m, (43))"};
    return ss;
}

}  // namespace fracdesign
