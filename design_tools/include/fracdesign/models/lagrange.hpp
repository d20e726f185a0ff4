// lagrange.hpp - nodes, quadrature and barycentric Lagrange bases for the pseudo-spectral beam.
//
// The bases of seed 004 eq. (3.56)-(3.59) are Lagrange polynomials on N+1 effort nodes and N flow
// nodes. They are evaluated in the barycentric form (Berrut & Trefethen 2004), which stays
// accurate at any N; the monomial/Vandermonde form breaks down by N = 12 (seed 004, App. D).
#pragma once
#include <Eigen/Dense>

namespace fracdesign {

// Gauss-Legendre nodes and weights on [a, b] (n >= 1 points; Newton on P_n from the Chebyshev guesses).
void gauss_legendre(int n, double a, double b, Eigen::VectorXd& nodes, Eigen::VectorXd& weights);

// Barycentric interpolation on distinct nodes x_0..x_n.
class BarycentricBasis {
public:
    explicit BarycentricBasis(const Eigen::VectorXd& nodes);
    const Eigen::VectorXd& nodes() const { return x_; }
    Eigen::Index size() const { return x_.size(); }
    // Values l_i(t) of every basis polynomial at t (exact Kronecker delta at a node).
    Eigen::VectorXd values(double t) const;
    // Derivatives l_i'(t) of every basis polynomial at t.
    Eigen::VectorXd derivatives(double t) const;

private:
    Eigen::VectorXd x_, w_;  // nodes and barycentric weights w_i = 1 / prod_{j != i}(x_i - x_j)
};

}  // namespace fracdesign
