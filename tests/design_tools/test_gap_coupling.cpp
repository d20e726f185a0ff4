// test_gap_coupling.cpp - effects in a declared spring (gap.coupling): a play
// and Kelvin-Voigt fractional damping in the gear of a two-mass drive.
//
// Plant: motor inertia I_M and link inertia I_L joined by a spring k (the
// seed 004 two-mass structure (4.8)-(4.12) at a smaller scale), torque on the
// motor, outputs motor and link velocity; the spring is declared as
// gap.coupling (docs/gap.md). The reference for the play is an RK4
// integration with 64 sub-steps per sample of the same plant with the spring
// torque k dz(q) (q = theta_M - psi), torque held over each sample (the
// zero-order hold of the nominal's discretisation).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "fracdesign/gap/diagnosis.hpp"
#include "gap_drive.hpp"

using namespace fracdesign::gap;

namespace {

// Gear mode sqrt(k (1/I_M + 1/I_L)) = 5.5 Hz, damped 5 % by d (a play in an
// undamped gear rattles for ever, and its contacts then depend on the last
// digit), and motor damping b.
const double kTs = 0.01, kIM = 1.0, kIL = 0.5, kK = 400.0, kD = 1.15, kB = 0.5;
const Eigen::Index kN = 3000;

nlohmann::json plant_doc()
{
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "two_mass"},
            {"time", "continuous"},
            {"A",
             {{0, 1, 0, 0},
              {-kK / kIM, -(kD + kB) / kIM, kK / kIM, kD / kIM},
              {0, 0, 0, 1},
              {kK / kIL, kD / kIL, -kK / kIL, -kD / kIL}}},
            {"B", {{0}, {1 / kIM}, {0}, {0}}},
            {"C", {{0, 1, 0, 0}, {0, 0, 0, 1}}},
            {"D", {{0}, {0}}},
            {"inputs", {"u"}},
            {"outputs", {"wm", "wl"}},
            {"gap",
             {{"force_input", "u"},
              {"coupling",
               {{"name", "gear"}, {"twist", {1, 0, -1, 0}}, {"torque", {0, -1 / kIM, 0, 1 / kIL}}, {"stiffness", kK}}}}}};
}

// Torque with reversals: the gear crosses its play both ways.
Signals drive()
{
    return multisine_record({"u", "wm", "wl"}, kTs, kN, {{4.0, 0.37, 0.0}, {2.0, 1.3, 1.0}, {1.0, 3.1, 2.0}});
}

// RK4 reference with a play of width w in the spring; returns [wm, wl] per sample
// (the state at the sample, before that sample's torque acts).
Eigen::MatrixXd play_reference(const Signals& s, double w)
{
    const double h = 0.5 * w;
    auto f = [&](const Eigen::Vector4d& x, double u) {
        const double q = x(0) - x(2);
        const double sp = kK * (q > h ? q - h : (q < -h ? q + h : 0.0)) + kD * (x(1) - x(3));
        return Eigen::Vector4d(x(1), (u - sp - kB * x(1)) / kIM, x(3), sp / kIL);
    };
    Eigen::Vector4d x = Eigen::Vector4d::Zero();
    Eigen::MatrixXd y(kN, 2);
    const int m = 64;
    const double dt = kTs / m;
    for (Eigen::Index k = 0; k < kN; ++k) {
        y(k, 0) = x(1);
        y(k, 1) = x(3);
        const double u = s.values(k, 0);
        for (int i = 0; i < m; ++i) {
            const Eigen::Vector4d k1 = f(x, u), k2 = f(x + 0.5 * dt * k1, u), k3 = f(x + 0.5 * dt * k2, u),
                                  k4 = f(x + dt * k3, u);
            x += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        }
    }
    return y;
}

double rms(const Eigen::MatrixXd& e) { return std::sqrt(e.squaredNorm() / double(e.size())); }

