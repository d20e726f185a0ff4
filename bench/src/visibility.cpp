// visibility.cpp - the visibility rule of the simulated families (visibility.hpp).
#include "fracbench/visibility.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fracbench {

double visibility(const Eigen::MatrixXd& with, const Eigen::MatrixXd& without, const std::vector<double>& noise_std)
{
    if (with.rows() != without.rows() || with.cols() != without.cols() || size_t(with.cols()) != noise_std.size() ||
        with.rows() == 0)
        throw std::invalid_argument("gap-bench: visibility needs two records of the same shape and one noise std per column");
    double best = 0;
    for (Eigen::Index c = 0; c < with.cols(); ++c) {
        if (!(noise_std[size_t(c)] > 0)) throw std::invalid_argument("gap-bench: visibility needs noise std > 0");
        const double rms = std::sqrt((with.col(c) - without.col(c)).squaredNorm() / double(with.rows()));
        best = std::max(best, rms / noise_std[size_t(c)]);
    }
    return best;
}

}  // namespace fracbench
