// Seed 001 FO-PI / FO-PD tuning: closed form, feasibility tests, bands, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "fracdesign/design/fopi_fopd.hpp"
#include "run_command.hpp"

using namespace fracdesign::design;

namespace {
constexpr double kPi = 3.14159265358979323846;

GharabPlant robot()
{
    GharabPlant p;
    p.K = 1.0;
    p.T = 1.0 / (5.8434 * 5.8434);
    p.lambda = 1.92;
    p.tau = 0.1613;
    return p;
}

std::string run_cli(const std::string& args, int* status)
{
    return run_command(std::string(FRACDESIGN_EXE) + " " + args, status);
}
}  // namespace

TEST(DesignFoPiPd, TunedLoopMeetsBothSpecsForRandomPlants)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        GharabPlant p;
        p.K = 0.2 + 3.0 * u(rng);
        p.T = 0.01 + 2.0 * u(rng);
        p.lambda = 1.01 + 0.99 * u(rng);
        p.tau = 0.5 * u(rng);
        const FoSpec s{0.1 + 10.0 * u(rng), 0.05 + 1.2 * u(rng), 0.05 + 0.95 * u(rng)};
        for (FoKind k : {FoKind::PI, FoKind::PD}) {
            const FoDesign d = tune_fo(k, p, s);
            const std::complex<double> err = d.loop(s.wc) + std::polar(1.0, s.phim);
            EXPECT_LT(std::abs(err), 1e-10) << "design " << i;
        }
    }
}

TEST(DesignFoPiPd, PiGainsAgreeWithTheCompactPolarForm)
{
    // notes/001 section 3.1: K_in = R w^a sin(phi_mn + psi)/sin(a pi/2),
    // K_pn = -R sin(phi_mn + psi + a pi/2)/sin(a pi/2), 1 + (j w)^lambda = R e^{j psi}.
    const FoDesign d = tune_fo(FoKind::PI, robot(), FoSpec{6.36, 0.25, 0.88});
    const std::complex<double> z = 1.0 + std::polar(std::pow(d.wcn, 1.92), 1.92 * kPi / 2);
    const double R = std::abs(z), psi = std::arg(z), sa = std::sin(0.88 * kPi / 2);
    EXPECT_NEAR(d.Kin, R * std::pow(d.wcn, 0.88) * std::sin(d.phimn + psi) / sa, 1e-13);
    EXPECT_NEAR(d.Kpn, -R * std::sin(d.phimn + psi + 0.88 * kPi / 2) / sa, 1e-13);
}

TEST(DesignFoPiPd, NormalisationUsesTauOverTToTheOneOverLambda)
{
    const FoDesign d = tune_fo(FoKind::PI, robot(), FoSpec{6.36, 0.25, 0.88});
    EXPECT_NEAR(d.Tl, 0.1589974, 1e-7);   // notes/001 C5
    EXPECT_NEAR(d.taun, 1.014482, 1e-6);  // erratum E1
    EXPECT_NEAR(d.wcn, 1.011223, 1e-6);
    EXPECT_NEAR(d.phimn, 1.275868, 1e-6);
}

TEST(DesignFoPiPd, LowFrequencyConditionFlipsExactlyAtTheClosedFormBoundary)
{
    // Move phi_m across the exact boundary pi - psi (seed 001 eq. (18)); K_in changes sign there.
    const GharabPlant p = robot();
    const FoDesign ref = tune_fo(FoKind::PI, p, FoSpec{6.36, 0.25, 0.88});
    const double bound = lf_phimn_bound(ref.wcn, p.lambda);
    const double phim_at_bound = bound - ref.taun * ref.wcn;
    const FoDesign below = tune_fo(FoKind::PI, p, FoSpec{6.36, phim_at_bound - 1e-9, 0.88});
    const FoDesign above = tune_fo(FoKind::PI, p, FoSpec{6.36, phim_at_bound + 1e-9, 0.88});
    EXPECT_GT(below.Kin, 0.0);
    EXPECT_LT(above.Kin, 0.0);
    EXPECT_NEAR(lf_phimn_bound(1.090722, 1.92), 0.71043, 1e-5);  // notes/001 C12
    EXPECT_NEAR(lf_phimn_bound(1.011223, 1.92), 1.46496, 1e-5);
}

TEST(DesignFoPiPd, PrintedCrossoverOfThePiIsReportedInfeasibleWithTheReason)
{
    const FoDesign d = tune_fo(FoKind::PI, robot(), FoSpec{6.86, 0.25, 0.88});
    EXPECT_FALSE(d.feasible());
    EXPECT_NEAR(d.Kin, -0.150216, 1e-6);
    EXPECT_EQ(d.reason().rfind("low_frequency", 0), 0u) << d.reason();
}

