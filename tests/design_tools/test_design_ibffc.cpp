// Seed 004 inversion-based feedforward by stable inversion of the sampled arm.
#include <gtest/gtest.h>

#include <cmath>

#include "fracdesign/design/ibffc.hpp"
#include "fracdesign/design/lqg.hpp"
#include "fracdesign/design/trajectory.hpp"

using namespace fracdesign;
using namespace fracdesign::design;

namespace {
constexpr double kPi = 3.14159265358979323846;

StateSpace arm()
{
    TimoshenkoParams b = wang_steel_beam();
    b.r_t = 0.5;
    return arm_measured_model(build_arm(b, wang_drive(), ArmOptions()).arm);
}
}  // namespace

TEST(DesignIbffc, IdealTorqueReproducesTheTipVelocityAndEndsAtTheGoal)
{
    const SinSquaredPtp p({0.0, kPi / 2, kPi / 2, 2 * kPi, 0.5, 2.0});
    const auto r = stable_inversion(arm(), 1.2e-3, [&](double t) { return p.eval(t)[1]; }, -2.0, 4.5);
    EXPECT_LT(r.rel_rms, 1e-6);
    EXPECT_GT(r.n_backward, 0);  // non-minimum phase: some modes run backward in time
    EXPECT_NEAR(r.theta_M.back(), kPi / 2, 1e-5);  // motor at the goal after the motion (slow rigid-body creep)
    EXPECT_NEAR(r.theta_M_dot.back(), 0.0, 1e-6);
    // pre-actuation: torque before the motion starts; bounded everywhere
    double pre = 0.0, umax = 0.0;
    for (size_t k = 0; k < r.t.size(); ++k) {
        if (r.t[k] < 0.5) pre = std::max(pre, std::fabs(r.u[k]));
        umax = std::max(umax, std::fabs(r.u[k]));
    }
    EXPECT_GT(pre, 1e-3);
    EXPECT_LT(umax, 100.0);
    // decayed at the horizon ends
    EXPECT_LT(std::fabs(r.u.front()), 1e-6);
    EXPECT_LT(std::fabs(r.u.back()), 1e-6);
}

TEST(DesignIbffc, BadArgumentsAreRefused)
{
    const auto yd = [](double) { return 0.0; };
    EXPECT_THROW(stable_inversion(arm(), 0.0, yd, 0.0, 1.0), std::invalid_argument);
    EXPECT_THROW(stable_inversion(arm(), 1e-3, yd, 1.0, 0.5), std::invalid_argument);
}
