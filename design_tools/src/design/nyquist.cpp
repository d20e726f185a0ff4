// nyquist.cpp - argument-principle stability test (fracdesign/design/nyquist.hpp).
#include "fracdesign/design/nyquist.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace fracdesign::design {
namespace {

using cplx = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

struct Walk {
    const std::function<cplx(cplx)>& L;
    double max_step;
    bool axis = false;  // track min |1 + L| (points on j w)
    double min_d = std::numeric_limits<double>::infinity(), w_min = 0.0;
    bool degenerate = false;

    cplx f(cplx s)
    {
        const cplx v = 1.0 + L(s);
        if (axis && std::abs(v) < min_d) min_d = std::abs(v), w_min = s.imag();
        if (!(std::abs(v) > 1e-300)) degenerate = true;
        return v;
    }
    // Change of arg f along path(t), t in [ta, tb]: accept a step when its increment is below
    // max_step and its two halves add up to it (no full turn hidden inside), else halve it.
    double seg(const std::function<cplx(double)>& path, double ta, cplx fa, double tb, cplx fb, int depth)
    {
        const double d = std::arg(fb / fa);
        const double tm = 0.5 * (ta + tb);
        if (depth > 55 || tb - ta <= 1e-13 * std::max(1.0, std::fabs(tm))) {
            if (std::fabs(d) > max_step) degenerate = true;  // 1 + L ~ 0 within a vanishing step
            return d;
        }
        const cplx fm = f(path(tm));
        const double d1 = std::arg(fm / fa), d2 = std::arg(fb / fm);
        if (std::fabs(d) <= max_step && std::fabs(d1 + d2 - d) < 1e-9) return d;
        return seg(path, ta, fa, tm, fm, depth + 1) + seg(path, tm, fm, tb, fb, depth + 1);
    }
    double along(const std::function<cplx(double)>& path, double t0, double t1, int n)
    {
        double total = 0.0;
        double ta = t0;
        cplx fa = f(path(t0));
        for (int i = 1; i <= n; ++i) {
            const double tb = t0 + (t1 - t0) * i / n;
            const cplx fb = f(path(tb));
            total += seg(path, ta, fa, tb, fb, 0);
            ta = tb;
            fa = fb;
        }
        return total;
    }
};

}  // namespace

NyquistResult nyquist_stability(const std::function<cplx(cplx)>& L, double w_lo, double w_hi,
                                const std::vector<double>& axis_poles, double pole_radius, double max_step)
{
    if (!(std::isfinite(w_lo) && std::isfinite(w_hi) && w_lo > 0.0 && w_hi > w_lo))
        throw std::invalid_argument("nyquist: needs 0 < w_lo < w_hi");
    if (!(pole_radius > 0.0 && pole_radius < 0.1) || !(max_step > 0.0 && max_step < 1.0))
        throw std::invalid_argument("nyquist: needs 0 < pole_radius < 0.1 and 0 < max_step < 1");
    std::vector<double> poles = axis_poles;
    std::sort(poles.begin(), poles.end());
    for (double p : poles)
        if (!(p > w_lo && p < w_hi)) throw std::invalid_argument("nyquist: axis poles must lie in (w_lo, w_hi)");
    Walk walk{L, max_step};
    // D_0: half circle s = w_lo e^{j theta}, theta from -pi/2 to pi/2
    const double d0 = walk.along([&](double th) { return std::polar(w_lo, th); }, -kPi / 2, kPi / 2, 64);
    // D_axis and D_poles: j w in log w from w_lo to w_hi, skirting j w_p on s = j w_p + r e^{j theta}
    double d_axis = 0.0, d_poles = 0.0, from = w_lo;
    const int per_decade = 200;
    auto axis_piece = [&](double a, double b) {
        walk.axis = true;
        const int n = std::max(4, static_cast<int>(per_decade * std::log10(b / a)));
        d_axis += walk.along([](double t) { return cplx(0.0, std::exp(t)); }, std::log(a), std::log(b), n);
        walk.axis = false;
    };
    for (double p : poles) {
        const double r = pole_radius * p;
        axis_piece(from, p - r);
        d_poles += walk.along([&](double th) { return cplx(0.0, p) + std::polar(r, th); }, -kPi / 2, kPi / 2, 64);
        from = p + r;
    }
    axis_piece(from, w_hi);
    const double d_tail = -std::arg(1.0 + L(cplx(0.0, w_hi)));
    const double n_real = (2.0 * (d_axis + d_poles + d_tail) + d0) / (2.0 * kPi);
    NyquistResult r;
    r.encirclements = static_cast<int>(std::lround(n_real));
    r.residual = std::fabs(n_real - r.encirclements);
    r.min_distance = walk.min_d;
    r.w_min = walk.w_min;
    r.degenerate = walk.degenerate;
    r.stable = !r.degenerate && r.encirclements == 0;
    std::ostringstream os;
    os.precision(6);
    if (r.degenerate)
        os << "1 + L vanishes on the contour (closed-loop pole on the imaginary axis near " << r.w_min << " rad/s)";
    else
        os << (r.encirclements == 0 ? "no encirclement" : std::to_string(-r.encirclements) + " clockwise encirclement(s)")
           << " of -1 (" << (r.encirclements == 0 ? "closed loop stable" : "closed loop unstable")
           << "), min |1 + L| = " << r.min_distance << " at " << r.w_min << " rad/s";
    r.detail = os.str();
    return r;
}

}  // namespace fracdesign::design
