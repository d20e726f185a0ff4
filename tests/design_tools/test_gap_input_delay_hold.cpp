// test_gap_input_delay_hold.cpp - a fractional input delay of a plant under
// the zero-order hold (a continuous document, or a discrete one with a
// generator) (replay.cpp, docs/gap.md "What the document
// states", gap.input_delay): between two samples the plant sees the older
// input for f Ts and the newer one for the rest of the sample, which the
// replay reproduces exactly (not by interpolating the two inputs).
// Two first-order lags, one per input (the force input u with a gain error,
// and a second input v), stepped at samples of the test's own choosing; the
// record is the lags' closed-form step responses, delayed by 2.37 samples
// (gap.input_delay) or by 1.6 (gap.input_delay 0.4 plus the input_delay
// effect's 1.2). Parameters are the test's own.
#include <gtest/gtest.h>

#include <cmath>

#include "fracdesign/gap/diagnosis.hpp"
#include "gap_drive.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 0.01, kA1 = 7.0, kB1 = 3.0, kA2 = 23.0, kB2 = 11.0;
const Eigen::Index kN = 400;

nlohmann::json doc(double delay_samples, bool discrete = false);

nlohmann::json doc(double delay_samples, bool discrete)
{
    if (discrete) {
        // The same lags held at kTs: a discrete document (its generator
        // log(A)/Ts, nominal.cpp discrete_generator, gives the hold back).
        const double e1 = std::exp(-kA1 * kTs), e2 = std::exp(-kA2 * kTs);
        nlohmann::json d = doc(delay_samples, false);
        d["time"] = "discrete";
        d["Ts"] = kTs;
        d["A"] = {{e1, 0}, {0, e2}};
        d["B"] = {{kB1 / kA1 * (1 - e1), 0}, {0, kB2 / kA2 * (1 - e2)}};
        return d;
    }
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "two_lags"},
            {"time", "continuous"},
            {"A", {{-kA1, 0}, {0, -kA2}}},
            {"B", {{kB1, 0}, {0, kB2}}},
            {"C", {{1, 0}, {0, 1}}},
            {"D", {{0, 0}, {0, 0}}},
            {"inputs", {"u", "v"}},
            {"outputs", {"y1", "y2"}},
            {"gap", {{"force_input", "u"}, {"input_delay", delay_samples * kTs}, {"initial_state", {{"given", {0, 0}}}}}}};
}

// Held steps: u and v change at these samples (value from that sample on).
struct Step {
    Eigen::Index k;
    double u, v;
};
const std::vector<Step> kSteps = {{20, 1.0, 0.0}, {57, -0.5, 2.0}, {133, 0.8, -1.0}, {211, 0.8, 0.3}, {290, -1.2, 0.3}};

double level(Eigen::Index k, bool first)
{
    double x = 0.0;
    for (const Step& s : kSteps)
        if (k >= s.k) x = first ? s.u : s.v;
    return x;
}

// The lag b/(s + a) driven by the held input delayed by d seconds, at t.
double exact(double t, double d, double a, double b, bool first, double gain)
{
    double y = 0.0, prev = 0.0;
    for (const Step& s : kSteps) {
        const double now = level(s.k, first), du = now - prev;
        prev = now;
        const double age = t - double(s.k) * kTs - d;
        if (age > 0) y += gain * du * b / a * (1.0 - std::exp(-a * age));
    }
    return y;
}

Signals record(double delay_s, double gain)
{
    Signals s = multisine_record({"u", "v", "y1", "y2"}, kTs, kN, {});
    for (Eigen::Index k = 0; k < kN; ++k) {
        const double t = double(k) * kTs;
        s.values(k, 0) = level(k, true);
        s.values(k, 1) = level(k, false);
        s.values(k, 2) = exact(t, delay_s, kA1, kB1, true, gain);
        s.values(k, 3) = exact(t, delay_s, kA2, kB2, false, 1.0);
    }
    return s;
}

double max_error(const nlohmann::json& d, const std::vector<EffectInstance>& e, double delay_s, double gain)
{
    const Signals s = record(delay_s, gain);
    const NominalModel m = nominal_from_json(d, kTs);
    const Eigen::MatrixXd y = replay(make_replay_setup(m, s, {"u", "v"}, {"y1", "y2"}), e).y;
    return (y - s.values.rightCols(2)).cwiseAbs().maxCoeff();
}

}  // namespace

TEST(GapInputDelayHold, a_fractional_delay_of_a_continuous_plant_is_replayed_exactly)
{
    // The nominal's own delay, 2.37 samples, both inputs, the force input through a gain error.
    EXPECT_LT(max_error(doc(2.37), {}, 2.37 * kTs, 1.0), 1e-9);
    EXPECT_LT(max_error(doc(2.37), {{Effect::gain_error, {1.3}}}, 2.37 * kTs, 1.3), 1e-9);
    // The nominal's 0.4 samples and the effect's 1.2 add up.
    EXPECT_LT(max_error(doc(0.4), {{Effect::input_delay, {1.2 * kTs}}}, 1.6 * kTs, 1.0), 1e-9);
    // A whole-sample delay needs nothing beyond the hold.
    EXPECT_LT(max_error(doc(3.0), {}, 3.0 * kTs, 1.0), 1e-9);
    // The record tells delays apart: replayed with 2 samples it is far off.
    // (The interpolation (1 - f) u(k - n) + f u(k - n - 1) alone, before
    // the hold's correction, missed the record by 0.008 after its steps (0.5 % of a step).)
    EXPECT_GT(max_error(doc(2.0), {}, 2.37 * kTs, 1.0), 1e-2);
}

// A discrete document of the same plant: its generator (log(A)/Ts, B's
// hold inverted) gives the same exact hold. Before, a discrete plant kept
// the interpolation alone (0.008 off after a step).
TEST(GapInputDelayHold, a_fractional_delay_of_a_discrete_plant_is_replayed_exactly)
{
    EXPECT_LT(max_error(doc(2.37, true), {}, 2.37 * kTs, 1.0), 1e-9);
    EXPECT_LT(max_error(doc(0.4, true), {{Effect::input_delay, {1.2 * kTs}}}, 1.6 * kTs, 1.0), 1e-9);
}
