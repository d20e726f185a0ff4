// test_models_lti.cpp - the shared StateSpace type: validation, transfer, poles, zeros, frequencies.
#include <gtest/gtest.h>

#include <cmath>

#include "fracdesign/models/collocated.hpp"
#include "fracdesign/models/lti.hpp"

using namespace fracdesign;

namespace {
StateSpace first_order(double a, double Ts)
{
    StateSpace s;
    s.A = Eigen::MatrixXd::Constant(1, 1, a);
    s.B = Eigen::MatrixXd::Ones(1, 1);
    s.C = Eigen::MatrixXd::Ones(1, 1);
    s.D = Eigen::MatrixXd::Zero(1, 1);
    s.Ts = Ts;
    return s;
}
}  // namespace

TEST(StateSpace, frequency_response_of_continuous_and_discrete_first_order_systems)
{
    const StateSpace c = first_order(-2.0, 0.0);
    EXPECT_NEAR(std::abs(c.frequency_response(3.0)(0, 0) - 1.0 / std::complex<double>(2.0, 3.0)), 0.0, 1e-15);
    const StateSpace d = first_order(0.5, 0.01);  // H(z) = 1/(z - 0.5) at z = e^{j w Ts}
    const std::complex<double> z = std::exp(std::complex<double>(0, 20.0 * 0.01));
    EXPECT_NEAR(std::abs(d.frequency_response(20.0)(0, 0) - 1.0 / (z - 0.5)), 0.0, 1e-15);
    EXPECT_FALSE(d.continuous());
}

TEST(StateSpace, zeros_and_natural_frequencies_of_the_collocated_plant)
{
    const CollocatedPlant p = collocated_plant(0.12);
    const StateSpace s = collocated_state_space(p, false);
    const std::vector<double> f = s.natural_frequencies_hz();
    ASSERT_EQ(f.size(), 2u);
    EXPECT_NEAR(f[0] * 2 * M_PI, p.a1, 1e-9);
    EXPECT_NEAR(f[1] * 2 * M_PI, p.a2, 1e-9);
    const Eigen::VectorXcd z = s.siso_zeros(0, 0);
    ASSERT_EQ(z.size(), 2);
    for (Eigen::Index i = 0; i < 2; ++i) {
        EXPECT_NEAR(z[i].real(), 0.0, 1e-8);
        EXPECT_NEAR(std::fabs(z[i].imag()), p.z1, 1e-8);
    }
}

TEST(StateSpace, validate_names_the_inconsistent_matrix)
{
    StateSpace s = first_order(-1, 0);
    EXPECT_NO_THROW(s.validate());
    s.B = Eigen::MatrixXd::Ones(2, 1);
    EXPECT_THROW(s.validate(), std::invalid_argument);
    s = first_order(-1, 0);
    s.A(0, 0) = NAN;
    try {
        s.validate();
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("matrix A"), std::string::npos);
    }
    s = first_order(-1, 0);
    s.inputs = {"a", "b"};
    EXPECT_THROW(s.validate(), std::invalid_argument);
    s = first_order(-1, -1.0);
    EXPECT_THROW(s.validate(), std::invalid_argument);
}

// balanced(): a diagonal similarity by powers of two. On a drawn system made
// badly scaled on purpose (states multiplied by 10^-6 .. 10^6), it keeps the
// poles and the transfer matrix, brings the rows' and columns' norms
// together, and scales without mixing states (x = S xb, S diagonal).
TEST(StateSpace, balanced_keeps_the_system_and_equalises_the_scales)
{
    const int n = 6;
    StateSpace s;
    s.A = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
        s.A(i, i) = -(1.0 + 3.0 * i);
        for (int j = 0; j < i; ++j) s.A(i, j) = std::sin(1.0 + i * 7.0 + j);
        if (i + 1 < n) s.A(i, i + 1) = 0.1 * std::cos(2.0 + i);  // a feedback path: the graph has cycles
    }
    s.B = Eigen::MatrixXd::Ones(n, 1);
    s.C = Eigen::MatrixXd::Ones(1, n);
    s.D = Eigen::MatrixXd::Zero(1, 1);
    Eigen::VectorXd scale(n);
    for (int i = 0; i < n; ++i) scale(i) = std::pow(10.0, 6.0 - 12.0 * i / (n - 1));  // lower entries up to 1e12
    StateSpace bad = s;  // x = diag(scale) x_bad
    bad.A = scale.asDiagonal().inverse() * s.A * scale.asDiagonal();
    bad.B = scale.asDiagonal().inverse() * s.B;
    bad.C = s.C * scale.asDiagonal();
    const StateSpace b = bad.balanced();
    for (double w : {0.01, 1.0, 30.0}) {
        const std::complex<double> h0 = bad.frequency_response(w)(0, 0), h1 = b.frequency_response(w)(0, 0);
        EXPECT_LT(std::abs(h1 - h0), 1e-12 * std::abs(h0)) << w;
    }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            if (i == j) EXPECT_EQ(b.A(i, i), bad.A(i, i));  // the diagonal is untouched
            if (s.A(i, j) == 0) EXPECT_EQ(b.A(i, j), 0.0);   // no state is mixed into another
        }
    double worst_ratio = 0;
    for (int i = 0; i < n; ++i) {
        const double r = b.A.row(i).cwiseAbs().sum() - std::fabs(b.A(i, i));
        const double c = b.A.col(i).cwiseAbs().sum() - std::fabs(b.A(i, i));
        if (r > 0 && c > 0) worst_ratio = std::max(worst_ratio, std::max(r / c, c / r));
    }
    EXPECT_LT(worst_ratio, 8.0);  // within a few powers of two (unbalanced: up to 1e12)
    EXPECT_GT(bad.A.norm(), 1e11);
    EXPECT_LT(b.A.norm(), 1e3);
}
