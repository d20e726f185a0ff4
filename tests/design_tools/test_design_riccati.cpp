// Riccati solvers (CARE sign function, DARE doubling), ZOH, and the named failure causes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fracdesign/design/riccati.hpp"

using namespace fracdesign;
using namespace fracdesign::design;
using Eigen::MatrixXd;

namespace {

// Lightly damped flexible structure: a rigid-body mode and `modes` resonances (rad/s).
StateSpace flexible(int modes, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 2 + 2 * modes;
    StateSpace s;
    s.A = MatrixXd::Zero(n, n);
    s.B = MatrixXd::Zero(n, 1);
    s.C = MatrixXd::Zero(1, n);
    s.D = MatrixXd::Zero(1, 1);
    s.A(0, 1) = 1.0;
    s.A(1, 1) = -0.05;
    s.B(1, 0) = 1.0;
    s.C(0, 0) = 1.0;
    for (int i = 0; i < modes; ++i) {
        const double w = 10.0 * (i + 1) * (1.0 + 0.3 * u(rng)), z = 0.005 + 0.02 * u(rng);
        const int k = 2 + 2 * i;
        s.A(k, k + 1) = 1.0;
        s.A(k + 1, k) = -w * w;
        s.A(k + 1, k + 1) = -2.0 * z * w;
        s.B(k + 1, 0) = 1.0 + u(rng);
        s.C(0, k) = 0.5 * u(rng);
    }
    return s;
}

}  // namespace

TEST(DesignRiccati, ScalarDareMatchesTheClosedForm)
{
    // x+ = a x + b u, q, r: X = root of b^2 X^2 + (r - a^2 r - q b^2) X - q r = 0 (positive root).
    const double a = 1.2, b = 0.5, q = 2.0, r = 0.3;
    const double B2 = b * b, c1 = r - a * a * r - q * B2;
    const double X = (-c1 + std::sqrt(c1 * c1 + 4.0 * B2 * q * r)) / (2.0 * B2);
    const auto s = solve_dare(MatrixXd::Constant(1, 1, a), MatrixXd::Constant(1, 1, b), MatrixXd::Constant(1, 1, q),
                              MatrixXd::Constant(1, 1, r));
    EXPECT_NEAR(s.X(0, 0), X, 1e-12 * X);
    EXPECT_NEAR(s.K(0, 0), a * b * X / (r + B2 * X), 1e-12);
    EXPECT_LT(s.stability, 1.0);
}

