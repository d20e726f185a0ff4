// test_gap_sites_limits.cpp - asymmetric saturation and dead zone at the
// drive of a servo axis (issue 17 item 3), each edge its own parameter.
//
// Plant (chosen here, not a seed's): a rigid axis J theta'' = Ka u - b theta'
// (J = 1.3e-3 kg m^2, b = 1.7e-3 Nm s/rad, Ka = 0.11 Nm/V) at 1 ms, a PD with
// a filtered difference on the position encoder, clipped to +-10 V, one cycle
// of computation delay; outputs position (in the loop) and a tachometer. The
// truth is this file's own loop: the axis stepped exactly (zero-order hold)
// with the drive's limits and dead zone applied to the delayed command.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gap_sites.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 1e-3, kJ = 1.3e-3, kB = 1.7e-3, kKa = 0.11, kClip = 10.0;
const Eigen::Index kN = 4000;
const double kWc = 2 * M_PI * 9.0;  // loop bandwidth
const double kKp = kJ * kWc * kWc / kKa, kKd = 1.4 * kJ * kWc / kKa, kA = std::exp(-kTs * 8 * kWc);
const double kInf = std::numeric_limits<double>::infinity();

struct Drive {
    double lim_lo = -kInf, lim_hi = kInf, dz_lo = 0, dz_hi = 0;
};

nlohmann::json servo_doc()
{
    const double g = (1 - kA) / kTs;
    return {{"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "servo_axis"},
            {"time", "continuous"},
            {"A", {{0, 1}, {0, -kB / kJ}}}, {"B", {{0}, {kKa / kJ}}}, {"C", {{1, 0}, {0, 1}}}, {"D", {{0}, {0}}},
            {"inputs", {"voltage"}}, {"outputs", {"position", "velocity"}},
            {"gap",
             {{"velocity", "velocity"}, {"force_input", "voltage"}, {"units", {{"voltage", "V"}}},
              {"closed_loop",
               {{"references", {"ref"}}, {"measured", {"position"}},
                {"controller",
                 {{"time", "discrete"}, {"Ts", kTs}, {"A", {{0, 0}, {-g, kA}}}, {"B", {{1, -1}, {g, -g}}},
                  {"C", {{-kKd * g, kKd * kA}}}, {"D", {{kKp + kKd * g, -(kKp + kKd * g)}}}}},
                {"delay_samples", 1}, {"saturation", kClip}}}}}};
}

// A two-tone reference (1 - cos start over 0.3 s) whose command reaches
// about 7 V in both directions all through the record.
double reference(double t)
{
    const double e = t >= 0.3 ? 1.0 : 0.5 * (1 - std::cos(M_PI * t / 0.3));
    return e * (2.3 * std::sin(2 * M_PI * 1.7 * t) + 0.4 * std::sin(2 * M_PI * 4.4 * t + 1.0));
}

Signals record(const Drive& d, double* peak = nullptr)
{
    Signals s;
    s.source = "servo axis";
    s.names = {"ref", "position", "velocity", "voltage_cmd"};
    s.Ts = kTs;
    s.values.resize(kN, 4);
    const double ex = std::exp(-kB / kJ * kTs), phi = (1 - ex) / (kB / kJ);
    double th = 0, v = 0, e_prev = 0, d_prev = 0, c_prev = 0, pk = 0;
    for (Eigen::Index k = 0; k < kN; ++k) {
        const double r = reference(double(k) * kTs);
        const double e = r - th, dd = kA * d_prev + (1 - kA) * (e - e_prev) / kTs;
        const double c = std::clamp(kKp * e + kKd * dd, -kClip, kClip);
        s.values.row(k) << r, th, v, c;
        if (k * kTs > 0.5) pk = std::max(pk, std::fabs(c));  // the peak after the start
        e_prev = e;
        d_prev = dd;
        double u = std::clamp(c_prev, d.lim_lo, d.lim_hi);
        u = u > d.dz_hi ? u - d.dz_hi : (u < d.dz_lo ? u - d.dz_lo : 0.0);
        c_prev = c;
        // Exact step of J v' = Ka u - b v with u held over the sample.
        const double vn = v * ex + kKa * u / kJ * phi;
        th += (kKa * u / kB) * kTs + (v - kKa * u / kB) * phi;
        v = vn;
    }
    if (peak) *peak = pk;
    gap_sites::add_noise(s, {"position", "velocity"}, 0.002, 5);
    return s;
}

GapResult run(const Signals& s)
{
    const NominalModel m = nominal_from_json(servo_doc(), kTs);
    GapOptions o;
    o.outputs = {"position", "velocity"};
    return diagnose(m, s, nullptr, o);
}

double effect_free_peak()
{
    double pk = 0;
    record(Drive(), &pk);
    return pk;
}

}  // namespace

TEST(GapSitesLimits, an_asymmetric_drive_limit_is_found_with_both_edges)
{
    const double pk = effect_free_peak();
    Drive d;
    d.lim_lo = -0.62 * pk;
    d.lim_hi = 0.77 * pk;
    gap_sites::expect_verdict(run(record(d)), "saturation", "force_input", "", {{"lower", d.lim_lo}, {"upper", d.lim_hi}});
}

// A dead zone as wide as a good part of the command (35 % and 22 % of its
// peak; the edges also come back within 10 % at 60 % and 50 %).
TEST(GapSitesLimits, a_wide_asymmetric_dead_zone_is_found_with_both_edges)
{
    const double pk = effect_free_peak();
    Drive d;
    d.dz_lo = -0.35 * pk;
    d.dz_hi = 0.22 * pk;
    gap_sites::expect_verdict(run(record(d)), "deadzone", "force_input", "", {{"lower", d.dz_lo}, {"upper", d.dz_hi}});
}

TEST(GapSitesLimits, a_record_without_them_is_not_blamed_on_a_limit_or_a_dead_zone)
{
    const GapResult r = run(record(Drive()));
    const std::string f = gap_sites::first_effect(r);
    EXPECT_NE(f, "saturation");
    EXPECT_NE(f, "deadzone");
}

TEST(GapSitesLimits, result_json_gives_both_edges_in_the_force_units)
{
    const double pk = effect_free_peak();
    Drive d;
    d.lim_lo = -0.62 * pk;
    d.lim_hi = 0.77 * pk;
    const nlohmann::json j = result_json(run(record(d)));
    EXPECT_EQ(j["verdict"]["params_unit"]["lower"], "V");
    EXPECT_EQ(j["verdict"]["params_unit"]["upper"], "V");
}
