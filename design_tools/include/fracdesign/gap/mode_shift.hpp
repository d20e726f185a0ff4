// mode_shift.hpp - a resonant mode of the nominal plant moved to another
// frequency and damping (the mode_shift effect, docs/gap.md "mode_shift").
//
// The plant is the nominal's discrete x(k+1) = A x(k) + B u(k) at Ts, of any
// realization (modal or not, with delay states). A resonant mode is a simple
// complex eigenvalue pair z, conj(z) of A with continuous equivalent
// s = log(z)/Ts = -zeta w + i w sqrt(1 - zeta^2), zeta < 1/sqrt(2). With its
// right and left eigenvectors v, w (A v = z v, w A = z w, w v = 1) the
// spectral projector P = v w splits off the pair; moving it to s' (f', zeta')
// with the mode's continuous input and output maps kept is
//   A' = A + 2 Re[(z' - z) P],                       z' = e^{s' Ts}
//   B' = B + 2 Re[(g' / g - 1) P B],                 g = (z - 1)/s, g' = (z' - 1)/s'
// (zero-order hold of the mode's block: its discrete input map is g times its
// continuous one), C and D unchanged. This is the real modal (block-diagonal)
// form's 2x2 block of the pair replaced, written without transforming the
// other states (so a defective remainder, e.g. a chain of delay states at
// z = 0, needs no diagonalisation). Every other eigenvalue of A stays.
#pragma once
#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "fracdesign/gap/nominal.hpp"

namespace fracdesign {
namespace gap {

struct PlantMode {
    double f_hz = 0, zeta = 0;     // continuous equivalent of the pair
    std::complex<double> z;        // discrete eigenvalue (Im z > 0)
    Eigen::VectorXcd v;            // right eigenvector
    Eigen::RowVectorXcd w;         // left eigenvector, w v = 1
    // -1: the mode moved at fixed modal mass (shift_plant_mode). Else the
    // index of the declared coupling whose spring moves it: the shift is that
    // spring's stiffness and damping change (shift_coupling_mode), named `via`.
    int coupling = -1;
    std::string via;
};

// The resonant modes of the open-loop plant A (not the loop's): simple
// complex pairs with zeta < 1/sqrt(2) and f <= 0.4/Ts (the band the where
// stage checks, diagnosis.cpp ModeCheck), slowest first. A pair closer than
// 1e-6 |z| to another eigenvalue is left out (its projector is ill-defined).
// Then, on a continuous plant, the same mode once more per declared coupling
// that moves it (coupling >= 0): one whose spring holds at least
// kCouplingModeShare of the mode's w^2 (first-order sensitivity
// |d lambda / d k| k / |lambda| >= kCouplingModeShare / 2, 1/2 for the mode of
// a lone spring).
constexpr double kCouplingModeShare = 0.1;
std::vector<PlantMode> resonant_plant_modes(const NominalModel& m);

// A' and B' of the plant with mode `pm` moved to f_hz, zeta, as a stiffness
// and damping change at fixed modal mass: in the mode's mechanical
// coordinates (q, q'), where the force input `force_input` drives its
// acceleration (q'' + 2 zeta w q' + w^2 q = u), the block's w and zeta
// change while the outputs' maps of q and q' and every input's continuous
// map are kept (mode_shift.cpp). A position output's share of the mode then
// scales by w^2/w'^2 and a rate output's is kept to O(zeta^2); the
// equations above (residues kept) are the same for rate outputs and are
// used when the force does not reach the mode. Every other eigenvalue of A
// stays; C and D are unchanged.
void shift_plant_mode(const PlantMode& pm, double Ts, double f_hz, double zeta, const Eigen::MatrixXd& A,
                      const Eigen::MatrixXd& B, int force_input, Eigen::MatrixXd& A2, Eigen::MatrixXd& B2);

// A' and B' of the plant with mode `pm` (pm.coupling >= 0) moved to
// f_hz, zeta by the declared spring's own change: the coupling's extra
// torque dk q + dc q' (q = twist x, q' = twist Ac x, the deflection's rate
// of a position-level twist) in the continuous plant,
//   Ac' = Ac + torque_c (dk twist + dc twist Ac),   Bc kept,
// with (dk, dc) the one real pair that puts an eigenvalue at
// s' = -zeta w' + i w' sqrt(1 - zeta^2): a rank-one change has
// det(s' - Ac') = det(s' - Ac) (1 - r (s' - Ac)^-1 torque_c), so with
// h = twist (s' - Ac)^-1 torque_c, dk h + dc (s' h - twist torque_c) = 1, two
// real equations. A', B' are Ac', Bc held (zero-order hold) at Ts. Exact for
// a spring that softens or stiffens (belt tension, a worn gear) whatever the
// plant's damping: the other modes and the rigid body move as the physics
// moves them, where shift_plant_mode keeps them. Falls back to
// shift_plant_mode where the pair is not determined (h and its rate term
// parallel at s').
void shift_coupling_mode(const PlantMode& pm, const NominalModel& m, double f_hz, double zeta, Eigen::MatrixXd& A2,
                         Eigen::MatrixXd& B2);

// How the report names the mode: "mode at 12.3 Hz, zeta 0.021".
std::string plant_mode_name(const PlantMode& pm);

}  // namespace gap
}  // namespace fracdesign
