// test_models_beam.cpp - pseudo-spectral PH Timoshenko beam of seed 004 (bases, matrices, structure,
// spectra against Table 3.1 / C.1) and its bad-input paths.
#include <gtest/gtest.h>

#include <cmath>

#include "fracdesign/models/lagrange.hpp"
#include "fracdesign/models/timoshenko_beam.hpp"

using namespace fracdesign;

TEST(Lagrange, gauss_legendre_integrates_degree_2n_minus_1_exactly)
{
    Eigen::VectorXd x, w;
    gauss_legendre(6, 0.0, 2.0, x, w);
    for (int deg = 0; deg <= 11; ++deg) {
        double q = 0;
        for (int i = 0; i < 6; ++i) q += w[i] * std::pow(x[i], deg);
        EXPECT_NEAR(q, std::pow(2.0, deg + 1) / (deg + 1), 1e-12 * std::pow(2.0, deg + 1)) << deg;
    }
    for (int i = 1; i < 6; ++i) EXPECT_LT(x[i - 1], x[i]);
    EXPECT_THROW(gauss_legendre(0, 0, 1, x, w), std::invalid_argument);
}

TEST(Lagrange, barycentric_basis_interpolates_and_differentiates_a_polynomial_exactly)
{
    Eigen::VectorXd nodes(5);
    nodes << 0.0, 0.2, 0.55, 0.8, 1.0;
    const BarycentricBasis b(nodes);
    Eigen::VectorXd f(5);
    for (int i = 0; i < 5; ++i) f[i] = std::pow(nodes[i], 4) - 2 * nodes[i];  // degree 4: reproduced exactly
    for (double t : {0.0, 0.1, 0.55, 0.93, 1.0}) {
        EXPECT_NEAR(b.values(t).dot(f), std::pow(t, 4) - 2 * t, 1e-13);
        EXPECT_NEAR(b.derivatives(t).dot(f), 4 * std::pow(t, 3) - 2, 1e-12) << t;
    }
    EXPECT_EQ(b.values(0.55), Eigen::VectorXd::Unit(5, 2));
    Eigen::VectorXd dup(2);
    dup << 0.5, 0.5;
    EXPECT_THROW(BarycentricBasis{dup}, std::invalid_argument);
}

TEST(PsBeam, matrices_satisfy_discrete_integration_by_parts_for_both_node_sets)
{
    for (auto c : {Collocation::GaussLegendre, Collocation::Equidistant})
        for (int N : {2, 5, 9, 12}) {
            const PsBeam b = build_ps_beam(wang_steel_beam(), N, c);
            EXPECT_EQ(b.D.rows(), N);
            EXPECT_EQ(b.D.cols(), N + 1);
            EXPECT_EQ(b.M.rows(), N + 1);
            EXPECT_LT(b.integration_by_parts_residual(), 1e-11) << N;
            EXPECT_EQ(b.S, b.S.transpose());
            EXPECT_EQ(b.S.llt().info(), Eigen::Success);
            EXPECT_NEAR(b.sigma, (N % 2) ? 1.0 : -1.0, 1e-12);  // (3.95) holds for odd N only
        }
}

TEST(PsBeam, ph_model_is_skew_and_power_balanced_with_damping)
{
    TimoshenkoParams p = wang_steel_beam();
    p.r_t = 0.3;
    p.r_r = 1e-4;
    const PsBeam b = build_ps_beam(p, 9);
    const PhSystem& s = b.ph;
    EXPECT_LT(s.skew_residual(), 1e-13);
    EXPECT_LT((s.D + s.D.transpose()).norm(), 1e-15);
    // dH/dt = u^T y - e^T R e with e = Q x (seed 004 (3.15))
    const Eigen::VectorXd x = Eigen::VectorXd::Random(36), u = Eigen::VectorXd::Random(4);
    const Eigen::VectorXd e = s.Q * x;
    const Eigen::VectorXd xd = (s.J - s.R) * e + s.B * u, y = s.B.transpose() * e + s.D * u;
    const double dH = e.dot(xd), rhs = u.dot(y) - e.dot(s.R * e);
    EXPECT_NEAR(dH, rhs, 1e-10 * (std::fabs(dH) + std::fabs(u.dot(y))));
    EXPECT_GT(e.dot(s.R * e), 0.0);
}