TEST(DesignRiccati, DoubleIntegratorCareMatchesTheClosedForm)
{
    // x'' = u, Q = diag(1, 0), R = 1: K = [1, sqrt(2)], X = [[sqrt2, 1], [1, sqrt2]].
    MatrixXd A(2, 2), B(2, 1);
    A << 0, 1, 0, 0;
    B << 0, 1;
    MatrixXd Q = MatrixXd::Zero(2, 2);
    Q(0, 0) = 1.0;
    const auto s = solve_care(A, B, Q, MatrixXd::Identity(1, 1));
    EXPECT_NEAR(s.K(0, 0), 1.0, 1e-12);
    EXPECT_NEAR(s.K(0, 1), std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(s.X(0, 1), 1.0, 1e-12);
    EXPECT_LT(s.residual, 1e-14);
}

TEST(DesignRiccati, DareSolutionOfAFlexibleArmIsStabilisingWithSmallResidual)
{
    for (int modes : {5, 11, 23}) {
        const StateSpace c = flexible(modes, 3u + modes);
        const StateSpace d = c2d_zoh(c, 1.2e-3);
        const MatrixXd Q = d.C.transpose() * d.C * 1e4 + MatrixXd::Identity(d.nx(), d.nx()) * 1e-3;
        const auto s = solve_dare(d.A, d.B, Q, MatrixXd::Identity(1, 1));
        EXPECT_LT(s.residual, 1e-11) << modes;
        EXPECT_LT(s.stability, 1.0);
        EXPECT_LT((s.X - s.X.transpose()).norm(), 1e-10 * s.X.norm());
        // X is the fixed point of the Riccati recursion: one more step leaves it unchanged.
        EXPECT_LT(dare_residual(d.A, d.B, Q, MatrixXd::Identity(1, 1), MatrixXd(), s.X), 1e-11);
    }
}

TEST(DesignRiccati, CrossTermIsEquivalentToTheShiftedProblem)
{
    const StateSpace d = c2d_zoh(flexible(3, 5), 1e-3);
    const Eigen::Index n = d.nx();
    const MatrixXd Q = MatrixXd::Identity(n, n), R = MatrixXd::Identity(1, 1) * 2.0;
    const MatrixXd S = MatrixXd::Constant(n, 1, 0.01);
    const auto s = solve_dare(d.A, d.B, Q, R, S);
    EXPECT_LT(s.residual, 1e-12);
    EXPECT_LT(dare_residual(d.A, d.B, Q, R, S, s.X), 1e-12);
    const auto c = solve_care(flexible(3, 5).A, flexible(3, 5).B, Q, R, S);
    EXPECT_LT(c.residual, 1e-10);
    EXPECT_LT(c.stability, 0.0);
}

TEST(DesignRiccati, ZohOfADoubleIntegratorIsExact)
{
    StateSpace c;
    c.A = MatrixXd::Zero(2, 2);
    c.A(0, 1) = 1.0;
    c.B = MatrixXd::Zero(2, 1);
    c.B(1, 0) = 1.0;
    c.C = MatrixXd::Identity(2, 2);
    c.D = MatrixXd::Zero(2, 1);
    const StateSpace d = c2d_zoh(c, 0.1);
    EXPECT_NEAR(d.A(0, 1), 0.1, 1e-15);
    EXPECT_NEAR(d.B(0, 0), 0.005, 1e-15);
    EXPECT_NEAR(d.B(1, 0), 0.1, 1e-15);
    EXPECT_EQ(d.Ts, 0.1);
    EXPECT_THROW(c2d_zoh(c, 0.0), std::invalid_argument);
    EXPECT_THROW(c2d_zoh(d, 0.1), std::invalid_argument);
}

TEST(DesignRiccati, UnstabilizableSystemIsNamed)
{
    MatrixXd A(2, 2), B(2, 1);
    A << 1.5, 0, 0, 0.5;
    B << 0, 1;  // the unstable mode 1.5 is not reachable
    try {
        solve_dare(A, B, MatrixXd::Identity(2, 2), MatrixXd::Identity(1, 1));
        FAIL();
    } catch (const RiccatiError& e) {
        EXPECT_EQ(e.cause, RiccatiError::Cause::Unstabilizable) << e.what();
        EXPECT_NE(std::string(e.what()).find("1.5"), std::string::npos) << e.what();
    }
    MatrixXd Ac(2, 2);
    Ac << 0.5, 0, 0, -1;
    try {
        solve_care(Ac, B, MatrixXd::Identity(2, 2), MatrixXd::Identity(1, 1));
        FAIL();
    } catch (const RiccatiError& e) {
        EXPECT_EQ(e.cause, RiccatiError::Cause::Unstabilizable) << e.what();
    }
}

TEST(DesignRiccati, UndetectableSystemIsNamed)
{
    MatrixXd A(2, 2), B(2, 1), Q = MatrixXd::Zero(2, 2);
    A << 1.0, 0, 0, 0.5;  // a marginal mode the weight does not see
    B << 1, 1;
    Q(1, 1) = 1.0;
    try {
        solve_dare(A, B, Q, MatrixXd::Identity(1, 1));
        FAIL();
    } catch (const RiccatiError& e) {
        EXPECT_EQ(e.cause, RiccatiError::Cause::Undetectable) << e.what();
    }
    MatrixXd Ac(2, 2);
    Ac << 0.0, 0, 0, -1;
    try {
        solve_care(Ac, B, Q, MatrixXd::Identity(1, 1));
        FAIL();
    } catch (const RiccatiError& e) {
        EXPECT_EQ(e.cause, RiccatiError::Cause::Undetectable) << e.what();
    }
}

TEST(DesignRiccati, BadWeightsAreRefused)
{
    const MatrixXd A = MatrixXd::Identity(2, 2) * 0.5, B = MatrixXd::Ones(2, 1);
    try {
        solve_dare(A, B, MatrixXd::Identity(2, 2), MatrixXd::Constant(1, 1, -1.0));
        FAIL();
    } catch (const RiccatiError& e) {
        EXPECT_EQ(e.cause, RiccatiError::Cause::RNotPosDef);
    }
    MatrixXd Q = MatrixXd::Identity(2, 2);
    Q(0, 1) = 1.0;
    EXPECT_THROW(solve_dare(A, B, Q, MatrixXd::Identity(1, 1)), RiccatiError);
    Q = MatrixXd::Identity(2, 2);
    Q(0, 0) = NAN;
    EXPECT_THROW(solve_care(A, B, Q, MatrixXd::Identity(1, 1)), RiccatiError);
    EXPECT_THROW(solve_care(A, B, MatrixXd::Identity(3, 3), MatrixXd::Identity(1, 1)), RiccatiError);
}
