// mode_shift.cpp - a resonant mode of the nominal plant moved to another
// frequency and damping (mode_shift.hpp gives the equations; the effect's
// descriptor is in effects.cpp, docs/gap.md "mode_shift").
#include "fracdesign/gap/mode_shift.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fracdesign {
namespace gap {

std::vector<PlantMode> resonant_plant_modes(const NominalModel& m)
{
    std::vector<PlantMode> out;
    const Eigen::Index n = m.A.rows();
    if (n == 0 || !m.A.allFinite()) return out;
    const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> right(m.A.cast<std::complex<double>>());
    const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> left(m.A.transpose().cast<std::complex<double>>());
    if (right.info() != Eigen::Success || left.info() != Eigen::Success) return out;
    const Eigen::VectorXcd& ev = right.eigenvalues();
    for (Eigen::Index i = 0; i < n; ++i) {
        const std::complex<double> z = ev(i);
        if (!(z.imag() > 1e-12) || std::abs(z) < 1e-12) continue;
        bool simple = true;
        for (Eigen::Index j = 0; j < n && simple; ++j)
            simple = j == i || std::abs(ev(j) - z) > 1e-6 * std::abs(z);
        if (!simple) continue;
        const std::complex<double> s = std::log(z) / m.Ts;
        const double wn = std::abs(s), zeta = -s.real() / wn, f = wn / (2 * M_PI);
        if (!(zeta < M_SQRT1_2) || f > 0.4 / m.Ts) continue;
        // The left eigenvector: the eigenvector of A^T at the same eigenvalue.
        Eigen::Index jl = 0;
        for (Eigen::Index j = 1; j < n; ++j)
            if (std::abs(left.eigenvalues()(j) - z) < std::abs(left.eigenvalues()(jl) - z)) jl = j;
        PlantMode pm;
        pm.f_hz = f;
        pm.zeta = zeta;
        pm.z = z;
        pm.v = right.eigenvectors().col(i);
        pm.w = left.eigenvectors().col(jl).transpose();
        const std::complex<double> wv = pm.w * pm.v;
        if (!(std::abs(wv) > 1e-12 * pm.w.norm() * pm.v.norm())) continue;
        pm.w /= wv;
        out.push_back(pm);
    }
    std::sort(out.begin(), out.end(), [](const PlantMode& a, const PlantMode& b) { return a.f_hz < b.f_hz; });
    return out;
}

void shift_plant_mode(const PlantMode& pm, double Ts, double f_hz, double zeta, const Eigen::MatrixXd& A,
                      const Eigen::MatrixXd& B, Eigen::MatrixXd& A2, Eigen::MatrixXd& B2)
{
    const double w = 2 * M_PI * f_hz;
    const std::complex<double> s2(-zeta * w, w * std::sqrt(std::max(0.0, 1 - zeta * zeta)));
    const std::complex<double> z2 = std::exp(s2 * Ts);
    const std::complex<double> s = std::log(pm.z) / Ts;
    const std::complex<double> g = (pm.z - 1.0) / s, g2 = (z2 - 1.0) / s2;
    const Eigen::MatrixXcd P = pm.v * pm.w;
    A2 = A + 2.0 * ((z2 - pm.z) * P).real();
    B2 = B + 2.0 * ((g2 / g - 1.0) * (P * B.cast<std::complex<double>>())).real();
}

std::string plant_mode_name(const PlantMode& pm)
{
    char b[80];
    std::snprintf(b, sizeof b, "mode at %.4g Hz, zeta %.3g", pm.f_hz, pm.zeta);
    return b;
}

}  // namespace gap
}  // namespace fracdesign
