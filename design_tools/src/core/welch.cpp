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

WelchResult welch_tfestimate(const std::vector<double>& x, const std::vector<double>& y, const WelchOptions& opt)
{
    auto bad = [](const std::string& m) { throw std::invalid_argument("welch: " + m); };
    if (x.size() != y.size()) bad("x and y must have the same length");
    for (size_t i = 0; i < x.size(); ++i)
        if (!std::isfinite(x[i]) || !std::isfinite(y[i])) bad("sample " + std::to_string(i) + " is not finite");
    if (!std::isfinite(opt.fs) || opt.fs <= 0) bad("fs must be finite and > 0");
    const int L = opt.nperseg;
    if (L < 2) bad("nperseg must be >= 2");
    if (static_cast<size_t>(L) > x.size()) bad("nperseg exceeds the record length");
    if (opt.noverlap < 0 || opt.noverlap >= L) bad("noverlap must be in [0, nperseg)");
    const int nfft = opt.nfft == 0 ? L : opt.nfft;
    if (nfft < L) bad("nfft must be >= nperseg");
    const std::vector<double> w = opt.window.empty() ? hamming_symmetric(L) : opt.window;
    if (static_cast<int>(w.size()) != L) bad("window must have nperseg samples");
    double w2 = 0.0;
    for (double v : w) w2 += v * v;

    const int step = L - opt.noverlap;
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
        double mx = 0.0, my = 0.0;
        if (opt.detrend_mean) {
            for (int i = 0; i < L; ++i) {
                mx += x[off + static_cast<size_t>(i)];
                my += y[off + static_cast<size_t>(i)];
            }
            mx /= L;
            my /= L;
        }
        std::fill(xs.begin(), xs.end(), 0.0);
        std::fill(ys.begin(), ys.end(), 0.0);
        for (int i = 0; i < L; ++i) {
            xs[static_cast<size_t>(i)] = w[static_cast<size_t>(i)] * (x[off + static_cast<size_t>(i)] - mx);
            ys[static_cast<size_t>(i)] = w[static_cast<size_t>(i)] * (y[off + static_cast<size_t>(i)] - my);
        }
        fft.fwd(X, xs);
        fft.fwd(Y, ys);
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
        // one-sided density scaling: DC and (even nfft) Nyquist are not doubled
        const bool single = (i == 0) || (nfft % 2 == 0 && i == nfft / 2);
        const double c = (single ? 1.0 : 2.0) / (opt.fs * w2 * K);
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
