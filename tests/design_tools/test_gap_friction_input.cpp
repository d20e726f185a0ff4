// test_gap_friction_input.cpp - gap.friction_input (docs/gap.md "What the
// document states"): friction acts on the named plant input, not on
// force_input, and that input needs no record column (open loop).
// A mass driven through an actuator lag (input u) with a second input f
// straight on the mass; parameters are the test's own.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fracdesign/gap/diagnosis.hpp"
#include "gap_drive.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 0.002;

// states [position, velocity, actuator torque]; u drives the actuator lag (0.02 s), f the mass;
// f_on_mass scales f's column (1: direct, 0: f reaches nothing).
nlohmann::json doc(const nlohmann::json& gap, double f_on_mass = 1.0)
{
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "lagged_mass"},
            {"time", "continuous"},
            {"A", {{0, 1, 0}, {0, -0.4, 2.0}, {0, 0, -50.0}}},
            {"B", {{0, 0}, {0, 2.0 * f_on_mass}, {50.0, 0}}},
            {"C", {{1, 0, 0}, {0, 1, 0}}},
            {"D", {{0, 0}, {0, 0}}},
            {"inputs", {"u", "f"}},
            {"outputs", {"q", "v"}},
            {"gap", gap}};
}

// `f_column`: the record has a (zero) column f, which an ordinary input needs.
Eigen::MatrixXd replayed(const nlohmann::json& d, double Fc, bool f_column = false)
{
    const std::vector<std::string> cols = f_column ? std::vector<std::string>{"u", "q", "v", "f"}
                                                   : std::vector<std::string>{"u", "q", "v"};
    const Signals s = multisine_record(cols, kTs, 2000, {{3.0, 0.7, 0.1}, {1.5, 2.3, 0.9}});
    const NominalModel m = nominal_from_json(d, kTs);
    std::vector<EffectInstance> e;
    if (Fc > 0) e.push_back({Effect::coulomb_friction, {Fc, 0.0}});
    return replay(make_replay_setup(m, s, {"u", "f"}, {"q", "v"}), e).y;
}

}  // namespace

TEST(GapFrictionInput, friction_acts_on_the_named_input_which_needs_no_column)
{
    const nlohmann::json base = {{"velocity", "v"}, {"force_input", "u"}, {"initial_state", {{"given", {0, 0, 0}}}}};
    nlohmann::json direct = base, nowhere = base;
    direct["friction_input"] = "f";
    nowhere["friction_input"] = "f";
    const Eigen::MatrixXd free = replayed(doc(direct), 0.0);
    // through f's direct column the friction moves the mass ...
    EXPECT_GT((replayed(doc(direct), 0.8) - free).cwiseAbs().maxCoeff(), 1e-3);
    // ... through a zero column it moves nothing ...
    EXPECT_LT((replayed(doc(nowhere, 0.0), 0.8) - replayed(doc(nowhere, 0.0), 0.0)).cwiseAbs().maxCoeff(), 1e-15);
    // ... and at force_input (default) it acts behind the actuator lag: another response
    EXPECT_GT((replayed(doc(base), 0.8, true) - replayed(doc(direct), 0.8)).cwiseAbs().maxCoeff(), 1e-4);
    // an ordinary input (friction at force_input) still needs its column
    EXPECT_THROW(replayed(doc(base), 0.8), std::runtime_error);
}

TEST(GapFrictionInput, an_input_the_model_lacks_is_refused_naming_the_field)
{
    try {
        nominal_from_json(doc({{"velocity", "v"}, {"friction_input", "tau"}}), kTs);
        FAIL() << "accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("model gap.friction_input: is \"tau\", must be the name of a model input"),
                  std::string::npos)
            << e.what();
    }
}

// The friction's scale (FitContext::Sf, where.cpp friction_scale): the drive
// u reaches the mass through an actuator of DC gain 1e-4 (u in units 10^4 x
// smaller than f's), so a friction of 2 % of the force the drive's rms
// command makes is 2e-6 rms(u) in numbers. Started in rms(u) (1/1024 ..
// 1/2), the smallest level is above any force the actuator makes: the mass
// never moves, the cost is flat, and gain_error was named; started in the
// friction input's own scale the friction is found.
TEST(GapFrictionInput, friction_in_the_friction_inputs_units_is_found_whatever_the_drives_units)
{
    const double kGain = 1e-4;
    nlohmann::json d = doc({{"velocity", "v"}, {"force_input", "u"}, {"friction_input", "f"},
                            {"initial_state", {{"given", {0, 0, 0}}}}});
    d["B"][2][0] = 50.0 * kGain;
    Signals s = multisine_record({"u", "q", "v"}, kTs, 4000, {{3.0 / kGain, 0.37, 0.1}, {1.5 / kGain, 1.3, 0.9}});
    const NominalModel m = nominal_from_json(d, kTs);
    double su = 0;
    for (Eigen::Index k = 0; k < s.samples(); ++k) su += s.values(k, 0) * s.values(k, 0);
    su = std::sqrt(su / double(s.samples()));
    const double Fc = 0.02 * kGain * su;  // the actuator's DC gain is kGain; 2 % of its rms force
    const ReplayTrace tr = replay(make_replay_setup(m, s, {"u", "f"}, {"q", "v"}), {{Effect::coulomb_friction, {Fc, 0.0}}});
    std::mt19937 rng(3);
    std::normal_distribution<double> n01(0.0, 1.0);
    for (Eigen::Index k = 0; k < s.samples(); ++k) {
        s.values(k, 1) = tr.y(k, 0) + 1e-5 * n01(rng);
        s.values(k, 2) = tr.y(k, 1) + 1e-4 * n01(rng);
    }
    GapOptions o;
    o.effects = {Effect::coulomb_friction, Effect::viscous_friction, Effect::gain_error};
    const GapResult r = diagnose(m, s, nullptr, o);
    ASSERT_FALSE(r.verdict.effects.empty()) << r.confidence.explanation;
    ASSERT_EQ(effect_name(r.verdict.effects[0].kind), "coulomb_friction") << r.confidence.explanation;
    EXPECT_NEAR(r.verdict.effects[0].params[0], Fc, 0.05 * Fc);
}
