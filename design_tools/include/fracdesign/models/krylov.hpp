// krylov.hpp - structure-preserving rational Krylov reduction of a PH system (seed 004 Sec. 3.5,
// eqs. (3.98)-(3.99), after Wolf, Lohmann, Eid & Kotyczka 2010 and Gugercin et al. 2012).
//
// V spans the block Krylov subspace {(s_i I - A)^-1 B} over the real shifts s_i (one block of m
// input columns per shift, orthonormalised), W = Q V, and
//   Q_r = V^T Q V,  J_r = Q_r^-1 V^T Q J Q V Q_r^-1,  R_r = Q_r^-1 V^T Q R Q V Q_r^-1,
//   B_r = Q_r^-1 V^T Q B,  D_r = D.
// The reduced model is again PH (J_r skew, R_r >= 0, Q_r > 0: passive) and matches H(s_i) of the full
// model at every shift. Thesis choice (Table 8.4): N = 9 (36 states) -> r = 12, shifts 16, 18.43, 115.6 rad/s.
#pragma once
#include <vector>

#include "fracdesign/models/ph_system.hpp"

namespace fracdesign {

// Reduces `full` with one block of B columns per real shift (rad/s). Throws std::invalid_argument for
// an empty/non-finite shift list, and std::runtime_error if s_i I - A is singular or the basis loses rank.
// V (n x r, orthonormal) is returned through `basis` when it is not null: x ~ V x_r.
PhSystem krylov_reduce(const PhSystem& full, const std::vector<double>& shifts, Eigen::MatrixXd* basis = nullptr);

// The thesis shifts of Table 8.4: {16, 18.43, 115.6} rad/s.
std::vector<double> wang_krylov_shifts();

}  // namespace fracdesign
