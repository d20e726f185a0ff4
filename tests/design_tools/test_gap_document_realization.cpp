// test_gap_document_realization.cpp - the rational realization of the seed 001
// process (fracdesign/models/fo_realization.hpp) meets the accuracy that
// docs/gap.md states, against the exact K/(1 + T (j w)^lambda), for processes
// the test draws (not the seed's), lambda below and above 1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "fracdesign/design/riccati.hpp"
#include "fracdesign/models/fo_realization.hpp"

#include "frac/mittag_leffler.h"

using namespace fracdesign;

namespace {

// The accuracy docs/gap.md states for the default band: over [2 pi/T_rec,
// pi/Ts], the realization's frequency response is within 0.2 % (relative)
// of the exact one (measured: at most 0.1 %, at Nyquist).
const double kStatedError = 2e-3;

}  // namespace

TEST(FoRealization, default_band_meets_the_stated_accuracy_over_the_records_band)
{
    std::mt19937 rng(20261202);
    std::uniform_real_distribution<double> U(0, 1);
    double worst = 0;
    for (int i = 0; i < 24; ++i) {
        FoProcess p;
        p.K = 0.2 + 4 * U(rng);
        p.lambda = 0.3 + 1.7 * U(rng);
        const double tc = std::pow(10.0, -1.5 + 2.5 * U(rng));  // time scale T^(1/lambda) in [0.03, 10] s
        p.T = std::pow(tc, p.lambda);
        const double Ts = std::pow(10.0, -3.0 + 1.5 * U(rng));   // 1 ms .. 32 ms
        const double Trec = Ts * std::pow(10.0, 3.0 + 1.5 * U(rng));  // 1e3 .. 3e4 samples
        const OustaloupBand b = default_oustaloup_band(Ts, Trec);
        const double e = foprocess_realization_error(p, b, 2 * M_PI / Trec, M_PI / Ts);
        worst = std::max(worst, e);
        EXPECT_LT(e, kStatedError) << "lambda " << p.lambda << " T " << p.T << " Ts " << Ts << " T_rec " << Trec << " N "
                                   << b.N;
    }
    std::printf("worst relative error of the default realization over [2 pi/T_rec, pi/Ts]: %.3g\n", worst);
}

// What the gap replay runs is the realization's zero-order hold, sample by
// sample over the whole record: its step response must follow the exact one,
// K (1 - E_lambda(-t^lambda / T)) (Mittag-Leffler, libfrac), to the end of
// the record. The frequency response above does not see a loss in the
// matrix exponential: unbalanced, the cascade's entries reached 1e12 and a
// 12 s record at 1 ms with lambda 1.09 ended its step at 0.33 for K = 1.86
// (found by an outside case named gain_error 5.2 for a dead zone).
TEST(FoRealization, zero_order_hold_follows_the_exact_step_response_to_the_records_end)
{
    std::mt19937 rng(20261206);
    std::uniform_real_distribution<double> U(0, 1);
    double worst = 0;
    std::vector<FoProcess> cases;
    std::vector<std::pair<double, double>> timing;  // (Ts, T_rec)
    {
        FoProcess p;  // the outside case
        p.K = 1.8560034906274818;
        p.T = 0.7914905561650936;
        p.lambda = 1.0922538233957197;
        cases.push_back(p);
        timing.push_back({0.001, 12.0});
    }
    for (int i = 0; i < 10; ++i) {
        FoProcess p;
        p.K = 0.2 + 4 * U(rng);
        p.lambda = 0.3 + 1.6 * U(rng);
        const double tc = std::pow(10.0, -1.5 + 2.0 * U(rng));
        p.T = std::pow(tc, p.lambda);
        const double Ts = std::pow(10.0, -3.0 + 1.0 * U(rng));
        cases.push_back(p);
        timing.push_back({Ts, std::max(20 * tc, Ts * std::pow(10.0, 3.5 + 0.8 * U(rng)))});
    }
    for (size_t i = 0; i < cases.size(); ++i) {
        const FoProcess& p = cases[i];
        const double Ts = timing[i].first, Trec = timing[i].second;
        const StateSpace d = design::c2d_zoh(foprocess_realization(p, default_oustaloup_band(Ts, Trec)), Ts);
        const long n = long(std::ceil(Trec / Ts));
        Eigen::VectorXd x = Eigen::VectorXd::Zero(d.nx());
        double err = 0;
        for (long k = 1; k <= n; ++k) {
            x = d.A * x + d.B;  // unit step held from t = 0
            if (k % std::max(1L, n / 40) != 0 && k != n) continue;
            const double t = double(k) * Ts;
            frac_real e = 0;
            ASSERT_EQ(frac_mittag_leffler(p.lambda, 1.0, -std::pow(t, p.lambda) / p.T, &e), FRAC_OK);
            err = std::max(err, std::fabs((d.C * x)(0) - p.K * (1 - e)) / p.K);
        }
        worst = std::max(worst, err);
        // the realization's 0.2 % in frequency, in the step: 0.5 % of K
        EXPECT_LT(err, 5e-3) << "lambda " << p.lambda << " T " << p.T << " Ts " << Ts << " T_rec " << Trec;
    }
    std::printf("worst step-response error of the realization's zero-order hold, relative to K: %.3g\n", worst);
}

TEST(FoRealization, static_gain_is_exact_and_integer_orders_need_no_filter)
{
    FoProcess p;
    p.K = 2.5;
    p.T = 0.7;
    p.lambda = 0.64;
    const StateSpace s = foprocess_realization(p, default_oustaloup_band(0.01, 30));
    EXPECT_NEAR(s.frequency_response(1e-9)(0, 0).real(), 2.5, 1e-6);
    p.lambda = 1.0;
    const StateSpace one = foprocess_realization(p, default_oustaloup_band(0.01, 30));
    EXPECT_EQ(one.nx(), 1);
    EXPECT_LT(foprocess_realization_error(p, default_oustaloup_band(0.01, 30), 1e-3, 1e3), 1e-12);
    p.lambda = 2.0;
    EXPECT_EQ(foprocess_realization(p, default_oustaloup_band(0.01, 30)).nx(), 2);
}

TEST(FoRealization, a_narrower_band_is_less_accurate_outside_it)
{
    // The error grows outside [wb, wh]: the band parameter matters.
    FoProcess p;
    p.K = 1;
    p.lambda = 0.55;
    p.T = std::pow(0.4, p.lambda);
    OustaloupBand narrow{1.0, 100.0, 3};
    EXPECT_GT(foprocess_realization_error(p, narrow, 0.01, 300), 10 * foprocess_realization_error(p, default_oustaloup_band(0.01, 20), 0.01, 300));
}

TEST(FoRealization, refuses_a_bad_band_naming_the_field)
{
    FoProcess p;
    auto msg = [&](OustaloupBand b) {
        try {
            foprocess_realization(p, b);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(msg({0, 10, 3}).find("realization.wb"), std::string::npos);
    EXPECT_NE(msg({1, 0.5, 3}).find("realization.wh"), std::string::npos);
    EXPECT_NE(msg({1, 10, 0}).find("realization.N"), std::string::npos);
}
