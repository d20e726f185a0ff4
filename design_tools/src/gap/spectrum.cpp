// spectrum.cpp - frequency bands and spectra of the diagnosis's residuals,
// all from the one estimator welch_psd (core/welch.cpp; see stages.hpp,
// docs/gap.md).
#include <algorithm>
#include <cmath>

#include "fracdesign/welch.hpp"
#include "stages.hpp"

namespace fracdesign {
namespace gap {

std::vector<std::pair<double, double>> band_edges(double Ts)
{
    const double nyq = 0.5 / Ts;
    std::vector<std::pair<double, double>> b;
    double lo = 0.0, hi = 0.1;
    while (lo < nyq) {
        b.push_back({lo, std::min(hi, nyq)});
        lo = hi;
        hi *= 10.0;
    }
    return b;
}

// Power of two >= n: records are zero-padded before the FFT (a prime length
// would fall back to an O(n^2) transform; padding keeps Parseval's total).
Eigen::Index fft_length(Eigen::Index n)
{
    Eigen::Index p = 1;
    while (p < n) p *= 2;
    return p;
}

// One-sided periodogram of x at fs = 1 (bins k / nfft, k = 0..nfft/2,
// nfft = fft_length(x.size())): the project's spectrum estimator welch_psd
// with one rectangular segment of the whole record, zero-padded; density
// P_k = s_k |X_k|^2 / n with s_k = 2 (1 at DC and Nyquist), n = x.size().
std::vector<double> periodogram(const Eigen::VectorXd& x)
{
    WelchOptions o;
    o.fs = 1.0;
    o.nperseg = int(x.size());
    o.noverlap = 0;
    o.nfft = int(fft_length(x.size()));
    o.window.assign(size_t(x.size()), 1.0);
    return welch_psd(std::vector<double>(x.data(), x.data() + x.size()), o).P;
}

// Energy of each column of x in each band: P_k n / N is the energy of bin k
// and its mirror N - k (Parseval: the bins add up to sum |x|^2); a column
// that is not finite (a diverged replay) has NaN energy in every band.
Eigen::MatrixXd band_energy(const Eigen::MatrixXd& x, double Ts, const std::vector<std::pair<double, double>>& bands)
{
    const Eigen::Index N = fft_length(x.rows());
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(Eigen::Index(bands.size()), x.cols());
    for (Eigen::Index c = 0; c < x.cols(); ++c) {
        if (!x.col(c).allFinite()) {
            E.col(c).setConstant(kNaN);
            continue;
        }
        const std::vector<double> P = periodogram(x.col(c));
        for (size_t k = 0; k < P.size(); ++k) {
            const double f = double(k) / (double(N) * Ts);
            for (size_t b = 0; b < bands.size(); ++b)
                if (f >= bands[b].first && (f < bands[b].second || b + 1 == bands.size())) {
                    E(Eigen::Index(b), c) += P[k] * double(x.rows()) / double(N);
                    break;
                }
        }
    }
    return E;
}

// Per band, per output: sqrt(band residual energy / n) / scale, so that the
// squares over the bands add up to nrmse^2.
std::vector<std::vector<double>> band_nrmse(const Eigen::MatrixXd& y, const Eigen::MatrixXd& yhat, double Ts,
                                            const std::vector<double>& scale)
{
    const auto bands = band_edges(Ts);
    const Eigen::MatrixXd E = band_energy(y - yhat, Ts, bands);
    std::vector<std::vector<double>> out(bands.size());
    for (size_t b = 0; b < bands.size(); ++b)
        for (Eigen::Index c = 0; c < y.cols(); ++c) {
            const double den = double(y.rows()) * scale[size_t(c)] * scale[size_t(c)];
            out[b].push_back(den > 0 ? std::sqrt(E(Eigen::Index(b), c) / den) : kNaN);
        }
    return out;
}

// Smoothed periodogram (5-bin moving average) of one signal.
std::vector<double> smoothed_spectrum(const Eigen::VectorXd& x)
{
    const std::vector<double> P = periodogram(x);
    const size_t H = P.size();
    std::vector<double> S(H, 0.0);
    for (size_t k = 0; k < H; ++k) {
        int cnt = 0;
        for (long j = long(k) - 2; j <= long(k) + 2; ++j)
            if (j >= 0 && j < long(H)) {
                S[k] += P[size_t(j)];
                ++cnt;
            }
        S[k] /= cnt;
    }
    return S;
}

}  // namespace gap
}  // namespace fracdesign
