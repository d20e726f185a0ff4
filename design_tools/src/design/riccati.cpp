// riccati.cpp - CARE (matrix sign function), DARE (structured doubling), ZOH.
#include "fracdesign/design/riccati.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>

#include <unsupported/Eigen/MatrixFunctions>

namespace fracdesign::design {
namespace {

using Eigen::MatrixXd;
using Cause = RiccatiError::Cause;

constexpr int kMaxIter = 100;

bool finite(const MatrixXd& M) { return M.allFinite(); }

// Problem after removing the cross term: A~ = A - B R^-1 S', Q~ = Q - S R^-1 S',
// G = B R^-1 B' (standard reduction; the gain is recovered with S afterwards).
struct Reduced {
    MatrixXd A, G, Q;
};

void check_input(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, const MatrixXd& S)
{
    const Eigen::Index n = A.rows(), m = B.cols();
    auto bad = [](const std::string& w) { throw RiccatiError(Cause::BadInput, w); };
    if (n == 0 || A.cols() != n) bad("A must be square and non-empty");
    if (B.rows() != n || m == 0) bad("B must have as many rows as A and at least one column");
    if (Q.rows() != n || Q.cols() != n) bad("Q must be n x n");
    if (R.rows() != m || R.cols() != m) bad("R must be m x m");
    if (S.size() != 0 && (S.rows() != n || S.cols() != m)) bad("S must be n x m (or empty)");
    if (!finite(A) || !finite(B) || !finite(Q) || !finite(R) || !finite(S)) bad("non-finite entry in A, B, Q, R or S");
    if ((Q - Q.transpose()).norm() > 1e-10 * (1.0 + Q.norm())) bad("Q must be symmetric");
    if ((R - R.transpose()).norm() > 1e-10 * (1.0 + R.norm())) bad("R must be symmetric");
    Eigen::LLT<MatrixXd> llt(0.5 * (R + R.transpose()));
    if (llt.info() != Eigen::Success) throw RiccatiError(Cause::RNotPosDef, "R is not positive definite");
}

Reduced reduce(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, const MatrixXd& S)
{
    Eigen::LLT<MatrixXd> llt(0.5 * (R + R.transpose()));
    Reduced r;
    r.G = B * llt.solve(B.transpose());
    r.G = 0.5 * (r.G + r.G.transpose());
    if (S.size() == 0) {
        r.A = A;
        r.Q = Q;
    } else {
        const MatrixXd RiSt = llt.solve(S.transpose());
        r.A = A - B * RiSt;
        r.Q = Q - S * RiSt;
        r.Q = 0.5 * (r.Q + r.Q.transpose());
    }
    return r;
}

std::string fmt_c(std::complex<double> z)
{
    std::ostringstream os;
    os.precision(6);
    os << z.real() << (z.imag() < 0 ? " - " : " + ") << std::fabs(z.imag()) << "j";
    return os.str();
}

// PBH tests on the modes of A outside the stability region (continuous: Re >= -margin,
// discrete: |lambda| >= 1 - margin). Throws the first cause found; returns if none.
void diagnose(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Qt, bool discrete, const std::string& fallback)
{
    const Eigen::Index n = A.rows();
    Eigen::EigenSolver<MatrixXd> es(A, false);
    const double scaleB = A.norm() + B.norm(), scaleQ = A.norm() + Qt.norm();
    for (Eigen::Index i = 0; i < n; ++i) {
        const std::complex<double> lam = es.eigenvalues()(i);
        const bool outside = discrete ? std::abs(lam) >= 1.0 - 1e-9 : lam.real() >= -1e-9;
        if (!outside) continue;
        Eigen::MatrixXcd M = A.cast<std::complex<double>>() - lam * Eigen::MatrixXcd::Identity(n, n);
        Eigen::MatrixXcd ctrb(n, n + B.cols());
        ctrb << M, B.cast<std::complex<double>>();
        Eigen::JacobiSVD<Eigen::MatrixXcd> sc(ctrb);
        if (sc.singularValues()(n - 1) <= 1e-9 * scaleB)
            throw RiccatiError(Cause::Unstabilizable, "(A, B) is not stabilizable: the mode lambda = " + fmt_c(lam) +
                                                          " of A is not controllable from B");
        const bool marginal = discrete ? std::abs(std::abs(lam) - 1.0) <= 1e-9 : std::fabs(lam.real()) <= 1e-9;
        Eigen::MatrixXcd obsv(2 * n, n);
        obsv << M, Qt.cast<std::complex<double>>();
        Eigen::JacobiSVD<Eigen::MatrixXcd> so(obsv);
        if (so.singularValues()(n - 1) <= 1e-9 * scaleQ && marginal)
            throw RiccatiError(Cause::Undetectable, "(Q, A) is not detectable: the mode lambda = " + fmt_c(lam) +
                                                        " of A on the stability boundary is not seen by the weight Q");
    }
    throw RiccatiError(Cause::NoConvergence, fallback);
}

double spectral(const MatrixXd& Acl, bool discrete)
{
    Eigen::EigenSolver<MatrixXd> es(Acl, false);
    double v = -std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < Acl.rows(); ++i)
        v = std::max(v, discrete ? std::abs(es.eigenvalues()(i)) : es.eigenvalues()(i).real());
    return v;
}

// Residual of the cross-term-free DARE at X and the closed loop A - B K(X).
MatrixXd dare_res(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, const MatrixXd& X,
                  MatrixXd& Acl)
{
    const MatrixXd BtX = B.transpose() * X;
    const MatrixXd K = (R + BtX * B).ldlt().solve(BtX * A);
    Acl = A - B * K;
    // Equivalent symmetric form: A'XA - X - A'XB K + Q = Acl' X Acl + K' R K - X + Q.
    MatrixXd res = Acl.transpose() * X * Acl + K.transpose() * R * K - X + Q;
    return 0.5 * (res + res.transpose());
}

// Newton refinement of a DARE solution (Hewer 1971): X <- X + D with
// D = Acl' D Acl + Res(X), the Stein equation solved by Smith's doubling
// (D <- D + S' D S, S <- S^2). At most two steps, kept only while the residual drops;
// it repairs the accuracy the doubling loses on badly scaled problems.
void refine_dare(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, MatrixXd& X)
{
    MatrixXd Acl;
    MatrixXd res = dare_res(A, B, Q, R, X, Acl);
    double rn = res.norm();
    for (int step = 0; step < 2 && rn > 0.0; ++step) {
        MatrixXd D = res, S = Acl;
        for (int k = 0; k < 60; ++k) {
            const MatrixXd inc = S.transpose() * D * S;
            D += inc;
            if (inc.norm() <= 1e-16 * D.norm()) break;
            S = S * S;
        }
        const MatrixXd Xn = X + 0.5 * (D + D.transpose());
        MatrixXd Acln;
        const MatrixXd resn = dare_res(A, B, Q, R, Xn, Acln);
        if (!(resn.norm() < rn) || !Xn.allFinite()) break;
        X = Xn;
        res = resn;
        rn = resn.norm();
    }
}

}  // namespace

