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
