// collocated.hpp - the two-lumped-mass flexible arm of seed 002 (Feliu-Batlle, Feliu-Talegon,
// San-Millan 2020), collocated channel motor angle -> base moment, eqs. (38)-(46).
//
//   G_c(s) = Gamma_c/theta_m = Ghat(s) P(s),  Ghat(s) = s^2 / (1 + 0.0071 s)^2 (43, with G_m (41))
//   P(s)   = 4.11 (s^2 + 636.65 + 19.1/m2) / (s^4 + (1455.2 + 21.83/m2) s^2 + 6948.4/m2)      (42)
//          = b (s^2 + z1^2) / ((s^2 + a1^2)(s^2 + a2^2)) = k1/(s^2 + a1^2) + k2/(s^2 + a2^2)  (45)
// damped with the Rayleigh law zeta(w) = (0.059/w + 2.9e-5 w)/2 (44) on every mode (46). The tip mass m2 is
// in lb inside the printed formulas (m2 in [0.01, 0.23] lb, nominal 0.12 lb); Gamma_c units are not
// printed by the paper. The numerator damping equals zeta(z1) exactly (notes 002 sec. 6.4).
#pragma once
#include <complex>
#include <vector>

#include "fracdesign/models/lti.hpp"

namespace fracdesign {

// The general damped oscillatory factor of seed 002 with n modes, eq. (22):
//   P(s) = sum_i k_i / (s^2 + 2 zeta_i a_i s + a_i^2)
// Lemma 1: with zeta = 0 it has the pole-zero interlacing property iff every k_i > 0.
struct CollocatedModes {
    std::vector<double> a;     // modal frequencies [rad/s], ascending, > 0
    std::vector<double> k;     // residues
    std::vector<double> zeta;  // damping ratios >= 0 (same length)
    void validate() const;     // std::invalid_argument naming the field (sizes, finiteness, a > 0, zeta >= 0)
};

// Residues of the product form (2) P = b prod_{j<n}(s^2 + z_j^2) / prod_i (s^2 + a_i^2) (a: n values, z: n-1):
// k_i = b prod_j (z_j^2 - a_i^2) / prod_{j != i} (a_j^2 - a_i^2); zeta = 0.
CollocatedModes pzi_to_modes(double b, const std::vector<double>& a, const std::vector<double>& z);

// P(j w) of (22).
std::complex<double> modal_P(const CollocatedModes& m, double w);

// Modal realisation: states [q_i, q_i'] per mode, q_i'' + 2 zeta_i a_i q_i' + a_i^2 q_i = u, y = sum k_i q_i.
StateSpace modal_state_space(const CollocatedModes& m);

struct CollocatedPlant {
    double m2_lb;              // tip mass [lb]
    double a1, z1, a2;         // undamped resonances / anti-resonance [rad/s]
    double b, k1, k2;          // gain and partial-fraction residues (k1 + k2 = b)
    double zeta1, zeta2, xi1;  // Rayleigh damping of a1, a2 and of the zero z1 (44)
};

constexpr double kFeliuM2Min = 0.01, kFeliuM2Max = 0.23, kFeliuM2Nominal = 0.12;  // lb

// Closed forms of notes 002 sec. 6.3: c2 = 1455.2 + 21.83/m2, c0 = 6948.4/m2,
// a_{1,2}^2 = (c2 -+ sqrt(c2^2 - 4 c0))/2, z1^2 = 636.65 + 19.1/m2, b = 4.11.
// Throws std::invalid_argument if m2 is not finite and > 0.
CollocatedPlant collocated_plant(double m2_lb);

// The two modes of the robot plant (a1, a2; k1, k2; zeta1, zeta2 or 0 when undamped).
CollocatedModes collocated_modes(const CollocatedPlant& p, bool damped = true);

// Rayleigh damping law (44).
double feliu_rayleigh_zeta(double w);

// P(j w) of (46) (damped = true) or (45) (undamped).
std::complex<double> collocated_P(const CollocatedPlant& p, double w, bool damped = true);

// Modal state space of P (modal_state_space of collocated_modes: 4 states [q1, q1', q2, q2']). The
// plant from the motor reference to Gamma_c is Ghat(s) P(s) with the known part (43).
StateSpace collocated_state_space(const CollocatedPlant& p, bool damped = true);

}  // namespace fracdesign
