// collocated.cpp - seed 002 fractional collocated damping design (Theorem 5,
// design procedure of Section 4, robot of Section 5).
#include "fracdesign/design/collocated.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace fracdesign::design {
namespace {

constexpr double kPi = 3.14159265358979323846;
using cplx = std::complex<double>;

cplx jpow(double w, double a) { return std::polar(std::pow(w, a), a * kPi / 2.0); }

cplx gm(double w)  // G_m (41)
{
    const cplx d = 1.0 + cplx(0.0, kFeliuEps * w);
    return 1.0 / (d * d);
}

// PM = 180 + angle(L) with the angle wrapped to (-360, 0] (notes 002 section 7).
double pm_deg(cplx L)
{
    double a = std::arg(L) * 180.0 / kPi;
    if (a > 0.0) a -= 360.0;
    return 180.0 + a;
}

// First w on a log grid in [lo, hi] (ratio step) where pred(w) holds, refined by bisection
// against the previous grid point; returns hi if none.
double first_exit(const std::function<bool(double)>& out, double lo, double hi, double ratio = 1.002)
{
    double prev = lo;
    if (out(lo)) return lo;
    for (double w = lo * ratio; w <= hi; w *= ratio) {
        if (out(w)) {
            double a = prev, b = w;
            while (b - a > 1e-12 * b) {
                const double m = std::sqrt(a * b);
                (out(m) ? b : a) = m;
            }
            return b;
        }
        prev = w;
    }
    return hi;
}

}  // namespace

double feliu_alpha(double phi0, int theorem_case)
{
    if (!(phi0 > 0.0 && phi0 <= kPi / 2.0)) throw std::invalid_argument("phi0 must lie in (0, pi/2] rad (Theorem 5)");
    if (theorem_case == 1) return 2.0 * phi0 / kPi;      // (6)
    if (theorem_case == 2) return 2.0 - 2.0 * phi0 / kPi;  // (9)
    throw std::invalid_argument("theorem case must be 1 or 2");
}

FdDesign design_fd(const CollocatedPlant& nominal, double phi0, double wc0, double alpha_override, bool q_approx)
{
    if (!(std::isfinite(wc0) && wc0 > 0.0)) throw std::invalid_argument("w_c0 must be finite and > 0");
    FdDesign d;
    d.nominal = nominal;
    d.phi0 = phi0;
    d.wc0 = wc0;
    d.q_approx = q_approx;
    if (wc0 > nominal.a1 && wc0 < nominal.z1)
        d.theorem_case = 1;
    else if (wc0 < nominal.a1)
        d.theorem_case = 2;
    else
        throw std::invalid_argument("w_c0 = " + std::to_string(wc0) + " rad/s is not covered by Theorem 5: it needs " +
                                    "a1 < w_c0 < z1 = (" + std::to_string(nominal.a1) + ", " +
                                    std::to_string(nominal.z1) + ") or w_c0 < a1");
    d.alpha_exact = feliu_alpha(phi0, d.theorem_case);
    if (alpha_override != 0.0) {
        if (!(std::isfinite(alpha_override) && alpha_override > 0.0 && alpha_override < 2.0))
            throw std::invalid_argument("alpha must lie in (0, 2)");
        d.alpha = alpha_override;
    } else {
        d.alpha = d.alpha_exact;
    }
    d.Kc = 1.0 / (std::pow(wc0, d.alpha) * std::abs(collocated_P(nominal, wc0, true)));  // (24), damped nominal
    return d;
}

cplx loop_fd(const FdDesign& d, const CollocatedPlant& p, double w, bool damped)
{
    // (49) with the approximation (48), else the exact (47) for which (1 + eps s)^2 G_m = 1.
    const cplx q = d.q_approx ? (1.0 + cplx(0.0, 2.0 * kFeliuEps * w)) * gm(w) : cplx(1.0);
    return d.Kc * jpow(w, d.alpha) * q * collocated_P(p, w, damped);
}

