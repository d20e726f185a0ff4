// krylov.cpp - structure-preserving rational block Krylov reduction (seed 004 Sec. 3.5, (3.98)-(3.99)).
#include "fracdesign/models/krylov.hpp"

#include <cmath>
#include <stdexcept>

namespace fracdesign {

std::vector<double> wang_krylov_shifts() { return {16.0, 18.43, 115.6}; }  // Table 8.4, rad/s

PhSystem krylov_reduce(const PhSystem& full, const std::vector<double>& shifts, Eigen::MatrixXd* basis)
{
    if (shifts.empty()) throw std::invalid_argument("krylov: shifts must not be empty");
    for (double s : shifts)
        if (!std::isfinite(s)) throw std::invalid_argument("krylov: shifts must be finite");
    const Eigen::Index n = full.J.rows(), m = full.B.cols();
    const Eigen::Index r = m * static_cast<Eigen::Index>(shifts.size());
    if (r > n) throw std::invalid_argument("krylov: shifts x inputs exceeds the full order");
    const Eigen::MatrixXd A = full.A();
    // Input Krylov blocks (s_i I - A)^-1 B: the reduced model matches H(s_i) (moment matching)
    Eigen::MatrixXd K(n, r);
    for (size_t i = 0; i < shifts.size(); ++i) {
        Eigen::MatrixXd M = -A;
        M.diagonal().array() += shifts[i];
        Eigen::FullPivLU<Eigen::MatrixXd> lu(M);
        if (!lu.isInvertible()) throw std::runtime_error("krylov: s I - A is singular at a shift");
        K.middleCols(static_cast<Eigen::Index>(i) * m, m) = lu.solve(full.B);
    }
    // Orthonormal basis V of span(K) (column-pivoted Householder QR detects a rank loss)
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(K);
    qr.setThreshold(1e-12);
    if (qr.rank() < r) throw std::runtime_error("krylov: the Krylov basis lost rank (repeated shifts?)");
    const Eigen::MatrixXd V = qr.householderQ() * Eigen::MatrixXd::Identity(n, r);

    // W = Q V (3.98); every projected matrix keeps its PH structure (3.99)
    const Eigen::MatrixXd QV = full.Q * V;
    PhSystem red;
    red.Q = V.transpose() * QV;
    red.Q = (0.5 * (red.Q + red.Q.transpose())).eval();
    const Eigen::LLT<Eigen::MatrixXd> llt(red.Q);
    if (llt.info() != Eigen::Success) throw std::runtime_error("krylov: V^T Q V is not positive definite");
    const Eigen::MatrixXd Qi = llt.solve(Eigen::MatrixXd::Identity(r, r));
    red.J = Qi * (QV.transpose() * full.J * QV) * Qi;
    red.R = Qi * (QV.transpose() * full.R * QV) * Qi;
    red.B = Qi * (QV.transpose() * full.B);
    red.D = full.D;
    red.inputs = full.inputs;
    red.outputs = full.outputs;
    for (Eigen::Index k = 0; k < r; ++k) red.states.push_back("xr[" + std::to_string(k) + "]");
    if (basis) *basis = V;
    return red;
}

}  // namespace fracdesign
