// timoshenko_beam.cpp - pseudo-spectral PH Timoshenko beam and its exact clamped-free frequencies
// (seed 004 Sec. 3.3-3.4 and App. C; see fracdesign/models/timoshenko_beam.hpp).
#include "fracdesign/models/timoshenko_beam.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fracdesign/models/lagrange.hpp"

namespace fracdesign {

namespace {

void require(bool ok, const std::string& msg)
{
    if (!ok) throw std::invalid_argument(msg);
}

void require_positive(double v, const char* name)
{
    require(std::isfinite(v) && v > 0, std::string("timoshenko beam: ") + name + " must be finite and > 0");
}

}  // namespace

void TimoshenkoParams::validate() const
{
    require_positive(L, "L");
    require_positive(rho, "rho");
    require_positive(I_rho, "I_rho");
    require_positive(K_s, "K_s");
    require_positive(K_b, "K_b");
    require(std::isfinite(r_t) && r_t >= 0, "timoshenko beam: r_t must be finite and >= 0");
    require(std::isfinite(r_r) && r_r >= 0, "timoshenko beam: r_r must be finite and >= 0");
}

TimoshenkoParams timoshenko_rectangular(double L, double h, double t, double density, double E, double poisson,
                                        double kappa)
{
    // A = h t, I = h t^3/12 (bending about the thin direction), G = E/(2(1+nu)) (notes 004a sec. 3.2)
    const double A = h * t, I = h * t * t * t / 12.0, G = E / (2.0 * (1.0 + poisson));
    TimoshenkoParams p;
    p.L = L;
    p.rho = density * A;
    p.I_rho = density * I;
    p.K_s = kappa * G * A;
    p.K_b = E * I;
    p.validate();
    return p;
}

TimoshenkoParams wang_steel_beam()
{
    return timoshenko_rectangular(1.2, 0.03, 0.005, 7856.0, 215e9, 0.28, 5.0 / 6.0);  // seed 004 Table 8.3
}

double PsBeam::integration_by_parts_residual() const
{
    Eigen::Matrix2d zeta = Eigen::Matrix2d::Zero();
    zeta(0, 0) = -1.0;
    zeta(1, 1) = 1.0;
    const Eigen::MatrixXd r = M * D + D.transpose() * M.transpose() - Phi.transpose() * zeta * Phi;
    return r.cwiseAbs().maxCoeff();
}

PsBeam build_ps_beam(const TimoshenkoParams& p, int N, Collocation c)
{
    p.validate();
    require(N >= 2, "timoshenko beam: N must be >= 2 (got " + std::to_string(N) + ")");
    const double L = p.L;
    PsBeam b;
    b.N = N;
    b.collocation = c;
    b.effort_nodes.resize(N + 1);
    b.flow_nodes.resize(N);
    if (c == Collocation::GaussLegendre) {
        // Fig. 3.5: zeros of Gauss-Legendre polynomials plus the two end points for the efforts
        Eigen::VectorXd x, w;
        gauss_legendre(N - 1, 0.0, L, x, w);
        b.effort_nodes[0] = 0.0;
        b.effort_nodes.segment(1, N - 1) = x;
        b.effort_nodes[N] = L;
        gauss_legendre(N, 0.0, L, x, w);
        b.flow_nodes = x;
    } else {
        for (int i = 0; i <= N; ++i) b.effort_nodes[i] = L * i / N;
        for (int k = 0; k < N; ++k) b.flow_nodes[k] = L * (k + 0.5) / N;
    }
    const BarycentricBasis we(b.effort_nodes), wf(b.flow_nodes);

    // D (3.62): derivative of the degree-N effort basis at the flow nodes
    b.D.resize(N, N + 1);
    for (int k = 0; k < N; ++k) b.D.row(k) = we.derivatives(b.flow_nodes[k]).transpose();
    // M (3.70), S (3.75): integrands of degree <= 2N, exact with N+1 Gauss points
    Eigen::VectorXd qx, qw;
    gauss_legendre(N + 1, 0.0, L, qx, qw);
    b.M = Eigen::MatrixXd::Zero(N + 1, N);
    b.S = Eigen::MatrixXd::Zero(N, N);
    for (int q = 0; q <= N; ++q) {
        const Eigen::VectorXd ve = we.values(qx[q]), vf = wf.values(qx[q]);
        b.M.noalias() += qw[q] * ve * vf.transpose();
        b.S.noalias() += qw[q] * vf * vf.transpose();
    }
    b.S = (0.5 * (b.S + b.S.transpose())).eval();  // exactly symmetric (the rounding of the sums is not)
    // Phi (3.60)
    b.Phi.resize(2, N + 1);
    const Eigen::RowVectorXd w0 = we.values(0.0).transpose(), wL = we.values(L).transpose();
    b.Phi.row(0) = w0;
    b.Phi.row(1) = wL;

    // Closed form of the I/O representation (3.87)-(3.93) (notes 004a sec. 2.3.4, DERIVED and verified):
    // A_0 = [M^T; w0], A_L = [M^T; wL], A_0^-1 = [P_0 | p_0], A_L^-1 = [P_L | p_L].
    Eigen::MatrixXd A0(N + 1, N + 1), AL(N + 1, N + 1);
    A0 << b.M.transpose(), w0;
    AL << b.M.transpose(), wL;
    const Eigen::MatrixXd A0i = A0.fullPivLu().inverse(), ALi = AL.fullPivLu().inverse();
    const Eigen::MatrixXd P0 = A0i.leftCols(N), PL = ALi.leftCols(N);
    const Eigen::VectorXd p0 = A0i.col(N), pL = ALi.col(N);
    const Eigen::MatrixXd Sinv = b.S.llt().solve(Eigen::MatrixXd::Identity(N, N));
    const Eigen::MatrixXd DPL = b.D * PL, DP0 = b.D * P0;
    const Eigen::VectorXd DpL = b.D * pL, Dp0 = b.D * p0;

    const int n = 4 * N;
    enum { PT = 0, PR = 1, ET = 2, ER = 3 };
    auto blk = [N](Eigen::MatrixXd& m, int r, int col) { return m.block(r * N, col * N, N, N); };
    PhSystem& ph = b.ph;
    ph.J = Eigen::MatrixXd::Zero(n, n);
    blk(ph.J, PT, ET) = DPL;
    blk(ph.J, PR, ET) = Sinv;
    blk(ph.J, PR, ER) = DPL;
    blk(ph.J, ET, PT) = DP0;
    blk(ph.J, ET, PR) = -Sinv;
    blk(ph.J, ER, PR) = DP0;
    // dissipation (3.86): R = blockdiag(r_t S^-1, r_r S^-1, 0, 0)
    ph.R = Eigen::MatrixXd::Zero(n, n);
    blk(ph.R, PT, PT) = p.r_t * Sinv;
    blk(ph.R, PR, PR) = p.r_r * Sinv;
    // Q = blockdiag(S/rho, S/I_rho, K_s S, K_b S) in the state order [p_t, p_r, eps_t, eps_r] (the thesis
    // prints the last two blocks swapped, notes 004a erratum 7)
    ph.Q = Eigen::MatrixXd::Zero(n, n);
    blk(ph.Q, PT, PT) = b.S / p.rho;
    blk(ph.Q, PR, PR) = b.S / p.I_rho;
    blk(ph.Q, ET, ET) = p.K_s * b.S;
    blk(ph.Q, ER, ER) = p.K_b * b.S;
    // B: columns w'(0), psi'(0), Q_s(L), M_b(L)
    ph.B = Eigen::MatrixXd::Zero(n, 4);
    ph.B.block(ET * N, 0, N, 1) = Dp0;
    ph.B.block(ER * N, 1, N, 1) = Dp0;
    ph.B.block(PT * N, 2, N, 1) = DpL;
    ph.B.block(PR * N, 3, N, 1) = DpL;
    // feedthrough (3.95) with sigma = -w^e(0)^T p_L = (-1)^(N+1)
    b.sigma = -w0.dot(pL);
    ph.D = Eigen::MatrixXd::Zero(4, 4);
    ph.D.topRightCorner(2, 2) = b.sigma * Eigen::Matrix2d::Identity();
    ph.D.bottomLeftCorner(2, 2) = -b.sigma * Eigen::Matrix2d::Identity();
    ph.inputs = {"w_dot(0) [m/s]", "psi_dot(0) [rad/s]", "Q_s(L) [N]", "M_b(L) [N m]"};
    ph.outputs = {"-Q_s(0) [N]", "-M_b(0) [N m]", "w_dot(L) [m/s]", "psi_dot(L) [rad/s]"};
    const char* names[4] = {"p_t", "p_r", "eps_t", "eps_r"};
    for (int v = 0; v < 4; ++v)
        for (int k = 0; k < N; ++k) ph.states.push_back(std::string(names[v]) + "[" + std::to_string(k) + "]");
    return b;
}

std::vector<double> clamped_free_frequencies_hz(const PsBeam& beam, int count)
{
    // clamped-free boundary (3.96): u_b = 0, so the spectrum of (J - R) Q
    std::vector<double> f = beam.ph.state_space().natural_frequencies_hz(1e-6);
    if (count >= 0 && static_cast<int>(f.size()) > count) f.resize(static_cast<size_t>(count));
    return f;
}

Eigen::Matrix4d timoshenko_frequency_matrix(const TimoshenkoParams& p, double w)
{
    // (C.6), (C.8), (C.10), (C.13): w below the critical frequency, lambda_1 real, i lambda_2 imaginary
    const double w2 = w * w;
    const double a = p.rho * w2 / p.K_s;
    const double c = p.K_s / p.K_b;
    const double bb = p.I_rho * w2 / p.K_b - c;
    const double d = a + bb + c;
    const double e = a * bb;
    const double disc = std::sqrt(d * d - 4.0 * e);
    const double r1 = -0.5 * d + 0.5 * disc, r2 = -0.5 * d - 0.5 * disc;
    const double l1 = std::sqrt(r1), l2 = std::sqrt(-r2);
    const double A = std::cosh(l1 * p.L), B = std::sinh(l1 * p.L), C = std::cos(l2 * p.L), D = std::sin(l2 * p.L);
    Eigen::Matrix4d m;
    m << 1, 0, 1, 0,
        0, l1 * ((a + c) + l1 * l1), 0, l2 * ((a + c) - l2 * l2),
        l1 * (l1 * l1 + d) * B, l1 * (l1 * l1 + d) * A, l2 * (l2 * l2 - d) * D, -l2 * (l2 * l2 - d) * C,
        (l1 * l1 + a) * A, (l1 * l1 + a) * B, (-l2 * l2 + a) * C, (-l2 * l2 + a) * D;
    return m;
}

std::vector<double> exact_clamped_free_frequencies_hz(const TimoshenkoParams& p, int count)
{
    p.validate();
    require(count >= 1, "exact frequencies: count must be >= 1");
    const double wc = std::sqrt(p.K_s / p.I_rho);  // critical frequency: (C.16) holds below it
    auto det = [&p](double w) { return timoshenko_frequency_matrix(p, w).determinant(); };
    // Bracket the sign changes of det M(w) on a grid of 1/200 of the Euler-Bernoulli fundamental
    // (1.875104/L)^2 sqrt(K_b/rho), far finer than the mode spacing, then bisect to full precision.
    const double w1 = std::pow(1.875104 / p.L, 2) * std::sqrt(p.K_b / p.rho);
    const double step = w1 / 200.0;
    std::vector<double> f;
    double wa = step * 1e-3, fa = det(wa);
    while (static_cast<int>(f.size()) < count) {
        const double wb = wa + step;
        if (wb >= wc) throw std::runtime_error("exact frequencies: fewer than count roots below the critical frequency");
        const double fb = det(wb);
        if ((fa < 0) != (fb < 0)) {
            double lo = wa, hi = wb, flo = fa;
            for (int it = 0; it < 200 && hi - lo > 1e-14 * hi; ++it) {
                const double mid = 0.5 * (lo + hi), fm = det(mid);
                if ((fm < 0) == (flo < 0)) {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            f.push_back(0.5 * (lo + hi) / (2.0 * M_PI));
        }
        wa = wb;
        fa = fb;
    }
    return f;
}

}  // namespace fracdesign
