// matvec.hpp - the replay's per-sample matrix-vector product y (+)= M x.
//
// A replay steps the nominal, the controller and the effects' small blocks
// once per sample, thousands of times per fit: at a servo's two or three
// states Eigen's general product spends more on its dispatch than on the
// arithmetic (perf: 30 % of a servo diagnosis). So for 2 to 8 rows and up to
// 8 columns the product is a plain loop. Up to 64 rows and 127 columns (an
// arm's 48 states, where the product is half of a diagnosis) it runs in
// blocks of 16 rows held in registers, in AVX2 where the CPU has it
// (matvec.cpp, chosen at run time). Single rows (Eigen takes a dot product
// there) and larger blocks keep Eigen's kernels.
//
// Invariant: the result is bit-identical to Eigen 3.4's column-major gemv
// (GeneralMatrixVector.h, without FMA contraction): per row the products
// are summed over the columns in order from zero, and that sum is then added
// to y (y = 0 + sum without add). A diagnosis on a closed loop with a
// quantizing or stick-slip element is sensitive to the last bit (servo bench
// seed 1 cases 0 and 59 change verdict under a reordered sum), so the fast
// path must not change the arithmetic. No allocation.
#pragma once

#include <Eigen/Dense>

namespace fracdesign {
namespace gap {

// y[i] = (add ? y[i] : 0) + sum_j M(i, j) x[j], the sum over j in order from
// zero; for r > 8, c < 128 (matvec.cpp).
void matvec_mid(const double* M, long r, long c, const double* x, double* y, bool add);
// The same without AVX2: what matvec_mid runs on a CPU without it (and what
// the tests check on one with it).
void matvec_mid_portable(const double* M, long r, long c, const double* x, double* y, bool add);

// y = M x (add: y += M x); x has M.cols() entries, y M.rows(); y must not alias x.
inline void matvec(const Eigen::MatrixXd& M, const double* x, double* y, bool add)
{
    const Eigen::Index r = M.rows(), c = M.cols();
    if (r >= 2 && r <= 8 && c <= 8) {
        const double* m = M.data();
        for (Eigen::Index i = 0; i < r; ++i) {
            double sum = 0.0;
            for (Eigen::Index j = 0; j < c; ++j) sum += m[j * r + i] * x[j];
            y[i] = (add ? y[i] : 0.0) + sum;
        }
        return;
    }
    if (r > 8 && r <= 64 && c < 128) {
        matvec_mid(M.data(), long(r), long(c), x, y, add);
        return;
    }
    Eigen::Map<Eigen::VectorXd> ym(y, r);
    const Eigen::Map<const Eigen::VectorXd> xm(x, c);
    if (add)
        ym.noalias() += M * xm;
    else
        ym.noalias() = M * xm;
}

}  // namespace gap
}  // namespace fracdesign
