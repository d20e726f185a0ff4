// mode_shift.cpp - a resonant mode of the nominal plant moved to another
// frequency and damping (mode_shift.hpp gives the equations; the effect's
// descriptor is in effects.cpp, docs/gap.md "mode_shift").
#include "fracdesign/gap/mode_shift.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fracdesign {
namespace gap {

namespace {

using Solver = Eigen::ComplexEigenSolver<Eigen::MatrixXcd>;

// The index of the eigenvalue of `ev` nearest t.
Eigen::Index nearest(const Eigen::VectorXcd& ev, std::complex<double> t)
{
    Eigen::Index k = 0;
    for (Eigen::Index j = 1; j < ev.size(); ++j)
        if (std::abs(ev(j) - t) < std::abs(ev(k) - t)) k = j;
    return k;
}

// The right eigenvector v of eigenvalue i of `right` and the left one w (the
// eigenvector of the transpose, `left`, at the same eigenvalue) scaled to
// w v = 1; false where w v vanishes (a projector that is ill-defined).
bool eigen_pair(const Solver& right, const Solver& left, Eigen::Index i, Eigen::VectorXcd& v, Eigen::RowVectorXcd& w)
{
    v = right.eigenvectors().col(i);
    w = left.eigenvectors().col(nearest(left.eigenvalues(), right.eigenvalues()(i))).transpose();
    const std::complex<double> wv = w * v;
    if (!(std::abs(wv) > 1e-12 * w.norm() * v.norm())) return false;
    w /= wv;
    return true;
}

}  // namespace

std::vector<PlantMode> resonant_plant_modes(const NominalModel& m)
{
    std::vector<PlantMode> out;
    const Eigen::Index n = m.A.rows();
    if (n == 0 || !m.A.allFinite()) return out;
    const Solver right(m.A.cast<std::complex<double>>());
    const Solver left(m.A.transpose().cast<std::complex<double>>());
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
        PlantMode pm;
        pm.f_hz = f;
        pm.zeta = zeta;
        pm.z = z;
        if (!eigen_pair(right, left, i, pm.v, pm.w)) continue;
        out.push_back(pm);
    }
    std::sort(out.begin(), out.end(), [](const PlantMode& a, const PlantMode& b) { return a.f_hz < b.f_hz; });
    // The coupling variants: a continuous plant (A = e^{Ac Ts}, same states)
    // and a coupling with its continuous torque column. The mode's continuous
    // eigenvalue lambda (nearest log(z)/Ts) and eigenvectors of Ac give the
    // spring's first-order share d lambda/d k = (wc torque_c)(twist vc), wc vc = 1.
    if (m.Ac.rows() != n || m.Bc.rows() != n || m.couplings.empty()) return out;
    const Solver cr(m.Ac.cast<std::complex<double>>());
    const Solver cl(m.Ac.transpose().cast<std::complex<double>>());
    if (cr.info() != Eigen::Success || cl.info() != Eigen::Success) return out;
    const size_t nmodal = out.size();
    for (size_t im = 0; im < nmodal; ++im) {
        const std::complex<double> s = std::log(out[im].z) / m.Ts;
        const Eigen::Index ir = nearest(cr.eigenvalues(), s);
        const std::complex<double> lam = cr.eigenvalues()(ir);
        if (std::abs(lam - s) > 1e-6 * std::abs(s)) continue;  // not the hold of Ac's eigenvalue
        Eigen::VectorXcd vc;
        Eigen::RowVectorXcd wc;
        if (!eigen_pair(cr, cl, ir, vc, wc)) continue;
        for (size_t ic = 0; ic < m.couplings.size(); ++ic) {
            const Coupling& cp = m.couplings[ic];
            if (cp.torque_c.size() != n || cp.twist.size() != n) continue;
            const std::complex<double> dl =
                (wc * cp.torque_c.cast<std::complex<double>>())(0) * (cp.twist.cast<std::complex<double>>() * vc)(0);
            if (!(std::abs(dl) * cp.stiffness / std::abs(lam) >= kCouplingModeShare / 2)) continue;
            PlantMode pm = out[im];
            pm.coupling = int(ic);
            pm.via = cp.name;
            out.push_back(pm);
        }
    }
    return out;
}

void shift_coupling_mode(const PlantMode& pm, const NominalModel& m, double f_hz, double zeta, Eigen::MatrixXd& A2,
                         Eigen::MatrixXd& B2)
{
    using cd = std::complex<double>;
    const Coupling& cp = m.couplings.at(size_t(pm.coupling));
    const Eigen::Index n = m.Ac.rows();
    const double w = 2 * M_PI * f_hz;
    const cd s2(-zeta * w, w * std::sqrt(std::max(0.0, 1 - zeta * zeta)));
    // h = twist (s' I - Ac)^-1 torque_c; the rate term's h_c = s' h - twist torque_c.
    const Eigen::MatrixXcd M = s2 * Eigen::MatrixXcd::Identity(n, n) - m.Ac.cast<cd>();
    const Eigen::VectorXcd g = M.partialPivLu().solve(cp.torque_c.cast<cd>());
    const cd h = (cp.twist.cast<cd>() * g)(0);
    const cd hc = s2 * h - cp.twist.dot(cp.torque_c);
    // dk Re h + dc Re hc = 1, dk Im h + dc Im hc = 0.
    const double det = h.real() * hc.imag() - hc.real() * h.imag();
    if (!std::isfinite(det) || !(std::fabs(det) > 1e-12 * std::abs(h) * std::abs(hc))) {
        shift_plant_mode(pm, m.Ts, f_hz, zeta, m.A, m.B, m.force_input, A2, B2);
        return;
    }
    const double dk = hc.imag() / det, dc = -h.imag() / det;
    const Eigen::MatrixXd Ac2 = m.Ac + cp.torque_c * (dk * cp.twist + dc * (cp.twist * m.Ac));
    zoh(Ac2, m.Bc, m.Ts, A2, B2);
}

