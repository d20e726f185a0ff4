// welch.cpp - Welch cross-spectral FRF estimator (see fracdesign/welch.hpp).
#include "fracdesign/welch.hpp"

#include <unsupported/Eigen/FFT>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fracdesign {

std::vector<double> hamming_symmetric(int n)
{
    if (n < 1) throw std::invalid_argument("welch: window length must be >= 1");
    std::vector<double> w(static_cast<size_t>(n), 1.0);
    if (n == 1) return w;
    for (int i = 0; i < n; ++i) w[static_cast<size_t>(i)] = 0.54 - 0.46 * std::cos(2.0 * M_PI * i / (n - 1));
    return w;
}

WelchOptions welch_matlab_segments(std::size_t M, int nsegments, double overlap, int nfft, double fs)
{
    if (nsegments < 1) throw std::invalid_argument("welch: nsegments must be >= 1");
    if (!(overlap >= 0 && overlap < 1)) throw std::invalid_argument("welch: overlap must be in [0, 1)");
    WelchOptions o;
    o.fs = fs;
    o.nperseg = static_cast<int>(std::floor(static_cast<double>(M) / (nsegments - (nsegments - 1) * overlap)));
    o.noverlap = static_cast<int>(std::lround(overlap * o.nperseg));
    o.nfft = nfft;
    return o;
}

namespace {

// Validates the options against a record of M samples and returns the window.
std::vector<double> checked_window(size_t M, const WelchOptions& opt)
{
    auto bad = [](const std::string& m) { throw std::invalid_argument("welch: " + m); };
    if (!std::isfinite(opt.fs) || opt.fs <= 0) bad("fs must be finite and > 0");
    const int L = opt.nperseg;
    if (L < 2) bad("nperseg must be >= 2");
    if (static_cast<size_t>(L) > M) bad("nperseg exceeds the record length");
    if (opt.noverlap < 0 || opt.noverlap >= L) bad("noverlap must be in [0, nperseg)");
    const int nfft = opt.nfft == 0 ? L : opt.nfft;
    if (nfft < L) bad("nfft must be >= nperseg");
    std::vector<double> w = opt.window.empty() ? hamming_symmetric(L) : opt.window;
    if (static_cast<int>(w.size()) != L) bad("window must have nperseg samples");
    return w;
}

void check_finite(const std::vector<double>& x)
{
    for (size_t i = 0; i < x.size(); ++i)
        if (!std::isfinite(x[i])) throw std::invalid_argument("welch: sample " + std::to_string(i) + " is not finite");
}

// Segment k of x, detrended if asked, windowed and zero-padded to nfft, transformed into X.
void segment_fft(Eigen::FFT<double>& fft, const std::vector<double>& x, size_t off, const std::vector<double>& w,
                 bool detrend, std::vector<double>& buf, std::vector<std::complex<double>>& X)
{
    const size_t L = w.size();
    double mx = 0.0;
    if (detrend) {
        for (size_t i = 0; i < L; ++i) mx += x[off + i];
        mx /= double(L);
    }
    std::fill(buf.begin(), buf.end(), 0.0);
    for (size_t i = 0; i < L; ++i) buf[i] = w[i] * (x[off + i] - mx);
    fft.fwd(X, buf);
}

// One-sided density scaling of bin i: DC and (even nfft) Nyquist are not doubled.
double density_scale(int i, int nfft, double fs, double w2, int K)
{
    const bool single = (i == 0) || (nfft % 2 == 0 && i == nfft / 2);
    return (single ? 1.0 : 2.0) / (fs * w2 * K);
}

}  // namespace

