// collocated.cpp - seed 002 fractional collocated damping design (Theorem 5,
// design procedure of Section 4, robot of Section 5).
#include "fracdesign/design/collocated.hpp"
#include "fracdesign/golden.hpp"

#include <algorithm>
#include <vector>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace fracdesign::design {
namespace {

constexpr double kPi = 3.14159265358979323846;
using cplx = std::complex<double>;

cplx jpow(double w, double a) { return std::polar(std::pow(w, a), a * kPi / 2.0); }

cplx gm(double eps, double w)  // G_m (41)
{
    const cplx d = 1.0 + cplx(0.0, eps * w);
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
    // (49) with the approximation (48), else the exact (47) for which (1 + eps s)^2 G_m = 1; the
    // controller inverts the nominal inner loop, the plant brings its own.
    const double ec = d.nominal.eps;
    const cplx q = d.q_approx ? (1.0 + cplx(0.0, 2.0 * ec * w)) * gm(p.eps, w)
                              : (1.0 + cplx(0.0, ec * w)) * (1.0 + cplx(0.0, ec * w)) * gm(p.eps, w);
    return d.Kc * jpow(w, d.alpha) * q * collocated_P(p, w, damped);
}

cplx loop_fd_s(const FdDesign& d, const CollocatedPlant& p, cplx s, bool damped)
{
    const double ec = d.nominal.eps;
    const cplx gm_s = 1.0 / ((1.0 + p.eps * s) * (1.0 + p.eps * s));
    const cplx q = d.q_approx ? (1.0 + 2.0 * ec * s) * gm_s : (1.0 + ec * s) * (1.0 + ec * s) * gm_s;
    cplx P = 0.0;
    const double z1 = damped ? p.zeta1 : 0.0, z2 = damped ? p.zeta2 : 0.0;
    P += p.k1 / (s * s + 2.0 * z1 * p.a1 * s + p.a1 * p.a1);
    P += p.k2 / (s * s + 2.0 * z2 * p.a2 * s + p.a2 * p.a2);
    return d.Kc * std::pow(s, d.alpha) * q * P;
}

NyquistResult loop_fd_nyquist(const FdDesign& d, const CollocatedPlant& p, bool damped)
{
    const double z1 = damped ? p.zeta1 : 0.0, z2 = damped ? p.zeta2 : 0.0, ec = d.nominal.eps;
    auto bound = [&](double r) {
        const double qn = d.q_approx ? 1.0 + 2.0 * ec * r : (1.0 + ec * r) * (1.0 + ec * r);
        const double q = qn / (1.0 + p.eps * p.eps * r * r);
        const double d1 = r * r - 2.0 * z1 * p.a1 * r - p.a1 * p.a1, d2 = r * r - 2.0 * z2 * p.a2 * r - p.a2 * p.a2;
        if (!(d1 > 0.0 && d2 > 0.0)) return std::numeric_limits<double>::infinity();
        return d.Kc * std::pow(r, d.alpha) * q * (p.k1 / d1 + p.k2 / d2);
    };
    // the bound falls like r^(alpha - 2) at the end (alpha < 2); scan far beyond both corners
    const double r_end = 1e6 * std::max(p.a2, p.eps > 0.0 ? 1.0 / p.eps : 0.0);
    double w_hi = 2.0 * p.a2;
    for (double r = 2.0 * p.a2; r < r_end; r *= 1.05)
        if (!(bound(r) < 0.5)) w_hi = 1.05 * r;
    std::vector<double> poles;
    if (z1 == 0.0) poles.push_back(p.a1);
    if (z2 == 0.0) poles.push_back(p.a2);
    return nyquist_stability([&](cplx s) { return loop_fd_s(d, p, s, damped); }, 1e-6 * p.a1, w_hi, poles);
}

cplx loop_pi(double Kp, double Ki, const CollocatedPlant& p, double w, bool damped)
{
    const cplx s(0.0, w);
    return (Kp + Ki / s) * s * s * gm(p.eps, w) * collocated_P(p, w, damped);
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

std::pair<Crossover, Crossover> modal_crossovers(const std::function<cplx(double)>& L, const CollocatedPlant& p,
                                                 int theorem_case)
{
    if (theorem_case != 1 && theorem_case != 2) throw std::invalid_argument("theorem case must be 1 or 2");
    // 800 grid points per decade (as many as Tables 1-2 need to resolve the narrow band above a2)
    const double lo = 1e-3 * p.a1, hi = 1e4 * p.a2;
    const auto c = crossovers(L, lo, hi, static_cast<int>(800.0 * std::log10(hi / lo)));
    const Crossover* m1 = nullptr;
    const Crossover* m2 = nullptr;
    for (const auto& x : c) {
        if (theorem_case == 1) {
            // Table 1: mode 1 in (a1, z1), mode 2 the highest crossover above a2 (P < 0 there)
            if (!m1 && x.w > p.a1 && x.w < p.z1) m1 = &x;
            if (x.w > p.a2) m2 = &x;
        } else {
            // Theorem 2 / 5 case 2: the crossovers where P > 0, mode 1 in (0, a1), mode 2 in (z1, a2)
            if (x.w < p.a1) m1 = &x;
            if (x.w > p.z1 && x.w < p.a2) m2 = &x;
        }
    }
    if (!m1 || !m2)
        throw std::runtime_error(theorem_case == 1 ? "loop has no crossover in (a1, z1) or above a2"
                                                   : "loop has no crossover in (0, a1) or in (z1, a2)");
    return {*m1, *m2};
}

std::pair<double, double> crossover_range(const FdDesign& d, const CollocatedArm& arm, double m2_lo, double m2_hi,
                                          int points)
{
    if (!(std::isfinite(m2_lo) && m2_lo > 0.0 && std::isfinite(m2_hi) && m2_hi >= m2_lo && points >= 1))
        throw std::invalid_argument("crossover range needs 0 < m2_lo <= m2_hi and points >= 1");
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < points; ++i) {
        const double m2 = m2_lo + (m2_hi - m2_lo) * i / std::max(1, points - 1);
        const CollocatedPlant p = arm.plant(m2);
        // Theorem 1: one root of (7) in (a1, z1) (case 1); Theorem 2: one root in (0, a1) (case 2).
        const double w_lo = d.theorem_case == 1 ? p.a1 * 1.0001 : p.a1 * 1e-4;
        const double w_hi = d.theorem_case == 1 ? p.z1 * 0.9999 : p.a1 * 0.9999;
        const auto c = crossovers([&](double w) { return loop_fd(d, p, w, false); }, w_lo, w_hi, 400);
        if (c.size() != 1)
            throw std::runtime_error("eq. (7) has " + std::to_string(c.size()) + " roots in " +
                                     (d.theorem_case == 1 ? "(a1, z1)" : "(0, a1)") + " at m2 = " + std::to_string(m2) +
                                     " " + arm.mass_unit() + " (Theorem " + (d.theorem_case == 1 ? "1" : "2") +
                                     " predicts exactly one)");
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
    const cplx g2 = (p.g2_s2 * s * s + p.g2_0) / den;  // (39), damped denominator of (46)
    return F.at(w) * gm(p.eps, w) * g2 / (1.0 + L(w));  // (50)
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
    if (!(tol_db > 0.0)) throw std::invalid_argument("tol_db must be > 0");
    if (start && !(start->fn > 0.0 && start->fd > 0.0 && start->beta > 0.0 && start->beta <= beta_max))
        throw std::invalid_argument("prefilter start needs f_n > 0, f_d > 0, 0 < beta <= beta_max");
    PrefilterResult best;
    // The band is a knife edge in f_n: at the optimum the ripple of |H| touches +-tol at two
    // frequencies (a low-frequency dip and the peak near 5.75 rad/s), and changing f_n by 0.5 %
    // drops the band from 7.5 to 1.9 or 5.5 rad/s. Any search on the band itself (grid or local)
    // steps over that edge. So the search works on the minimax form: for given (f_d, beta),
    //   r(f_n, W) = max_{w <= W} | 20 log10 |H(j w)| |  is the max of a part falling and a part
    //   rising with f_n (dip and peak), so min over f_n is found by a scan + golden section, and
    //   B(f_d, beta) = the largest W with min_{f_n} r(f_n, W) <= tol (bisection in log W)
    // is the best band reachable at (f_d, beta), continuous in them. B is maximised globally:
    // a grid over (log f_d, beta), then Nelder-Mead from the 3 best grid points (and the
    // caller's start). H = F(j w) B_0(j w) with B_0 = G_m G_2/(1 + L) cached on the grid of
    // flat_band (1e-3 rad/s x 1.005^k), so one evaluation of r costs no loop evaluation.
    constexpr double kRatio = 1.005, kWTop = 100.0;
    std::vector<double> wg, lw, b2;  // w, log w, |B_0|^2
    const Prefilter unit{0.0, 0.0, 1.0};
    for (double w = 1e-3; w <= kWTop; w *= kRatio) {
        wg.push_back(w);
        lw.push_back(std::log(w));
        b2.push_back(std::norm(closed_loop_tip(L, unit, p, w, true)));
    }
    // |F(j w)|^2 = (1 + 2 a cos(pi beta/2) + a^2)/(1 + (f_d w)^2), a = f_n w^beta: real arithmetic;
    // the ripple in dB from the extreme |H|^2 (one log per evaluation).
    auto ripple = [&](double lfn, double lfd, double beta, double W) {
        ++best.evaluations;
        const double fd2 = std::exp(2.0 * lfd), c2 = 2.0 * std::cos(beta * kPi / 2.0);
        auto h2 = [&](double w, double l, double bb) {
            const double a = std::exp(lfn + beta * l);
            return (1.0 + a * (c2 + a)) / (1.0 + fd2 * w * w) * bb;
        };
        // the grid points below W and W itself, so that r is continuous in W
        double hi = h2(W, std::log(W), std::norm(closed_loop_tip(L, unit, p, W, true))), lo = hi;
        for (size_t i = 0; i < wg.size() && wg[i] < W; ++i) {
            const double v = h2(wg[i], lw[i], b2[i]);
            hi = std::max(hi, v);
            lo = std::min(lo, v);
        }
        return std::max(10.0 * std::log10(hi), -10.0 * std::log10(lo));
    };
    const double lfn_lo = std::log(1e-3), lfn_hi = std::log(1.0);
    // min over log f_n of r: a scan (25 points over [1e-3, 1], or 7 points of 0.05 around a
    // previous optimum `*lfn_best` when `warm`), then golden section in the best bracket.
    auto fn_min = [&](double lfd, double beta, double W, double* lfn_best, bool warm) {
        const int n_scan = warm ? 7 : 25;
        const double h = warm ? 0.05 : (lfn_hi - lfn_lo) / 24.0, x0 = warm ? *lfn_best - 3 * h : lfn_lo;
        int ib = 0;
        double fb = std::numeric_limits<double>::infinity();
        for (int i = 0; i < n_scan; ++i) {
            const double v = ripple(x0 + i * h, lfd, beta, W);
            if (v < fb) fb = v, ib = i;
        }
        double a = x0 + std::max(0, ib - 1) * h, b = x0 + std::min(n_scan - 1, ib + 1) * h;
        const GoldenResult m = golden_section_min([&](double x) { return ripple(x, lfd, beta, W); }, a, b, 1e-4, 1000);
        *lfn_best = m.fx <= fb ? m.x : x0 + ib * h;
        return std::min(m.fx, fb);
    };
    // B(f_d, beta): bisection in log W on [1, 20] rad/s (the -3 dB bandwidth is about 10) to 2e-4
    // relative; 0 if not even W = 1 is reachable. Also returns the f_n that reaches it.
    auto band_at = [&](double lfd, double beta, double* lfn_out) {
        if (!(beta > 0.0 && beta <= beta_max) || !(lfd > std::log(1e-6) && lfd < std::log(10.0))) return 0.0;
        double lo = 0.0, hi = std::log(20.0), lfn = 0.0;
        if (fn_min(lfd, beta, 1.0, &lfn, false) > tol_db) return 0.0;
        *lfn_out = lfn;
        bool first = true;
        while (hi - lo > 2e-4) {
            const double mid = 0.5 * (lo + hi);
            double l = *lfn_out;
            if (fn_min(lfd, beta, std::exp(mid), &l, !first) <= tol_db) {
                lo = mid;
                *lfn_out = l;
                first = false;
            } else {
                hi = mid;
            }
        }
        return std::exp(lo);
    };
    struct Point {
        double lfd, beta, lfn, band;
    };
    std::vector<Point> grid;
    constexpr int kFd = 9, kBeta = 10;
    const double sfd = std::log(300.0) / (kFd - 1), sb = beta_max / kBeta;
    for (int j = 0; j < kFd; ++j)
        for (int k = 1; k <= kBeta; ++k) {
            Point q{std::log(1e-3) + j * sfd, k * sb, 0.0, 0.0};
            q.band = band_at(q.lfd, q.beta, &q.lfn);
            grid.push_back(q);
        }
    std::sort(grid.begin(), grid.end(), [](const Point& a, const Point& b) { return a.band > b.band; });
    std::vector<Point> starts(grid.begin(), grid.begin() + std::min<size_t>(2, grid.size()));
    if (start) {
        Point q{std::log(start->fd), start->beta, 0.0, 0.0};
        q.band = band_at(q.lfd, q.beta, &q.lfn);
        starts.insert(starts.begin(), q);
    }
    // Nelder-Mead (maximising B) in (log f_d, beta) from each start; initial simplex half a grid step.
    Point bestp = starts.front();
    for (const Point& s0 : starts) {
        std::array<Point, 3> v{s0, s0, s0};
        v[1].lfd += 0.5 * sfd;
        v[2].beta += (s0.beta + 0.5 * sb <= beta_max ? 0.5 : -0.5) * sb;
        for (int i = 1; i < 3; ++i) v[i].band = band_at(v[i].lfd, v[i].beta, &v[i].lfn);
        auto mk = [&](double lfd, double beta) {
            Point q{lfd, beta, 0.0, 0.0};
            q.band = band_at(lfd, beta, &q.lfn);
            return q;
        };
        for (int it = 0; it < 30; ++it) {
            std::sort(v.begin(), v.end(), [](const Point& a, const Point& b) { return a.band > b.band; });
            if (std::max(std::fabs(v[1].lfd - v[0].lfd) + std::fabs(v[2].lfd - v[0].lfd),
                         std::fabs(v[1].beta - v[0].beta) + std::fabs(v[2].beta - v[0].beta)) < 1e-4)
                break;
            const double cf = 0.5 * (v[0].lfd + v[1].lfd), cb = 0.5 * (v[0].beta + v[1].beta);
            const Point r = mk(2 * cf - v[2].lfd, 2 * cb - v[2].beta);
            if (r.band > v[0].band) {
                const Point e = mk(3 * cf - 2 * v[2].lfd, 3 * cb - 2 * v[2].beta);
                v[2] = e.band > r.band ? e : r;
            } else if (r.band > v[1].band) {
                v[2] = r;
            } else {
                const Point c = mk(0.5 * (cf + v[2].lfd), 0.5 * (cb + v[2].beta));
                if (c.band > v[2].band) {
                    v[2] = c;
                } else {
                    for (int i = 1; i < 3; ++i) v[i] = mk(0.5 * (v[0].lfd + v[i].lfd), 0.5 * (v[0].beta + v[i].beta));
                }
            }
        }
        for (const Point& q : v)
            if (q.band > bestp.band) bestp = q;
    }
    best.F = Prefilter{std::exp(bestp.lfn), std::exp(bestp.lfd), bestp.beta};
    best.band = flat_band([&](double w) { return closed_loop_tip(L, best.F, p, w, true); }, tol_db);
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
              {"eps", d.nominal.eps}}},
            {"nominal", {{"m2", d.nominal.m2}, {"a1", d.nominal.a1}, {"z1", d.nominal.z1}, {"a2", d.nominal.a2}}}};
}

}  // namespace fracdesign::design
