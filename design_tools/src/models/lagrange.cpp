// lagrange.cpp - Gauss-Legendre quadrature and barycentric Lagrange bases (fracdesign/models/lagrange.hpp).
#include "fracdesign/models/lagrange.hpp"

#include <cmath>
#include <stdexcept>

namespace fracdesign {

void gauss_legendre(int n, double a, double b, Eigen::VectorXd& nodes, Eigen::VectorXd& weights)
{
    if (n < 1) throw std::invalid_argument("gauss_legendre: n must be >= 1");
    nodes.resize(n);
    weights.resize(n);
    for (int i = 0; i < n; ++i) {
        // Newton on P_n from the Chebyshev-like guess cos(pi (i + 3/4)/(n + 1/2)); the three-term
        // recurrence gives P_n and P_{n-1}, and P_n' = n (x P_n - P_{n-1})/(x^2 - 1).
        double x = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = pk;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::fabs(dx) < 1e-16) break;
        }
        // ascending order on [a, b]
        nodes[n - 1 - i] = 0.5 * (a + b) + 0.5 * (b - a) * x;
        weights[n - 1 - i] = (b - a) / ((1.0 - x * x) * dp * dp);
    }
}

BarycentricBasis::BarycentricBasis(const Eigen::VectorXd& nodes) : x_(nodes), w_(nodes.size())
{
    const Eigen::Index n = x_.size();
    if (n < 1) throw std::invalid_argument("barycentric basis: no nodes");
    for (Eigen::Index i = 0; i < n; ++i) {
        double prod = 1.0;
        for (Eigen::Index j = 0; j < n; ++j)
            if (j != i) {
                const double d = x_[i] - x_[j];
                if (d == 0.0) throw std::invalid_argument("barycentric basis: nodes must be distinct");
                prod *= d;
            }
        w_[i] = 1.0 / prod;
    }
}

Eigen::VectorXd BarycentricBasis::values(double t) const
{
    const Eigen::Index n = x_.size();
    Eigen::VectorXd l(n);
    for (Eigen::Index i = 0; i < n; ++i)
        if (t == x_[i]) {
            l.setZero();
            l[i] = 1.0;
            return l;
        }
    // second (true) barycentric form: l_i(t) = (w_i/(t - x_i)) / sum_j w_j/(t - x_j)
    double s = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
        l[i] = w_[i] / (t - x_[i]);
        s += l[i];
    }
    return l / s;
}

Eigen::VectorXd BarycentricBasis::derivatives(double t) const
{
    const Eigen::Index n = x_.size();
    Eigen::VectorXd d(n);
    for (Eigen::Index m = 0; m < n; ++m)
        if (t == x_[m]) {
            // at a node: l_i'(x_m) = (w_i/w_m)/(x_m - x_i) for i != m, l_m' = -sum of the others
            double sum = 0.0;
            for (Eigen::Index i = 0; i < n; ++i)
                if (i != m) {
                    d[i] = (w_[i] / w_[m]) / (x_[m] - x_[i]);
                    sum += d[i];
                }
            d[m] = -sum;
            return d;
        }
    // off the nodes: l_i' = l_i (sum_j w_j/(t-x_j)^2 / sum_j w_j/(t-x_j) - 1/(t - x_i))
    const Eigen::VectorXd l = values(t);
    double s1 = 0.0, s2 = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) {
        const double r = 1.0 / (t - x_[j]);
        s1 += w_[j] * r;
        s2 += w_[j] * r * r;
    }
    for (Eigen::Index i = 0; i < n; ++i) d[i] = l[i] * (s2 / s1 - 1.0 / (t - x_[i]));
    return d;
}

}  // namespace fracdesign
