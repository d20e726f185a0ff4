// fopi_fopd.cpp - seed 001 FO-PI^alpha / FO-PD^mu tuning and feasibility.
#include "fracdesign/design/fopi_fopd.hpp"
#include "fracdesign/design/nyquist.hpp"
#include "fracdesign/golden.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <boost/math/tools/toms748_solve.hpp>
#include <nlohmann/json.hpp>

namespace fracdesign::design {
namespace {

constexpr double kPi = 3.14159265358979323846;

// (j w)^a for w > 0: w^a e^{j a pi/2} (principal branch).
std::complex<double> jpow(double w, double a) { return std::polar(std::pow(w, a), a * kPi / 2.0); }

std::string fmt(double v)
{
    std::ostringstream os;
    os.precision(10);
    os << v;
    return os.str();
}

void require(bool ok, const std::string& what)
{
    if (!ok) throw std::invalid_argument(what);
}

FoDesign design_at(FoKind kind, const GharabPlant& p, FoSpec s, double wc)
{
    s.wc = wc;
    return tune_fo(kind, p, s);
}

// Closed-loop stability of the real loop L = C^(s) K e^{-tau s}/(1 + T s^lambda) (the PD's
// characteristic equation (40) is 1 + G C^ = 0) by the argument principle (design/nyquist.hpp).
// On |s| = r, Re s >= 0: |e^{-tau s}| <= 1, |C^| <= |Kp| + |Kx| r^q (q = -alpha or mu) and
// |1 + T s^lambda| >= T r^lambda - 1, so |L| <= |K| (|Kp| + |Kx| r^q)/(T r^lambda - 1), which
// decreases in r once T r^lambda > 1 when q < lambda; w_hi is where this bound is below 1/2.
// The plant has no poles in Re s >= 0 for lambda < 2 (they sit at |arg s| = pi/lambda); for
// lambda = 2 the poles +-j T^(-1/2) are skirted. The origin is skirted at T^(-1/lambda) 1e-6.
FeasibilityTest nyquist_test(const FoDesign& d)
{
    const GharabPlant& p = d.plant;
    const bool pi = d.kind == FoKind::PI;
    const double q = pi ? -d.spec.order : d.spec.order, kx = pi ? d.Ki : d.Kd;
    FeasibilityTest t{"nyquist", false, 0.0, 0.0, ""};
    if (q >= p.lambda) {
        t.detail = "mu = " + fmt(q) + " >= lambda: |L(j w)| does not vanish at high frequency, no argument test";
        return t;
    }
    auto bound = [&](double r) { return std::fabs(p.K) * (std::fabs(d.Kp) + std::fabs(kx) * std::pow(r, q)) /
                                        (p.T * std::pow(r, p.lambda) - 1.0); };
    // w_hi is searched up to 1e4 in normalised frequency (w T^(1/lambda)); a loop whose bound falls
    // slower (mu just below lambda) is left undecided, which counts as a failed test.
    const double w_cap = 1e4 / d.Tl;
    double w_hi = std::pow(2.0 / p.T, 1.0 / p.lambda);
    while (w_hi < w_cap && !(bound(w_hi) < 0.5)) w_hi *= 1.2;
    if (!(bound(w_hi) < 0.5)) {
        t.detail = "|L| on Re s >= 0 is not provably below 1/2 up to w = 1e4/T^(1/lambda) = " + fmt(w_cap) +
                   " rad/s (mu close to lambda?): stability not decided";
        return t;
    }
    const double w_lo = 1e-6 / d.Tl;
    std::vector<double> poles;
    if (p.lambda == 2.0) poles.push_back(1.0 / std::sqrt(p.T));
    const auto L = [&](std::complex<double> s) {
        const std::complex<double> c = pi ? d.Kp + d.Ki * std::pow(s, -d.spec.order) : d.Kp + d.Kd * std::pow(s, d.spec.order);
        return c * p.K * std::exp(-p.tau * s) / (1.0 + p.T * std::pow(s, p.lambda));
    };
    const NyquistResult n = nyquist_stability(L, w_lo, w_hi, poles);
    t.pass = n.stable;
    t.value = n.stable ? n.min_distance : -n.min_distance;
    t.detail = "argument principle on C G with the delay, w in [" + fmt(w_lo) + ", " + fmt(w_hi) + "] rad/s: " + n.detail;
    return t;
}

}  // namespace

void GharabPlant::validate() const
{
    require(std::isfinite(K) && K != 0.0, "plant K must be finite and non-zero");
    require(std::isfinite(T) && T > 0.0, "plant T must be finite and > 0");
    require(std::isfinite(lambda) && lambda > 1.0 && lambda <= 2.0, "plant lambda must lie in (1, 2]");
    require(std::isfinite(tau) && tau >= 0.0, "plant tau must be finite and >= 0");
}

std::complex<double> GharabPlant::freq(double w) const
{
    return K * std::polar(1.0, -w * tau) / (1.0 + T * jpow(w, lambda));
}

double lf_phimn_bound(double wcn, double lambda) { return kPi - std::arg(1.0 + jpow(wcn, lambda)); }

double rhfc_max_slope(FoKind kind, double wcn, double lambda, double order, double Kpn, double Kx)
{
    // slope(w) = d ln m / d ln w = Re(s C_n'(s)/C_n(s)) - Re(lambda s^lambda/(1 + s^lambda)), s = j w:
    // with s C' = -alpha K_in s^-alpha (PI) or mu K_dn s^mu (PD); analytic, so no finite differences.
    auto slope = [&](double lw) {
        const double w = std::exp(lw);
        const std::complex<double> q = kind == FoKind::PI ? Kx * jpow(w, -order) : Kx * jpow(w, order);
        const std::complex<double> sl = jpow(w, lambda);
        const double v = (kind == FoKind::PI ? -order : order) * (q / (Kpn + q)).real() - (lambda * sl / (1.0 + sl)).real();
        return std::isnan(v) ? std::numeric_limits<double>::infinity() : v;  // |C| = 0 or lambda = 2 at w = 1
    };
    // Bracket every local maximum on a log grid (400 per decade, 20000 per decade on [0.8, 1.25] where
    // the plant resonance sits, w_peak = (-cos(lambda pi/2))^(1/lambda), notes/001 section 3.4), then
    // refine each by golden section to 1e-12 in ln w.
    const double l0 = std::log(wcn), l1 = std::log(std::max(1000.0 * wcn, 1000.0));
    std::vector<double> grid{l0};
    const double r0 = std::log(0.8), r1 = std::log(1.25);
    while (grid.back() < l1) {
        const double l = grid.back();
        const double h = (l >= r0 && l < r1 ? std::log(10.0) / 20000.0 : std::log(10.0) / 400.0);
        grid.push_back(std::min(l1, l + h));
    }
    std::vector<double> f(grid.size());
    for (size_t i = 0; i < grid.size(); ++i) f[i] = slope(grid[i]);
    double best = std::max(f.front(), f.back());
    for (size_t i = 1; i + 1 < grid.size(); ++i) {
        if (!(f[i] >= f[i - 1] && f[i] >= f[i + 1])) continue;
        best = std::max(best, f[i]);
        if (std::isinf(f[i])) continue;
        const GoldenResult g = golden_section_min([&](double l) { return -slope(l); }, grid[i - 1], grid[i + 1], 1e-12, 200);
        best = std::max(best, -g.fx);
    }
    return best;
}

FoDesign tune_fo(FoKind kind, const GharabPlant& plant, const FoSpec& spec)
{
    plant.validate();
    require(std::isfinite(spec.wc) && spec.wc > 0.0, "crossover w_c must be finite and > 0");
    require(std::isfinite(spec.phim) && spec.phim > -kPi && spec.phim < kPi, "phase margin must lie in (-pi, pi) rad");
    if (kind == FoKind::PI)
        require(std::isfinite(spec.order) && spec.order > 0.0 && spec.order <= 1.0,
                "PI order alpha must lie in (0, 1] (seed 001 eq. (5))");
    else
        require(std::isfinite(spec.order) && spec.order > 0.0 && spec.order < 2.0,
                "PD order mu must lie in (0, 2) (seed 001 eq. (29))");

    FoDesign d;
    d.kind = kind;
    d.plant = plant;
    d.spec = spec;
    const double lam = plant.lambda, a = spec.order;
    // Normalisation, eq. (4) and (10); erratum E1: tau_n = tau / T^(1/lambda).
    d.Tl = std::pow(plant.T, 1.0 / lam);
    d.wcn = spec.wc * d.Tl;
    d.taun = plant.tau / d.Tl;
    d.phimn = spec.phim + d.taun * d.wcn;
    const double wl = std::pow(d.wcn, lam), sa = std::sin(a * kPi / 2.0);

    double kx = 0.0;
    if (kind == FoKind::PI) {
        // eq. (15) and (16)
        d.Kin = std::pow(d.wcn, a) / sa * (wl * std::sin(d.phimn + lam * kPi / 2.0) + std::sin(d.phimn));
        d.Kpn = -1.0 / sa * (wl * std::sin(d.phimn + (lam + a) * kPi / 2.0) + std::sin(d.phimn + a * kPi / 2.0));
        // eq. (14): C(s) = C_n(s Tl) / K
        d.Kp = d.Kpn / plant.K;
        d.Ki = d.Kin / (plant.K * std::pow(d.Tl, a));
        kx = d.Kin;
    } else {
        // eq. (31)-(34) with erratum E3: Z from the delay-free G_n* and phi_mn,
        // Z = -e^{j phi_mn} (1 + (j w_cn)^lambda); (32) uses K_dn (printed K_d).
        const std::complex<double> Z = -std::polar(1.0, d.phimn) * (1.0 + jpow(d.wcn, lam));
        d.Kdn = Z.imag() / (std::pow(d.wcn, a) * sa);
        d.Kpn = Z.real() - d.Kdn * std::pow(d.wcn, a) * std::cos(a * kPi / 2.0);
        d.Kp = d.Kpn / plant.K;
        d.Kd = d.Kdn * std::pow(d.Tl, a) / plant.K;
        d.delta = 1.0 / plant.K;  // Section 4.2: positive feedback delta = 1/K, eq. (37)
        kx = d.Kdn;
    }

    // eq. (17): tau_n < tau_n,max = phi_mn / w_cn, i.e. phi_m > 0. Whether the delayed loop is
    // stable is not decided here (a phi_mn beyond pi only means the delay turns the phase further):
    // the "nyquist" test below decides it on the loop with the delay.
    FeasibilityTest delay{"delay_limit", spec.phim > 0.0, d.taun, d.phimn / d.wcn, ""};
    delay.detail = "eq. (17): tau_n = " + fmt(d.taun) + (spec.phim > 0.0 ? " < " : " >= ") +
                   "tau_n,max = phi_mn/w_cn = " + fmt(d.phimn / d.wcn) + " (needs phi_m > 0)";
    d.tests.push_back(delay);

    if (kind == FoKind::PI) {
        const double bound = lf_phimn_bound(d.wcn, lam);
        // K_in > 0 <=> sin(phi_mn + psi) > 0; with phi_mn in its principal range this
        // is the exact interval -psi < phi_mn < pi - psi (notes/001 section 3.2).
        const double psi = kPi - bound;
        FeasibilityTest lf{"low_frequency", d.phimn > -psi && d.phimn < bound, d.Kin, 0.0, ""};
        lf.detail = "eq. (18): K_in = " + fmt(d.Kin) + (lf.pass ? " > 0" : " <= 0") + "; exact boundary phi_mn = " +
                    fmt(d.phimn) + (d.phimn < bound ? " < " : " >= ") + "pi - arg(1 + (j w_cn)^lambda) = " + fmt(bound);
        d.tests.push_back(lf);
    }

    const double slope = rhfc_max_slope(kind, d.wcn, lam, a, d.Kpn, kx);
    FeasibilityTest rh{"rhfc", slope < 0.0, slope, 0.0, ""};
    rh.detail = std::string("eq. ") + (kind == FoKind::PI ? "(22)" : "(35)") + ": |C_n G_n*| beyond w_cn " +
                (rh.pass ? "strictly decreasing" : "not strictly decreasing") + " (largest d ln|L|/d ln w " +
                fmt(slope) + ")";
    d.tests.push_back(rh);

    if (kind == FoKind::PD) {
        // Section 4.3: stability condition K_p + delta > 0; normalised delta_n = 1.
        FeasibilityTest st{"pd_stability", d.Kpn + 1.0 > 0.0, d.Kpn + 1.0, 0.0, ""};
        st.detail = "Section 4.3: K_pn + delta_n = " + fmt(d.Kpn + 1.0) + (st.pass ? " > 0" : " <= 0");
        d.tests.push_back(st);
    }
    d.tests.push_back(nyquist_test(d));
    return d;
}

bool FoDesign::feasible() const
{
    for (const auto& t : tests)
        if (!t.pass) return false;
    return true;
}

std::string FoDesign::reason() const
{
    for (const auto& t : tests)
        if (!t.pass) return t.name + ": " + t.detail;
    return "";
}

std::complex<double> FoDesign::controller(double w) const
{
    return kind == FoKind::PI ? Kp + Ki * jpow(w, -spec.order) : Kp + Kd * jpow(w, spec.order);
}

std::complex<double> FoDesign::loop(double w) const { return controller(w) * plant.freq(w); }

std::vector<std::pair<double, double>> feasible_bands(FoKind kind, const GharabPlant& plant, const FoSpec& spec,
                                                      double w_lo, double w_hi, int grid)
{
    require(std::isfinite(w_lo) && std::isfinite(w_hi) && w_lo > 0.0 && w_hi > w_lo,
            "band search needs 0 < w_lo < w_hi");
    require(grid >= 2, "band search needs at least 2 grid points");
    std::vector<double> w(grid);
    std::vector<FoDesign> d(grid);
    for (int i = 0; i < grid; ++i) {
        w[i] = w_lo * std::pow(w_hi / w_lo, static_cast<double>(i) / (grid - 1));
        d[i] = design_at(kind, plant, spec, w[i]);
    }
    auto feasible = [&](double x) { return design_at(kind, plant, spec, x).feasible(); };
    // The continuous margin of a test along w_c (pass <=> margin > 0); the nyquist test only has an
    // integer verdict and is located by bisection on it.
    auto margin = [&](const std::string& name, double x) {
        const FoDesign e = design_at(kind, plant, spec, x);
        if (name == "low_frequency") return e.Kin;                    // eq. (18): K_in > 0
        if (name == "pd_stability") return e.Kpn + 1.0;               // Section 4.3
        for (const auto& t : e.tests)
            if (t.name == "rhfc") return -t.value;                     // eq. (22)/(35): max slope < 0
        return 0.0;
    };
    // Edge between w[i] and w[i+1] (feasibility differs): the first test whose verdict differs is
    // the one that switches; its margin's root is bracketed there and refined by TOMS 748 (Boost.Math)
    // to kEdgeTol relative. Bisection on the feasibility itself when the switching test has no
    // continuous margin or when the refined point is not the switch of the whole verdict.
    auto edge = [&](int i) {
        const bool a_ok = d[i].feasible();
        const double tol = kEdgeTol;
        std::string name;
        for (size_t k = 0; k < d[i].tests.size() && name.empty(); ++k)
            if (d[i].tests[k].pass != d[i + 1].tests[k].pass) name = d[i].tests[k].name;
        if (name == "low_frequency" || name == "pd_stability" || name == "rhfc") {
            const double fa = margin(name, w[i]), fb = margin(name, w[i + 1]);
            if (std::isfinite(fa) && std::isfinite(fb) && (fa > 0.0) != (fb > 0.0)) {
                std::uintmax_t it = 200;
                const auto br = boost::math::tools::toms748_solve(
                    [&](double x) { return margin(name, x); }, w[i], w[i + 1], fa, fb,
                    [tol](double x, double y) { return std::fabs(y - x) <= tol * std::fabs(y); }, it);
                const double ok_side = a_ok ? br.first : br.second, other = a_ok ? br.second : br.first;
                if (feasible(ok_side) && !feasible(other)) return ok_side;
            }
        }
        double a = w[i], b = w[i + 1];
        while (b - a > tol * b) {
            const double m = std::sqrt(a * b);
            (feasible(m) == a_ok ? a : b) = m;
        }
        return a_ok ? a : b;  // the feasible side
    };
    std::vector<std::pair<double, double>> bands;
    double start = d[0].feasible() ? w[0] : 0.0;
    for (int i = 0; i + 1 < grid; ++i) {
        if (d[i].feasible() == d[i + 1].feasible()) continue;
        const double e = edge(i);
        if (d[i + 1].feasible())
            start = e;
        else
            bands.emplace_back(start, e);
    }
    if (d[grid - 1].feasible()) bands.emplace_back(start, w[grid - 1]);
    return bands;
}

nlohmann::json to_json(const FoDesign& d)
{
    const bool pi = d.kind == FoKind::PI;
    nlohmann::json tests = nlohmann::json::array();
    for (const auto& t : d.tests)
        tests.push_back({{"name", t.name}, {"pass", t.pass}, {"value", t.value}, {"bound", t.bound}, {"detail", t.detail}});
    nlohmann::json j = {
        {"schema", pi ? "frac.design.fopi" : "frac.design.fopd"},
        {"version", 1},
        {"source", "seed 001 (Gharab & Feliu-Batlle 2023) eqs. (4), (10), (14)-(18), (22), (29)-(35); erratum E1, E3"},
        {"plant", {{"K", d.plant.K}, {"T", d.plant.T}, {"lambda", d.plant.lambda}, {"tau", d.plant.tau}}},
        {"spec", {{"wc", d.spec.wc}, {"phim", d.spec.phim}, {pi ? "alpha" : "mu", d.spec.order}}},
        {"normalised", {{"Tl", d.Tl}, {"wcn", d.wcn}, {"taun", d.taun}, {"phimn", d.phimn}, {"Kpn", d.Kpn}}},
        {"feasible", d.feasible()},
        {"tests", tests},
    };
    if (pi) {
        j["normalised"]["Kin"] = d.Kin;
        j["controller"] = {{"form", "C(s) = Kp + Ki s^-alpha"}, {"Kp", d.Kp}, {"Ki", d.Ki}, {"alpha", d.spec.order}};
    } else {
        j["normalised"]["Kdn"] = d.Kdn;
        j["controller"] = {{"form", "C(s) = (Kp + delta) + Kd s^mu, u = C e + delta y"},
                           {"Kp", d.Kp}, {"Kd", d.Kd}, {"mu", d.spec.order}, {"delta", d.delta}};
    }
    if (!d.feasible()) j["reason"] = d.reason();
    return j;
}

}  // namespace fracdesign::design
