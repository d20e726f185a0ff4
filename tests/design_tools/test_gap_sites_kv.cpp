// test_gap_sites_kv.cpp - Kelvin-Voigt fractional damping c D^alpha on the
// flexible modes of a link (issue 17 item 3), declared as a list of modal
// couplings, with c and alpha identified.
//
// Plant (chosen here): a hub (J = 0.02 kg m^2) carrying a link with two
// flexible modes in modal coordinates, eta_i'' = -w_i^2 eta_i - 2 z_i w_i
// eta_i' + b_i u (3.4 Hz and 13.1 Hz, z = 0.01), a PD on the hub angle and
// rate, outputs hub rate and a tip rate that sees both modes. The document
// declares the modes as gap.coupling [{"modal": ..}, {"modal": ..}]. Truth:
// this file's own integration, 10 exact sub-steps per sample of the linear
// plant with the damping force c D^alpha eta_i held over each sub-step,
// D^alpha by Grunwald-Letnikov at the sub-step over the whole history (no
// short memory), so neither the replay's operator nor its memory rule is
// the reference.
#include <gtest/gtest.h>

#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>

#include "gap_sites.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 2e-3, kJ = 0.02, kKp = 2.0, kKd = 0.25;
const double kW[2] = {2 * M_PI * 3.4, 2 * M_PI * 13.1}, kZ = 0.01, kBm[2] = {30.0, -18.0}, kTip[2] = {0.05, -0.03};
const Eigen::Index kN = 3000;
const int kSub = 10;

Eigen::MatrixXd plant_A()
{
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, 6);
    A(0, 1) = 1;
    for (int i = 0; i < 2; ++i) {
        A(2 + 2 * i, 3 + 2 * i) = 1;
        A(3 + 2 * i, 2 + 2 * i) = -kW[i] * kW[i];
        A(3 + 2 * i, 3 + 2 * i) = -2 * kZ * kW[i];
    }
    return A;
}

Eigen::VectorXd plant_B()
{
    Eigen::VectorXd B = Eigen::VectorXd::Zero(6);
    B(1) = 1 / kJ;
    B(3) = kBm[0];
    B(5) = kBm[1];
    return B;
}

