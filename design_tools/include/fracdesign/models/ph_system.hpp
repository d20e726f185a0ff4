// ph_system.hpp - linear port-Hamiltonian systems (seed 004, Def. 3.2, eq. (3.93)):
//
//   x' = (J - R) Q x + B u,   y = B^T Q x + D u,   H(x) = 1/2 x^T Q x
//
// with J = -J^T, R = R^T >= 0, Q = Q^T >= 0 and D = -D^T (skew feedthrough), so that the power balance
// dH/dt = u^T y - (Qx)^T R (Qx) <= u^T y holds (seed 004 eq. (3.15)).
#pragma once
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "fracdesign/models/lti.hpp"

namespace fracdesign {

struct PhSystem {
    Eigen::MatrixXd J, R, Q, B, D;
    std::vector<std::string> inputs, outputs, states;

    Eigen::MatrixXd A() const { return (J - R) * Q; }
    // The equivalent state space (A = (J-R)Q, B, C = B^T Q, D).
    StateSpace state_space() const;
    // max|J + J^T| / max|J| (0 for an exactly skew J): the structure check of seed 004 Prop. 3.6.
    double skew_residual() const;
};

}  // namespace fracdesign
