// test_gap_output_hold.cpp - gap.output_hold (docs/gap.md "What the document
// states"): a sensor read every n samples whose reading is held in between
// (the HIL rig's IMU: a reading every h PLC cycles). On a first-order lag the
// test simulates itself (its own exact discretisation, not the replay), read
// every 4 samples at phase 3:
//  - the replay with the hold reproduces the record to rounding, the phase
//    taken from the record or stated; a wrong stated phase does not;
//  - with noise the held record is diagnosed `none`, while the LTI nominal
//    without the hold leaves a gap well above it;
//  - each malformed field is refused with one message naming it.
// Parameters are the test's own.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fracdesign/gap/diagnosis.hpp"
#include "gap_drive.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 0.01, kA = 2 * M_PI * 2.3, kB = 1.7 * kA;
const Eigen::Index kN = 3000;
const int kEvery = 4, kPhase = 3;

nlohmann::json lag_doc(const nlohmann::json& gap)
{
    return {{"schema", "frac.model"}, {"version", 1},        {"kind", "statespace"},
            {"name", "held_lag"},     {"time", "continuous"}, {"A", {{-kA}}},
            {"B", {{kB}}},            {"C", {{1.0}, {1.0}}},  {"D", {{0.0}, {0.0}}},
            {"inputs", {"u"}},        {"outputs", {"y", "y_sample"}}, {"gap", gap}};
}

nlohmann::json hold(int phase = -1)
{
    nlohmann::json h = {{"every", kEvery}, {"sample", "y_sample"}};
    if (phase >= 0) h["phase"] = phase;
    return {{"initial_state", {{"given", {0.0}}}}, {"output_hold", {{"y", h}}}};
}

// y(k) = x(j), j the last reading sample <= k ((j - kPhase) mod kEvery = 0; x(0) before the first),
// x(k+1) = a x(k) + b u(k) (exact zero-order hold of the lag), from x(0) = 0 (stated: initial_state given).
Signals held_record(double noise_sd)
{
    Signals s = multisine_record({"u", "y"}, kTs, kN, {{1.0, 0.31, 0.2}, {0.6, 1.7, 1.1}, {0.4, 4.1, 2.3}});
    const double a = std::exp(-kA * kTs), b = kB / kA * (1 - a);
    std::mt19937 rng(11);
    std::normal_distribution<double> n(0.0, 1.0);
    double x = 0, reading = 0;
    for (Eigen::Index k = 0; k < kN; ++k) {
        if (k == 0 || (k - kPhase) % kEvery == 0) reading = x + noise_sd * n(rng);
        s.values(k, 1) = reading;
        x = a * x + b * s.values(k, 0);
    }
    return s;
}

double max_abs_error(const nlohmann::json& doc, const Signals& s)
{
    const NominalModel m = nominal_from_json(doc, kTs);
    const ReplayTrace tr = replay(make_replay_setup(m, s, {}, {"y"}), {});
    return (tr.y.col(0) - s.values.col(1)).cwiseAbs().maxCoeff();
}

std::string refusal(const nlohmann::json& gap)
{
    try {
        nominal_from_json(lag_doc(gap), kTs);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(accepted)";
}

}  // namespace

TEST(GapOutputHold, replay_holds_each_reading_at_the_records_phase)
{
    const Signals s = held_record(0.0);
    const NominalModel m = nominal_from_json(lag_doc(hold()), kTs);
    EXPECT_EQ(make_replay_setup(m, s, {}, {"y"}).hold_phase, std::vector<int>{kPhase});
    EXPECT_LT(max_abs_error(lag_doc(hold()), s), 1e-12);
    EXPECT_LT(max_abs_error(lag_doc(hold(kPhase)), s), 1e-12);
    EXPECT_GT(max_abs_error(lag_doc(hold((kPhase + 2) % kEvery)), s), 0.05);
    EXPECT_GT(max_abs_error(lag_doc({{"initial_state", {{"given", {0.0}}}}}), s), 0.05);
}

TEST(GapOutputHold, held_noisy_record_is_none_and_the_lti_nominal_is_not_at_the_floor)
{
    const Signals clean = held_record(0.0), s = held_record(0.01);
    GapOptions o;
    o.effects = {Effect::output_delay, Effect::gain_error, Effect::sensor_offset, Effect::quantization};
    const GapResult held = diagnose(nominal_from_json(lag_doc(hold()), kTs), s, nullptr, o);
    EXPECT_TRUE(held.verdict.effects.empty()) << effect_name(held.verdict.effects[0].kind);
    // the noise alone, on the held-out part (the last 30 %)
    const Eigen::Index h0 = kN - Eigen::Index(std::round(0.3 * double(kN)));
    const Eigen::VectorXd y = s.values.col(1);
    const double sd = std::sqrt((y.array() - y.mean()).square().mean());
    const Eigen::VectorXd e = (s.values.col(1) - clean.values.col(1)).tail(kN - h0);
    const double noise = std::sqrt(e.squaredNorm() / double(e.size())) / sd;
    EXPECT_LT(held.gap_before_total, 1.1 * noise) << held.gap_before_total << " against " << noise;
    const GapResult lti = diagnose(nominal_from_json(lag_doc({{"initial_state", {{"given", {0.0}}}}}), kTs), s, nullptr, o);
    EXPECT_GT(lti.gap_before_total, 3 * noise) << lti.gap_before_total << " against " << noise;
}

TEST(GapOutputHold, malformed_fields_are_refused_naming_the_field)
{
    const auto has = [](const std::string& m, const std::string& want) { return m.find(want) != std::string::npos; };
    EXPECT_PRED2(has, refusal({{"output_hold", 4}}), "model gap.output_hold: is 4");
    EXPECT_PRED2(has, refusal({{"output_hold", {{"z", {{"every", 4}}}}}}), "gap.output_hold.z: is");
    EXPECT_PRED2(has, refusal({{"output_hold", {{"y", {{"sample", "y_sample"}}}}}}), "gap.output_hold.y: is");
    EXPECT_PRED2(has, refusal({{"output_hold", {{"y", {{"every", 1}}}}}}), "gap.output_hold.y.every: is 1");
    EXPECT_PRED2(has, refusal({{"output_hold", {{"y", {{"every", 2.5}}}}}}), "gap.output_hold.y.every: is 2.5");
    EXPECT_PRED2(has, refusal({{"output_hold", {{"y", {{"every", 4}, {"sample", "w"}}}}}}), "gap.output_hold.y.sample: is \"w\"");
    EXPECT_PRED2(has, refusal({{"output_hold", {{"y", {{"every", 4}, {"phase", 4}}}}}}), "gap.output_hold.y.phase: is 4");
    EXPECT_PRED2(has, refusal({{"output_hold", {{"y", {{"every", 4}, {"lag", 1}}}}}}), "gap.output_hold.y.lag: is 1");
}
