// test_gap_effects.cpp - the gap diagnosis names each injected effect.
//
// A mass-spring-damper (open loop, outputs position and velocity) is driven by
// a multisine with velocity reversals; the "measured" record is the replay of
// the nominal model with one known effect plus 0.2 % measurement noise. The
// diagnosis must rank the injected effect first and remove most of the gap.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fracdesign/gap/diagnosis.hpp"
#include "gap_drive.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 0.01;
const Eigen::Index kN = 3000;

nlohmann::json plant_doc()
{
    const double m = 1.0, c = 2.0, k = 20.0;
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "mass_spring_damper"},
            {"time", "continuous"},
            {"A", {{0.0, 1.0}, {-k / m, -c / m}}},
            {"B", {{0.0}, {1.0 / m}}},
            {"C", {{1.0, 0.0}, {0.0, 1.0}}},
            {"D", {{0.0}, {0.0}}},
            {"inputs", {"u"}},
            {"outputs", {"x", "v"}},
            {"gap", {{"velocity", "v"}, {"force_input", "u"}}}};
}

Signals drive()
{
    return multisine_record({"u", "x", "v"}, kTs, kN, {{10.0, 0.23, 0.0}, {5.0, 0.71, 1.0}, {3.0, 1.9, 2.0}, {2.0, 3.3, 0.5}});
}

// The same plant under a PD position loop: the reference r drives it, and the
// loop makes an input delay distinguishable from an output delay (in open
// loop on a linear plant the two are the same map).
nlohmann::json loop_doc()
{
    nlohmann::json d = plant_doc();
    d["gap"]["closed_loop"] = {{"references", {"r"}},
                               {"measured", {"x", "v"}},
                               {"controller", {{"time", "discrete"}, {"Ts", kTs}, {"D", {{40.0, -40.0, -4.0}}}}}};
    return d;
}

// The record: nominal + `truth`, with 0.2 % noise on each output; a
// quantizing sensor rounds the noisy value (noise before the quantizer).
Signals record(const NominalModel& m, const std::vector<EffectInstance>& truth)
{
    Signals s = drive();
    if (m.closed_loop) {
        s.names = {"r", "x", "v"};
        s.values.col(0) *= 0.05;
    }
    std::vector<EffectInstance> dynamic;
    std::vector<double> steps;
    for (const EffectInstance& e : truth) {
        if (e.kind == Effect::quantization) steps = e.params;
        else dynamic.push_back(e);
    }
    const ReplaySetup setup = make_replay_setup(m, s, {}, {"x", "v"});
    const ReplayTrace tr = replay(setup, dynamic);
    std::mt19937 rng(7);
    std::normal_distribution<double> n(0.0, 1.0);
    for (int c = 0; c < 2; ++c) {
        const double sd = std::sqrt((tr.y.col(c).array() - tr.y.col(c).mean()).square().mean());
        for (Eigen::Index k = 0; k < kN; ++k) {
            double y = tr.y(k, c) + 0.002 * sd * n(rng);
            if (!steps.empty()) y = steps[size_t(c)] * std::round(y / steps[size_t(c)]);
            s.values(k, c + 1) = y;
        }
    }
    return s;
}

struct Case {
    Effect effect;
    std::vector<double> params;
    Site site = Site::force_input;
};

void expect_found(const Case& c, double min_shrink, bool closed_loop = false)
{
    const NominalModel m = nominal_from_json(closed_loop ? loop_doc() : plant_doc(), kTs);
    const Signals data = record(m, {{c.effect, c.params, c.site}});
    GapOptions opt;
    const GapResult r = diagnose(m, data, nullptr, opt);
    ASSERT_FALSE(r.candidates.empty());
    const FitReport& top = r.candidates.front();
    ASSERT_EQ(top.effects.size(), 1u) << effect_name(c.effect) << ": top candidate is none";
    EXPECT_EQ(effect_name(top.effects[0].kind), effect_name(c.effect));
    EXPECT_GE(top.shrink, min_shrink) << effect_name(c.effect);
    ASSERT_FALSE(r.verdict.effects.empty());
    EXPECT_EQ(effect_name(r.verdict.effects[0].kind), effect_name(c.effect));
}

}  // namespace

