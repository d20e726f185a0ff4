// test_gap_where.cpp - the time windows of the gap diagnosis carry the
// operating condition of the nominal replay there (docs/gap.md "Where").
//
// Open-loop mass-damper v' = u - v, x' = v at Ts = 0.01 s over 40 s (40
// windows of 1 s). The input makes a standstill (0-5 s), steady motion, a
// velocity reversal at 15 s and the largest force, a short pulse of
// u = 3 at 30-31 s. The "measured" record is the nominal replay plus a 5 Hz
// burst in four windows; each burst's window must be flagged with its
// condition.
#include <gtest/gtest.h>

#include <cmath>

#include "fracdesign/gap/diagnosis.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 0.01;
const Eigen::Index kN = 4000;

// A unit mass x'' = u + a21 x + a22 x' (outputs x and v), open loop.
nlohmann::json second_order_doc(const char* name, double a21, double a22)
{
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", name},
            {"time", "continuous"},
            {"A", {{0.0, 1.0}, {a21, a22}}},
            {"B", {{0.0}, {1.0}}},
            {"C", {{1.0, 0.0}, {0.0, 1.0}}},
            {"D", {{0.0}, {0.0}}},
            {"inputs", {"u"}},
            {"outputs", {"x", "v"}},
            {"gap", {{"velocity", "v"}, {"force_input", "u"}}}};
}

nlohmann::json model_doc() { return second_order_doc("mass_damper", 0.0, -1.0); }

double input(double t)
{
    if (t < 5) return 0.0;
    if (t < 15) return 1.0;
    if (t < 25) return -1.0;
    if (t >= 30 && t < 31) return 3.0;
    return 0.0;
}

const Window* window_at(const GapResult& r, double t)
{
    for (const Window& w : r.windows)
        if (w.t0 <= t && t < w.t1) return &w;
    return nullptr;
}

}  // namespace

TEST(GapWhere, windows_are_labelled_with_standstill_reversal_acceleration_and_torque_limit)
{
    const NominalModel m = nominal_from_json(model_doc(), kTs);
    Signals s;
    s.source = "synthetic";
    s.names = {"u", "x", "v"};
    s.Ts = kTs;
    s.values = Eigen::MatrixXd::Zero(kN, 3);
    for (Eigen::Index k = 0; k < kN; ++k) s.values(k, 0) = input(double(k) * kTs);
    const ReplayTrace nom = replay(make_replay_setup(m, s, {}, {"x", "v"}), {});
    const double bursts[] = {2.0, 15.0, 30.0, 10.0};
    for (Eigen::Index k = 0; k < kN; ++k) {
        const double t = double(k) * kTs;
        double b = 0;
        for (double c : bursts)
            if (t >= c + 0.2 && t < c + 0.8) b = 0.05 * std::sin(2 * M_PI * 5 * t);
        s.values(k, 1) = nom.y(k, 0);
        s.values(k, 2) = nom.y(k, 1) + b;
    }
    GapOptions opt;
    opt.effects = {Effect::gain_error};
    const GapResult r = diagnose(m, s, nullptr, opt);
    const struct {
        double t;
        const char* label;
    } want[] = {{2.5, "standstill"},
                {15.5, "velocity reversal"},
                {15.5, "high acceleration"},
                {30.5, "near torque limit"},
                {30.5, "high acceleration"},
                {10.5, "steady motion"}};
    for (const auto& w : want) {
        const Window* win = window_at(r, w.t);
        ASSERT_NE(win, nullptr) << "no flagged window at " << w.t << " s";
        EXPECT_NE(win->condition.find(w.label), std::string::npos) << w.t << " s: " << win->condition;
    }
    EXPECT_EQ(window_at(r, 2.5)->condition.find("reversal"), std::string::npos);
    EXPECT_EQ(window_at(r, 10.5)->condition, "steady motion");
    EXPECT_EQ(window_at(r, 20.5), nullptr);  // no burst, no flag
}

namespace {

// Mass-spring-damper x'' = u - 2 zeta w x' - w^2 x (outputs x and v), open
// loop, at Ts = 0.01 s.
nlohmann::json msd_doc(double f_hz, double zeta)
{
    const double w = 2 * M_PI * f_hz;
    return second_order_doc("msd", -w * w, -2 * zeta * w);
}

// The nominal (2 Hz, zeta 0.05) checked against a record of the "true" plant,
// driven by a broadband input (a sum of 200 sines, 0.05-20 Hz).
ModeCheck check_against(double f_true, double zeta_true)
{
    const NominalModel nominal = nominal_from_json(msd_doc(2.0, 0.05), kTs), truth = nominal_from_json(msd_doc(f_true, zeta_true), kTs);
    Signals s;
    s.source = "synthetic";
    s.names = {"u", "x", "v"};
    s.Ts = kTs;
    s.values = Eigen::MatrixXd::Zero(kN, 3);
    for (Eigen::Index k = 0; k < kN; ++k)
        for (int i = 1; i <= 200; ++i) s.values(k, 0) += std::sin(2 * M_PI * 0.1 * i * double(k) * kTs + 0.37 * i * i);
    const ReplayTrace tr = replay(make_replay_setup(truth, s, {}, {"x", "v"}), {});
    s.values.rightCols(2) = tr.y;
    GapOptions opt;
    opt.effects = {Effect::gain_error};
    const GapResult r = diagnose(nominal, s, nullptr, opt);
    EXPECT_EQ(r.modes.size(), 1u);
    return r.modes.empty() ? ModeCheck{} : r.modes[0];
}

}  // namespace

TEST(GapWhere, a_mode_at_1_5x_its_modelled_frequency_is_flagged_shifted_at_the_measured_frequency)
{
    const ModeCheck m = check_against(3.0, 0.05);
    EXPECT_EQ(m.flag, "shifted");
    EXPECT_NEAR(m.measured_peak_hz, 3.0, 0.15);
    EXPECT_NEAR(m.f_hz, 2.0, 1e-6);
}

TEST(GapWhere, a_mode_with_a_quarter_of_its_damping_is_flagged_mis_damped)
{
    EXPECT_EQ(check_against(2.0, 0.0125).flag, "mis-damped");
}

TEST(GapWhere, the_modelled_mode_is_ok)
{
    EXPECT_EQ(check_against(2.0, 0.05).flag, "ok");
}
