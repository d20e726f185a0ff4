// lti.cpp - the shared LTI state-space type (see fracdesign/models/lti.hpp).
#include "fracdesign/models/lti.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fracdesign {

namespace {
void check_finite(const Eigen::MatrixXd& m, const char* name)
{
    if (!m.allFinite()) throw std::invalid_argument(std::string("state space: matrix ") + name + " has a non-finite entry");
}
}  // namespace

void StateSpace::validate() const
{
    const Eigen::Index n = A.rows();
    if (A.cols() != n) throw std::invalid_argument("state space: matrix A must be square");
    if (B.rows() != n) throw std::invalid_argument("state space: matrix B must have as many rows as A");
    if (C.cols() != n) throw std::invalid_argument("state space: matrix C must have as many columns as A");
    if (D.rows() != C.rows() || D.cols() != B.cols())
        throw std::invalid_argument("state space: matrix D must be outputs x inputs");
    check_finite(A, "A");
    check_finite(B, "B");
    check_finite(C, "C");
    check_finite(D, "D");
    if (!inputs.empty() && static_cast<Eigen::Index>(inputs.size()) != B.cols())
        throw std::invalid_argument("state space: inputs must name every column of B");
    if (!outputs.empty() && static_cast<Eigen::Index>(outputs.size()) != C.rows())
        throw std::invalid_argument("state space: outputs must name every row of C");
    if (!states.empty() && static_cast<Eigen::Index>(states.size()) != n)
        throw std::invalid_argument("state space: states must name every state");
    if (!std::isfinite(Ts) || Ts < 0) throw std::invalid_argument("state space: Ts must be finite and >= 0");
}

Eigen::MatrixXcd StateSpace::transfer(std::complex<double> s) const
{
    Eigen::MatrixXcd M = -A.cast<std::complex<double>>();
    M.diagonal().array() += s;
    Eigen::MatrixXcd X = M.partialPivLu().solve(B.cast<std::complex<double>>());
    return C.cast<std::complex<double>>() * X + D.cast<std::complex<double>>();
}

Eigen::MatrixXcd StateSpace::frequency_response(double w) const
{
    const std::complex<double> jw(0.0, w);
    return transfer(continuous() ? jw : std::exp(jw * Ts));
}

StateSpace StateSpace::balanced() const
{
    StateSpace b = *this;
    const Eigen::Index n = nx();
    if (n == 0) return b;
    // Parlett-Reinsch: repeat over the states, scaling state i by a power of
    // two f when that lowers ||row_i|| + ||col_i|| (off-diagonal, 1-norms) by
    // more than 5 % (LAPACK dgebal's factor 0.95), until no state changes.
    constexpr double radix = 2.0;
    bool changed = true;
    for (int sweep = 0; changed && sweep < 200; ++sweep) {
        changed = false;
        for (Eigen::Index i = 0; i < n; ++i) {
            double c = 0, r = 0;
            for (Eigen::Index j = 0; j < n; ++j) {
                if (j == i) continue;
                c += std::fabs(b.A(j, i));
                r += std::fabs(b.A(i, j));
            }
            if (!(c > 0) || !(r > 0) || !std::isfinite(c) || !std::isfinite(r)) continue;
            double g = r / radix, f = 1.0;
            const double s = c + r;
            while (c < g) {
                f *= radix;
                c *= radix;
                r /= radix;
                g = r / radix;
            }
            g = r * radix;
            while (c >= g) {
                f /= radix;
                c /= radix;
                r *= radix;
                g = r * radix;
            }
            if ((c + r) >= 0.95 * s * 1.0 || f == 1.0) continue;
            // x_i = f xb_i: column i of A and C times f, row i of A and B over f.
            b.A.col(i) *= f;
            b.A.row(i) /= f;
            b.B.row(i) /= f;
            b.C.col(i) *= f;
            changed = true;
        }
    }
    return b;
}

Eigen::VectorXcd StateSpace::poles() const
{
    if (A.rows() == 0) return Eigen::VectorXcd();
    Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
    return es.eigenvalues();
}

std::vector<double> StateSpace::natural_frequencies_hz(double tol_rad_s) const
{
    const Eigen::VectorXcd ev = poles();
    std::vector<double> f;
    for (Eigen::Index i = 0; i < ev.size(); ++i)
        if (ev[i].imag() > tol_rad_s) f.push_back(ev[i].imag() / (2.0 * M_PI));
    std::sort(f.begin(), f.end());
    return f;
}

Eigen::VectorXcd StateSpace::siso_zeros(Eigen::Index i, Eigen::Index j) const
{
    const Eigen::Index n = A.rows();
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(n + 1, n + 1), E = Eigen::MatrixXd::Zero(n + 1, n + 1);
    P.topLeftCorner(n, n) = A;
    P.topRightCorner(n, 1) = B.col(j);
    P.bottomLeftCorner(1, n) = C.row(i);
    P(n, n) = D(i, j);
    E.topLeftCorner(n, n).setIdentity();
    Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> ges(P, E, false);
    const Eigen::VectorXcd al = ges.alphas();
    const Eigen::VectorXd be = ges.betas();
    const double scale = std::max(1.0, P.cwiseAbs().maxCoeff());
    std::vector<std::complex<double>> z;
    for (Eigen::Index k = 0; k < al.size(); ++k)
        if (std::abs(be[k]) * scale > 1e-12 * std::abs(al[k])) z.push_back(al[k] / be[k]);  // else infinite
    Eigen::VectorXcd out(static_cast<Eigen::Index>(z.size()));
    for (size_t k = 0; k < z.size(); ++k) out[static_cast<Eigen::Index>(k)] = z[k];
    return out;
}

}  // namespace fracdesign
