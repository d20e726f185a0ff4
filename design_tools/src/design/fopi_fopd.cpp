// fopi_fopd.cpp - seed 001 FO-PI^alpha / FO-PD^mu tuning and feasibility.
#include "fracdesign/design/fopi_fopd.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

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

// Feasible at w_c for the given plant/spec (used by the band search).
bool feasible_at(FoKind kind, const GharabPlant& p, FoSpec s, double wc)
{
    s.wc = wc;
    return tune_fo(kind, p, s).feasible();
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

double rhfc_worst_slope(FoKind kind, double wcn, double lambda, double order, double Kpn, double Kx, int points)
{
    double worst = -std::numeric_limits<double>::infinity();
    double prev = 0.0;
    for (int i = 0; i < points; ++i) {
        const double w = wcn * std::pow(1000.0, static_cast<double>(i) / (points - 1));
        const std::complex<double> c =
            kind == FoKind::PI ? Kpn + Kx * jpow(w, -order) : Kpn + Kx * jpow(w, order);
        const double m = std::abs(c) / std::abs(1.0 + jpow(w, lambda));
        if (i > 0) worst = std::max(worst, (m - prev) / prev);
        prev = m;
    }
    return worst;
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

    // eq. (17): tau_n < tau_n,max = phi_mn / w_cn, i.e. phi_m > 0. phi_mn is the phase
    // margin of the delay-free loop, so it must also stay below pi: beyond, the
    // delay has wrapped the loop phase by a full turn and (17) no longer is a margin.
    FeasibilityTest delay{"delay_limit", spec.phim > 0.0 && d.phimn < kPi, d.taun, d.phimn / d.wcn, ""};
    delay.detail = "eq. (17): tau_n = " + fmt(d.taun) + (spec.phim > 0.0 ? " < " : " >= ") +
                   "tau_n,max = phi_mn/w_cn = " + fmt(d.phimn / d.wcn) + " (needs phi_m > 0) and phi_mn = " +
                   fmt(d.phimn) + (d.phimn < kPi ? " < pi" : " >= pi (delay wraps the phase a full turn)");
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

    const double slope = rhfc_worst_slope(kind, d.wcn, lam, a, d.Kpn, kx);
    FeasibilityTest rh{"rhfc", slope < 0.0, slope, 0.0, ""};
    rh.detail = std::string("eq. ") + (kind == FoKind::PI ? "(22)" : "(35)") +
                ": |C_n G_n*| on (w_cn, 1000 w_cn] " + (rh.pass ? "strictly decreasing" : "not strictly decreasing") +
                " (largest relative step " + fmt(slope) + ")";
    d.tests.push_back(rh);

    if (kind == FoKind::PD) {
        // Section 4.3: stability condition K_p + delta > 0; normalised delta_n = 1.
        FeasibilityTest st{"pd_stability", d.Kpn + 1.0 > 0.0, d.Kpn + 1.0, 0.0, ""};
        st.detail = "Section 4.3: K_pn + delta_n = " + fmt(d.Kpn + 1.0) + (st.pass ? " > 0" : " <= 0");
        d.tests.push_back(st);
    }
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
    std::vector<char> ok(grid);
    for (int i = 0; i < grid; ++i) {
        w[i] = w_lo * std::pow(w_hi / w_lo, static_cast<double>(i) / (grid - 1));
        ok[i] = feasible_at(kind, plant, spec, w[i]);
    }
    // Refine the transition between w[i] (state s_i) and w[i+1] by bisection.
    auto edge = [&](double a, double b, bool a_ok) {
        while (b - a > 1e-9 * b) {
            const double m = std::sqrt(a * b);
            if (feasible_at(kind, plant, spec, m) == a_ok)
                a = m;
            else
                b = m;
        }
        return a_ok ? a : b;  // the feasible side
    };
    std::vector<std::pair<double, double>> bands;
    double start = ok[0] ? w[0] : 0.0;
    for (int i = 0; i + 1 < grid; ++i) {
        if (ok[i] == ok[i + 1]) continue;
        const double e = edge(w[i], w[i + 1], ok[i]);
        if (ok[i + 1])
            start = e;
        else
            bands.emplace_back(start, e);
    }
    if (ok[grid - 1]) bands.emplace_back(start, w[grid - 1]);
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