TEST(PsBeam, spectrum_reproduces_table_3_1_and_does_not_depend_on_the_nodes)
{
    const std::vector<double> gl = clamped_free_frequencies_hz(build_ps_beam(wang_steel_beam(), 9), 5);
    const std::vector<double> eq =
        clamped_free_frequencies_hz(build_ps_beam(wang_steel_beam(), 9, Collocation::Equidistant), 5);
    const double table[5] = {2.9343, 18.3873, 51.4782, 100.8914, 168.2584};
    for (int i = 0; i < 5; ++i) {
        EXPECT_NEAR(gl[i], table[i], 1e-4);
        EXPECT_NEAR(gl[i], eq[i], 1e-6 * gl[i]);
    }
}

TEST(PsBeam, converges_to_the_exact_frequencies_of_appendix_c)
{
    const std::vector<double> ex = exact_clamped_free_frequencies_hz(wang_steel_beam(), 5);
    const double c1[5] = {2.9343, 18.3873, 51.4781, 100.8570, 166.6820};
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(ex[i], c1[i], 5e-5);
    double prev = 1e9;
    for (int N : {5, 9, 12, 16}) {
        const double err = std::fabs(clamped_free_frequencies_hz(build_ps_beam(wang_steel_beam(), N), 5)[4] - ex[4]);
        EXPECT_LT(err, prev) << N;
        prev = err;
    }
    EXPECT_LT(prev, 1e-3);
    // the determinant of (C.16) vanishes at a root
    const Eigen::Matrix4d m = timoshenko_frequency_matrix(wang_steel_beam(), 2 * M_PI * ex[0]);
    EXPECT_LT(std::fabs(m.determinant()) / m.cwiseAbs().rowwise().sum().prod(), 1e-9);
}

TEST(PsBeam, rigid_rotation_gives_the_static_gains)
{
    const StateSpace s = build_ps_beam(wang_steel_beam(), 9).ph.state_space();
    const Eigen::MatrixXcd H = s.transfer(1e-7);
    EXPECT_NEAR(H(2, 1).real(), 1.2, 1e-6);  // w_dot(L)/psi_dot(0) -> L
    EXPECT_NEAR(H(3, 1).real(), 1.0, 1e-6);  // psi_dot(L)/psi_dot(0) -> 1
}

TEST(PsBeam, table_8_3_coefficients_are_derived_from_the_section)
{
    const TimoshenkoParams p = wang_steel_beam();
    EXPECT_NEAR(p.rho, 1.1784, 1e-12);
    EXPECT_NEAR(p.I_rho, 2.4550e-6, 1e-15);
    EXPECT_NEAR(p.K_b, 67.1875, 1e-9);
    EXPECT_NEAR(p.K_s, 1.0498046875e7, 1e-3);
}

TEST(PsBeam, bad_parameters_are_refused_with_the_field_named)
{
    auto msg = [](const TimoshenkoParams& p, int N) {
        try {
            build_ps_beam(p, N);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(msg(wang_steel_beam(), 1).find("N must be >= 2"), std::string::npos);
    TimoshenkoParams p = wang_steel_beam();
    p.L = -1.2;
    EXPECT_NE(msg(p, 9).find(": L "), std::string::npos);
    p = wang_steel_beam();
    p.K_s = NAN;
    EXPECT_NE(msg(p, 9).find("K_s"), std::string::npos);
    p = wang_steel_beam();
    p.r_t = -1;
    EXPECT_NE(msg(p, 9).find("r_t"), std::string::npos);
    p = wang_steel_beam();
    p.rho = INFINITY;
    EXPECT_THROW(exact_clamped_free_frequencies_hz(p, 3), std::invalid_argument);
}
