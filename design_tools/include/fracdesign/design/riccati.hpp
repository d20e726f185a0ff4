// riccati.hpp - algebraic Riccati equations and ZOH discretisation (seed 004 Ch. 6-7).
//
// Continuous (CARE):  A'X + X A - (X B + S) R^-1 (B'X + S') + Q = 0,   K = R^-1 (B'X + S')
// Discrete   (DARE):  A'X A - X - (A'X B + S)(R + B'X B)^-1 (B'X A + S') + Q = 0,
//                     K = (R + B'X B)^-1 (B'X A + S')
// The stabilising solution X = X' >= 0 is returned with the closed loop A - B K,
// its spectral abscissa / radius, and the relative residual
//   ||Res(X)||_F / max(1, ||Q||_F + ||X||_F)   (Res = the left-hand side above).
//
// Methods (no code taken from elsewhere, algorithms from the literature):
//  - DARE: structured doubling algorithm (Chu, Fan & Lin 2005) on the symplectic
//    pencil with G = B R^-1 B', H = Q - S R^-1 S', A <- A - B R^-1 S'; quadratic convergence;
//    then up to two Newton steps (Hewer 1971) whose Stein equations are solved by Smith's
//    doubling, kept while the residual drops (restores accuracy on badly scaled problems).
//  - CARE: Newton-scaled matrix sign function of the Hamiltonian (Roberts 1971,
//    Byers 1987), then X from the stable invariant subspace by least squares.
// A failure is diagnosed by PBH tests on the modes of A and thrown as RiccatiError
// naming the cause: unstabilizable (a mode outside the stability region not
// controllable from B), undetectable (such a mode unobservable from Q), R not
// positive definite, or no convergence.
#pragma once
#include <Eigen/Dense>
#include <stdexcept>
#include <string>

#include "fracdesign/models/lti.hpp"

namespace fracdesign::design {

struct RiccatiError : std::runtime_error {
    enum class Cause { BadInput, RNotPosDef, Unstabilizable, Undetectable, NoConvergence };
    Cause cause;
    RiccatiError(Cause c, const std::string& what) : std::runtime_error(what), cause(c) {}
};

struct RiccatiSolution {
    Eigen::MatrixXd X;          // stabilising solution
    Eigen::MatrixXd K;          // optimal gain, u = -K x
    double residual = 0.0;      // relative residual (see above)
    double stability = 0.0;     // CARE: max Re eig(A-BK) (< 0); DARE: max |eig(A-BK)| (< 1)
    int iterations = 0;
};

// Empty S means no cross term. Throws RiccatiError on failure.
RiccatiSolution solve_care(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                           const Eigen::MatrixXd& R, const Eigen::MatrixXd& S = Eigen::MatrixXd());
RiccatiSolution solve_dare(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                           const Eigen::MatrixXd& R, const Eigen::MatrixXd& S = Eigen::MatrixXd());

// The residuals as defined above, for any X (used by the tests and the bench).
double care_residual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                     const Eigen::MatrixXd& R, const Eigen::MatrixXd& S, const Eigen::MatrixXd& X);
double dare_residual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                     const Eigen::MatrixXd& R, const Eigen::MatrixXd& S, const Eigen::MatrixXd& X);

// Zero-order-hold discretisation (seed 004 (7.3)-(7.7)): exp([[A, B],[0, 0]] Ts) =
// [[Ad, Bd],[0, I]] (Eigen's scaling-and-squaring Pade matrix exponential).
// Returns a discrete StateSpace with Ts set; C, D and names are copied.
// Throws std::invalid_argument if sys is not continuous or Ts is not finite and > 0.
StateSpace c2d_zoh(const StateSpace& sys, double Ts);

// First-order hold of an input ramped linearly over each step from u[k-1] to u[k] (a drive whose
// torque ramps between its reported values, hil/drive.h): x[k+1] = Ad x[k] + B_prev u[k-1] + B_now u[k]
// with Ad = e^{A Ts}, P = int_0^Ts e^{A s} ds B, R = int_0^Ts e^{A (Ts - s)} B s ds, B_prev = P - R/Ts,
// B_now = R/Ts (the blocks of exp([[A, B, 0], [0, 0, I], [0, 0, 0]] Ts)). Exact for a piecewise-linear
// input. Throws std::invalid_argument as c2d_zoh.
struct FohDiscretisation {
    Eigen::MatrixXd Ad, B_prev, B_now;
};
FohDiscretisation c2d_foh(const StateSpace& sys, double Ts);

}  // namespace fracdesign::design
