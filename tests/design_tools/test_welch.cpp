// test_welch.cpp - the Welch FRF estimator against scipy.signal.csd/welch (fixture generated once by
// tests/design_tools/fixtures/welch_scipy.py) and its bad-input paths.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <nlohmann/json.hpp>

#include "fracdesign/welch.hpp"

using namespace fracdesign;

namespace {

nlohmann::json load_fixture()
{
    std::ifstream in(std::string(FRAC_SOURCE_DIR) + "/tests/design_tools/fixtures/welch_scipy.json");
    EXPECT_TRUE(in.good());
    return nlohmann::json::parse(in);
}

double max_rel(const std::vector<double>& got, const std::vector<double>& ref)
{
    double m = 0, scale = 0;
    for (double r : ref) scale = std::max(scale, std::fabs(r));
    for (size_t i = 0; i < ref.size(); ++i) m = std::max(m, std::fabs(got[i] - ref[i]));
    return m / scale;
}

}  // namespace

TEST(Welch, matches_scipy_csd_and_welch_on_the_fixture)
{
    const nlohmann::json fx = load_fixture();
    const std::vector<double> x = fx["x"], y = fx["y"];
    ASSERT_EQ(fx["cases"].size(), 2u);
    for (const auto& c : fx["cases"]) {
        WelchOptions o;
        o.fs = fx["fs"];
        o.nperseg = c["nperseg"];
        o.noverlap = c["noverlap"];
        o.nfft = c["nfft"];
        o.detrend_mean = c["detrend_mean"];
        const WelchResult r = welch_tfestimate(x, y, o);
        const std::vector<double> f = c["f"], pxx = c["Pxx"], pyy = c["Pyy"], re = c["Pxy_re"], im = c["Pxy_im"];
        ASSERT_EQ(r.f.size(), f.size());
        std::vector<double> gre, gim;
        for (const auto& v : r.Pxy) {
            gre.push_back(v.real());
            gim.push_back(v.imag());
        }
        EXPECT_LT(max_rel(r.f, f), 1e-14);
        EXPECT_LT(max_rel(r.Pxx, pxx), 1e-10) << "nfft " << o.nfft;
        EXPECT_LT(max_rel(r.Pyy, pyy), 1e-10);
        EXPECT_LT(max_rel(gre, re), 1e-10);
        EXPECT_LT(max_rel(gim, im), 1e-10);
        for (size_t i = 0; i < r.Txy.size(); ++i) {
            const std::complex<double> t = std::complex<double>(re[i], im[i]) / pxx[i];
            EXPECT_NEAR(std::abs(r.Txy[i] - t) / std::abs(t), 0.0, 1e-9);
        }
    }
}

TEST(Welch, h1_estimate_recovers_a_known_filter)
{
    // y = (0.2 + 0.3 z^-1)/(1 - 0.5 z^-1) x: the H1 estimate tends to H(e^{j w}) for a long record
    std::vector<double> x(200000), y(x.size());
    unsigned s = 12345u;
    for (auto& v : x) {
        s = s * 1103515245u + 12345u;
        v = ((s >> 8) & 0xffff) / 65536.0 - 0.5;
    }
    double yp = 0, xp = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        y[i] = 0.5 * yp + 0.2 * x[i] + 0.3 * xp;
        yp = y[i];
        xp = x[i];
    }
    WelchOptions o;
    o.fs = 1.0;
    o.nperseg = 1024;
    o.noverlap = 512;
    const WelchResult r = welch_tfestimate(x, y, o);
    for (size_t i = 1; i + 1 < r.f.size(); i += 37) {
        const std::complex<double> z = std::exp(std::complex<double>(0, -2 * M_PI * r.f[i]));
        const std::complex<double> h = (0.2 + 0.3 * z) / (1.0 - 0.5 * z);
        EXPECT_LT(std::abs(r.Txy[i] - h) / std::abs(h), 2e-2) << "f = " << r.f[i];
        EXPECT_GT(r.Cxy[i], 0.99);
    }
}

