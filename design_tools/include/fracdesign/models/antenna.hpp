// antenna.hpp - exact transfer function of the fractionally damped flexible antenna of seed 000
// (Haro-Olmo, Tejado, Vinagre, Feliu-Batlle, Fractal Fract. 2023, 7, 621), eq. (25):
//
//   G(s) = Gamma_coup(s)/Theta_m(s)
//        = -EI (1 + zeta s^alpha) beta (sin(bL) cosh(bL) - cos(bL) sinh(bL)) / (1 + cos(bL) cosh(bL))
//   beta^4 = -((rho/EI) s^2 + gamma s^lambda) / (1 + zeta s^alpha)
//
// beta^4 as corrected in notes 000 section 2.5: the paper prints -(rho/EI)(s^2 + gamma s^lambda)/(...),
// which contradicts gamma = c_v/(EI); only the corrected form reproduces the paper's Table 4.
// G depends on beta^4 only (all four fourth roots give the same value), so the principal root is used.
// s^alpha at s = j w uses the principal branch w^alpha (cos(alpha pi/2) + j sin(alpha pi/2)).
//
// Everything is templated on the scalar T so that identification can evaluate G with ceres::Jet
// (automatic derivatives). The scalar functions are found by argument-dependent lookup (std:: for
// double, ceres:: for Jet); this header includes no Ceres header.
#pragma once
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fracdesign {

// A minimal complex number over any scalar T (std::complex<T> is only specified for float types).
template <typename T>
struct Cx {
    T re, im;
    Cx() : re(T(0)), im(T(0)) {}
    Cx(T r, T i) : re(r), im(i) {}
    explicit Cx(T r) : re(r), im(T(0)) {}
};
template <typename T> Cx<T> operator+(const Cx<T>& a, const Cx<T>& b) { return {a.re + b.re, a.im + b.im}; }
template <typename T> Cx<T> operator-(const Cx<T>& a, const Cx<T>& b) { return {a.re - b.re, a.im - b.im}; }
template <typename T> Cx<T> operator*(const Cx<T>& a, const Cx<T>& b)
{
    return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
template <typename T> Cx<T> operator*(const T& k, const Cx<T>& a) { return {k * a.re, k * a.im}; }
template <typename T> Cx<T> operator/(const Cx<T>& a, const Cx<T>& b)
{
    const T d = b.re * b.re + b.im * b.im;
    return {(a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d};
}
template <typename T> Cx<T> cx_sin(const Cx<T>& z)
{
    using std::cos; using std::cosh; using std::sin; using std::sinh;
    return {sin(z.re) * cosh(z.im), cos(z.re) * sinh(z.im)};
}
template <typename T> Cx<T> cx_cos(const Cx<T>& z)
{
    using std::cos; using std::cosh; using std::sin; using std::sinh;
    return {cos(z.re) * cosh(z.im), -sin(z.re) * sinh(z.im)};
}
template <typename T> Cx<T> cx_sinh(const Cx<T>& z)
{
    using std::cos; using std::cosh; using std::sin; using std::sinh;
    return {sinh(z.re) * cos(z.im), cosh(z.re) * sin(z.im)};
}
template <typename T> Cx<T> cx_cosh(const Cx<T>& z)
{
    using std::cos; using std::cosh; using std::sin; using std::sinh;
    return {cosh(z.re) * cos(z.im), sinh(z.re) * sin(z.im)};
}
// Principal root z^(1/4) = |z|^(1/4) exp(j arg(z)/4).
template <typename T> Cx<T> cx_fourth_root(const Cx<T>& z)
{
    using std::atan2; using std::cos; using std::sin; using std::sqrt;
    const T r = sqrt(sqrt(z.re * z.re + z.im * z.im));
    const T ph = atan2(z.im, z.re) / T(4);
    return {sqrt(r) * cos(ph), sqrt(r) * sin(ph)};
}
// (j w)^a on the principal branch, w > 0.
template <typename T> Cx<T> cx_jw_pow(const T& w, const T& a)
{
    using std::cos; using std::pow; using std::sin;
    const T h = T(1.57079632679489661923) * a;  // pi/2
    const T m = pow(w, a);
    return {m * cos(h), m * sin(h)};
}

// The six damping structures of seed 000 Table 2 (fixed values in brackets):
//   I   integer internal         free zeta          [alpha 1, lambda 0, gamma 0]
//   II  integer external         free gamma         [alpha 0, zeta 0, lambda 1]
//   III integer int. + ext.      free zeta, gamma   [alpha 1, lambda 1]
//   IV  fractional internal      free zeta, alpha   [lambda 0, gamma 0]
//   V   fractional external      free gamma, lambda [alpha 0, zeta 0]
//   VI  fractional int. + ext.   free zeta, alpha, gamma, lambda
enum class AntennaStructure { I = 1, II, III, IV, V, VI };

// Damping parameters (seed 000 Sec. 4): zeta = c_d/E [s^alpha], gamma = c_v/(EI) [s^lambda m^-4].
template <typename T>
struct AntennaDamping {
    T zeta, alpha, gamma, lambda;
};

// Number of free parameters of a structure (1, 1, 2, 2, 2, 4).
inline int antenna_free_count(AntennaStructure s)
{
    switch (s) {
    case AntennaStructure::I: case AntennaStructure::II: return 1;
    case AntennaStructure::III: case AntennaStructure::IV: case AntennaStructure::V: return 2;
    case AntennaStructure::VI: return 4;
    }
    throw std::invalid_argument("antenna structure: unknown value");
}

// Names of the free parameters in the order `antenna_damping` reads them.
inline const char* const* antenna_free_names(AntennaStructure s)
{
    static const char* const i[] = {"zeta"}, *ii[] = {"gamma"}, *iii[] = {"zeta", "gamma"},
                             *iv[] = {"zeta", "alpha"}, *v[] = {"gamma", "lambda"},
                             *vi[] = {"zeta", "alpha", "gamma", "lambda"};
    switch (s) {
    case AntennaStructure::I: return i;
    case AntennaStructure::II: return ii;
    case AntennaStructure::III: return iii;
    case AntennaStructure::IV: return iv;
    case AntennaStructure::V: return v;
    case AntennaStructure::VI: return vi;
    }
    throw std::invalid_argument("antenna structure: unknown value");
}

// Damping of a structure from its free parameters (in the order of antenna_free_names), Table 2.
template <typename T>
AntennaDamping<T> antenna_damping(AntennaStructure s, const T* free)
{
    switch (s) {
    case AntennaStructure::I: return {free[0], T(1), T(0), T(0)};
    case AntennaStructure::II: return {T(0), T(0), free[0], T(1)};
    case AntennaStructure::III: return {free[0], T(1), free[1], T(1)};
    case AntennaStructure::IV: return {free[0], free[1], T(0), T(0)};
    case AntennaStructure::V: return {T(0), T(0), free[0], free[1]};
    case AntennaStructure::VI: return {free[0], free[1], free[2], free[3]};
    }
    throw std::invalid_argument("antenna structure: unknown value");
}

// Fixed physical constants of the link (seed 000 Table 1: carbon-fibre rod).
struct AntennaLink {
    double L = 0.98;        // length [m]
    double rho = 4.7e-3;    // mass per length [kg/m]
    double E = 1.15e11;     // Young's modulus [N/m^2]
    double I = 7.85e-13;    // area moment [m^4]
    double EI() const { return E * I; }
    void validate() const;  // std::invalid_argument naming the field
};

// G(j w) of eq. (25) with the corrected beta^4, w > 0 in rad/s, in N m/rad.
template <typename T>
Cx<T> antenna_frf(const AntennaLink& link, const AntennaDamping<T>& d, const T& w)
{
    const T EI = T(link.EI());
    const Cx<T> s2(-(w * w), T(0));                      // (j w)^2
    const Cx<T> one(T(1), T(0));
    const Cx<T> internal = one + d.zeta * cx_jw_pow(w, d.alpha);   // 1 + zeta s^alpha
    const Cx<T> external = T(link.rho) / EI * s2 + d.gamma * cx_jw_pow(w, d.lambda);
    const Cx<T> beta4 = Cx<T>(T(0), T(0)) - external / internal;  // corrected beta^4, notes 000 sec. 2.5
    const Cx<T> beta = cx_fourth_root(beta4);
    const Cx<T> x = T(link.L) * beta;
    const Cx<T> sx = cx_sin(x), cx = cx_cos(x), shx = cx_sinh(x), chx = cx_cosh(x);
    const Cx<T> num = sx * chx - cx * shx;
    const Cx<T> den = one + cx * chx;
    return T(-1) * EI * (internal * beta * num / den);
}

// Convenience for double.
inline std::complex<double> antenna_frf(const AntennaLink& link, const AntennaDamping<double>& d, double w)
{
    const Cx<double> g = antenna_frf<double>(link, d, w);
    return {g.re, g.im};
}

// The nominal (Table 3 mean, Table 5) parameter sets of seed 000 with omega-dependent weights.
AntennaDamping<double> haro_nominal_III();  // zeta 5.4e-5, alpha 1, gamma 2.0e-2, lambda 1
AntennaDamping<double> haro_nominal_VI();   // zeta 7.1e-5, alpha 0.996, gamma 5.5e-2, lambda 0.594

// Undamped clamped-free resonances (roots of 1 + cos x cosh x = 0) and anti-resonances (tan x = tanh x),
// omega_i = (x_i/L)^2 sqrt(EI/rho), the first `count` of each, in rad/s.
std::vector<double> antenna_undamped_poles(const AntennaLink& link, int count);
std::vector<double> antenna_undamped_zeros(const AntennaLink& link, int count);

// Resonance peak of |G(j w)| inside [w_lo, w_hi] (golden-section on a bracket found by a fine scan):
// returns {w_peak [rad/s], 20 log10 |G| [dB]}.
std::pair<double, double> antenna_peak(const AntennaLink& link, const AntennaDamping<double>& d, double w_lo,
                                       double w_hi);

}  // namespace fracdesign
