// Seed 004 sin^2 point-to-point trajectory and rigid-body feedforward.
#include <gtest/gtest.h>

#include <cmath>

#include "fracdesign/design/trajectory.hpp"

using namespace fracdesign::design;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST(DesignTrajectory, DerivativesAreConsistentAndContinuousUpToJerk)
{
    const SinSquaredPtp p({0.0, kPi / 2, kPi / 2, 2 * kPi, 0.5, 2.0});
    const double h = 1e-6;
    for (double t = 0.4; t < 2.1; t += 0.0137) {  // off the borders, where the snap jumps
        const auto a = p.eval(t), b = p.eval(t + h), c = p.eval(t - h);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR((b[k] - c[k]) / (2 * h), a[k + 1], 1e-5 * (1 + std::fabs(a[k + 1]))) << t;
    }
    // continuity of q .. jerk at the phase borders (absolute 0.5, 1.0, 1.5, 2.0)
    for (double tb : {0.5, 1.0, 1.5, 2.0}) {
        const auto l = p.eval(tb - 1e-9), r = p.eval(tb + 1e-9);
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(l[k], r[k], 1e-6) << "border " << tb << " derivative " << k;
    }
    EXPECT_NEAR(p.eval(0.75)[3], 0.0, 1e-9);
    EXPECT_NEAR(p.eval(0.625)[3], 4 * kPi * kPi, 1e-9);  // max jerk 4 pi^2 (notes 004b C4)
}

TEST(DesignTrajectory, LongerRequestedDurationLowersTheCruiseVelocity)
{
    const SinSquaredPtp p({0.0, kPi / 2, kPi / 2, 2 * kPi, 0.0, 3.0});
    EXPECT_NEAR(p.duration(), 3.0, 1e-12);
    EXPECT_LT(p.qd_cruise(), kPi / 2);
    EXPECT_NEAR(p.eval(3.0)[0], kPi / 2, 1e-12);
    EXPECT_NEAR(p.eval(3.0)[1], 0.0, 1e-12);
    const SinSquaredPtp down({1.0, 0.0, 1.0, 4.0, 0.0, 0.0});
    EXPECT_NEAR(down.eval(down.t_end())[0], 0.0, 1e-12);
    EXPECT_LT(down.eval(0.5 * down.t_end())[1], 0.0);
}

TEST(DesignTrajectory, ImpossibleOrMalformedSpecsAreRefused)
{
    try {
        SinSquaredPtp({0.0, kPi / 2, kPi / 2, 2 * kPi, 0.5, 1.5});
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("minimum 2.0"), std::string::npos) << e.what();
    }
    EXPECT_THROW(SinSquaredPtp({0.0, 0.0, 1.0, 1.0, 0.0, 0.0}), std::invalid_argument);
    EXPECT_THROW(SinSquaredPtp({0.0, 1.0, -1.0, 1.0, 0.0, 0.0}), std::invalid_argument);
    EXPECT_THROW(SinSquaredPtp({0.0, NAN, 1.0, 1.0, 0.0, 0.0}), std::invalid_argument);
}

TEST(DesignTrajectory, RigidBodyFeedforwardBalancesTheSpring)
{
    // (4.14): c_s (theta_M* - theta_l*) = I_l theta_l*'' (the link is accelerated by the spring).
    const SinSquaredPtp p({0.0, kPi / 2, kPi / 2, 2 * kPi, 0.5, 2.0});
    const double I_M = 5.8624, I_l = 0.7221, c_s = 1.0e4;
    for (double t : {0.6, 1.2, 1.8}) {
        const auto q = p.eval(t);
        const auto f = rigid_body_feedforward(q, I_M, I_l, c_s);
        EXPECT_NEAR(c_s * (f[0] - q[0]), I_l * q[2], 1e-9);
        EXPECT_NEAR(f[3], I_M * f[2] + I_l * q[2], 1e-9);  // total torque = both inertias accelerated
    }
    EXPECT_THROW(rigid_body_feedforward(p.eval(1.0), 0.0, I_l, c_s), std::invalid_argument);
}
