// test_gap_sites_offset.cpp - an offset on a sensor inside the loop (issue
// 17 item 3: "offsets on in-loop sensors"; item 4: the initial state).
//
// Plant (drawn here, not a seed's): a mass on a spring with viscous damping,
// m x'' + c x' + k x = u, at 2 ms under a discrete PD, u = kp (r - x_m) - kd
// v_m, whose position encoder reads x_m = x + o with an offset o. The record
// starts at rest and follows reference steps. The loop drives the reading,
// not the mass, to r: the mass settles at r - o and the encoder at r, so
// (the loop being linear) the encoder's record is the nominal loop's
// response from x_m(0) = o, and after the start transient nothing in it
// tells the offset. Two cases:
// - a dual-sensor axis: a load-side scale x_load = x (not in the loop, no
//   offset) shows the mass r - o against the encoder's r on every hold: the
//   offset is named with its size, the scale's own offset ~0;
// - the encoder alone, the initial state fitted (x0 through the first
//   sample): the record is explained exactly without an effect, and the
//   verdict must be `none`, not a guess. (Stated at rest, its only evidence
//   is the start transient, which lies in the fit part: the held-out tail
//   cannot confirm it, docs/gap.md "Offsets in the loop".)
// The truth is this file's own: each sample's control, then the plant's
// zero-order hold over the sample, noise on the readings.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gap_drive.hpp"
#include "gap_sites.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 0.002;
const Eigen::Index kN = 4000;

struct Axis {
    double m, c, k, kp, kd, offset;
};

// The drawn axis: a 40-120 % overshoot-free PD, the offset 4-12 % of the stroke (r in +-1).
Axis draw(std::mt19937& rng)
{
    std::uniform_real_distribution<double> U(0, 1);
    Axis a;
    a.m = 0.5 + 1.5 * U(rng);
    a.k = a.m * std::pow(2 * M_PI * (0.5 + 1.5 * U(rng)), 2);  // open-loop 0.5-2 Hz
    a.c = 2 * 0.05 * std::sqrt(a.k * a.m);
    const double wc = 2 * M_PI * (4 + 4 * U(rng));  // closed loop 4-8 Hz, zeta 0.6-0.9
    a.kp = a.m * wc * wc - a.k;
    a.kd = 2 * (0.6 + 0.3 * U(rng)) * wc * a.m - a.c;
    a.offset = (U(rng) < 0.5 ? -1 : 1) * (0.04 + 0.08 * U(rng));
    return a;
}

// The nominal: outputs x (the encoder), v and, with `scale`, x_load.
nlohmann::json doc(const Axis& a, const char* initial_state, bool scale)
{
    nlohmann::json C = {{1, 0}, {0, 1}}, D = {{0}, {0}}, outs = {"x", "v"};
    if (scale) {
        C.push_back({1, 0});
        D.push_back({0});
        outs.push_back("x_load");
    }
    return {{"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "axis"}, {"time", "continuous"},
            {"A", {{0, 1}, {-a.k / a.m, -a.c / a.m}}}, {"B", {{0}, {1 / a.m}}}, {"C", C},
            {"D", D}, {"inputs", {"u"}}, {"outputs", outs},
            {"gap",
             {{"velocity", "v"}, {"force_input", "u"}, {"initial_state", initial_state},
              {"closed_loop",
               {{"references", {"r"}},
                {"measured", {"x", "v"}},
                {"controller", {{"kind", "statespace"}, {"time", "discrete"}, {"Ts", kTs}, {"D", {{a.kp, -a.kp, -a.kd}}}}}}}}}};
}

// The loop from rest under reference steps in +-1 held 0.4-1.2 s; readings with 0.5 % noise.
Signals record(const Axis& a, unsigned seed)
{
    Eigen::MatrixXd Ac(2, 2), Bc(2, 1), Ad, Bd;
    Ac << 0, 1, -a.k / a.m, -a.c / a.m;
    Bc << 0, 1 / a.m;
    zoh(Ac, Bc, kTs, Ad, Bd);
    const std::vector<double> ref = held_levels(kN, unsigned(seed), -1, 1, 200, 600, 100);
    Signals s;
    s.source = "in-loop offset truth";
    s.names = {"r", "u", "x", "v", "x_load"};
    s.Ts = kTs;
    s.values.resize(kN, 5);
    Eigen::Vector2d z = Eigen::Vector2d::Zero();
    for (Eigen::Index n = 0; n < kN; ++n) {
        const double r = ref[size_t(n)];
        const double xm = z(0) + a.offset, vm = z(1);
        const double u = a.kp * (r - xm) - a.kd * vm;
        s.values.row(n) << r, u, xm, vm, z(0);
        z = Ad * z + Bd * u;
    }
    gap_sites::add_noise(s, {"x", "v", "x_load"}, 0.005, seed + 1);
    return s;
}

GapResult diagnosed(const Axis& a, const char* initial_state, bool scale, const Signals& s)
{
    GapOptions o;
    o.threads = 2;
    return diagnose(nominal_from_json(doc(a, initial_state, scale), kTs), s, nullptr, o);
}

}  // namespace