void shift_plant_mode(const PlantMode& pm, double Ts, double f_hz, double zeta, const Eigen::MatrixXd& A,
                      const Eigen::MatrixXd& B, int force_input, Eigen::MatrixXd& A2, Eigen::MatrixXd& B2)
{
    using cd = std::complex<double>;
    const double w = 2 * M_PI * f_hz;
    const cd s2(-zeta * w, w * std::sqrt(std::max(0.0, 1 - zeta * zeta)));
    const cd z2 = std::exp(s2 * Ts);
    const cd s = std::log(pm.z) / Ts;
    const cd g = (pm.z - 1.0) / s;
    // The force's modal coordinate, continuous: eta_B = w B_c = w B / g.
    cd etaB = 0.0;
    if (force_input >= 0 && force_input < B.cols()) etaB = (pm.w * B.col(force_input).cast<cd>())(0) / g;
    const double bnorm = force_input >= 0 && force_input < B.cols() ? B.col(force_input).norm() : 0.0;
    if (!(std::abs(etaB) > 1e-9 * pm.w.norm() * std::max(bnorm, 1e-300) / std::max(std::abs(g), 1e-300))) {
        // The force does not reach the mode: its eigenvalue pair moved with
        // the continuous input and output maps (residues) kept.
        const cd g2 = (z2 - 1.0) / s2;
        const Eigen::MatrixXcd P = pm.v * pm.w;
        A2 = A + 2.0 * ((z2 - pm.z) * P).real();
        B2 = B + 2.0 * ((g2 / g - 1.0) * (P * B.cast<cd>())).real();
        return;
    }
    // The mode in its mechanical coordinates z = (q, q'): the force enters
    // its acceleration, q'' + 2 zeta w q' + w^2 q = u, so M = [[0, 1],
    // [-|s|^2, 2 Re s]] with input [0; 1]. Its eigenvector [1; s] is v / kappa
    // with kappa = 1/((s - conj s) eta_B) (the companion's left eigenvector
    // [-conj s, 1]/(s - conj s) reads the input as 1/(s - conj s)). With
    // x = T z on the mode's subspace, T [1; s] = v / kappa, and z = S x,
    // S = 2 Re([1; s] kappa w) (S T = I, S zero on the other modes).
    const cd kappa = 1.0 / ((s - std::conj(s)) * etaB);
    const Eigen::VectorXcd u = pm.v / kappa;
    const Eigen::Index n = A.rows();
    Eigen::MatrixXd T(n, 2), S(2, n);
    T.col(1) = u.imag() / s.imag();
    T.col(0) = u.real() - s.real() * T.col(1);
    S.row(0) = 2.0 * (kappa * pm.w).real();
    S.row(1) = 2.0 * (kappa * s * pm.w).real();
    // The shifted mode keeps T (the output maps of q and q'), the force's
    // [0; 1] and every input's continuous map in z: the zero-order hold of
    // M is (Phi, Gamma = M^-1 (Phi - I)), so S B = Gamma c per input and the
    // shifted S B' = Gamma' c. A stiffness change at fixed modal mass: a
    // position output's share of the mode scales by w^2/w'^2, a rate
    // output's stays (to O(zeta^2)); keeping the residues instead left a
    // 45 % stiffness drop on a linear scale 12 % off in frequency.
    auto hold = [&](cd sc, Eigen::Matrix2d& Phi, Eigen::Matrix2d& Gam) {
        Eigen::Matrix2d M;
        M << 0.0, 1.0, -std::norm(sc), 2.0 * sc.real();
        Eigen::MatrixXd Phi_x, Gam_x;
        zoh(M, Eigen::Matrix2d::Identity(), Ts, Phi_x, Gam_x);
        Phi = Phi_x;
        Gam = Gam_x;
    };
    Eigen::Matrix2d Phi, Gam, Phi2, Gam2;
    hold(s, Phi, Gam);
    hold(s2, Phi2, Gam2);
    A2 = A + T * (Phi2 - Phi) * S;
    B2 = B + T * (Gam2 * Gam.inverse() - Eigen::Matrix2d::Identity()) * (S * B);
}

std::string plant_mode_name(const PlantMode& pm)
{
    char b[80];
    std::snprintf(b, sizeof b, "mode at %.4g Hz, zeta %.3g", pm.f_hz, pm.zeta);
    return pm.coupling >= 0 ? std::string(b) + ", by the coupling '" + pm.via + "'" : std::string(b);
}

}  // namespace gap
}  // namespace fracdesign
