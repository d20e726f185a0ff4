// filters.cpp - Butterworth design, filtfilt, central differences (see filters.hpp).
#include "fracdesign/ident/filters.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace fracdesign {
namespace ident {

std::vector<Biquad> butter_lowpass(int order, double fc_hz, double fs_hz)
{
    if (order < 1 || order > 16) throw std::invalid_argument("butter_lowpass: order must be 1..16");
    if (!(fs_hz > 0.0) || !(fc_hz > 0.0) || !(fc_hz < 0.5 * fs_hz))
        throw std::invalid_argument("butter_lowpass: need 0 < fc < fs/2");
    // Pre-warped analog cut-off for the bilinear map s = 2 fs (z-1)/(z+1).
    const double wa = 2.0 * fs_hz * std::tan(M_PI * fc_hz / fs_hz);
    const double k2 = 2.0 * fs_hz;
    std::vector<Biquad> sos;
    // Analog poles wa*exp(j*pi*(2i+order+1)/(2 order)), i = 0..order-1; the
    // upper-half-plane ones pair with their conjugates into biquads.
    for (int i = 0; i < order / 2; ++i) {
        const std::complex<double> p = wa * std::exp(std::complex<double>(0.0, M_PI * (2.0 * i + order + 1) / (2.0 * order)));
        // Section wa^2/(s^2 - 2 Re(p) s + |p|^2) mapped by the bilinear transform.
        const double c1 = -2.0 * p.real(), c0 = std::norm(p);
        const double a0 = k2 * k2 + c1 * k2 + c0;
        Biquad q;
        q.b0 = c0 / a0;
        q.b1 = 2.0 * c0 / a0;
        q.b2 = c0 / a0;
        q.a1 = (2.0 * c0 - 2.0 * k2 * k2) / a0;
        q.a2 = (k2 * k2 - c1 * k2 + c0) / a0;
        sos.push_back(q);
    }
    if (order % 2) {  // the real pole -wa: wa/(s + wa)
        const double a0 = k2 + wa;
        sos.push_back({wa / a0, wa / a0, 0.0, (wa - k2) / a0, 0.0});
    }
    return sos;
}

namespace {

// One pass of the cascade over x (in place), each section's DF2T state set to
// the steady state for a constant input equal to its first input sample.
void cascade(const std::vector<Biquad>& sos, std::vector<double>& x)
{
    for (const Biquad& q : sos) {
        const double g = (q.b0 + q.b1 + q.b2) / (1.0 + q.a1 + q.a2);
        const double c = x.front();
        double s2 = (q.b2 - q.a2 * g) * c;
        double s1 = (q.b1 - q.a1 * g) * c + s2;
        for (double& v : x) {
            const double in = v;
            const double y = q.b0 * in + s1;
            s1 = q.b1 * in - q.a1 * y + s2;
            s2 = q.b2 * in - q.a2 * y;
            v = y;
        }
    }
}

}  // namespace

std::vector<double> filtfilt(const std::vector<Biquad>& sos, const std::vector<double>& x, std::size_t pad)
{
    const std::size_t n = x.size();
    if (n < 2) throw std::invalid_argument("filtfilt: need at least 2 samples");
    if (pad == 0) pad = 3 * (2 * sos.size() + 1);
    if (pad > n - 1) pad = n - 1;
    // Odd reflection about the end points keeps value and slope continuous.
    std::vector<double> y;
    y.reserve(n + 2 * pad);
    for (std::size_t i = pad; i >= 1; --i) y.push_back(2.0 * x[0] - x[i]);
    y.insert(y.end(), x.begin(), x.end());
    for (std::size_t i = 1; i <= pad; ++i) y.push_back(2.0 * x[n - 1] - x[n - 1 - i]);
    cascade(sos, y);
    std::reverse(y.begin(), y.end());
    cascade(sos, y);
    std::reverse(y.begin(), y.end());
    return std::vector<double>(y.begin() + long(pad), y.begin() + long(pad + n));
}

std::vector<double> central_difference(const std::vector<double>& x, double dt)
{
    const std::size_t n = x.size();
    if (n < 2) throw std::invalid_argument("central_difference: need at least 2 samples");
    std::vector<double> d(n);
    d[0] = (x[1] - x[0]) / dt;
    d[n - 1] = (x[n - 1] - x[n - 2]) / dt;
    for (std::size_t k = 1; k + 1 < n; ++k) d[k] = (x[k + 1] - x[k - 1]) / (2.0 * dt);
    return d;
}

}  // namespace ident
}  // namespace fracdesign