TEST(GapEffects, input_delay_is_found_in_closed_loop) { expect_found({Effect::input_delay, {0.05}}, 0.8, true); }
// Known limitation: under this PD loop a 30 ms sensor delay and an actuator
// delay give held-out gaps within the noise of each other, and the diagnosis
// ranks input_delay first. The test holds what is true today: a delay is found
// and it removes the gap.
TEST(GapEffects, output_delay_is_found_as_a_delay_in_closed_loop)
{
    const NominalModel m = nominal_from_json(loop_doc(), kTs);
    const Signals data = record(m, {{Effect::output_delay, {0.03, 0.03}}});
    const GapResult r = diagnose(m, data, nullptr, GapOptions());
    ASSERT_EQ(r.candidates.front().effects.size(), 1u);
    const Effect top = r.candidates.front().effects[0].kind;
    EXPECT_TRUE(top == Effect::output_delay || top == Effect::input_delay) << effect_name(top);
    EXPECT_GE(r.candidates.front().shrink, 0.8);
}
TEST(GapEffects, coulomb_friction_is_found) { expect_found({Effect::coulomb_friction, {2.0, 0.5}}, 0.8); }
TEST(GapEffects, viscous_friction_is_found) { expect_found({Effect::viscous_friction, {3.0}}, 0.8); }
TEST(GapEffects, stribeck_friction_is_found) { expect_found({Effect::stribeck_friction, {1.0, 4.0, 0.3}}, 0.8); }
// Stribeck velocities the test draws from a small share of the record's rms
// velocity to several times it: the hump covers the slow reversals only, or
// nearly every speed the record holds (an outside servo case with vs above
// its speeds came out coulomb_friction: its fit from two starts ended in the
// Coulomb solution Fs < Fc; and at vs = 4 rms(v) a Stribeck fit leaving a
// gap 3.6 x smaller than Coulomb's ranked behind it on the parameter
// penalty). Named first; Fc and Fs within 10 % up to vs = 1.5 rms(v).
TEST(GapEffects, stribeck_friction_is_found_for_stribeck_velocities_across_the_records_speeds)
{
  for (bool closed_loop : {false, true}) {
    const NominalModel m = nominal_from_json(closed_loop ? loop_doc() : plant_doc(), kTs);
    Signals base = drive();
    if (closed_loop) {
        base.names = {"r", "x", "v"};
        base.values.col(0) *= 0.05;
    }
    const ReplayTrace nom = replay(make_replay_setup(m, base, {}, {"x", "v"}), {});
    const double sv = std::sqrt(nom.v.squaredNorm() / double(nom.v.size()));
    std::mt19937 rng(20261206);
    std::uniform_real_distribution<double> U(0, 1);
    for (double share : {0.08, 0.4, 1.5, 4.0}) {
        const double Fc = 0.5 + 1.5 * U(rng), Fs = Fc * (1.6 + 0.9 * U(rng)), vs = share * sv * (0.8 + 0.4 * U(rng));
        SCOPED_TRACE(std::string(closed_loop ? "closed loop" : "open loop") + ": Fc " + std::to_string(Fc) + " Fs " + std::to_string(Fs) + " vs " + std::to_string(vs));
        const GapResult r = diagnose(m, record(m, {{Effect::stribeck_friction, {Fc, Fs, vs}}}), nullptr, GapOptions());
        ASSERT_FALSE(r.verdict.effects.empty());
        std::string listed;
        for (const FitReport& c : r.candidates)
            listed += (c.effects.empty() ? std::string("none") : effect_name(c.effects[0].kind)) + " gap " + std::to_string(c.gap) + "; ";
        EXPECT_EQ(effect_name(r.verdict.effects[0].kind), "stribeck_friction") << listed;
        // Beyond the record's speeds the curve is Fs - (Fs - Fc) (v/vs)^2 there:
        // the name, not Fc and vs apart.
        if (r.verdict.effects[0].kind != Effect::stribeck_friction || share > 2) continue;
        EXPECT_NEAR(r.verdict.effects[0].params[0], Fc, 0.1 * Fc);
        EXPECT_NEAR(r.verdict.effects[0].params[1], Fs, 0.1 * Fs);
    }
  }
}
TEST(GapEffects, backlash_is_found) { expect_found({Effect::backlash, {4.0}}, 0.8); }
TEST(GapEffects, deadzone_is_found) { expect_found({Effect::deadzone, {-3.0, 3.0}}, 0.8); }
TEST(GapEffects, saturation_is_found) { expect_found({Effect::saturation, {-10.0, 10.0}}, 0.8); }
TEST(GapEffects, fractional_damping_is_found) { expect_found({Effect::fractional_damping, {2.0, 0.5}}, 0.8); }
TEST(GapEffects, unmodelled_mode_is_found) { expect_found({Effect::unmodelled_mode, {6.0, 0.03, 0.01, 0.2}, Site::output}, 0.8); }
TEST(GapEffects, gain_error_is_found) { expect_found({Effect::gain_error, {1.3}}, 0.8); }
TEST(GapEffects, sensor_offset_is_found) { expect_found({Effect::sensor_offset, {0.1, 0.2}}, 0.8); }
TEST(GapEffects, quantization_is_found) { expect_found({Effect::quantization, {0.05, 0.1}}, 0.5); }

