// test_models_collocated.cpp - seed 002's collocated plant (38)-(46) and seed 001's fractional process.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fracdesign/models/collocated.hpp"
#include "fracdesign/models/foprocess.hpp"

#include <Eigen/Dense>

using namespace fracdesign;

TEST(Collocated, nominal_modal_data_match_the_paper)
{
    const CollocatedPlant p = collocated_plant(0.12);
    EXPECT_NEAR(p.a1, 6.0140, 5e-5);
    EXPECT_NEAR(p.z1, 28.2102, 5e-5);
    EXPECT_NEAR(p.a2, 40.0119, 5e-5);
    EXPECT_NEAR(p.k1, 1.99527, 5e-6);
    EXPECT_NEAR(p.k2, 2.11473, 5e-6);
    EXPECT_NEAR(p.k1 + p.k2, p.b, 1e-12);
    EXPECT_NEAR(std::abs(collocated_P(p, 10.0, false)), 0.0298492, 5e-8);  // notes 002 sec. 6.5
    EXPECT_NEAR(std::abs(collocated_P(p, 10.0, true)), 0.0298479, 5e-8);
}

TEST(Collocated, poles_and_zeros_interlace_over_the_tip_mass_range)
{
    for (int i = 0; i <= 100; ++i) {
        const CollocatedPlant p = collocated_plant(0.01 + 0.22 * i / 100.0);
        EXPECT_LT(p.a1, p.z1);
        EXPECT_LT(p.z1, p.a2);
        EXPECT_GT(p.k1, 0);
        EXPECT_GT(p.k2, 0);
        // Rayleigh damping: the zero damping of the partial-fraction sum equals zeta(z1) (notes 002 6.4)
        EXPECT_NEAR((p.k1 * p.zeta2 * p.a2 + p.k2 * p.zeta1 * p.a1) / (p.b * p.z1), p.xi1, 1e-12);
    }
}

TEST(Collocated, partial_fractions_equal_the_factorised_form_46)
{
    const CollocatedPlant p = collocated_plant(0.23);
    for (double w : {0.5, 4.4, 20.0, 39.0, 100.0}) {
        const std::complex<double> s(0, w);
        const std::complex<double> f = p.b * (s * s + 2.0 * p.xi1 * p.z1 * s + p.z1 * p.z1) /
                                       ((s * s + 2.0 * p.zeta1 * p.a1 * s + p.a1 * p.a1) *
                                        (s * s + 2.0 * p.zeta2 * p.a2 * s + p.a2 * p.a2));
        EXPECT_LT(std::abs(collocated_P(p, w) - f), 1e-9 * std::abs(f)) << w;
        // and the modal state space has the same response
        EXPECT_LT(std::abs(collocated_state_space(p).frequency_response(w)(0, 0) - f), 1e-12 * std::abs(f));
    }
    EXPECT_THROW(collocated_plant(0.0), std::invalid_argument);
    EXPECT_THROW(collocated_plant(NAN), std::invalid_argument);
}

TEST(FoProcess, normalisation_uses_t_to_the_one_over_lambda)
{
    const FoProcess p = feliu_benftima_robot();
    EXPECT_NEAR(p.time_scale(), 0.1589974, 1e-7);
    EXPECT_NEAR(p.normalised_delay(), 1.014482, 1e-6);
    // erratum E1: the printed tau/T^lambda is a different number
    EXPECT_GT(std::fabs(p.normalised_delay() - p.tau / std::pow(p.T, p.lambda)), 1.0);
    // G(j w) = K G_n(j w T^(1/lambda)) for every w
    for (double w : {0.3, 5.8434, 40.0})
        EXPECT_LT(std::abs(p.frf(w) - p.K * p.normalised_frf(p.normalised_frequency(w))), 1e-12 * std::abs(p.frf(w)));
    // |G| at w0 peaks (underdamped for lambda > 1)
    EXPECT_GT(std::abs(p.frf(5.8434)), 5.0);
}

