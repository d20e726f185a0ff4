// timoshenko_beam.hpp - the port-Hamiltonian Timoshenko beam of seed 004 (M. Wang, PhD thesis, TUM),
// its structure-preserving pseudo-spectral discretisation (Sec. 3.4.1, after Moulla, Lefevre &
// Maschke 2012) and the exact clamped-free natural frequencies (Appendix C).
//
// State x = [p_t; p_r; eps_t; eps_r] (N coefficients each, on the flow basis), SI units:
//   p_t  = rho dw/dt [kg/s], p_r = I_rho dpsi/dt [kg m/s], eps_t = dw/dz - psi [-], eps_r = dpsi/dz [1/m].
// Inputs  u = [w'(0) ; psi'(0) ; Q_s(L) ; M_b(L)]  (boundary velocities [m/s], [rad/s], shear force [N],
//             bending moment [N m])                                   seed 004 eq. (3.91)
// Outputs y = [-Q_s(0) ; -M_b(0) ; w'(L) ; psi'(L)]                   seed 004 eq. (3.92)
// (here ' means d/dt.)
#pragma once
#include <Eigen/Dense>
#include <vector>

#include "fracdesign/models/ph_system.hpp"

namespace fracdesign {

// Distributed parameters of the beam, seed 004 eq. (3.37), (3.52).
struct TimoshenkoParams {
    double L = 0.0;       // length [m]
    double rho = 0.0;     // mass per length [kg/m]
    double I_rho = 0.0;   // rotary inertia per length [kg m]
    double K_s = 0.0;     // shear stiffness kappa G A [N]
    double K_b = 0.0;     // bending stiffness E I [N m^2]
    double r_t = 0.0;     // translational viscous damping per length [N s/m^2] (thesis gives no value)
    double r_r = 0.0;     // rotational viscous damping per length [N s] (thesis gives no value)

    // Throws std::invalid_argument naming the bad field (non-finite, L/rho/I_rho/K_s/K_b <= 0, r < 0).
    void validate() const;
};

// A rectangular homogeneous section, bending about the thin direction (thickness t, height h).
TimoshenkoParams timoshenko_rectangular(double L, double h, double t, double density, double E, double poisson,
                                        double kappa);
// The steel beam of seed 004 Table 8.3 (1.2 x 0.03 x 0.005 m, 7856 kg/m^3, 215 GPa, nu 0.28, kappa 5/6),
// undamped: rho = 1.1784 kg/m, I_rho = 2.4550e-6 kg m, K_b = 67.1875 N m^2, K_s = 1.0498046875e7 N.
TimoshenkoParams wang_steel_beam();

enum class Collocation {
    GaussLegendre,  // efforts: {0, L} + zeros of P_{N-1}; flows: zeros of P_N
    Equidistant     // efforts: N+1 equidistant points incl. 0, L; flows: midpoints of N equal cells
};

// The discretised beam: the matrices of seed 004 Sec. 3.4.1 and the 4N-state PH model (3.93).
struct PsBeam {
    int N = 0;
    Collocation collocation = Collocation::GaussLegendre;
    Eigen::VectorXd effort_nodes;  // N+1 points xi_i in [0, L]
    Eigen::VectorXd flow_nodes;    // N points z_k in [0, L]
    Eigen::MatrixXd D;             // N x (N+1), D(k,i) = dw_i^e/dz (z_k)                    (3.62)
    Eigen::MatrixXd M;             // (N+1) x N, M(i,k) = int w_i^e w_k^f dz                  (3.70)
    Eigen::MatrixXd S;             // N x N,     S(k,l) = int w_k^f w_l^f dz                  (3.75)
    Eigen::MatrixXd Phi;           // 2 x (N+1), rows w^e(0)^T, w^e(L)^T                      (3.60)
    double sigma = 1.0;            // feedthrough sign -w^e(0)^T p_L = (-1)^(N+1) (notes 004a: (3.95) holds
                                   // as printed only for odd N)
    PhSystem ph;                   // 4N states, inputs/outputs as in the file comment

    // Residual max|M D + D^T M^T - Phi^T zeta Phi| of the discrete integration by parts, zeta =
    // diag(-1, 1); (B.6) with its sign corrected (notes 004a erratum 8).
    double integration_by_parts_residual() const;
};

// Builds the pseudo-spectral model with N >= 2 collocation points (throws std::invalid_argument otherwise).
PsBeam build_ps_beam(const TimoshenkoParams& p, int N, Collocation c = Collocation::GaussLegendre);

// The first `count` clamped-free natural frequencies in Hz of the clamped-free beam with zero boundary
// inputs (seed 004 Table 3.1): the eigenvalues of (J - R) Q.
std::vector<double> clamped_free_frequencies_hz(const PsBeam& beam, int count);

// Exact clamped-free natural frequencies in Hz (seed 004 App. C: roots of det M(w) of (C.16), w below the
// critical frequency sqrt(K_s/I_rho)), the first `count` ones, ascending.
std::vector<double> exact_clamped_free_frequencies_hz(const TimoshenkoParams& p, int count);

// The matrix M(w) of (C.16) (rows: X(0) = 0, X'''(0)+(a+c)X'(0) = 0, X'''(L)+dX'(L) = 0, X''(L)+aX(L) = 0).
Eigen::Matrix4d timoshenko_frequency_matrix(const TimoshenkoParams& p, double w);

}  // namespace fracdesign
