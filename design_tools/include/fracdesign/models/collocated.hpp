// collocated.hpp - the two-lumped-mass flexible arm of seed 002 (Feliu-Batlle, Feliu-Talegon,
// San-Millan 2020), collocated channel motor angle -> base moment, eqs. (38)-(46).
//
//   G_c(s) = Gamma_c/theta_m = Ghat(s) P(s),  Ghat(s) = s^2 / (1 + 0.0071 s)^2 (43, with G_m (41))
//   P(s)   = 4.11 (s^2 + 636.65 + 19.1/m2) / (s^4 + (1455.2 + 21.83/m2) s^2 + 6948.4/m2)      (42)
//          = b (s^2 + z1^2) / ((s^2 + a1^2)(s^2 + a2^2)) = k1/(s^2 + a1^2) + k2/(s^2 + a2^2)  (45)
// damped with the Rayleigh law zeta(w) = (0.059/w + 2.9e-5 w)/2 (44) on every mode (46). The tip mass m2 is
// in lb inside the printed formulas (m2 in [0.01, 0.23] lb, nominal 0.12 lb); Gamma_c units are not
// printed by the paper. The numerator damping equals zeta(z1) exactly (notes 002 sec. 6.4).
// Those are the paper's robot (CollocatedArm::Form::Printed); CollocatedArm::Form::Physical derives the
// same structure for any masses, link stiffness, middle-mass position, inner loop and damping law.
#pragma once
#include <complex>
#include <stdexcept>
#include <string>
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

constexpr double kFeliuM2Min = 0.01, kFeliuM2Max = 0.23, kFeliuM2Nominal = 0.12;  // lb (Sec. 5.1)
constexpr double kFeliuEps = 0.0071;  // inner-loop time constant of G_m (41) [s]

// One frozen plant of the family: the modal data of P (42)/(45)/(46), the inner loop G_m (41) and
// the tip transfer G_2 (39), G_2(s) = (g2_s2 s^2 + g2_0) / ((s^2 + 2 zeta1 a1 s + a1^2)(s^2 + 2 zeta2 a2 s + a2^2))
// (undamped numerator, damped denominators: notes 002 AMBIG 14; G_2(0) = 1 for the undamped plant).
struct CollocatedPlant {
    double m2 = 0;             // tip mass, in the unit of its CollocatedArm (lb for the printed form, kg otherwise)
    double a1, z1, a2;         // undamped resonances / anti-resonance [rad/s]
    double b, k1, k2;          // gain and partial-fraction residues (k1 + k2 = b)
    double zeta1, zeta2, xi1;  // Rayleigh damping of a1, a2 and of the zero z1 (44)
    double eps = kFeliuEps;    // inner position loop G_m = 1/(1 + eps s)^2 (41) [s]
    double g2_s2 = 0, g2_0 = 0;  // numerator of G_2 (39)
};

// A bad arm parameter: `field` is the document path (e.g. "link.EI"), what() names field, value and range.
struct CollocatedArmError : std::invalid_argument {
    CollocatedArmError(const std::string& field, const std::string& problem);
    std::string field, problem;
};

// The two-lumped-mass arm family over the tip mass m2 (the uncertain parameter of seed 002 Sec. 5).
//  - Printed: the paper's robot, the coefficients of (38)-(42) as printed (m2 in lb inside them).
//  - Physical: any arm of the same structure (ref. [21], Sec. 5.1): a massless Euler-Bernoulli link of
//    length L and flexural rigidity EI clamped to the hub, point masses m1 at x1 (0 < x1 < L) and m2 at
//    the tip on pinned joints (no moments at the masses), moment sensor at the base. With the flexibility
//    of the clamped link f11 = x1^3/(3EI), f12 = x1^2 (3L - x1)/(6EI), f22 = L^3/(3EI), K = F^-1, the
//    angles theta_i of the masses obey M theta'' + K' (theta - theta_m 1) = 0, M = diag(m1 x1^2, m2 L^2),
//    K' = X K X, X = diag(x1, L); the base moment is Gamma = 1' K' (theta_m 1 - theta), so
//      Gamma_c/theta_m = g s^2 P(s),  P(s) = 1' K' (M s^2 + K')^-1 M 1,  theta_2/theta_m = [(M s^2 + K')^-1 K' 1]_2,
//    with g the sensor reading per N m (the paper's Gamma_c unit is not printed). For x1 = L/2 this gives
//    the printed structure of (38)-(40) exactly (a1^2 a2^2 = 7 c^2/(m1 m2), z1^2 = 7c/m1 + 1.75c/m2 with
//    c = 48 EI/(7 L^3)).
// Both forms: G_m = 1/(1 + eps s)^2 (41) and Rayleigh damping zeta(w) = (rayleigh_a/w + rayleigh_b w)/2 (44).
struct CollocatedArm {
    enum class Form { Printed, Physical };
    Form form = Form::Printed;
    double L = 0, EI = 0, m1 = 0, x1 = 0;  // Physical only: m, N m^2, kg, m
    double moment_gain = 1.0;             // Physical only: Gamma_c reading per N m (> 0)
    double eps = kFeliuEps;               // s, in [0, 1]
    double rayleigh_a = 0.059, rayleigh_b = 2.9e-5;  // 1/s and s, >= 0 (0, 0: undamped)
    double m2_nominal = kFeliuM2Nominal, m2_min = kFeliuM2Min, m2_max = kFeliuM2Max;  // lb (Printed) or kg (Physical)
    // Throws CollocatedArmError for the first bad field (finite, > 0 / >= 0, x1 < L,
    // m2_min <= m2_nominal <= m2_max).
    void validate() const;
    // The frozen plant at tip mass m2 (> 0; outside [m2_min, m2_max] is allowed, the range is the design's).
    CollocatedPlant plant(double m2) const;
    double zeta(double w) const { return 0.5 * (rayleigh_a / w + rayleigh_b * w); }
    const char* mass_unit() const { return form == Form::Printed ? "lb" : "kg"; }
};

// The paper's robot (Sec. 5.1): the printed form, m2 in [0.01, 0.23] lb, nominal 0.12 lb.
CollocatedArm feliu_robot_arm();

// feliu_robot_arm().plant(m2_lb): the closed forms of notes 002 sec. 6.3, c2 = 1455.2 + 21.83/m2,
// c0 = 6948.4/m2, a_{1,2}^2 = (c2 -+ sqrt(c2^2 - 4 c0))/2, z1^2 = 636.65 + 19.1/m2, b = 4.11.
// Throws std::invalid_argument if m2 is not finite and > 0.
CollocatedPlant collocated_plant(double m2_lb);

// The two modes of the robot plant (a1, a2; k1, k2; zeta1, zeta2 or 0 when undamped).
CollocatedModes collocated_modes(const CollocatedPlant& p, bool damped = true);

// P(j w) of (46) (damped = true) or (45) (undamped).
std::complex<double> collocated_P(const CollocatedPlant& p, double w, bool damped = true);

// Modal state space of P (modal_state_space of collocated_modes: 4 states [q1, q1', q2, q2']). The
// plant from the motor reference to Gamma_c is Ghat(s) P(s) with the known part (43).
StateSpace collocated_state_space(const CollocatedPlant& p, bool damped = true);

}  // namespace fracdesign