cplx loop_pi(double Kp, double Ki, const CollocatedPlant& p, double w, bool damped)
{
    const cplx s(0.0, w);
    return (Kp + Ki / s) * s * s * gm(w) * collocated_P(p, w, damped);
}

std::vector<Crossover> crossovers(const std::function<cplx(double)>& L, double w_lo, double w_hi, int grid)
{
    std::vector<Crossover> out;
    auto f = [&](double w) { return std::log(std::abs(L(w))); };
    double wp = w_lo, fp = f(w_lo);
    for (int i = 1; i < grid; ++i) {
        const double w = w_lo * std::pow(w_hi / w_lo, static_cast<double>(i) / (grid - 1));
        const double fw = f(w);
        if ((fp > 0.0) != (fw > 0.0)) {
            double a = wp, b = w;
            const bool a_pos = fp > 0.0;
            while (b - a > 1e-12 * b) {
                const double m = std::sqrt(a * b);
                ((f(m) > 0.0) == a_pos ? a : b) = m;
            }
            const double wc = std::sqrt(a * b);
            out.push_back({wc, pm_deg(L(wc))});
        }
        wp = w;
        fp = fw;
    }
    return out;
}

std::pair<Crossover, Crossover> modal_crossovers(const std::function<cplx(double)>& L, const CollocatedPlant& p)
{
    const auto c = crossovers(L, 0.1, 1e4);
    const Crossover* m1 = nullptr;
    const Crossover* m2 = nullptr;
    for (const auto& x : c) {
        if (!m1 && x.w > p.a1 && x.w < p.z1) m1 = &x;
        if (x.w > p.a2) m2 = &x;
    }
    if (!m1 || !m2) throw std::runtime_error("loop has no crossover in (a1, z1) or above a2");
    return {*m1, *m2};
}

std::pair<double, double> crossover_range(const FdDesign& d, double m2_lo, double m2_hi, int points)
{
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < points; ++i) {
        const double m2 = m2_lo + (m2_hi - m2_lo) * i / std::max(1, points - 1);
        const CollocatedPlant p = collocated_plant(m2);
        const auto c = crossovers([&](double w) { return loop_fd(d, p, w, false); }, p.a1 * 1.0001, p.z1 * 0.9999, 400);
        if (c.size() != 1)
            throw std::runtime_error("eq. (7) has " + std::to_string(c.size()) + " roots in (a1, z1) at m2 = " +
                                     std::to_string(m2) + " lb (Theorem 1 predicts exactly one)");
        lo = std::min(lo, c[0].w);
        hi = std::max(hi, c[0].w);
    }
    return {lo, hi};
}

cplx Prefilter::at(double w) const { return (1.0 + fn * jpow(w, beta)) / (1.0 + cplx(0.0, fd * w)); }

cplx closed_loop_tip(const std::function<cplx(double)>& L, const Prefilter& F, const CollocatedPlant& p, double w,
                     bool damped)
{
    const cplx s(0.0, w);
    const double z1 = damped ? p.zeta1 : 0.0, z2 = damped ? p.zeta2 : 0.0;
    const cplx den = (s * s + 2.0 * z1 * p.a1 * s + p.a1 * p.a1) * (s * s + 2.0 * z2 * p.a2 * s + p.a2 * p.a2);
    const cplx g2 = -(5.457 / p.m2_lb) * (s * s - 1273.3) / den;  // (39), damped denominator of (46)
    return F.at(w) * gm(w) * g2 / (1.0 + L(w));                   // (50)
}

double bandwidth_3db(const std::function<cplx(double)>& H)
{
    const double lim = std::pow(10.0, -3.0 / 20.0);
    return first_exit([&](double w) { return std::abs(H(w)) < lim; }, 1e-3, 1e3);
}

double flat_band(const std::function<cplx(double)>& H, double tol_db)
{
    return first_exit([&](double w) { return std::fabs(20.0 * std::log10(std::abs(H(w)))) > tol_db; }, 1e-3, 1e3,
                      1.005);
}