TEST(Welch, psd_is_the_auto_spectrum_of_tfestimate_and_keeps_parseval)
{
    // welch_psd(x) = Pxx of welch_tfestimate(x, .); with one rectangular segment its bins integrate to
    // the mean square (Parseval for the one-sided density).
    std::vector<double> x(3000), y(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        x[i] = std::sin(0.37 * double(i)) + 0.25 * std::cos(0.011 * double(i) * double(i) / 100.0);
        y[i] = 0.5 * x[i];
    }
    WelchOptions o;
    o.fs = 200.0;
    o.nperseg = 512;
    o.noverlap = 128;
    const WelchResult r = welch_tfestimate(x, y, o);
    const WelchPsd p = welch_psd(x, o);
    ASSERT_EQ(p.P.size(), r.Pxx.size());
    EXPECT_EQ(p.segments, r.segments);
    for (size_t i = 0; i < p.P.size(); ++i) EXPECT_NEAR(p.P[i], r.Pxx[i], 1e-12 * (1 + r.Pxx[i]));
    WelchOptions one;
    one.fs = 200.0;
    one.nperseg = int(x.size());
    one.noverlap = 0;
    one.nfft = 4096;
    one.window.assign(x.size(), 1.0);
    const WelchPsd q = welch_psd(x, one);
    double ms = 0, integral = 0;
    for (double v : x) ms += v * v / double(x.size());
    for (double v : q.P) integral += v * one.fs / one.nfft;
    EXPECT_NEAR(integral, ms, 1e-9 * ms);
    x[17] = NAN;
    EXPECT_THROW(welch_psd(x, o), std::invalid_argument);
}

TEST(Welch, matlab_segmentation_of_seed000_gives_eight_segments)
{
    // seed 000 Sec. 5.1: 8 Hamming segments, 15 % overlap, nfft = 160000, 120 s at 1 kHz
    const WelchOptions o = welch_matlab_segments(120000, 8, 0.15, 160000, 1000.0);
    EXPECT_EQ(o.nperseg, 17266);
    EXPECT_EQ(o.noverlap, 2590);
    EXPECT_EQ((120000 - o.noverlap) / (o.nperseg - o.noverlap), 8);
}

TEST(Welch, hamming_is_symmetric_with_matlab_end_values)
{
    const std::vector<double> w = hamming_symmetric(11);
    EXPECT_NEAR(w[0], 0.08, 1e-15);
    EXPECT_NEAR(w[5], 1.0, 1e-15);
    EXPECT_NEAR(w[10], 0.08, 1e-15);
    EXPECT_THROW(hamming_symmetric(0), std::invalid_argument);
}

TEST(Welch, bad_input_is_refused_with_the_option_named)
{
    std::vector<double> x(100, 1.0), y(100, 2.0);
    WelchOptions o;
    o.nperseg = 32;
    o.noverlap = 16;
    auto msg = [&](const std::vector<double>& a, const std::vector<double>& b, const WelchOptions& op) {
        try {
            welch_tfestimate(a, b, op);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(msg(x, std::vector<double>(99, 1.0), o).find("same length"), std::string::npos);
    std::vector<double> xn = x;
    xn[7] = NAN;
    EXPECT_NE(msg(xn, y, o).find("sample 7"), std::string::npos);
    WelchOptions b = o;
    b.nperseg = 200;
    EXPECT_NE(msg(x, y, b).find("nperseg"), std::string::npos);
    b = o;
    b.noverlap = 32;
    EXPECT_NE(msg(x, y, b).find("noverlap"), std::string::npos);
    b = o;
    b.nfft = 16;
    EXPECT_NE(msg(x, y, b).find("nfft"), std::string::npos);
    b = o;
    b.fs = 0;
    EXPECT_NE(msg(x, y, b).find("fs"), std::string::npos);
    b = o;
    b.window = {1.0, 2.0};
    EXPECT_NE(msg(x, y, b).find("window"), std::string::npos);
}