WelchPsd welch_psd(const std::vector<double>& x, const WelchOptions& opt)
{
    check_finite(x);
    const std::vector<double> w = checked_window(x.size(), opt);
    double w2 = 0.0;
    for (double v : w) w2 += v * v;
    const int L = opt.nperseg, nfft = opt.nfft == 0 ? L : opt.nfft, step = L - opt.noverlap;
    const int K = static_cast<int>((x.size() - static_cast<size_t>(opt.noverlap)) / static_cast<size_t>(step));
    const int nb = nfft / 2 + 1;
    WelchPsd r;
    r.segments = K;
    r.P.assign(static_cast<size_t>(nb), 0.0);
    Eigen::FFT<double> fft;
    std::vector<double> buf(static_cast<size_t>(nfft));
    std::vector<std::complex<double>> X;
    for (int k = 0; k < K; ++k) {
        segment_fft(fft, x, static_cast<size_t>(k) * static_cast<size_t>(step), w, opt.detrend_mean, buf, X);
        for (int i = 0; i < nb; ++i) r.P[static_cast<size_t>(i)] += std::norm(X[static_cast<size_t>(i)]);
    }
    r.f.resize(static_cast<size_t>(nb));
    for (int i = 0; i < nb; ++i) {
        r.P[static_cast<size_t>(i)] *= density_scale(i, nfft, opt.fs, w2, K);
        r.f[static_cast<size_t>(i)] = i * opt.fs / nfft;
    }
    return r;
}

WelchResult welch_tfestimate(const std::vector<double>& x, const std::vector<double>& y, const WelchOptions& opt)
{
    if (x.size() != y.size()) throw std::invalid_argument("welch: x and y must have the same length");
    for (size_t i = 0; i < x.size(); ++i)
        if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
            throw std::invalid_argument("welch: sample " + std::to_string(i) + " is not finite");
    const std::vector<double> w = checked_window(x.size(), opt);
    double w2 = 0.0;
    for (double v : w) w2 += v * v;
    const int L = opt.nperseg, nfft = opt.nfft == 0 ? L : opt.nfft, step = L - opt.noverlap;
    const int K = static_cast<int>((x.size() - static_cast<size_t>(opt.noverlap)) / static_cast<size_t>(step));
    const int nb = nfft / 2 + 1;
    WelchResult r;
    r.segments = K;
    r.Pxx.assign(static_cast<size_t>(nb), 0.0);
    r.Pyy.assign(static_cast<size_t>(nb), 0.0);
    r.Pxy.assign(static_cast<size_t>(nb), 0.0);
    Eigen::FFT<double> fft;
    std::vector<double> xs(static_cast<size_t>(nfft)), ys(static_cast<size_t>(nfft));
    std::vector<std::complex<double>> X, Y;
    for (int k = 0; k < K; ++k) {
        const size_t off = static_cast<size_t>(k) * static_cast<size_t>(step);
        segment_fft(fft, x, off, w, opt.detrend_mean, xs, X);
        segment_fft(fft, y, off, w, opt.detrend_mean, ys, Y);
        for (int i = 0; i < nb; ++i) {
            const std::complex<double> a = X[static_cast<size_t>(i)], b = Y[static_cast<size_t>(i)];
            r.Pxx[static_cast<size_t>(i)] += std::norm(a);
            r.Pyy[static_cast<size_t>(i)] += std::norm(b);
            r.Pxy[static_cast<size_t>(i)] += std::conj(a) * b;
        }
    }
    r.f.resize(static_cast<size_t>(nb));
    r.Txy.resize(static_cast<size_t>(nb));
    r.Cxy.resize(static_cast<size_t>(nb));
    for (int i = 0; i < nb; ++i) {
        const double c = density_scale(i, nfft, opt.fs, w2, K);
        const size_t u = static_cast<size_t>(i);
        r.Pxx[u] *= c;
        r.Pyy[u] *= c;
        r.Pxy[u] *= c;
        r.f[u] = i * opt.fs / nfft;
        r.Txy[u] = r.Pxy[u] / r.Pxx[u];
        r.Cxy[u] = std::norm(r.Pxy[u]) / (r.Pxx[u] * r.Pyy[u]);
    }
    return r;
}

}  // namespace fracdesign