PrefilterResult optimise_prefilter(const std::function<cplx(double)>& L, const CollocatedPlant& p, double beta_max,
                                   double tol_db, const Prefilter* start)
{
    if (!(beta_max > 0.0)) throw std::invalid_argument("beta_max must be > 0");
    if (start && !(start->fn > 0.0 && start->fd > 0.0 && start->beta > 0.0 && start->beta <= beta_max))
        throw std::invalid_argument("prefilter start needs f_n > 0, f_d > 0, 0 < beta <= beta_max");
    PrefilterResult best;
    struct Point {
        double lfn, lfd, beta, v;
    };
    auto eval = [&](double lfn, double lfd, double beta) {
        ++best.evaluations;
        const Prefilter F{std::exp(lfn), std::exp(lfd), beta};
        return flat_band([&](double w) { return closed_loop_tip(L, F, p, w, true); }, tol_db);
    };
    // Starts: the caller's point (if any) and the 6 best points of a coarse grid
    // (f_n in [1e-3, 1], f_d in [1e-3, 0.3], beta in (0, beta_max]).
    std::vector<Point> grid;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 13; ++j)
            for (int k = 1; k <= 12; ++k) {
                const double lfn = std::log(1e-3) + i * std::log(1e3) / 15.0;
                const double lfd = std::log(1e-3) + j * std::log(300.0) / 12.0;
                const double beta = beta_max * k / 12.0;
                grid.push_back({lfn, lfd, beta, eval(lfn, lfd, beta)});
            }
    std::sort(grid.begin(), grid.end(), [](const Point& a, const Point& b) { return a.v > b.v; });
    grid.resize(6);
    if (start) {
        const double lfn = std::log(start->fn), lfd = std::log(start->fd);
        grid.insert(grid.begin(), Point{lfn, lfd, start->beta, eval(lfn, lfd, start->beta)});
    }
    // Pattern search over all 26 neighbour directions in (log f_n, log f_d, beta): the band is
    // discontinuous (it collapses when a ripple peak leaves the band) and its optimum sits on a
    // ridge between two active ripple constraints, so diagonal moves are needed. Move to the best
    // improving neighbour; halve the steps when none improves. The result is a local optimum.
    Point bestp = grid.front();
    for (Point c : grid) {
        double step = 0.2, bstep = 0.04;
        while (step > 1e-4) {
            Point next = c;
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int db = -1; db <= 1; ++db) {
                        const double beta = c.beta + db * bstep;
                        if ((dx == 0 && dy == 0 && db == 0) || !(beta > 0.0 && beta <= beta_max)) continue;
                        const double v = eval(c.lfn + dx * step, c.lfd + dy * step, beta);
                        if (v > next.v + 1e-9) next = {c.lfn + dx * step, c.lfd + dy * step, beta, v};
                    }
            if (next.v > c.v)
                c = next;
            else
                step *= 0.5, bstep *= 0.5;
        }
        if (c.v > bestp.v) bestp = c;
    }
    best.F = Prefilter{std::exp(bestp.lfn), std::exp(bestp.lfd), bestp.beta};
    best.band = bestp.v;
    return best;
}

nlohmann::json to_json(const FdDesign& d)
{
    return {{"schema", "frac.design.collocated"},
            {"version", 1},
            {"source", "seed 002 (Feliu-Batlle et al. 2020) Theorem 5, eqs. (6), (9), (24), (47)-(49)"},
            {"theorem_case", d.theorem_case},
            {"phi0", d.phi0},
            {"wc0", d.wc0},
            {"alpha_exact", d.alpha_exact},
            {"controller",
             {{"form", d.q_approx ? "C(s) = Kc (1 + 2 eps s) s^(alpha-2)" : "C(s) = Kc (1 + eps s)^2 s^(alpha-2)"},
              {"Kc", d.Kc},
              {"alpha", d.alpha},
              {"eps", kFeliuEps}}},
            {"nominal", {{"m2_lb", d.nominal.m2_lb}, {"a1", d.nominal.a1}, {"z1", d.nominal.z1}, {"a2", d.nominal.a2}}}};
}

}  // namespace fracdesign::design
