// test_gap_nested_friction.cpp - the nested Coulomb / Stribeck pair
// (which.cpp, docs/gap.md "Nested effects"): a Stribeck fit whose curve does
// not fall (Fs <= Fc) is a Coulomb friction without offset, so the Coulomb
// candidate is never scored worse than it, and a Coulomb machine is named
// coulomb_friction with its level.
// A mass behind an actuator lag, driven by a slow multisine through zero
// velocity; the friction levels are the test's own, drawn over a range that
// puts some of them far from the candidates' starts (a tenth and 0.6 of the
// input's std).
#include <gtest/gtest.h>

#include <random>

#include "fracdesign/gap/diagnosis.hpp"
#include "gap_drive.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 0.002;

nlohmann::json doc()
{
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "lagged_mass"},
            {"time", "continuous"},
            {"A", {{0, 1, 0}, {0, -0.4, 2.0}, {0, 0, -50.0}}},
            {"B", {{0}, {0}, {50.0}}},
            {"C", {{1, 0, 0}, {0, 1, 0}}},
            {"D", {{0}, {0}}},
            {"inputs", {"u"}},
            {"outputs", {"q", "v"}},
            {"gap", {{"velocity", "v"}, {"force_input", "u"}, {"initial_state", {{"given", {0, 0, 0}}}}, {"noise", {{"q", 1e-4}, {"v", 1e-3}}}}}};
}

const FitReport* single(const GapResult& r, Effect e)
{
    for (const FitReport& f : r.candidates)
        if (f.effects.size() == 1 && f.effects[0].kind == e) return &f;
    return nullptr;
}

}  // namespace

TEST(GapNestedFriction, coulomb_is_never_scored_below_a_stribeck_fit_lying_on_it)
{
    const NominalModel m = nominal_from_json(doc(), kTs);
    std::mt19937 rng(20261203);
    std::uniform_real_distribution<double> level(0.05, 1.2), offset(-0.1, 0.1);
    int reached = 0;
    for (int c = 0; c < 4; ++c) {
        Signals s = multisine_record({"u", "q", "v"}, kTs, 4000, {{1.5, 0.4, 0.1}, {0.6, 1.1, 0.9}, {0.3, 2.9, 2.0}});
        const double Fc = level(rng), off = offset(rng);
        const ReplayTrace t =
            replay(make_replay_setup(m, s, {"u"}, {"q", "v"}), {{Effect::coulomb_friction, {Fc, off}}}, s.values.rows());
        std::normal_distribution<double> nq(0.0, 1e-4), nv(0.0, 1e-3);
        for (Eigen::Index k = 0; k < s.values.rows(); ++k) {
            s.values(k, 1) = t.y(k, 0) + nq(rng);
            s.values(k, 2) = t.y(k, 1) + nv(rng);
        }
        GapOptions o;
        o.effects = {Effect::coulomb_friction, Effect::stribeck_friction, Effect::viscous_friction};
        const GapResult r = diagnose(m, s, nullptr, o);
        const FitReport* cf = single(r, Effect::coulomb_friction);
        const FitReport* sf = single(r, Effect::stribeck_friction);
        ASSERT_TRUE(cf && sf) << "case " << c;
        const std::vector<double>& sp = sf->effects[0].params;  // Fc, Fs, vs
        if (sp[1] <= sp[0])
            EXPECT_LE(cf->gap, sf->gap * (1 + 1e-6)) << "case " << c << " Fc " << Fc << " Stribeck Fc " << sp[0] << " Fs "
                                                     << sp[1];
        ASSERT_FALSE(r.verdict.effects.empty()) << "case " << c << " Fc " << Fc;
        // A level near the drive's (the mass sticks most of the record) makes
        // the cost so sharp that no fit reaches the truth's basin (case 3: the
        // cost rises tenfold 0.5 % away from Fc; Coulomb's best fit leaves
        // 357 x the noise floor, a Stribeck fit with vs at its lower bound
        // 157 x). There the claim is an honest status, not the name.
        if (!(cf->gap < 10 * r.noise_floor)) {
            EXPECT_EQ(r.confidence.status, "partly_explained") << "case " << c;
            continue;
        }
        ++reached;
        EXPECT_EQ(r.verdict.effects[0].kind, Effect::coulomb_friction) << "case " << c << " Fc " << Fc;
        if (r.verdict.effects[0].kind == Effect::coulomb_friction)
            EXPECT_NEAR(r.verdict.effects[0].params[0], Fc, 0.05 * Fc) << "case " << c;
    }
    EXPECT_GE(reached, 3);  // cases 0-2
}
