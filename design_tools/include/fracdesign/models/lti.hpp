// lti.hpp - continuous (or discrete) LTI state-space model shared by every model of fracdesign.
//
//   continuous:  x' = A x + B u,        y = C x + D u
//   discrete:    x[k+1] = A x[k] + B u[k], y[k] = C x[k] + D u[k]   (sample time Ts > 0)
//
// Every rational model (Timoshenko beam, 2-mass drive, arm, collocated plant of seed 002) produces
// one with named inputs, outputs and states (SI units in the names' documentation). Irrational models
// (the antenna of seed 000, the fractional process of seed 001) only expose frequency responses.
#pragma once
#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

namespace fracdesign {

struct StateSpace {
    Eigen::MatrixXd A, B, C, D;
    std::vector<std::string> inputs;   // one name per column of B (e.g. "tau_M [N m]")
    std::vector<std::string> outputs;  // one name per row of C
    std::vector<std::string> states;   // one name per state (may be empty: then x1..xn)
    double Ts = 0.0;                   // 0: continuous time; > 0: discrete, sample time in s

    bool continuous() const { return Ts == 0.0; }
    Eigen::Index nx() const { return A.rows(); }
    Eigen::Index nu() const { return B.cols(); }
    Eigen::Index ny() const { return C.rows(); }

    // Throws std::invalid_argument (one line naming the matrix) when dimensions disagree, names have the
    // wrong count, an entry is not finite, or Ts < 0.
    void validate() const;
    // Transfer matrix H(s) = C (sI - A)^-1 B + D at a complex point s (continuous: s = j w; discrete: z).
    Eigen::MatrixXcd transfer(std::complex<double> s) const;
    // H at s = j w (continuous) or z = exp(j w Ts) (discrete), w in rad/s.
    Eigen::MatrixXcd frequency_response(double w) const;
    // Eigenvalues of A.
    Eigen::VectorXcd poles() const;
    // Undamped/lightly damped natural frequencies in Hz: |Im lambda|/(2 pi) of the eigenvalues of A with
    // Im lambda > tol_rad_s, ascending, each conjugate pair counted once (continuous models only).
    std::vector<double> natural_frequencies_hz(double tol_rad_s = 1e-6) const;
    // The same system in balanced state coordinates: x = S xb with S diagonal,
    // powers of two, so that each state's row and column of A have about the
    // same norm (Parlett & Reinsch, Numer. Math. 13 (1969), the scaling step
    // of LAPACK's dgebal without its permutations). A poorly scaled
    // realization (an Oustaloup cascade over eleven decades has entries of
    // 1e12 beside 1e-5) loses the accuracy of its matrix exponential; the
    // balanced one has the same eigenvalues, transfer matrix and, the scaling
    // being exact in binary floating point, the same products up to rounding.
    // The state names are kept (each state is scaled, not mixed).
    StateSpace balanced() const;
    // Transmission zeros of the SISO channel (output i, input j): finite generalized eigenvalues of the
    // Rosenbrock pencil [[A, b],[c, d]] - s [[I,0],[0,0]].
    Eigen::VectorXcd siso_zeros(Eigen::Index i, Eigen::Index j) const;
};

}  // namespace fracdesign