std::string load_error(const nlohmann::json& doc)
{
    try {
        nominal_from_json(doc, kTs);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(GapCoupling, zero_play_and_zero_damping_replay_the_nominal)
{
    const NominalModel m = nominal_from_json(plant_doc(), kTs);
    ASSERT_EQ(m.couplings.size(), 1u);
    const ReplaySetup s = make_replay_setup(m, drive(), {}, {"wm", "wl"});
    const ReplayTrace nom = replay(s, {});
    const ReplayTrace zero = replay(s, {{Effect::backlash, {0.0}, Site::coupling}, {Effect::fractional_damping, {0.0, 0.5}, Site::coupling}});
    EXPECT_LT((zero.y - nom.y).cwiseAbs().maxCoeff(), 1e-9 * nom.y.cwiseAbs().maxCoeff());
    // The deflection the replay reports is theta_M - psi.
    EXPECT_GT(nom.twist.cwiseAbs().maxCoeff(), 0.0);
}

TEST(GapCoupling, the_sub_stepped_play_follows_a_fine_rk4_reference)
{
    const NominalModel m = nominal_from_json(plant_doc(), kTs);
    const Signals s = drive();
    const ReplaySetup setup = make_replay_setup(m, s, {}, {"wm", "wl"});
    const double w = 0.02;  // about twice the largest nominal deflection
    const Eigen::MatrixXd ref = play_reference(s, w), ref0 = play_reference(s, 0.0);
    const ReplayTrace nom = replay(setup, {});
    const ReplayTrace pl = replay(setup, {{Effect::backlash, {w}, Site::coupling}});
    // Without the play the reference is the nominal (RK4 vs the exact ZOH model).
    EXPECT_LT(rms(ref0 - nom.y), 1e-6 * rms(nom.y));
    // With it: the replay's error is a small part of the play's effect.
    const double effect = rms(ref - ref0), err = rms(ref - pl.y);
    EXPECT_GT(effect, 0.05 * rms(ref0));
    EXPECT_LT(err, 0.05 * effect) << "effect " << effect << " error " << err;
}

TEST(GapCoupling, kelvin_voigt_damping_in_the_gear_damps_the_gear_mode)
{
    const NominalModel m = nominal_from_json(plant_doc(), kTs);
    Signals s = drive();
    s.values.col(0).setZero();
    for (Eigen::Index k = 10; k < 13; ++k) s.values(k, 0) = 10.0;  // a torque pulse rings the gear mode
    const ReplaySetup setup = make_replay_setup(m, s, {}, {"wm", "wl"});
    const ReplayTrace nom = replay(setup, {});
    // c D^0.5 at the gear mode (34.6 rad/s) acts as a viscous d = c w^-0.5
    // sin(pi/4) = 6 Nm s/rad, five times the nominal gear damping.
    const ReplayTrace kv = replay(setup, {{Effect::fractional_damping, {50.0, 0.5}, Site::coupling}});
    const Eigen::Index a = 60, n = 100;  // 0.5 .. 1.5 s after the pulse
    const double ring_nom = nom.twist.segment(a, n).cwiseAbs().maxCoeff(), ring_kv = kv.twist.segment(a, n).cwiseAbs().maxCoeff();
    EXPECT_GT(ring_nom, 1e-3);
    EXPECT_LT(ring_kv, 0.1 * ring_nom) << ring_nom << " " << ring_kv;
    // A damping in the gear only: the link's velocity follows the nominal's rigid-body motion.
    const Eigen::VectorXd lag = (kv.y.col(1) - nom.y.col(1)).segment(a, n);
    EXPECT_LT(std::fabs(lag.mean()), 0.05 * nom.y.col(1).segment(a, n).cwiseAbs().maxCoeff());
}

TEST(GapCoupling, a_gear_play_is_found_in_the_coupling_with_its_width)
{
    const NominalModel m = nominal_from_json(plant_doc(), kTs);
    Signals s = drive();
    const double w = 0.015;
    const Eigen::MatrixXd ref = play_reference(s, w);
    std::mt19937 rng(11);
    std::normal_distribution<double> n(0.0, 1.0);
    for (int c = 0; c < 2; ++c) {
        const double sd = std::sqrt((ref.col(c).array() - ref.col(c).mean()).square().mean());
        for (Eigen::Index k = 0; k < kN; ++k) s.values(k, c + 1) = ref(k, c) + 0.002 * sd * n(rng);
    }
    const GapResult r = diagnose(m, s, nullptr, GapOptions());
    ASSERT_FALSE(r.verdict.effects.empty());
    EXPECT_EQ(effect_name(r.verdict.effects[0].kind), "backlash");
    EXPECT_TRUE(r.verdict.effects[0].site == Site::coupling);
    EXPECT_NEAR(r.verdict.effects[0].params[0], w, 0.1 * w);
    EXPECT_GE(r.verdict.shrink, 0.8);
    const nlohmann::json j = result_json(r);
    EXPECT_EQ(j["verdict"]["sites"][0], "coupling");
}

TEST(GapCoupling, malformed_couplings_are_refused_with_one_message_each)
{
    auto with = [](const char* key, const nlohmann::json& v) {
        nlohmann::json d = plant_doc();
        d["gap"]["coupling"][key] = v;
        return d;
    };
    nlohmann::json no_k = plant_doc();
    no_k["gap"]["coupling"].erase("stiffness");
    EXPECT_NE(load_error(with("twist", {1, 0, -1})).find("'twist' must list 4 numbers"), std::string::npos);
    EXPECT_NE(load_error(with("torque", {0, 0, 0, 0})).find("'torque' is all zero"), std::string::npos);
    EXPECT_NE(load_error(with("twist", {1, 0, "x", 0})).find("non-numeric"), std::string::npos);
    EXPECT_NE(load_error(no_k).find("missing number 'stiffness'"), std::string::npos);
    EXPECT_NE(load_error(with("stiffness", -1.0)).find("'stiffness' must be a finite number > 0"), std::string::npos);
    EXPECT_NE(load_error(with("states", {0, 1, 7})).find("'states' entries must be integers in [0, 3]"), std::string::npos);
    EXPECT_NE(load_error(with("states", {0, 1, 1, 2})).find("twice"), std::string::npos);
    EXPECT_NE(load_error(with("states", {0, 1})).find("must vanish outside 'states'"), std::string::npos);
    EXPECT_NE(load_error(with("substeps", 0)).find("'substeps' must be in [1, 256]"), std::string::npos);
    // A discrete plant with a pure delay state: its block has no logarithm
    // unless 'states' leaves the delay out.
    nlohmann::json d = plant_doc();
    d["time"] = "discrete";
    d["Ts"] = kTs;
    d["A"] = {{1, kTs, 0}, {0, 1, 0}, {0, 1, 0}};
    d["B"] = {{0}, {kTs}, {0}};
    d["C"] = {{0, 1, 0}, {0, 0, 1}};
    d["gap"]["coupling"] = {{"twist", {1, 0, 0}}, {"torque", {0, kTs, 0}}, {"stiffness", 1.0}};
    EXPECT_NE(load_error(d).find("no real matrix logarithm"), std::string::npos) << load_error(d);
    d["gap"]["coupling"]["states"] = {0, 1};
    EXPECT_EQ(load_error(d), "");
}
