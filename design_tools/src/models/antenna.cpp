// antenna.cpp - seed 000 antenna: nominal parameter sets, undamped poles/zeros, resonance peaks.
#include "fracdesign/models/antenna.hpp"
#include "fracdesign/golden.hpp"

#include <cmath>
#include <functional>

namespace fracdesign {

void AntennaLink::validate() const
{
    auto pos = [](double v, const char* name) {
        if (!std::isfinite(v) || v <= 0) throw std::invalid_argument(std::string("antenna: ") + name + " must be finite and > 0");
    };
    pos(L, "L");
    pos(rho, "rho");
    pos(E, "E");
    pos(I, "I");
}

AntennaDamping<double> haro_nominal_III() { return {5.4e-5, 1.0, 2.0e-2, 1.0}; }    // Table 5
AntennaDamping<double> haro_nominal_VI() { return {7.1e-5, 0.996, 5.5e-2, 0.594}; }  // Table 5

namespace {

// The first `count` roots of f on x > 0, where f has exactly one root in each interval
// (x0 + k pi, x0 + (k + 1) pi], k = 0, 1, ...: bisection on the sign change.
std::vector<double> roots_per_period(const std::function<double(double)>& f, int count, double x0)
{
    std::vector<double> r;
    for (int k = 0; k < count; ++k) {
        double lo = x0 + k * M_PI + 1e-9, hi = x0 + (k + 1) * M_PI;
        double flo = f(lo);
        for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
            const double mid = 0.5 * (lo + hi), fm = f(mid);
            if ((fm < 0) == (flo < 0)) {
                lo = mid;
                flo = fm;
            } else {
                hi = mid;
            }
        }
        r.push_back(0.5 * (lo + hi));
    }
    return r;
}

}  // namespace

std::vector<double> antenna_undamped_poles(const AntennaLink& link, int count)
{
    link.validate();
    // 1 + cos x cosh x = 0, scaled by 1/cosh x: cos x + sech x = 0; it is +-1 + sech(k pi) at x = k pi, so
    // exactly one root in each (k pi, (k + 1) pi]
    const auto x = roots_per_period([](double v) { return std::cos(v) + 1.0 / std::cosh(v); }, count, 0.0);
    std::vector<double> w;
    for (double xi : x) w.push_back(xi * xi / (link.L * link.L) * std::sqrt(link.EI() / link.rho));
    return w;
}

std::vector<double> antenna_undamped_zeros(const AntennaLink& link, int count)
{
    link.validate();
    // tan x = tanh x (the numerator sin x cosh x - cos x sinh x of (25), scaled by 1/cosh x), x > 0: the
    // function is +-1 at x = (k + 1/2) pi, so exactly one root in each ((k + 1/2) pi, (k + 3/2) pi]
    const auto x = roots_per_period([](double v) { return std::sin(v) - std::cos(v) * std::tanh(v); }, count, 0.5 * M_PI);
    std::vector<double> w;
    for (double xi : x) w.push_back(xi * xi / (link.L * link.L) * std::sqrt(link.EI() / link.rho));
    return w;
}

std::pair<double, double> antenna_peak(const AntennaLink& link, const AntennaDamping<double>& d, double w_lo,
                                       double w_hi)
{
    if (!(w_lo > 0 && w_hi > w_lo)) throw std::invalid_argument("antenna peak: need 0 < w_lo < w_hi");
    auto mag = [&](double w) { return std::abs(antenna_frf(link, d, w)); };
    const int n = 20000;
    int best = 0;
    double bm = -1;
    for (int i = 0; i <= n; ++i) {
        const double m = mag(w_lo + (w_hi - w_lo) * i / n);
        if (m > bm) {
            bm = m;
            best = i;
        }
    }
    // golden-section refinement on the bracket around the best grid point
    const double a = w_lo + (w_hi - w_lo) * std::max(0, best - 1) / n, b = w_lo + (w_hi - w_lo) * std::min(n, best + 1) / n;
    const GoldenResult m = golden_section_min([&](double w) { return -mag(w); }, a, b, 1e-12 * b, 200);
    const double wp = 0.5 * (m.a + m.b);
    return {wp, 20.0 * std::log10(mag(wp))};
}

}  // namespace fracdesign
