// test_gap_sites_gear.cpp - the gear site (issue 17 item 3, "backlash between
// a motor-side encoder and the load, reported as a play"): under a rigid
// nominal, a compliant gear with a play splits the body into a motor and a
// load; the motor-side encoder reads theta_cm + r q (gear.cpp). The replay
// of the site matches an independent simulation of the two bodies, the
// diagnosis names the play at the gear with its width in the position's
// unit, and a gear without a play is named the mode at that site, not
// backlash.
//
// Plant (chosen here, not a seed's): a rigid axis J theta'' = Ka u - b J
// theta' (J = 2.1e-3 kg m^2, b = 1.9 1/s, Ka = 0.15 N m/V) at 1 ms under a
// PD position loop (kp 1.4 V/rad, kd 0.04 V s/rad, +-10 V), tracking
// smooth moves with reversals. The truth is this file's own: the motor
// ((1 - r) J) and the load (r J), each with viscous b times its inertia,
// joined by a spring k and damper c with a play of width w (the dead-zone
// shaft model, T = k dz(q) + c q'), stepped by RK4 with 64 sub-steps per
// sample under the held command.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "fracdesign/gap/diagnosis.hpp"
#include "fracdesign/gap/effects.hpp"
#include "fracdesign/gap/nominal.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 1e-3, kJ = 2.1e-3, kB = 1.9, kKa = 0.15, kKp = 1.4, kKd = 0.04;
const Eigen::Index kN = 5000;

nlohmann::json axis_doc(bool closed_loop)
{
    nlohmann::json d = {{"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "axis"},
                        {"time", "continuous"}, {"A", {{0, 1}, {0, -kB}}}, {"B", {{0}, {kKa / kJ}}},
                        {"C", {{1, 0}, {0, 1}}}, {"D", {{0}, {0}}},
                        {"inputs", {"u"}}, {"outputs", {"position", "velocity"}},
                        {"gap", {{"velocity", "velocity"}, {"force_input", "u"}, {"initial_state", "at_rest"},
                                 {"units", {{"u", "V"}, {"position", "rad"}, {"velocity", "rad/s"}}}}}};
    if (closed_loop)
        d["gap"]["closed_loop"] = {{"references", {"reference"}}, {"measured", {"position", "velocity"}},
                                   {"controller", {{"time", "discrete"}, {"Ts", kTs}, {"A", {{0.0}}}, {"B", {{0.0, 0.0, 0.0}}},
                                                   {"C", {{0.0}}}, {"D", {{kKp, -kKp, -kKd}}}}},
                                   {"delay_samples", 0}, {"saturation", 10.0}};
    return d;
}

struct Gear {
    double w, r, f, zeta;  // play [rad], load share, contact frequency [Hz], damping
};

// The two bodies' state derivative: x = [th_m, th_l, v_m, v_l].
Eigen::Vector4d two_body(const Eigen::Vector4d& x, double u, const Gear& g)
{
    const double Jm = (1 - g.r) * kJ, Jl = g.r * kJ, mu = Jm * Jl / kJ;
    const double wg = 2 * M_PI * g.f, k = wg * wg * mu, c = 2 * g.zeta * wg * mu;
    const double q = x(0) - x(1), dz = q - std::min(std::max(q, -0.5 * g.w), 0.5 * g.w);
    const double T = k * dz + c * (x(2) - x(3));
    Eigen::Vector4d d;
    d << x(2), x(3), (kKa * u - kB * Jm * x(2) - T) / Jm, (T - kB * Jl * x(3)) / Jl;
    return d;
}

// The reference: smooth moves of 0.2-0.6 rad, each way, 0.3-0.6 s, with rests.
Eigen::VectorXd reference()
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> amp(0.2, 0.6), dur(0.3, 0.6), rest(0.05, 0.3);
    Eigen::VectorXd r = Eigen::VectorXd::Zero(kN);
    double t = 0.1, pos = 0;
    int sign = 1;
    while (t < kN * kTs) {
        const double d = dur(rng), a = sign * amp(rng);
        for (Eigen::Index k = 0; k < kN; ++k) {
            const double s = std::min(std::max((k * kTs - t) / d, 0.0), 1.0);
            if (k * kTs >= t) r(k) = pos + a * (s - std::sin(2 * M_PI * s) / (2 * M_PI));
        }
        pos += a;
        sign = -sign;
        t += d + rest(rng);
    }
    return r;
}

