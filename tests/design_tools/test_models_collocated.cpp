// test_models_collocated.cpp - seed 002's collocated plant (38)-(46) and seed 001's fractional process.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fracdesign/models/collocated.hpp"
#include "fracdesign/models/foprocess.hpp"

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