TEST(FoProcess, bad_parameters_are_refused_with_the_field_named)
{
    FoProcess p = feliu_benftima_robot();
    p.T = -1;
    try {
        p.validate();
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("T "), std::string::npos);
    }
    p = feliu_benftima_robot();
    p.tau = NAN;
    EXPECT_THROW(p.validate(), std::invalid_argument);
    p = feliu_benftima_robot();
    p.lambda = 2.5;
    EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(CollocatedModes, pzi_product_form_has_positive_residues_and_equal_response)
{
    // Lemma 1 on the robot: the product form (42) gives the residues k1, k2
    const CollocatedPlant p = collocated_plant(0.12);
    const CollocatedModes m = pzi_to_modes(p.b, {p.a1, p.a2}, {p.z1});
    EXPECT_NEAR(m.k[0], p.k1, 1e-12);
    EXPECT_NEAR(m.k[1], p.k2, 1e-12);
    // five interlaced modes: all residues positive, and the sum (22) equals the product (2)
    const std::vector<double> a = {1.0, 4.0, 9.0, 30.0, 100.0}, z = {2.0, 6.0, 20.0, 50.0};
    const CollocatedModes f = pzi_to_modes(3.0, a, z);
    for (double k : f.k) EXPECT_GT(k, 0.0);
    for (double w : {0.5, 3.0, 25.0, 200.0}) {
        std::complex<double> prod = 3.0;
        const std::complex<double> s2 = -w * w;
        for (double zi : z) prod *= s2 + zi * zi;
        for (double ai : a) prod /= s2 + ai * ai;
        EXPECT_LT(std::abs(modal_P(f, w) - prod), 1e-12 * std::abs(prod)) << w;
        EXPECT_LT(std::abs(modal_state_space(f).frequency_response(w)(0, 0) - prod), 1e-9 * std::abs(prod));
    }
    // broken interlacing (a zero above the next pole): some residue is not positive
    const CollocatedModes br = pzi_to_modes(3.0, {1.0, 4.0, 9.0}, {5.0, 6.0});
    EXPECT_LE(std::min({br.k[0], br.k[1], br.k[2]}), 0.0);
    EXPECT_THROW(pzi_to_modes(1.0, {1.0, 2.0}, {}), std::invalid_argument);
    CollocatedModes bad = f;
    bad.zeta[2] = -0.1;
    EXPECT_THROW(modal_state_space(bad), std::invalid_argument);
}

namespace {
constexpr double kLb = 0.45359237;  // kg per lb

// An arm the paper does not print (SI): a 0.8 m link of EI 2.5 N m^2, 0.3 kg at 0.35 m, tip 0.2 kg.
CollocatedArm unprinted_arm()
{
    CollocatedArm a;
    a.form = CollocatedArm::Form::Physical;
    a.L = 0.8, a.EI = 2.5, a.m1 = 0.3, a.x1 = 0.35, a.moment_gain = 1.0;
    a.eps = 0.004, a.rayleigh_a = 0.08, a.rayleigh_b = 4e-5;
    a.m2_nominal = 0.2, a.m2_min = 0.05, a.m2_max = 0.5;
    return a;
}

// Gamma/theta_m and theta_2/theta_m at s = j w by a direct solve of M theta'' + K'(theta - theta_m 1) = 0
// with K' = X F^-1 X from the clamped-link flexibility, independent of the closed forms of the model.
std::pair<std::complex<double>, std::complex<double>> direct_response(const CollocatedArm& a, double m2, double w)
{
    Eigen::Matrix2d F;
    F << std::pow(a.x1, 3) / (3 * a.EI), a.x1 * a.x1 * (3 * a.L - a.x1) / (6 * a.EI),
        a.x1 * a.x1 * (3 * a.L - a.x1) / (6 * a.EI), std::pow(a.L, 3) / (3 * a.EI);
    const Eigen::Matrix2d X = Eigen::Vector2d(a.x1, a.L).asDiagonal();
    const Eigen::Matrix2d Kp = X * F.inverse() * X;
    const Eigen::Matrix2d M = Eigen::Vector2d(a.m1 * a.x1 * a.x1, m2 * a.L * a.L).asDiagonal();
    const std::complex<double> s(0, w);
    const Eigen::Matrix2cd A = M.cast<std::complex<double>>() * s * s + Kp.cast<std::complex<double>>();
    const Eigen::Vector2cd th = A.lu().solve((Kp * Eigen::Vector2d::Ones()).cast<std::complex<double>>());
    const std::complex<double> gamma = a.moment_gain * (Kp.cast<std::complex<double>>() * (Eigen::Vector2cd::Ones() - th)).sum();
    return {gamma, th(1)};
}
}  // namespace

