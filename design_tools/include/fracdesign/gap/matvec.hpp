// matvec.hpp - the replay's per-sample matrix-vector product y (+)= M x.
//
// A replay steps the nominal, the controller and the effects' small blocks
// once per sample, thousands of times per fit: at a servo's two or three
// states Eigen's general product spends more on its dispatch than on the
// arithmetic (perf: 30 % of a servo diagnosis). So for 2 to 8 rows and up
// to 127 columns the product is a plain loop, the rows' sums side by side;
// from 9 up to 64 rows and 127 columns (an arm's 48 states, where the
// product is half of a diagnosis) it runs in blocks of up to 32 rows held in
// registers, in AVX2 where the CPU has it (matvec.cpp, chosen at run time).
// Single rows (Eigen takes a dot product there, whose order of additions
// depends on the data's alignment from 3 columns on) and larger blocks keep
// Eigen's kernels, but for a single row of one or two columns (a plain
// product or sum of two, which is what Eigen's dot product computes there).
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

// R rows (2 to 8), up to 127 columns (more, and Eigen adds partial sums of
// column blocks to y): the R sums side by side over the columns, so that
// their additions overlap (an arm's 2 x 48 output map).
template <int R>
inline void matvec_rows(const double* m, Eigen::Index c, const double* x, double* y, bool add)
{
    double s[R] = {};
    for (Eigen::Index j = 0; j < c; ++j)
        for (int i = 0; i < R; ++i) s[i] += m[j * R + i] * x[j];
    for (int i = 0; i < R; ++i) y[i] = (add ? y[i] : 0.0) + s[i];
}

// y = M x (add: y += M x); x has M.cols() entries, y M.rows(); y must not alias x.
inline void matvec(const Eigen::MatrixXd& M, const double* x, double* y, bool add)
{
    const Eigen::Index r = M.rows(), c = M.cols();
    if (r == 1 && c <= 2) {
        // A single row is Eigen's dot product: its first product, plus the
        // second (in packets or not, whatever the alignment: a sum of two
        // is one addition), added to y (a controller's output row, C x and
        // D e of a PD: Eigen's dispatch was 15 % of a servo diagnosis).
        const double* m = M.data();
        const double sum = c == 0 ? 0.0 : (c == 1 ? m[0] * x[0] : m[0] * x[0] + m[1] * x[1]);
        y[0] = (add ? y[0] : 0.0) + sum;
        return;
    }
    if (r >= 2 && r <= 8 && c < 128) {
        switch (r) {
        case 2: matvec_rows<2>(M.data(), c, x, y, add); return;
        case 3: matvec_rows<3>(M.data(), c, x, y, add); return;
        case 4: matvec_rows<4>(M.data(), c, x, y, add); return;
        case 5: matvec_rows<5>(M.data(), c, x, y, add); return;
        case 6: matvec_rows<6>(M.data(), c, x, y, add); return;
        case 7: matvec_rows<7>(M.data(), c, x, y, add); return;
        default: matvec_rows<8>(M.data(), c, x, y, add); return;
        }
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
