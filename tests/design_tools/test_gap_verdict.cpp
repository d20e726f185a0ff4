// test_gap_verdict.cpp - honest verdicts: a nominal whose replay diverges, a
// constant or overflowing channel are refused with one message naming the
// channel; parameters the record does not identify are flagged; candidates
// the record cannot tell apart are named with the experiment that would.
//
// The plant is a first-order lag v' = -a v + b u with a and b derived here
// (not a seed's), driven open loop by a multisine.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "fracdesign/gap/diagnosis.hpp"
#include "gap_drive.hpp"

using namespace fracdesign::gap;
namespace fs = std::filesystem;

namespace {

const double kTs = 0.01;
const Eigen::Index kN = 2000;
// a = 2 pi x 0.7 Hz corner, b = a x 1.3 (static gain 1.3)
const double kA = 2 * M_PI * 0.7, kB = 1.3 * kA;

nlohmann::json lag_doc(double a)
{
    return {{"schema", "frac.model"}, {"version", 1},       {"kind", "statespace"}, {"name", "lag"},
            {"time", "continuous"},   {"A", {{-a}}},        {"B", {{kB}}},          {"C", {{1.0}}},
            {"D", {{0.0}}},           {"inputs", {"u"}},    {"outputs", {"v"}},
            {"gap", {{"velocity", "v"}, {"force_input", "u"}, {"units", {{"u", "V"}, {"v", "rad/s"}}}}}};
}

// The record: the nominal lag with `truth`, plus 0.3 % noise; the command
// a multisine on `offset`.
Signals record(const std::vector<EffectInstance>& truth, double offset = 0.0)
{
    Signals s = multisine_record({"u", "v"}, kTs, kN, {{1.0, 0.31, 0.0}, {0.6, 1.7, 1.0}, {0.4, 4.3, 2.0}});
    s.values.col(0).array() += offset;
    const NominalModel m = nominal_from_json(lag_doc(kA), kTs);
    const ReplayTrace tr = replay(make_replay_setup(m, s, {}, {"v"}), truth);
    const double sd = std::sqrt((tr.y.col(0).array() - tr.y.col(0).mean()).square().mean());
    std::mt19937 rng(11);
    std::normal_distribution<double> n(0.0, 1.0);
    for (Eigen::Index k = 0; k < kN; ++k) s.values(k, 1) = tr.y(k, 0) + 0.003 * sd * n(rng);
    return s;
}

std::string error_of(const NominalModel& m, const Signals& s, const GapOptions& o)
{
    try {
        diagnose(m, s, nullptr, o);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

GapOptions few(std::vector<Effect> e)
{
    GapOptions o;
    o.effects = std::move(e);
    return o;
}

}  // namespace

TEST(GapVerdict, refuses_a_nominal_whose_replay_diverges)
{
    // A = [[+50]]: the replay grows as e^{50 t}.
    const NominalModel m = nominal_from_json(lag_doc(-50.0), kTs);
    const std::string err = error_of(m, record({}), few({Effect::coulomb_friction}));
    EXPECT_NE(err.find("diverges"), std::string::npos) << err;
    EXPECT_NE(err.find("'v'"), std::string::npos) << err;
    EXPECT_NE(err.find("unstable"), std::string::npos) << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
}

TEST(GapVerdict, cli_exits_non_zero_on_a_diverging_nominal_and_writes_nothing)
{
    const fs::path d = fs::temp_directory_path() / "gap_verdict_cli";
    fs::remove_all(d);
    fs::create_directories(d);
    std::ofstream(d / "model.json") << lag_doc(-50.0).dump();
    const Signals s = record({});
    {
        std::ofstream c(d / "run.csv");
        c << "t,u,v\n";
        c.precision(17);
        for (Eigen::Index k = 0; k < s.samples(); ++k) c << double(k) * kTs << "," << s.values(k, 0) << "," << s.values(k, 1) << "\n";
    }
    const std::string cmd = std::string(FRACDESIGN_EXE) + " gap --model " + (d / "model.json").string() + " --data " +
                            (d / "run.csv").string() + " --effects coulomb_friction --out " + (d / "out").string() +
                            " 2> " + (d / "err.txt").string() + " > /dev/null";
    const int rc = std::system(cmd.c_str());
    EXPECT_NE(rc, 0);
    std::ifstream e(d / "err.txt");
    const std::string err((std::istreambuf_iterator<char>(e)), std::istreambuf_iterator<char>());
    EXPECT_NE(err.find("diverges"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(d / "out"));
    fs::remove_all(d);
}

TEST(GapVerdict, refuses_a_constant_output_channel_by_name)
{
    const NominalModel m = nominal_from_json(lag_doc(kA), kTs);
    Signals s = record({});
    s.values.col(1).setConstant(0.25);
    const std::string err = error_of(m, s, few({Effect::gain_error}));
    EXPECT_NE(err.find("'v'"), std::string::npos) << err;
    EXPECT_NE(err.find("constant"), std::string::npos) << err;
}

TEST(GapVerdict, refuses_an_overflowing_sample_by_name)
{
    const NominalModel m = nominal_from_json(lag_doc(kA), kTs);
    Signals s = record({});
    s.values(700, 1) = 1e308;
    const std::string err = error_of(m, s, few({Effect::gain_error}));
    EXPECT_NE(err.find("'v'"), std::string::npos) << err;
    EXPECT_NE(err.find("overflow"), std::string::npos) << err;
    EXPECT_NE(err.find("t = 7"), std::string::npos) << err;
}

TEST(GapVerdict, flags_a_parameter_at_its_bound_and_not_the_true_effects)
{
    // Viscous friction Fv = 0.35 a (in the lag's force units per velocity);
    // the backlash candidate, fitted on a record without one, has its width
    // at its lower bound 0. (The dead-zone candidate is no such case since
    // its edges are signed: it mimics part of the friction with edges of
    // -0.211 +- 0.003 and 0.213 +- 0.003, not at 0; the old "0.1 % of the
    // range" rule flagged them, and arm_b's Coulomb 5.93 +- 0.001, falsely.)
    const double Fv = 0.35 * kA / kB;
    const NominalModel m = nominal_from_json(lag_doc(kA), kTs);
    const GapResult r = diagnose(m, record({{Effect::viscous_friction, {Fv}}}), nullptr,
                                 few({Effect::viscous_friction, Effect::backlash, Effect::deadzone}));
    ASSERT_EQ(r.verdict.effects.size(), 1u);
    EXPECT_EQ(r.verdict.effects[0].kind, Effect::viscous_friction);
    EXPECT_NEAR(r.verdict.effects[0].params[0], Fv, 0.05 * Fv);
    EXPECT_TRUE(r.verdict.identification[0][0].identified()) << r.verdict.identification[0][0].text;
    bool seen = false;
    for (const FitReport& c : r.candidates) {
        if (c.effects.size() != 1) continue;
        if (c.effects[0].kind == Effect::backlash) {
            seen = true;
            EXPECT_EQ(c.identification[0][0].why, Unidentified::lower_bound) << c.identification[0][0].text;
            EXPECT_NE(c.identification[0][0].text.find("lower bound 0"), std::string::npos) << c.identification[0][0].text;
        }
        if (c.effects[0].kind == Effect::deadzone)  // well-determined edges off their bound 0 are identified
            for (size_t z = 0; z < 2; ++z)
                if (std::fabs(c.effects[0].params[z]) > 5 * c.stddev[0][z])
                    EXPECT_TRUE(c.identification[0][z].identified()) << c.identification[0][z].text;
    }
    EXPECT_TRUE(seen);
    const nlohmann::json j = result_json(r);
    EXPECT_EQ(j["verdict"]["params_unit"]["Fv"], "V/(rad/s)");
    EXPECT_TRUE(j["verdict"]["unidentified"].empty());
    EXPECT_TRUE(j["verdict"]["unidentified_kind"].empty());
}

TEST(GapVerdict, names_input_and_output_delay_as_look_alikes_in_open_loop)
{
    // Open loop on a linear one-output plant an input delay and an output
    // delay are the same map: the verdict must say so and name the experiment.
    const double d = 7 * kTs;
    const NominalModel m = nominal_from_json(lag_doc(kA), kTs);
    const GapResult r = diagnose(m, record({{Effect::input_delay, {d}}}), nullptr,
                                 few({Effect::input_delay, Effect::output_delay, Effect::gain_error}));
    ASSERT_FALSE(r.verdict.effects.empty());
    const std::string first = effect_name(r.verdict.effects[0].kind);
    EXPECT_TRUE(first == "input_delay" || first == "output_delay") << first;
    ASSERT_EQ(r.confidence.look_alikes.size(), 1u);
    const std::string other = first == "input_delay" ? "output_delay" : "input_delay";
    EXPECT_EQ(r.confidence.look_alikes[0].effect, other);
    EXPECT_NE(r.confidence.look_alikes[0].experiment.find("closed-loop"), std::string::npos);
    EXPECT_EQ(r.confidence.runner_up, other);
    EXPECT_LT(r.confidence.margin, 0.01);
    const nlohmann::json j = result_json(r);
    EXPECT_EQ(j["verdict"]["confidence"]["look_alikes"][0]["effect"], other);
}

TEST(GapVerdict, a_clear_verdict_has_no_look_alike_and_a_margin)
{
    const NominalModel m = nominal_from_json(lag_doc(kA), kTs);
    const GapResult r = diagnose(m, record({{Effect::gain_error, {1.25}}}), nullptr,
                                 few({Effect::gain_error, Effect::saturation, Effect::deadzone}));
    ASSERT_FALSE(r.verdict.effects.empty());
    EXPECT_EQ(r.verdict.effects[0].kind, Effect::gain_error);
    EXPECT_TRUE(r.confidence.look_alikes.empty());
    EXPECT_GT(r.confidence.margin, 0.05);
    // Without gap.noise: explained when the verdict removes >= kExplainedShrink.
    EXPECT_GE(r.verdict.shrink, kExplainedShrink);
    EXPECT_EQ(r.confidence.status, "explained");
}

namespace {

// The lag's document stating the record's sensor noise (gap.noise): the
// record()'s 0.3 % of the output's std, computed from the record itself.
nlohmann::json lag_doc_with_noise(const Signals& s)
{
    const Eigen::VectorXd v = s.values.col(1);
    const double sd = std::sqrt((v.array() - v.mean()).square().mean());
    nlohmann::json d = lag_doc(kA);
    d["gap"]["noise"] = {{"v", 0.003 * sd}};
    return d;
}

}  // namespace

TEST(GapVerdict, status_says_at_noise_floor_unexplained_partly_explained_and_no_candidate)
{
    // A clean record with the noise stated: at the floor, none.
    {
        const Signals s = record({});
        const GapResult r = diagnose(nominal_from_json(lag_doc_with_noise(s), kTs), s, nullptr, few({Effect::gain_error}));
        EXPECT_TRUE(r.verdict.effects.empty());
        EXPECT_EQ(r.confidence.status, "at_noise_floor") << r.confidence.explanation;
    }
    // A delay no candidate can take (only saturation tried), the noise
    // stated: none, but the gap is far above the floor: unexplained, with
    // the ratio in the sentence. Without gap.noise: no_candidate.
    {
        const Signals s = record({{Effect::input_delay, {9 * kTs}}});
        const GapResult r = diagnose(nominal_from_json(lag_doc_with_noise(s), kTs), s, nullptr, few({Effect::saturation}));
        EXPECT_TRUE(r.verdict.effects.empty());
        EXPECT_GT(r.gap_before_total, 10 * r.noise_floor_limit);
        EXPECT_EQ(r.confidence.status, "unexplained") << r.confidence.explanation;
        EXPECT_NE(r.confidence.explanation.find("noise floor"), std::string::npos);
        const GapResult q = diagnose(nominal_from_json(lag_doc(kA), kTs), s, nullptr, few({Effect::saturation}));
        EXPECT_TRUE(q.verdict.effects.empty());
        EXPECT_EQ(q.confidence.status, "no_candidate") << q.confidence.explanation;
        EXPECT_EQ(result_json(q)["verdict"]["confidence"]["status"], "no_candidate");
    }
    // A gain error and a delay, only the gain tried, the noise stated: the
    // gain is found but leaves the delay's part above the floor.
    {
        const Signals s = record({{Effect::gain_error, {1.4}}, {Effect::input_delay, {6 * kTs}}});
        const GapResult r = diagnose(nominal_from_json(lag_doc_with_noise(s), kTs), s, nullptr, few({Effect::gain_error}));
        ASSERT_FALSE(r.verdict.effects.empty());
        EXPECT_GT(r.verdict.gap, r.noise_floor_limit);
        EXPECT_EQ(r.confidence.status, "partly_explained") << r.confidence.explanation;
    }
}

TEST(GapVerdict, fracdesign_prints_its_version)
{
    const fs::path out = fs::temp_directory_path() / "fracdesign_version.txt";
    ASSERT_EQ(std::system((std::string(FRACDESIGN_EXE) + " --version > " + out.string()).c_str()), 0);
    std::ifstream in(out);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line.rfind("fracdesign ", 0), 0u) << line;
    EXPECT_NE(line.find('.'), std::string::npos) << line;
    fs::remove(out);
}

TEST(GapVerdict, candidate_fits_give_the_same_result_on_one_and_on_two_threads)
{
    const NominalModel m = nominal_from_json(lag_doc(kA), kTs);
    const Signals s = record({{Effect::coulomb_friction, {0.08, 0.0}}, {Effect::input_delay, {3 * kTs}}});
    GapOptions o;
    o.effects = {Effect::coulomb_friction, Effect::viscous_friction, Effect::input_delay, Effect::gain_error,
                 Effect::deadzone, Effect::sensor_offset};
    o.threads = 1;
    nlohmann::json one = result_json(diagnose(m, s, nullptr, o));
    o.threads = 2;
    int lines = 0;
    o.progress = [&](const std::string&) { ++lines; };
    nlohmann::json two = result_json(diagnose(m, s, nullptr, o));
    // One per fit: the six effects, the dead zone's symmetric restriction and
    // Coulomb's without offset (EffectDescriptor::nested), and one per
    // continued fit (which.cpp).
    EXPECT_EQ(lines, 8 + two["data"]["continued_candidates"].get<int>());
    // Two effects: the forward selection's trial sets, its backward step's
    // drops and the look-alike swaps ran on the workers too (how_far.cpp).
    EXPECT_EQ(two["verdict"]["effects"].size(), 2u) << two["verdict"]["effects"].dump();
    one.erase("seconds");
    two.erase("seconds");
    EXPECT_EQ(one.dump(), two.dump());
}

TEST(GapVerdict, flags_a_limit_edge_the_command_never_reaches)
{
    // The command is the multisine on an offset of 1 (its least value is
    // derived below, about -0.9): a true upper limit of 0.6 of its largest
    // value clips it, a true lower limit of 3 x its least value is never
    // reached. The record identifies the upper edge only; the lower edge,
    // whether fitted alone or mirrored by the symmetric fit, must be flagged.
    const double off = 1.0;
    const Signals probe = record({}, off);
    const double umin = probe.values.col(0).minCoeff(), umax = probe.values.col(0).maxCoeff();
    ASSERT_LT(umin, 0.0);
    const double lower = 3 * umin, upper = 0.6 * umax;
    // The symmetric fit's mirrored edge -upper lies below the command too, so
    // it replays the record exactly with one parameter fewer and wins.
    ASSERT_GT(upper, -umin);
    const NominalModel m = nominal_from_json(lag_doc(kA), kTs);
    const GapResult r = diagnose(m, record({{Effect::saturation, {lower, upper}}}, off), nullptr, few({Effect::saturation, Effect::gain_error}));
    ASSERT_FALSE(r.verdict.effects.empty());
    ASSERT_EQ(r.verdict.effects[0].kind, Effect::saturation);
    EXPECT_NEAR(r.verdict.effects[0].params[1], upper, 0.02 * upper);
    EXPECT_TRUE(r.verdict.identification[0][1].identified()) << r.verdict.identification[0][1].text;
    EXPECT_EQ(r.verdict.identification[0][0].why, Unidentified::never_reached) << r.verdict.identification[0][0].text;
    EXPECT_EQ(r.verdict.identification[0][0].text.rfind("never reached", 0), 0u) << r.verdict.identification[0][0].text;
    // The fitted lower edge, if the fit put it inside the command's range,
    // would clip the record: it lies below the command's least value.
    EXPECT_LT(r.verdict.effects[0].params[0], umin + 0.02 * std::fabs(umin));
    const nlohmann::json j = result_json(r);
    EXPECT_TRUE(j["verdict"]["unidentified"].contains("lower"));
    EXPECT_EQ(j["verdict"]["unidentified_kind"]["lower"], "never_reached");
    EXPECT_FALSE(j["verdict"]["unidentified_kind"].contains("upper"));
    EXPECT_EQ(r.confidence.status, "explained");
    EXPECT_NE(r.confidence.explanation.find("1 of its 2 parameters are not identified"), std::string::npos) << r.confidence.explanation;
}

TEST(GapVerdict, coulomb_and_stribeck_hold_the_same_term)
{
    // Forward selection (how_far.cpp) never adds one of these to a set
    // holding the other: Stribeck contains Coulomb's Fc sgn(v).
    EXPECT_TRUE(same_term(Effect::coulomb_friction, Effect::stribeck_friction));
    EXPECT_TRUE(same_term(Effect::stribeck_friction, Effect::coulomb_friction));
    EXPECT_FALSE(same_term(Effect::coulomb_friction, Effect::coulomb_friction));
    EXPECT_FALSE(same_term(Effect::coulomb_friction, Effect::viscous_friction));
    EXPECT_FALSE(same_term(Effect::stribeck_friction, Effect::viscous_friction));
    EXPECT_FALSE(same_term(Effect::input_delay, Effect::output_delay));
    // With the sites: fractional damping to ground holds viscous friction
    // (its alpha = 1 end), either way round; in a coupling's spring it is
    // another term, and the site-free pairs stay as they are.
    const Site F = Site::force_input, K = Site::coupling;
    EXPECT_TRUE(same_term(Effect::fractional_damping, F, Effect::viscous_friction, F));
    EXPECT_TRUE(same_term(Effect::viscous_friction, F, Effect::fractional_damping, F));
    EXPECT_FALSE(same_term(Effect::fractional_damping, K, Effect::viscous_friction, F));
    EXPECT_FALSE(same_term(Effect::viscous_friction, F, Effect::fractional_damping, K));
    EXPECT_TRUE(same_term(Effect::coulomb_friction, F, Effect::stribeck_friction, F));
    EXPECT_FALSE(same_term(Effect::fractional_damping, F, Effect::coulomb_friction, F));
    EXPECT_FALSE(same_term(Effect::fractional_damping, F, Effect::fractional_damping, F));
}