TEST(GapSitesOffset, an_encoder_offset_in_the_loop_is_named_against_a_load_side_scale)
{
    std::mt19937 rng(2411);
    for (int i = 0; i < 2; ++i) {
        const Axis a = draw(rng);
        SCOPED_TRACE("axis " + std::to_string(i) + ": offset " + std::to_string(a.offset));
        const Signals s = record(a, 31 + unsigned(i));
        const GapResult r = diagnosed(a, "at_rest", true, s);
        gap_sites::expect_verdict(r, "sensor_offset", "force_input", "", {{"offset_x", a.offset}}, 0.05);
        EXPECT_LT(std::fabs(result_json(r)["verdict"]["params"]["offset_x_load"].get<double>()), 0.05 * std::fabs(a.offset));
    }
}

// The encoder alone, the initial state fitted: the offset is the start the
// fit chooses, the record is explained without it, and the verdict says so
// (none), not a confident effect made from the start's transient.
TEST(GapSitesOffset, the_encoder_alone_with_a_fitted_start_is_explained_without_an_effect)
{
    std::mt19937 rng(2411);
    const Axis a = draw(rng);
    const Signals s = record(a, 31);
    const GapResult r = diagnosed(a, "fitted", false, s);
    EXPECT_EQ(gap_sites::first_effect(r), "none") << gap_sites::candidates_text(result_json(r));
    // and the replay is at the noise: the gap before is the 0.5 % noise over the output's std, not the offset
    EXPECT_LT(r.gap_before_total, 0.05);
}

// The encoder alone, stated at rest, and a second record from rest as the
// held-out data (`--validate`, scored from its first sample): the start
// transient is then held-out evidence and the offset is named.
TEST(GapSitesOffset, the_encoder_alone_at_rest_is_named_on_a_validation_record_from_rest)
{
    std::mt19937 rng(2411);
    const Axis a = draw(rng);
    const Signals fit = record(a, 31), check = record(a, 57);
    GapOptions o;
    o.threads = 2;
    const GapResult r = diagnose(nominal_from_json(doc(a, "at_rest", false), kTs), fit, &check, o);
    gap_sites::expect_verdict(r, "sensor_offset", "force_input", "", {{"offset_x", a.offset}}, 0.05);
}

// The dual-sensor axis with the start fitted (the document does not say it
// starts at rest): only the difference of the two readings' offsets shows,
// so an encoder offset and the opposite offset on the scale are the same
// record. One offset explains it (the offset of one sensor alone is a
// variant of its own), and of the two the loop's sensor is named: its
// offset moves the machine. The start goes through the first sample less
// the offset (else the encoder's offset replays a start transient the
// record does not have, and only the scale's matched: named on x_load).
TEST(GapSitesOffset, an_encoder_offset_with_a_fitted_start_is_named_on_the_encoder)
{
    std::mt19937 rng(2411);
    for (int i = 0; i < 2; ++i) {
        const Axis a = draw(rng);
        const Signals s = record(a, 31 + unsigned(i));
        // Either order of the compared outputs: where the two offsets leave
        // the same held-out gap, the loop's sensor is named, not the first.
        for (const std::vector<std::string>& outs :
             {std::vector<std::string>{"x", "v", "x_load"}, std::vector<std::string>{"x_load", "x", "v"}}) {
            SCOPED_TRACE("axis " + std::to_string(i) + ": offset " + std::to_string(a.offset) + ", first output " + outs[0]);
            GapOptions o;
            o.threads = 2;
            o.outputs = outs;
            const GapResult r = diagnose(nominal_from_json(doc(a, "fitted", true), kTs), s, nullptr, o);
            gap_sites::expect_verdict(r, "sensor_offset", "force_input", "", {{"offset_x", a.offset}}, 0.05);
            EXPECT_EQ(result_json(r)["verdict"]["params"]["offset_x_load"].get<double>(), 0.0);
        }
    }
}

// The encoder alone, stated at rest, one record (no --validate): the start
// transient (the reading o at rest, the loop reacting to it) lies in the
// fit rows, and where the spring to ground is soft against kp the held-out
// tail is the nominal's within the noise (the mass settles at
// kp (r - o)/(kp + k), the reading k o/(kp + k) off). The start being
// stated, that transient is evidence: sensor_offset is the verdict with the
// offset within 5 %, from the fit rows alone (status fit_part_only) where
// the tail holds nothing; before, that axis was none. With the start fitted
// the record stays none (the_encoder_alone_with_a_fitted_start_...).
TEST(GapSitesOffset, the_encoder_alone_at_rest_is_named_from_the_fit_rows)
{
    std::mt19937 rng(2411);
    int fit_part = 0;
    for (int i = 0; i < 2; ++i) {
        const Axis a = draw(rng);
        SCOPED_TRACE("axis " + std::to_string(i) + ": offset " + std::to_string(a.offset));
        const GapResult r = diagnosed(a, "at_rest", false, record(a, 31 + unsigned(i)));
        ASSERT_EQ(gap_sites::first_effect(r), "sensor_offset") << gap_sites::candidates_text(result_json(r));
        EXPECT_NEAR(result_json(r)["verdict"]["params"]["offset_x"].get<double>(), a.offset, 0.05 * std::fabs(a.offset));
        std::printf("axis %d: %s: %s\n", i, r.confidence.status.c_str(), r.confidence.explanation.c_str());
        fit_part += r.confidence.status == "fit_part_only";
        // A weak verdict the record singles out: the second pass on the measured outputs named other
        // effects (an offset of the wrong size with Coulomb friction), and the first pass stands.
        if (r.confidence.status == "partly_explained")
            EXPECT_NE(r.loop_feedback_note.find("other effects than the first pass singled out"), std::string::npos)
                << r.loop_feedback_note;
    }
    EXPECT_GE(fit_part, 1);
}