TEST(GapEffects, none_when_the_nominal_explains_the_data)
{
    const NominalModel m = nominal_from_json(plant_doc(), kTs);
    const Signals data = record(m, {});
    const GapResult r = diagnose(m, data, nullptr, GapOptions());
    EXPECT_TRUE(r.verdict.effects.empty());
    EXPECT_EQ(result_json(r)["verdict"]["effects"][0], "none");
}

TEST(GapEffects, coulomb_parameters_are_recovered_with_uncertainty)
{
    const NominalModel m = nominal_from_json(plant_doc(), kTs);
    const Signals data = record(m, {{Effect::coulomb_friction, {2.0, 0.5}}});
    GapOptions opt;
    opt.effects = {Effect::coulomb_friction, Effect::viscous_friction};
    const GapResult r = diagnose(m, data, nullptr, opt);
    ASSERT_EQ(r.candidates.front().effects.size(), 1u);
    const FitReport& f = r.candidates.front();
    EXPECT_NEAR(f.effects[0].params[0], 2.0, 0.1 * 2.0);
    EXPECT_NEAR(f.effects[0].params[1], 0.5, 0.1);
    EXPECT_TRUE(std::isfinite(f.stddev[0][0]) && f.stddev[0][0] > 0);
}

TEST(GapEffects, result_json_has_the_fixed_keys)
{
    const NominalModel m = nominal_from_json(plant_doc(), kTs);
    const Signals data = record(m, {{Effect::viscous_friction, {3.0}}});
    GapOptions opt;
    opt.effects = {Effect::viscous_friction, Effect::gain_error};
    const nlohmann::json j = result_json(diagnose(m, data, nullptr, opt));
    EXPECT_EQ(j["schema"], "frac.gap");
    EXPECT_EQ(j["version"], 1);
    EXPECT_EQ(j["metric"], "nrmse");
    EXPECT_TRUE(j["gap_before"].contains("x") && j["gap_before"].contains("v"));
    EXPECT_EQ(j["where"]["outputs"].size(), 2u);
    EXPECT_TRUE(j["where"]["bands_hz"].is_array() && j["where"]["bands_hz"][0].size() == 3u);
    EXPECT_TRUE(j["where"]["windows_s"].is_array());
    ASSERT_EQ(j["candidates"].size(), 3u);  // two effects and none
    for (const auto& c : j["candidates"])
        for (const char* k : {"effect", "params", "gap_after", "shrink"}) EXPECT_TRUE(c.contains(k)) << k;
    EXPECT_EQ(j["candidates"][0]["effect"], "viscous_friction");
    for (const char* k : {"effects", "params", "gap_after", "shrink"}) EXPECT_TRUE(j["verdict"].contains(k)) << k;
}

