// Tests of the frequency-domain antenna fit (fracdesign/ident/antenna_fit.hpp).
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fracdesign/ident/antenna_fit.hpp"
#include "fracdesign/ident/haro_synthetic.hpp"

using namespace fracdesign;
using namespace fracdesign::ident;

namespace {

const AntennaDamping<double> kVI = {7.1e-5, 0.996, 0.055, 0.594};

Frf synthetic(const AntennaDamping<double>& d, int k0, int k1, int stride)
{
    Frf f;
    for (double w : haro_grid(k0, k1)) f.w.push_back(w);
    std::vector<double> w;
    for (std::size_t i = 0; i < f.w.size(); i += std::size_t(stride)) w.push_back(f.w[i]);
    f.w = w;
    for (double x : f.w) f.G.push_back(antenna_frf(AntennaLink(), d, x));
    return f;
}

}  // namespace

TEST(AntennaFit, weights_follow_eq27_and_sum_to_one)
{
    const std::vector<double> w = {1.0, 2.0, 4.0};
    const auto c = frf_weights(w, FrfWeighting::Constant);
    const auto i = frf_weights(w, FrfWeighting::InverseOmega);
    EXPECT_DOUBLE_EQ(c[1], 1.0 / 3.0);
    EXPECT_NEAR(i[0] + i[1] + i[2], 1.0, 1e-15);
    EXPECT_DOUBLE_EQ(i[0] / i[2], 4.0);
    EXPECT_EQ(haro_grid().size(), 7907u);
    EXPECT_NEAR(haro_grid().back(), 100.0 * M_PI, 1e-9);
}

TEST(AntennaFit, noiseless_type_vi_is_recovered_with_both_weightings)
{
    const Frf f = synthetic(kVI, 94, 8000, 8);
    for (FrfWeighting wt : {FrfWeighting::Constant, FrfWeighting::InverseOmega}) {
        AntennaFitOptions o;
        o.weighting = wt;
        o.starts = 4;
        const auto r = fit_antenna(f, AntennaStructure::VI, o);
        EXPECT_TRUE(r.converged) << r.full_report;
        EXPECT_NEAR(r.params[0] / kVI.zeta, 1.0, 1e-6) << weighting_name(wt);
        EXPECT_NEAR(r.params[1] / kVI.alpha, 1.0, 1e-6);
        EXPECT_NEAR(r.params[2] / kVI.gamma, 1.0, 1e-6);
        EXPECT_NEAR(r.params[3] / kVI.lambda, 1.0, 1e-6);
        EXPECT_LT(r.cost, 1e-16);
    }
}

TEST(AntennaFit, same_seed_same_result_and_covariance_reported)
{
    Frf f = synthetic(kVI, 94, 8000, 16);
    std::mt19937_64 g(3);
    std::normal_distribution<double> n(0.0, 0.05);
    for (auto& v : f.G) v += std::abs(v) * std::complex<double>(n(g), n(g));
    AntennaFitOptions o;
    o.starts = 3;
    o.seed = 7;
    const auto a = fit_antenna(f, AntennaStructure::III, o);
    const auto b = fit_antenna(f, AntennaStructure::III, o);
    EXPECT_EQ(a.params, b.params);
    EXPECT_EQ(a.start_costs, b.start_costs);
    ASSERT_EQ(a.std_dev.size(), 2u);
    EXPECT_GT(a.std_dev[0], 0.0);
    EXPECT_GT(a.std_dev[1], 0.0);
    EXPECT_EQ(a.names, (std::vector<std::string>{"zeta", "gamma"}));
}

TEST(AntennaFit, not_converged_fit_says_so_with_the_ceres_report)
{
    const Frf f = synthetic(kVI, 94, 8000, 16);
    AntennaFitOptions o;
    o.starts = 1;
    o.max_iterations = 1;
    const auto r = fit_antenna(f, AntennaStructure::VI, o);
    EXPECT_FALSE(r.converged);
    EXPECT_NE(r.full_report.find("Termination"), std::string::npos);
    EXPECT_NE(r.summary.find("NO_CONVERGENCE"), std::string::npos) << r.summary;
}

TEST(AntennaFit, refuses_bad_frf_and_options)
{
    Frf f = synthetic(kVI, 94, 200, 1);
    AntennaFitOptions o;
    Frf g = f;
    g.G[5] = {NAN, 0.0};
    EXPECT_THROW(fit_antenna(g, AntennaStructure::I, o), std::invalid_argument);
    g = f;
    std::swap(g.w[3], g.w[4]);
    EXPECT_THROW(fit_antenna(g, AntennaStructure::I, o), std::invalid_argument);
    g = f;
    g.w.resize(5);
    g.G.resize(5);
    EXPECT_THROW(fit_antenna(g, AntennaStructure::I, o), std::invalid_argument);
    o.starts = 0;
    EXPECT_THROW(fit_antenna(f, AntennaStructure::I, o), std::invalid_argument);
    EXPECT_THROW(parse_structure("VII"), std::invalid_argument);
    EXPECT_EQ(parse_structure("IV"), AntennaStructure::IV);
}

TEST(AntennaFit, fused_kernel_value_and_gradient_match_the_model_and_its_automatic_derivatives)
{
    using J4 = ceres::Jet<double, 4>;
    for (const AntennaDamping<double>& d : {kVI, AntennaDamping<double>{5.4e-5, 1.0, 0.02, 1.0},
                                            AntennaDamping<double>{0.0, 0.0, 0.046, 1.247},
                                            AntennaDamping<double>{2.49e-4, 0.832, 0.0, 0.0}})
        for (double w : {3.7, 16.1, 70.0, 100.6, 281.7, 314.0}) {
            const AntennaDamping<J4> dj = {J4(d.zeta, 0), J4(d.alpha, 1), J4(d.gamma, 2), J4(d.lambda, 3)};
            const Cx<J4> g = antenna_frf<J4>(AntennaLink(), dj, J4(w));
            std::array<std::complex<double>, 4> a;
            const std::complex<double> v = antenna_frf_with_gradient(AntennaLink(), d, w, &a);
            const std::complex<double> m = antenna_frf(AntennaLink(), d, w);
            EXPECT_LE(std::abs(v - m), 1e-12 * std::abs(m)) << "w " << w;
            for (int i = 0; i < 4; ++i) {
                const std::complex<double> ad(g.re.v[i], g.im.v[i]);
                EXPECT_LE(std::abs(a[std::size_t(i)] - ad), 1e-8 * (std::abs(ad) + 1e-12)) << "w " << w << " i " << i;
            }
        }
}

TEST(AntennaFit, analytic_and_automatic_derivatives_give_the_same_fit)
{
    const Frf f = haro_synthetic_frf(kVI, haro_grid(94, 8000), 0.05, 2);
    Frf g;
    for (std::size_t i = 0; i < f.w.size(); i += 8) {
        g.w.push_back(f.w[i]);
        g.G.push_back(f.G[i]);
    }
    AntennaFitOptions o;
    o.starts = 2;
    const auto a = fit_antenna(g, AntennaStructure::V, o);
    o.derivatives = Derivatives::Automatic;
    const auto b = fit_antenna(g, AntennaStructure::V, o);
    EXPECT_NEAR(a.cost / b.cost, 1.0, 1e-9);
    for (std::size_t i = 0; i < a.params.size(); ++i) EXPECT_NEAR(a.params[i] / b.params[i], 1.0, 1e-5);
}
