// test_gap_spectrum.cpp - the diagnosis's bands and spectra (src/gap/spectrum.cpp),
// all on the one estimator welch_psd: Parseval over the bands, a sine in its
// band and at its bin, a diverged (non-finite) residual as NaN, not an error.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "../../design_tools/src/gap/stages.hpp"

using namespace fracdesign::gap;

namespace {

// n samples (not a power of two: the estimator pads) of a sine of amplitude a
// at f0 plus white noise of std sd.
Eigen::VectorXd sine(Eigen::Index n, double Ts, double f0, double a, double sd, unsigned seed)
{
    std::mt19937 g(seed);
    std::normal_distribution<double> w(0.0, sd);
    Eigen::VectorXd x(n);
    for (Eigen::Index k = 0; k < n; ++k) x(k) = a * std::sin(2 * M_PI * f0 * double(k) * Ts + 0.3) + w(g);
    return x;
}

}  // namespace

TEST(GapSpectrum, band_energies_add_up_to_the_signal_energy_and_a_sine_lies_in_its_band)
{
    const double Ts = 0.01;
    for (const double f0 : {0.37, 3.3, 27.0}) {
        const Eigen::VectorXd x = sine(5000, Ts, f0, 1.5, 0.01, 7);
        const auto bands = band_edges(Ts);
        const Eigen::MatrixXd E = band_energy(x, Ts, bands);
        EXPECT_NEAR(E.sum(), x.squaredNorm(), 1e-9 * x.squaredNorm()) << f0;
        for (size_t b = 0; b < bands.size(); ++b)
            if (f0 >= bands[b].first && f0 < bands[b].second) EXPECT_GT(E(Eigen::Index(b), 0), 0.95 * E.sum()) << f0;
    }
}

TEST(GapSpectrum, smoothed_spectrum_peaks_at_the_sine_bin)
{
    const double Ts = 0.002, f0 = 41.0;
    const Eigen::VectorXd x = sine(3000, Ts, f0, 1.0, 0.05, 3);
    const std::vector<double> S = smoothed_spectrum(x);
    const double df = 1.0 / (double(fft_length(x.size())) * Ts);
    ASSERT_EQ(S.size(), size_t(fft_length(x.size()) / 2 + 1));
    size_t kmax = 0;
    for (size_t k = 0; k < S.size(); ++k)
        if (S[k] > S[kmax]) kmax = k;
    EXPECT_NEAR(double(kmax) * df, f0, df);
}

TEST(GapSpectrum, a_column_that_is_not_finite_has_nan_energy_and_the_others_are_kept)
{
    const double Ts = 0.01;
    Eigen::MatrixXd x(500, 2);
    x.col(0) = sine(500, Ts, 2.0, 1.0, 0.0, 1);
    x.col(1) = x.col(0);
    x(123, 1) = std::numeric_limits<double>::infinity();
    const auto bands = band_edges(Ts);
    const Eigen::MatrixXd E = band_energy(x, Ts, bands);
    EXPECT_NEAR(E.col(0).sum(), x.col(0).squaredNorm(), 1e-9 * x.col(0).squaredNorm());
    for (size_t b = 0; b < bands.size(); ++b) EXPECT_TRUE(std::isnan(E(Eigen::Index(b), 1))) << b;
}