TEST(DesignFoPiPd, RhfcImpliesLoopGainBelowOneBeyondCrossover)
{
    // notes/001 C14: any design passing (22) has |L| < 1 beyond w_c.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int tested = 0;
    for (int i = 0; i < 300; ++i) {
        GharabPlant p;
        p.T = 0.05 + u(rng);
        p.lambda = 1.05 + 0.9 * u(rng);
        p.tau = 0.0;
        const FoSpec s{0.2 + 3.0 * u(rng), 0.1 + 1.3 * u(rng), 0.1 + 0.9 * u(rng)};
        const FoDesign d = tune_fo(FoKind::PI, p, s);
        if (!d.tests[2].pass) continue;
        ++tested;
        for (int k = 1; k <= 400; ++k) {
            const double w = s.wc * std::pow(1000.0, k / 400.0);
            EXPECT_LT(std::abs(d.loop(w)), 1.0) << "design " << i << " at w = " << w;
        }
    }
    EXPECT_GT(tested, 20);
}

TEST(DesignFoPiPd, PiFeasibleBandMatchesTheNotes)
{
    const auto b = feasible_bands(FoKind::PI, robot(), FoSpec{1.0, 0.25, 0.88}, 1.0, 20.0, 300);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_NEAR(b[0].first, 6.250, 6.25e-3);
    EXPECT_NEAR(b[0].second, 6.439, 6.4e-3);
    for (double wc : {b[0].first * 1.0001, 6.36, b[0].second * 0.9999})
        EXPECT_TRUE(tune_fo(FoKind::PI, robot(), FoSpec{wc, 0.25, 0.88}).feasible()) << wc;
    for (double wc : {b[0].first * 0.999, b[0].second * 1.001})
        EXPECT_FALSE(tune_fo(FoKind::PI, robot(), FoSpec{wc, 0.25, 0.88}).feasible()) << wc;
}

TEST(DesignFoPiPd, PdBandFirstSegmentMatchesTheNotes)
{
    const auto b = feasible_bands(FoKind::PD, robot(), FoSpec{1.0, 0.25, 0.88}, 1.0, 60.0, 300);
    ASSERT_EQ(b.size(), 1u);  // phi_mn >= pi removes the wrapped segments
    EXPECT_NEAR(b[0].first, 6.259, 6.3e-3);   // notes/001 C16
    EXPECT_NEAR(b[0].second, 11.249, 1.1e-2);
}

TEST(DesignFoPiPd, MalformedPlantOrSpecIsRefusedNamingTheField)
{
    GharabPlant p = robot();
    p.lambda = 2.2;
    try {
        tune_fo(FoKind::PI, p, FoSpec{1, 0.5, 0.5});
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("lambda"), std::string::npos);
    }
    EXPECT_THROW(tune_fo(FoKind::PI, robot(), FoSpec{1, 0.5, 1.5}), std::invalid_argument);
    EXPECT_THROW(tune_fo(FoKind::PD, robot(), FoSpec{-1, 0.5, 0.5}), std::invalid_argument);
    EXPECT_THROW(tune_fo(FoKind::PD, robot(), FoSpec{1, NAN, 0.5}), std::invalid_argument);
    p = robot();
    p.T = 0.0;
    EXPECT_THROW(tune_fo(FoKind::PD, p, FoSpec{1, 0.5, 0.5}), std::invalid_argument);
}

TEST(DesignFoPiPd, CliReportsInfeasibleSpecWithReasonAndBand)
{
    int st = 0;
    const std::string out =
        run_cli("tune fopi --w0 5.8434 --lambda 1.92 --tau 0.1613 --wc 6.86 --phim 0.25 --alpha 0.88", &st);
    EXPECT_EQ(st, 1);
    EXPECT_NE(out.find("infeasible specification: low_frequency"), std::string::npos) << out;
    EXPECT_NE(out.find("[6.25"), std::string::npos) << out;
    run_cli("tune fopi --w0 5.8434 --lambda 1.92 --tau 0.1613 --wc 6.36 --phim 0.25 --alpha 0.88 --json", &st);
    EXPECT_EQ(st, 0);
    run_cli("tune fopi --w0 5.8434 --lambda 1.92 --wc 6.36 --phim 0.25", &st);
    EXPECT_EQ(st, 2);
}