// The record of the two bodies under the PD loop (closed loop) or under the
// recorded command `u_in` (open loop, when given); the encoder reads the
// motor (plus `noise` rad of white noise).
Signals truth_record(const Gear& g, double noise, const Eigen::VectorXd* u_in = nullptr)
{
    const Eigen::VectorXd ref = reference();
    Signals s;
    s.source = "two-body truth";
    s.names = {"reference", "u", "position", "velocity"};
    s.Ts = kTs;
    s.values.resize(kN, 4);
    Eigen::Vector4d x = Eigen::Vector4d::Zero();
    std::mt19937 rng(3);
    std::normal_distribution<double> n(0.0, 1.0);
    const int sub = 64;
    const double h = kTs / sub;
    for (Eigen::Index k = 0; k < kN; ++k) {
        const double pm = x(0) + noise * n(rng), vm = x(2) + 10 * noise * n(rng);
        const double u = u_in ? (*u_in)(k) : std::min(std::max(kKp * (ref(k) - pm) - kKd * vm, -10.0), 10.0);
        s.values(k, 0) = ref(k);
        s.values(k, 1) = u;
        s.values(k, 2) = pm;
        s.values(k, 3) = vm;
        for (int i = 0; i < sub; ++i) {
            const Eigen::Vector4d k1 = two_body(x, u, g), k2 = two_body(x + 0.5 * h * k1, u, g),
                                  k3 = two_body(x + 0.5 * h * k2, u, g), k4 = two_body(x + h * k3, u, g);
            x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        }
    }
    return s;
}

double rms(const Eigen::VectorXd& a) { return std::sqrt(a.array().square().mean()); }

const Gear kPlay{0.012, 0.45, 95.0, 0.12};

}  // namespace

TEST(GapSitesGear, the_site_is_a_free_body_with_a_velocity_and_no_coupling)
{
    const GearSite g = gear_site(nominal_from_json(axis_doc(false), kTs));
    ASSERT_TRUE(g.ok) << g.why;
    EXPECT_EQ(g.p, 0);
    EXPECT_EQ(g.j, 1);
    EXPECT_EQ(g.kappa, 1.0);
    EXPECT_EQ(g.position_output, 0);
    // A spring to ground: not a free body.
    nlohmann::json d = axis_doc(false);
    d["A"] = {{0, 1}, {-400, -kB}};
    const GearSite s = gear_site(nominal_from_json(d, kTs));
    EXPECT_FALSE(s.ok);
    EXPECT_NE(s.why.find("spring to ground"), std::string::npos) << s.why;
    // No velocity output named.
    d = axis_doc(false);
    d["gap"].erase("velocity");
    EXPECT_FALSE(gear_site(nominal_from_json(d, kTs)).ok);
    // A declared coupling holds its own play.
    d = axis_doc(false);
    d["gap"]["coupling"] = {{"name", "shaft"}, {"twist", {1, 0}}, {"torque", {0, -1}}, {"stiffness", 10.0}};
    EXPECT_FALSE(gear_site(nominal_from_json(d, kTs)).ok);
    EXPECT_TRUE(effect_sites(Effect::backlash, nominal_from_json(d, kTs), 2, 0).size() == 2);
    EXPECT_EQ(effect_sites(Effect::backlash, nominal_from_json(axis_doc(false), kTs), 2, 0).back().first, Site::gear);
}