double care_residual(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, const MatrixXd& S,
                     const MatrixXd& X)
{
    const MatrixXd XBS = S.size() ? MatrixXd(X * B + S) : MatrixXd(X * B);
    const MatrixXd res = A.transpose() * X + X * A - XBS * R.llt().solve(XBS.transpose()) + Q;
    return res.norm() / std::max(1.0, Q.norm() + X.norm());
}

double dare_residual(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, const MatrixXd& S,
                     const MatrixXd& X)
{
    const MatrixXd XA = X * A;
    const MatrixXd AXBS = S.size() ? MatrixXd(XA.transpose() * B + S) : MatrixXd(XA.transpose() * B);
    const MatrixXd res =
        A.transpose() * XA - X - AXBS * (R + B.transpose() * X * B).ldlt().solve(AXBS.transpose()) + Q;
    return res.norm() / std::max(1.0, Q.norm() + X.norm());
}

RiccatiSolution solve_dare(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R,
                           const MatrixXd& S)
{
    check_input(A, B, Q, R, S);
    const Eigen::Index n = A.rows();
    Reduced p = reduce(A, B, Q, R, S);
    // Structured doubling (SDA), Chu, Fan & Lin 2005: with W_k = I + G_k H_k,
    //   A_{k+1} = A_k W_k^-1 A_k,  G_{k+1} = G_k + A_k W_k^-1 G_k A_k',
    //   H_{k+1} = H_k + A_k' H_k W_k^-1 A_k;  H_k -> X quadratically when the
    // symplectic pencil has no eigenvalue on the unit circle.
    MatrixXd Ak = p.A, Gk = p.G, Hk = p.Q;
    const MatrixXd I = MatrixXd::Identity(n, n);
    RiccatiSolution sol;
    bool converged = false;
    for (int k = 0; k < kMaxIter; ++k) {
        Eigen::PartialPivLU<MatrixXd> lu(I + Gk * Hk);
        const MatrixXd V1 = lu.solve(Ak);  // W^-1 A
        const MatrixXd V2 = lu.solve(Gk);  // W^-1 G
        MatrixXd Hn = Hk + Ak.transpose() * (Hk * V1);
        MatrixXd Gn = Gk + Ak * V2 * Ak.transpose();
        Ak = Ak * V1;
        Hn = 0.5 * (Hn + Hn.transpose());
        Gk = 0.5 * (Gn + Gn.transpose());
        sol.iterations = k + 1;
        if (!finite(Hn) || !finite(Ak)) break;
        const double change = (Hn - Hk).norm();
        Hk.swap(Hn);
        if (change <= 1e-15 * Hk.norm()) {
            converged = true;
            break;
        }
    }
    if (!converged || !finite(Hk))
        diagnose(p.A, B, p.Q, true, "structured doubling did not converge in " + std::to_string(sol.iterations) +
                                        " iterations (a pencil eigenvalue on or near the unit circle)");
    sol.X = Hk;
    refine_dare(p.A, B, p.Q, R, sol.X);
    const MatrixXd BtX = B.transpose() * sol.X;
    const MatrixXd rhs = S.size() ? MatrixXd(BtX * A + S.transpose()) : MatrixXd(BtX * A);
    sol.K = (R + BtX * B).ldlt().solve(rhs);
    sol.stability = spectral(A - B * sol.K, true);
    if (!(sol.stability < 1.0))
        diagnose(p.A, B, p.Q, true, "the solution found does not stabilise A - B K (spectral radius " +
                                        std::to_string(sol.stability) + ")");
    sol.residual = dare_residual(A, B, Q, R, S, sol.X);
    return sol;
}