TEST(CollocatedArm, PhysicalFormWithTheRobotsDataGivesThePrintedCoefficients)
{
    // Middle mass at L/2, m1 = 0.12 lb: the printed 1455.2 = 16 c/m1 fixes c = 48 EI/(7 L^3), hence EI;
    // b = g c L^2 fixes the (unprinted) moment gain. Then a1, z1, a2 and G_2 must follow for every m2.
    CollocatedArm a;
    a.form = CollocatedArm::Form::Physical;
    a.L = 12 * 0.0254;
    a.x1 = a.L / 2;
    a.m1 = 0.12 * kLb;
    const double c = 1455.2 * a.m1 / 16.0;
    a.EI = 7.0 * c * std::pow(a.L, 3) / 48.0;
    a.moment_gain = 4.11 / (c * a.L * a.L);
    a.m2_nominal = 0.12 * kLb, a.m2_min = 0.01 * kLb, a.m2_max = 0.23 * kLb;
    a.validate();
    for (double m2 : {0.01, 0.12, 0.23}) {
        const CollocatedPlant ph = a.plant(m2 * kLb), pr = collocated_plant(m2);
        EXPECT_NEAR(ph.a1, pr.a1, 1e-3 * pr.a1) << m2;
        EXPECT_NEAR(ph.z1, pr.z1, 1e-3 * pr.z1) << m2;
        EXPECT_NEAR(ph.a2, pr.a2, 1e-3 * pr.a2) << m2;
        EXPECT_NEAR(ph.b, pr.b, 1e-12);
        EXPECT_NEAR(ph.g2_s2 / ph.g2_0, pr.g2_s2 / pr.g2_0, 2e-3 * std::fabs(pr.g2_s2 / pr.g2_0)) << m2;  // zero 1273.3
    }
}

TEST(CollocatedArm, UnprintedArmMatchesADirectSolveOfTheLumpedMassEquations)
{
    const CollocatedArm a = unprinted_arm();
    a.validate();
    for (double m2 : {a.m2_min, a.m2_nominal, a.m2_max}) {
        const CollocatedPlant p = a.plant(m2);
        EXPECT_LT(p.a1, p.z1);
        EXPECT_LT(p.z1, p.a2);
        EXPECT_GT(p.k1, 0.0);
        EXPECT_GT(p.k2, 0.0);
        EXPECT_NEAR(p.g2_0 / (p.a1 * p.a1 * p.a2 * p.a2), 1.0, 1e-12);  // G_2(0) = 1: rigid rotation
        EXPECT_EQ(p.eps, a.eps);
        EXPECT_NEAR(p.zeta1, 0.5 * (a.rayleigh_a / p.a1 + a.rayleigh_b * p.a1), 1e-15);
        for (double w : {0.3 * p.a1, 1.7 * p.a1, 0.5 * (p.z1 + p.a2), 3.0 * p.a2}) {
            const auto [gamma, th2] = direct_response(a, m2, w);
            const std::complex<double> s(0, w);
            const std::complex<double> g = s * s * collocated_P(p, w, false);
            EXPECT_LT(std::abs(g - gamma), 1e-9 * std::abs(gamma)) << m2 << " " << w;
            const std::complex<double> g2 =
                (p.g2_s2 * s * s + p.g2_0) / ((s * s + p.a1 * p.a1) * (s * s + p.a2 * p.a2));
            EXPECT_LT(std::abs(g2 - th2), 1e-9 * std::abs(th2)) << m2 << " " << w;
        }
    }
}

TEST(CollocatedArm, EachBadFieldIsRefusedNamingFieldValueAndRange)
{
    struct Case {
        const char* field;
        void (*spoil)(CollocatedArm&);
        const char* value;
    };
    const Case cases[] = {
        {"link.L", [](CollocatedArm& a) { a.L = -1; }, "-1"},
        {"link.EI", [](CollocatedArm& a) { a.EI = 0; }, "0"},
        {"masses.m1", [](CollocatedArm& a) { a.m1 = NAN; }, "nan"},
        {"masses.x1", [](CollocatedArm& a) { a.x1 = 0.9; }, "0.9"},
        {"moment_gain", [](CollocatedArm& a) { a.moment_gain = -2; }, "-2"},
        {"masses.m2", [](CollocatedArm& a) { a.m2_nominal = 0.7; }, "0.7"},
        {"masses.m2_range[1]", [](CollocatedArm& a) { a.m2_max = 0.01; }, "0.01"},
        {"inner_loop.eps", [](CollocatedArm& a) { a.eps = 2.0; }, "2"},
        {"damping.rayleigh_b", [](CollocatedArm& a) { a.rayleigh_b = -1e-5; }, "-1e-05"},
    };
    for (const Case& c : cases) {
        CollocatedArm a = unprinted_arm();
        c.spoil(a);
        try {
            a.validate();
            ADD_FAILURE() << c.field << " accepted";
        } catch (const CollocatedArmError& e) {
            EXPECT_EQ(e.field, c.field);
            const std::string m = e.what();
            EXPECT_NE(m.find(std::string("is ") + c.value + ", must be"), std::string::npos) << m;
        }
    }
    CollocatedArm printed = feliu_robot_arm();
    printed.m2_nominal = 0.5;  // outside the printed range [0.01, 0.23] lb
    EXPECT_THROW(printed.validate(), CollocatedArmError);
}