TEST(GapSitesGear, the_replay_matches_the_two_bodies)
{
    // Open loop on the closed loop's command: the same contacts, no loop to hide an error.
    const Signals loop = truth_record(kPlay, 0.0);
    const Eigen::VectorXd u = loop.col("u");
    const Signals data = truth_record(kPlay, 0.0, &u);
    const NominalModel m = nominal_from_json(axis_doc(false), kTs);
    const ReplaySetup s = make_replay_setup(m, data, {}, {"position", "velocity"});
    const ReplayTrace with = replay(s, {{Effect::backlash, {kPlay.w, kPlay.r, kPlay.f, kPlay.zeta}, Site::gear, 0}});
    const ReplayTrace rigid = replay(s, {});
    // The gear's own share of the reading, and what the replay leaves of it
    // (measured: position 0.3 %, velocity 0.8 % of the gear's share).
    for (Eigen::Index c = 0; c < 2; ++c) {
        const Eigen::VectorXd y = data.values.col(2 + c);
        const double gear = rms(y - rigid.y.col(c)), left = rms(y - with.y.col(c));
        EXPECT_GT(gear, 0.0);
        EXPECT_LT(left, 0.03 * gear) << "output " << c << ": " << left << " of " << gear;
    }
    // Without the play, the mode at the gear is the linear two-body split.
    const Gear lin{0.0, kPlay.r, kPlay.f, kPlay.zeta};
    const Signals d0 = truth_record(lin, 0.0, &u);
    const ReplaySetup s0 = make_replay_setup(m, d0, {}, {"position", "velocity"});
    const ReplayTrace mode = replay(s0, {{Effect::unmodelled_mode, {lin.r, lin.f, lin.zeta}, Site::gear, 0}});
    const ReplayTrace rigid0 = replay(s0, {});
    for (Eigen::Index c = 0; c < 2; ++c) {
        const Eigen::VectorXd y = d0.values.col(2 + c);
        EXPECT_LT(rms(y - mode.y.col(c)), 0.03 * rms(y - rigid0.y.col(c))) << "output " << c;
    }
}

namespace {

GapResult diagnose_loop(const Signals& data)
{
    const NominalModel m = nominal_from_json(axis_doc(true), kTs);
    GapOptions o;
    o.effects = {Effect::backlash, Effect::unmodelled_mode, Effect::coulomb_friction, Effect::deadzone,
                 Effect::output_delay};
    o.outputs = {"position", "velocity"};
    return diagnose(m, data, nullptr, o);
}

// The verdict's first effect is `kind` at the gear, with [width,] share and
// f_hz within 10 %, 10 % and 5 % of g's (the width only with a play).
void expect_gear(const GapResult& r, Effect kind, const Gear& g)
{
    ASSERT_FALSE(r.verdict.effects.empty());
    const EffectInstance& e = r.verdict.effects[0];
    EXPECT_EQ(e.kind, kind);
    ASSERT_EQ(e.site, Site::gear);
    const size_t o = kind == Effect::backlash ? 1 : 0;
    ASSERT_EQ(e.params.size(), 3 + o);
    if (o) EXPECT_NEAR(e.params[0], g.w, 0.1 * g.w);
    EXPECT_NEAR(e.params[o], g.r, 0.1 * g.r);
    EXPECT_NEAR(e.params[o + 1], g.f, 0.05 * g.f);
}

}  // namespace

TEST(GapSitesGear, the_diagnosis_names_the_play_in_the_gear_with_its_width)
{
    const GapResult r = diagnose_loop(truth_record(kPlay, 2e-5));
    expect_gear(r, Effect::backlash, kPlay);
    EXPECT_GE(r.verdict.shrink, 0.8);
    const nlohmann::json j = result_json(r);
    EXPECT_EQ(j["verdict"]["sites"][0], "gear");
    EXPECT_EQ(j["verdict"]["params_unit"]["width"], "rad");
    EXPECT_EQ(site_phrase("backlash", "gear", ""), " (in a gear behind the motor-side sensors)");
}

// Without a play the smooth moves barely ring the gear (rms 3.7e-5 rad at
// the encoder against the rigid replay): the encoder here resolves 2e-6 rad.
TEST(GapSitesGear, a_gear_without_play_is_the_mode_at_the_gear_not_backlash)
{
    const Gear lin{0.0, 0.35, 70.0, 0.08};
    expect_gear(diagnose_loop(truth_record(lin, 2e-6)), Effect::unmodelled_mode, lin);
}