TEST(GapWhere, band_shares_sum_to_one_and_band_nrmse_adds_up)
{
    const NominalModel m = nominal_from_json(plant_doc(), kTs);
    const Signals data = record(m, {{Effect::coulomb_friction, {2.0, 0.0}}});
    GapOptions opt;
    opt.effects = {Effect::coulomb_friction};
    const GapResult r = diagnose(m, data, nullptr, opt);
    double share = 0;
    for (const auto& b : r.bands) share += b[2];
    EXPECT_NEAR(share, 1.0, 1e-9);
    for (size_t c = 0; c < r.outputs.size(); ++c) {
        double sq = 0;
        for (const auto& b : r.band_nrmse_before) sq += b[c] * b[c];
        EXPECT_NEAR(std::sqrt(sq), r.gap_before[c], 1e-6 * r.gap_before[c]);
    }
}

// A servo axis under a filtered-difference PD clipped to +-10 V (0.5 ms,
// J, b, Ka and the loop of an outside case, not a seed's), its smoothed step
// reference over 5 s, the truth a Stribeck friction whose vs lies above most
// of the record's speeds. Started only from (Fc, Fs, vs) = (0.05, 0.15, 0.1)
// and (0.2, 0.4, 0.3) x (rms u, rms v) the fit ended in the Coulomb solution
// (Fs < Fc) and coulomb_friction was named; the screened grid of starts
// finds it: named first, Fc and Fs within 5 %.
TEST(GapEffects, stribeck_friction_is_found_on_a_servo_under_a_clipped_pd)
{
    const double Ts = 0.0005;
    const nlohmann::json doc = {
        {"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "servo"}, {"time", "discrete"}, {"Ts", Ts},
        {"A", {{1.0, 0.000499765655078018}, {0.0, 0.999062766781736}}}, {"B", {{6.866355852492335e-05}, {0.274611318177814}}},
        {"C", {{1.0, 0.0}, {0.0, 1.0}}}, {"D", {{0.0}, {0.0}}}, {"inputs", {"u"}}, {"outputs", {"theta", "w"}},
        {"gap",
         {{"velocity", "w"}, {"force_input", "u"}, {"initial_state", "at_rest"},
          {"closed_loop",
           {{"references", {"r"}}, {"measured", {"theta"}}, {"saturation", 10.0},
            {"controller",
             {{"time", "discrete"}, {"Ts", Ts}, {"A", {{0.8792480576972133, -241.5038846055735}, {0.0, 0.0}}},
              {"B", {{241.5038846055735, -241.5038846055735}, {1.0, -1.0}}},
              {"C", {{0.0720719410902538, -19.796067323647513}}}, {"D", {{21.6797405150362, -21.6797405150362}}}}}}}}}};
    const NominalModel m = nominal_from_json(doc, Ts);
    const long n = 10000;
    std::vector<double> ref = held_levels(n, 11u, -1.4, 1.4, 600, 1600, 400);
    double s = 0;
    for (double& r : ref) r = s += (r - s) * (1 - std::exp(-Ts / 0.05));  // smoothed steps
    Signals sig;
    sig.source = "stribeck servo";
    sig.names = {"r", "theta", "w"};
    sig.Ts = Ts;
    sig.values = Eigen::MatrixXd::Zero(n, 3);
    for (long k = 0; k < n; ++k) sig.values(k, 0) = ref[size_t(k)];
    const double Fc = 0.33, Fs = 0.627, vs = 3.44;
    const ReplayTrace tr = replay(make_replay_setup(m, sig, {}, {"theta"}), {{Effect::stribeck_friction, {Fc, Fs, vs}}});
    std::mt19937 rng(5);
    std::normal_distribution<double> N01(0.0, 1.0);
    for (long k = 0; k < n; ++k) sig.values(k, 1) = tr.y(k, 0) + 2.4e-5 * N01(rng);
    GapOptions o;
    o.outputs = {"theta"};
    const GapResult r = diagnose(m, sig, nullptr, o);
    ASSERT_FALSE(r.verdict.effects.empty());
    ASSERT_EQ(effect_name(r.verdict.effects[0].kind), "stribeck_friction");
    EXPECT_NEAR(r.verdict.effects[0].params[0], Fc, 0.05 * Fc);
    EXPECT_NEAR(r.verdict.effects[0].params[1], Fs, 0.05 * Fs);
}
