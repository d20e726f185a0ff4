// The argument-principle stability test (design/nyquist.hpp) on loops whose stability limit is
// known in closed form: rational, with an integrator, a pole on the axis, dead time and a fractional power.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "fracdesign/design/nyquist.hpp"

using namespace fracdesign::design;
using cplx = std::complex<double>;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST(Nyquist, ThirdOrderLagIsStableBelowTheRouthGain)
{
    // 1 + K/(s + 1)^3 = 0: s^3 + 3 s^2 + 3 s + 1 + K, Routh: stable iff 9 > 1 + K, i.e. K < 8;
    // beyond, two closed-loop poles in Re s > 0 (N = P - Z = -2).
    for (double K : {2.0, 7.5, 8.5, 20.0}) {
        const auto r = nyquist_stability([K](cplx s) { return K / ((s + 1.0) * (s + 1.0) * (s + 1.0)); }, 1e-6, 1e3);
        EXPECT_EQ(r.stable, K < 8.0) << K << ": " << r.detail;
        EXPECT_EQ(r.encirclements, K < 8.0 ? 0 : -2) << K;
        EXPECT_LT(r.residual, 1e-6) << K;
    }
}

TEST(Nyquist, IntegratorWithDeadTimeIsStableBelowHalfPiOverTau)
{
    // 1 + K e^{-tau s}/s = 0 is stable iff K tau < pi/2 (crossover w = K, phase -pi/2 - K tau).
    const double tau = 0.7;
    for (double f : {0.5, 0.95, 1.05, 1.8}) {
        const double K = f * kPi / (2.0 * tau);
        const auto r = nyquist_stability([&](cplx s) { return K * std::exp(-tau * s) / s; }, 1e-6, 10.0 * K);
        EXPECT_EQ(r.stable, f < 1.0) << f << ": " << r.detail;
    }
}

TEST(Nyquist, PoleOnTheAxisIsSkirted)
{
    // L = K (s + 1)/(s^2 + 1): closed loop s^2 + K s + 1 + K, stable iff K > 0 (and K > -1).
    for (double K : {2.0, 0.3, -0.5}) {
        const auto r = nyquist_stability([K](cplx s) { return K * (s + 1.0) / (s * s + 1.0); }, 1e-6, 1e4, {1.0});
        EXPECT_EQ(r.stable, K > 0.0) << K << ": " << r.detail;
        EXPECT_EQ(r.encirclements, K > 0.0 ? 0 : -2) << K;
    }
}

TEST(Nyquist, FractionalIntegratorWithDelayHasItsClosedFormLimit)
{
    // L = K e^{-tau s} s^-a: |L| = 1 at w = K^(1/a), phase -a pi/2 - w tau; stable iff a pi/2 + K^(1/a) tau < pi.
    const double a = 0.5, tau = 1.0;
    const double K_crit = std::pow((kPi - a * kPi / 2.0) / tau, a);
    for (double f : {0.8, 0.97, 1.03, 1.3}) {
        const double K = f * K_crit;
        const auto r =
            nyquist_stability([&](cplx s) { return K * std::exp(-tau * s) * std::pow(s, -a); }, 1e-8, 1e3 * K * K);
        EXPECT_EQ(r.stable, f < 1.0) << f << ": " << r.detail;
    }
}

TEST(Nyquist, MalformedRangeIsRefused)
{
    const auto L = [](cplx s) { return 1.0 / (s + 1.0); };
    EXPECT_THROW(nyquist_stability(L, 0.0, 1.0), std::invalid_argument);
    EXPECT_THROW(nyquist_stability(L, 2.0, 1.0), std::invalid_argument);
    EXPECT_THROW(nyquist_stability(L, 1e-3, 1.0, {5.0}), std::invalid_argument);  // pole outside (w_lo, w_hi)
}