nlohmann::json arm_doc()
{
    const Eigen::MatrixXd A = plant_A();
    const Eigen::VectorXd B = plant_B();
    nlohmann::json a = nlohmann::json::array(), b = nlohmann::json::array();
    for (int i = 0; i < 6; ++i) {
        a.push_back(std::vector<double>(A.row(i).data(), A.row(i).data() + 0));
        for (int j = 0; j < 6; ++j) a.back().push_back(A(i, j));
        b.push_back({B(i)});
    }
    return {{"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "flexible_link"},
            {"time", "continuous"}, {"A", a}, {"B", b},
            {"C", {{1, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0}, {0, 1, 0, kTip[0], 0, kTip[1]}}},
            {"D", {{0}, {0}, {0}}},
            {"inputs", {"torque"}}, {"outputs", {"hub_angle", "hub_rate", "tip_rate"}},
            {"gap",
             {{"velocity", "hub_rate"}, {"force_input", "torque"},
              {"coupling",
               {{{"name", "mode 1"}, {"modal", {{"position", 2}, {"rate", 3}}}},
                {{"name", "mode 2"}, {"modal", {{"position", 4}, {"rate", 5}}}}}},
              {"closed_loop",
               {{"references", {"ref", "ref_rate"}}, {"measured", {"hub_angle", "hub_rate"}},
                {"controller", {{"time", "discrete"}, {"Ts", kTs}, {"D", {{kKp, kKd, -kKp, -kKd}}}}}}}}}};
}

double ref(double t, double* rd)
{
    const double a[4] = {0.4, 0.08, 0.03, 0.03}, f[4] = {0.45, 1.7, 3.9, 12.5}, p[4] = {0, 1, 2, 0.5};
    double r = 0, d = 0;
    for (int i = 0; i < 4; ++i) {
        r += a[i] * std::sin(2 * M_PI * f[i] * t + p[i]);
        d += a[i] * 2 * M_PI * f[i] * std::cos(2 * M_PI * f[i] * t + p[i]);
    }
    *rd = d;
    return r;
}

// The record with c D^alpha on mode `mode` (c = 0: none).
Signals record(int mode, double c, double alpha)
{
    const double h = kTs / kSub;
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(8, 8);
    M.topLeftCorner(6, 6) = plant_A() * h;
    M.block(0, 6, 6, 1) = plant_B() * h;
    M(3 + 2 * mode, 7) = -h;  // the damping force on the mode (unit modal mass)
    const Eigen::MatrixXd E = M.exp();
    const Eigen::MatrixXd Ph = E.topLeftCorner(6, 6);
    const Eigen::VectorXd G = E.block(0, 6, 6, 1), H = E.block(0, 7, 6, 1);
    std::vector<double> w(size_t(kN * kSub) + 1, 1.0), hist;
    for (size_t j = 1; j < w.size(); ++j) w[j] = w[j - 1] * (1 - (alpha + 1) / double(j));
    const double hs = std::pow(h, -alpha);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(6);
    Signals s;
    s.source = "flexible link";
    s.Ts = kTs;
    s.names = {"ref", "ref_rate", "hub_angle", "hub_rate", "tip_rate"};
    s.values.resize(kN, 5);
    for (Eigen::Index k = 0; k < kN; ++k) {
        double rd;
        const double r = ref(double(k) * kTs, &rd);
        s.values.row(k) << r, rd, x(0), x(1), x(1) + kTip[0] * x(3) + kTip[1] * x(5);
        const double u = kKp * (r - x(0)) + kKd * (rd - x(1));
        for (int i = 0; i < kSub; ++i) {
            hist.push_back(x(2 + 2 * mode));
            double d = 0;
            for (size_t j = 0; j < hist.size(); ++j) d += w[j] * hist[hist.size() - 1 - j];
            x = Ph * x + G * u + H * (c * hs * d);
        }
    }
    gap_sites::add_noise(s, {"hub_rate", "tip_rate"}, 0.002, 3);
    return s;
}

GapResult run(const Signals& s)
{
    GapOptions o;
    o.outputs = {"hub_rate", "tip_rate"};
    return diagnose(nominal_from_json(arm_doc(), kTs), s, nullptr, o);
}

// c that adds the damping ratio zeta to mode i (c w^alpha sin(pi alpha/2) = 2 zeta w^2).
double c_for(int i, double zeta, double alpha)
{
    return 2 * zeta * kW[i] * kW[i] / (std::pow(kW[i], alpha) * std::sin(M_PI * alpha / 2));
}

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

TEST(GapSitesKelvinVoigt, the_modal_couplings_are_read_from_the_modes)
{
    const NominalModel m = nominal_from_json(arm_doc(), kTs);
    ASSERT_EQ(m.couplings.size(), 2u);
    EXPECT_EQ(m.couplings[1].name, "mode 2");
    EXPECT_NEAR(m.couplings[0].stiffness, kW[0] * kW[0], 1e-9 * kW[0] * kW[0]);
    // The slowest oscillation of each block is its mode (closed-loop-free, the plant's own).
    EXPECT_NEAR(m.couplings[0].w_slow, kW[0] * std::sqrt(1 - kZ * kZ), 1e-6 * kW[0]);
}

TEST(GapSitesKelvinVoigt, damping_of_the_first_link_mode_is_found_there_with_c_and_alpha)
{
    const double alpha = 0.57, c = c_for(0, 0.06, alpha);
    gap_sites::expect_verdict(run(record(0, c, alpha)), "fractional_damping", "coupling", "mode 1",
                              {{"c", c}, {"alpha", alpha}});
}

TEST(GapSitesKelvinVoigt, damping_of_the_second_link_mode_is_found_there_with_c_and_alpha)
{
    const double alpha = 0.36, c = c_for(1, 0.08, alpha);
    gap_sites::expect_verdict(run(record(1, c, alpha)), "fractional_damping", "coupling", "mode 2",
                              {{"c", c}, {"alpha", alpha}});
}

TEST(GapSitesKelvinVoigt, a_record_without_it_is_not_blamed_on_fractional_damping)
{
    EXPECT_NE(gap_sites::first_effect(run(record(0, 0.0, 0.5))), "fractional_damping");
}

TEST(GapSitesKelvinVoigt, malformed_modal_couplings_are_refused_with_one_message_each)
{
    auto with = [](const nlohmann::json& cp) {
        nlohmann::json d = arm_doc();
        d["gap"]["coupling"] = cp;
        return d;
    };
    EXPECT_NE(load_error(with(nlohmann::json::array())).find("an empty list"), std::string::npos);
    EXPECT_NE(load_error(with({{{"name", "a"}, {"modal", {{"position", 2}, {"rate", 3}}}},
                               {{"name", "a"}, {"modal", {{"position", 4}, {"rate", 5}}}}}))
                  .find("two couplings are named 'a'"),
              std::string::npos);
    EXPECT_NE(load_error(with({{{"modal", {{"position", 2}, {"rate", 9}}}}})).find("gap.coupling[0]: 'modal' needs 'rate'"),
              std::string::npos);
    EXPECT_NE(load_error(with({{"modal", {{"position", 3}, {"rate", 2}}}})).find("must be the integral of rate state"),
              std::string::npos);
    EXPECT_NE(load_error(with({{"modal", {{"position", 0}, {"rate", 1}}}})).find("is not an oscillating mode"),
              std::string::npos);
    EXPECT_NE(load_error(with({{"modal", {{"position", 2}, {"rate", 3}}}, {"stiffness", 1.0}})).find("either 'modal' or 'stiffness'"),
              std::string::npos);
    nlohmann::json d = with({{"modal", {{"position", 2}, {"rate", 3}}}});
    d["time"] = "discrete";
    d["Ts"] = kTs;
    EXPECT_NE(load_error(d).find("'modal' needs a continuous plant"), std::string::npos);
    EXPECT_EQ(load_error(with({{"modal", {{"position", 2}, {"rate", 3}}}})), "");
}
