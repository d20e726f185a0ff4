// collocated.cpp - the two-lumped-mass arm of seed 002, eqs. (38)-(46).
#include "fracdesign/models/collocated.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fracdesign {

CollocatedArmError::CollocatedArmError(const std::string& f, const std::string& p)
    : std::invalid_argument("collocated arm: field '" + f + "': " + p), field(f), problem(p)
{
}

namespace {

std::string num(double v)
{
    std::ostringstream os;
    os.precision(10);
    os << v;
    return os.str();
}

void need(bool ok, const std::string& field, double v, const std::string& allowed)
{
    if (!ok) throw CollocatedArmError(field, "is " + num(v) + ", must be " + allowed);
}

// Partial fractions (45) of P = b (s^2 + z1^2)/((s^2 + a1^2)(s^2 + a2^2)), Lemma 1: k1, k2 > 0 under
// pole-zero interlacing; Rayleigh damping (44) on both modes; the zero damping of the sum (46) is
// (k1 zeta2 a2 + k2 zeta1 a1)/(b z1), which equals zeta(z1) exactly for Rayleigh damping (notes 002 sec. 6.4).
void finish(CollocatedPlant& p, const CollocatedArm& arm, double a1s, double a2s, double z1s)
{
    p.a1 = std::sqrt(a1s);
    p.a2 = std::sqrt(a2s);
    p.z1 = std::sqrt(z1s);
    p.k1 = p.b * (z1s - a1s) / (a2s - a1s);
    p.k2 = p.b * (a2s - z1s) / (a2s - a1s);
    p.zeta1 = arm.zeta(p.a1);
    p.zeta2 = arm.zeta(p.a2);
    p.xi1 = arm.zeta(p.z1);
    p.eps = arm.eps;
}

}  // namespace

void CollocatedArm::validate() const
{
    const std::string mu = std::string(" ") + mass_unit();
    auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
    auto nonneg = [](double v) { return std::isfinite(v) && v >= 0.0; };
    if (form == Form::Physical) {
        need(pos(L), "link.L", L, "finite and > 0 (m)");
        need(pos(EI), "link.EI", EI, "finite and > 0 (N m^2)");
        need(pos(m1), "masses.m1", m1, "finite and > 0 (kg)");
        need(pos(x1) && x1 < L, "masses.x1", x1, "in (0, link.L) = (0, " + num(L) + ") m");
        need(pos(moment_gain), "moment_gain", moment_gain, "finite and > 0 (reading per N m)");
    }
    const std::string m2f = form == Form::Physical ? "masses.m2" : "m2_lb";
    const std::string rf = form == Form::Physical ? "masses.m2_range" : "m2_range_lb";
    need(pos(m2_nominal), m2f, m2_nominal, "finite and > 0" + mu);
    need(pos(m2_min), rf + "[0]", m2_min, "finite and > 0" + mu);
    need(std::isfinite(m2_max) && m2_max >= m2_min, rf + "[1]", m2_max, ">= " + rf + "[0] = " + num(m2_min) + mu);
    need(m2_nominal >= m2_min && m2_nominal <= m2_max, m2f, m2_nominal,
         "inside " + rf + " = [" + num(m2_min) + ", " + num(m2_max) + "]" + mu);
    need(nonneg(eps) && eps <= 1.0, "inner_loop.eps", eps, "in [0, 1] s");
    need(nonneg(rayleigh_a), "damping.rayleigh_a", rayleigh_a, "finite and >= 0 (1/s)");
    need(nonneg(rayleigh_b), "damping.rayleigh_b", rayleigh_b, "finite and >= 0 (s)");
}

CollocatedPlant CollocatedArm::plant(double m2) const
{
    if (!std::isfinite(m2) || m2 <= 0)
        throw std::invalid_argument("collocated plant: m2 must be finite and > 0 (" + std::string(mass_unit()) + ")");
    CollocatedPlant p;
    p.m2 = m2;
    if (form == Form::Printed) {
        // (42): denominator s^4 + c2 s^2 + c0, numerator b (s^2 + z1^2); (39): G_2 numerator
        const double c2 = 1455.2 + 21.83 / m2, c0 = 6948.4 / m2;
        const double disc = std::sqrt(c2 * c2 - 4.0 * c0);
        p.b = 4.11;
        p.g2_s2 = -5.457 / m2;
        p.g2_0 = 5.457 * 1273.3 / m2;
        finish(p, *this, 0.5 * (c2 - disc), 0.5 * (c2 + disc), 636.65 + 19.1 / m2);
        return p;
    }
    // Physical form (see the header): K' = X F^-1 X with the clamped-link flexibility F.
    const double f11 = x1 * x1 * x1 / (3.0 * EI), f12 = x1 * x1 * (3.0 * L - x1) / (6.0 * EI),
                 f22 = L * L * L / (3.0 * EI);
    const double det = f11 * f22 - f12 * f12;  // > 0: F is a flexibility (Gram) matrix
    const double K11 = x1 * x1 * f22 / det, K12 = -x1 * L * f12 / det, K22 = L * L * f11 / det;
    const double M1 = m1 * x1 * x1, M2 = m2 * L * L;
    const double c2 = K11 / M1 + K22 / M2, c0 = (K11 * K22 - K12 * K12) / (M1 * M2);
    const double disc = std::sqrt(c2 * c2 - 4.0 * c0);
    const double u1 = K11 + K12, u2 = K12 + K22;  // K' 1
    // P = g 1'K' adj(M s^2 + K') M 1 / det(M s^2 + K'); theta_2/theta_m = [adj(M s^2 + K') K' 1]_2 / det
    p.b = moment_gain * (u1 + u2);
    const double z1s = (u1 * (K22 * M1 - K12 * M2) + u2 * (K11 * M2 - K12 * M1)) / (M1 * M2 * (u1 + u2));
    p.g2_s2 = u2 / M2;
    p.g2_0 = (K11 * u2 - K12 * u1) / (M1 * M2);
    finish(p, *this, 0.5 * (c2 - disc), 0.5 * (c2 + disc), z1s);
    return p;
}

CollocatedArm feliu_robot_arm() { return CollocatedArm{}; }

CollocatedPlant collocated_plant(double m2) { return feliu_robot_arm().plant(m2); }

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