RiccatiSolution solve_care(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R,
                           const MatrixXd& S)
{
    check_input(A, B, Q, R, S);
    const Eigen::Index n = A.rows();
    Reduced p = reduce(A, B, Q, R, S);
    // Hamiltonian H = [[A, -G], [-Q, -A']]; its stable invariant subspace is span [I; X].
    MatrixXd Z(2 * n, 2 * n);
    Z << p.A, -p.G, -p.Q, -p.A.transpose();
    // Matrix sign function with determinant scaling (Byers 1987):
    //   Z <- (c Z + (c Z)^-1) / 2,  c = |det Z|^(-1/(2n)).
    RiccatiSolution sol;
    bool converged = false;
    for (int k = 0; k < kMaxIter; ++k) {
        Eigen::PartialPivLU<MatrixXd> lu(Z);
        const MatrixXd Zi = lu.inverse();
        double logdet = 0.0;
        for (Eigen::Index i = 0; i < 2 * n; ++i) logdet += std::log(std::fabs(lu.matrixLU()(i, i)));
        const double c = std::exp(-logdet / (2.0 * n));
        const MatrixXd Zn = 0.5 * (c * Z + Zi / c);
        sol.iterations = k + 1;
        if (!finite(Zn) || !std::isfinite(c)) break;
        const double change = (Zn - Z).lpNorm<1>();
        Z = Zn;
        if (change <= 1e-13 * Z.lpNorm<1>()) {
            converged = true;
            break;
        }
    }
    if (!converged)
        diagnose(p.A, B, p.Q, false, "the matrix sign iteration did not converge in " + std::to_string(sol.iterations) +
                                         " iterations (a Hamiltonian eigenvalue on or near the imaginary axis)");
    // sign(H) [I; X] = -[I; X]:  [W12; W22 + I] X = -[W11 + I; W21]  (least squares).
    MatrixXd lhs(2 * n, n), rhs(2 * n, n);
    lhs << Z.topRightCorner(n, n), Z.bottomRightCorner(n, n) + MatrixXd::Identity(n, n);
    rhs << Z.topLeftCorner(n, n) + MatrixXd::Identity(n, n), Z.bottomLeftCorner(n, n);
    sol.X = lhs.colPivHouseholderQr().solve(-rhs);
    sol.X = 0.5 * (sol.X + sol.X.transpose());
    if (!finite(sol.X)) diagnose(p.A, B, p.Q, false, "the stable invariant subspace is not a graph [I; X]");
    const MatrixXd rhsK = S.size() ? MatrixXd(B.transpose() * sol.X + S.transpose()) : MatrixXd(B.transpose() * sol.X);
    sol.K = R.llt().solve(rhsK);
    sol.stability = spectral(A - B * sol.K, false);
    if (!(sol.stability < 0.0))
        diagnose(p.A, B, p.Q, false, "the solution found does not stabilise A - B K (spectral abscissa " +
                                         std::to_string(sol.stability) + ")");
    sol.residual = care_residual(A, B, Q, R, S, sol.X);
    return sol;
}

StateSpace c2d_zoh(const StateSpace& sys, double Ts)
{
    if (!sys.continuous()) throw std::invalid_argument("c2d_zoh: the model is already discrete");
    if (!std::isfinite(Ts) || Ts <= 0.0) throw std::invalid_argument("c2d_zoh: Ts must be finite and > 0");
    sys.validate();
    const Eigen::Index n = sys.nx(), m = sys.nu();
    MatrixXd M = MatrixXd::Zero(n + m, n + m);
    M.topLeftCorner(n, n) = sys.A * Ts;
    M.topRightCorner(n, m) = sys.B * Ts;
    const MatrixXd E = M.exp();
    StateSpace d = sys;
    d.A = E.topLeftCorner(n, n);
    d.B = E.topRightCorner(n, m);
    d.Ts = Ts;
    return d;
}

FohDiscretisation c2d_foh(const StateSpace& sys, double Ts)
{
    if (!sys.continuous()) throw std::invalid_argument("c2d_foh: the model is already discrete");
    if (!std::isfinite(Ts) || Ts <= 0.0) throw std::invalid_argument("c2d_foh: Ts must be finite and > 0");
    sys.validate();
    const Eigen::Index n = sys.nx(), m = sys.nu();
    MatrixXd M = MatrixXd::Zero(n + 2 * m, n + 2 * m);
    M.topLeftCorner(n, n) = sys.A * Ts;
    M.block(0, n, n, m) = sys.B * Ts;
    M.block(n, n + m, m, m) = MatrixXd::Identity(m, m);
    // M = [[A Ts, B Ts, 0], [0, 0, I], [0, 0, 0]] is the system in tau = s / Ts driven by u0 + v tau:
    // its exponential's (1,2) block is P, its (1,3) block int_0^1 e^{A Ts (1 - tau)} B Ts tau dtau = R / Ts.
    const MatrixXd E = M.exp();
    FohDiscretisation d;
    d.Ad = E.topLeftCorner(n, n);
    const MatrixXd P = E.block(0, n, n, m), R_over_T = E.block(0, n + m, n, m);
    d.B_prev = P - R_over_T;
    d.B_now = R_over_T;
    return d;
}

}  // namespace fracdesign::design
