// test_gap_sites_series.cpp - the unmodelled mode in series at the force
// input (issue 17 item 3) is replayed exactly: the plant sees the mode's
// path over each sample, not only its mean.
//
// Plant (chosen here, not a seed's): a rigid axis J theta'' = Ka u - b theta'
// (J = 1.3e-3 kg m^2, b = 1.7e-3 Nm s/rad, Ka = 0.11 Nm/V) at 1 ms, open loop,
// driven by random levels held 5-40 ms; a 38 Hz resonance (zeta 0.04) between
// the drive and the axis (w Ts = 0.24). The truth is this file's own: the
// joint system [mode; axis] under the held input, stepped by its zero-order
// hold. The per-sample mean of the mode alone (the replay before) is off by
// 1.0e-5 (position) and 1.4e-5 (velocity) of the output's std here (open
// loop; under a loop that limit-cycles such an error moves the cycle's
// phase and grows along the record); the exact hold by rounding only.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fracdesign/gap/effects.hpp"
#include "fracdesign/gap/nominal.hpp"
#include "gap_drive.hpp"

using namespace fracdesign::gap;

namespace {

const double kTs = 1e-3, kJ = 1.3e-3, kB = 1.7e-3, kKa = 0.11, kF = 38.0, kZeta = 0.04;
const Eigen::Index kN = 3000;

nlohmann::json axis_doc(bool discrete)
{
    nlohmann::json d = {{"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "axis"},
                        {"C", {{1, 0}, {0, 1}}}, {"D", {{0}, {0}}},
                        {"inputs", {"voltage"}}, {"outputs", {"position", "velocity"}},
                        {"gap", {{"velocity", "velocity"}, {"force_input", "voltage"}, {"initial_state", "at_rest"}}}};
    Eigen::MatrixXd A(2, 2), B(2, 1);
    A << 0, 1, 0, -kB / kJ;
    B << 0, kKa / kJ;
    if (!discrete) {
        d["time"] = "continuous";
        d["A"] = {{A(0, 0), A(0, 1)}, {A(1, 0), A(1, 1)}};
        d["B"] = {{B(0, 0)}, {B(1, 0)}};
        return d;
    }
    Eigen::MatrixXd Ad, Bd;
    zoh(A, B, kTs, Ad, Bd);
    d["time"] = "discrete";
    d["Ts"] = kTs;
    d["A"] = {{Ad(0, 0), Ad(0, 1)}, {Ad(1, 0), Ad(1, 1)}};
    d["B"] = {{Bd(0, 0)}, {Bd(1, 0)}};
    return d;
}

// The record: u held per sample, the truth's position and velocity.
Signals truth_record()
{
    const double w = 2 * M_PI * kF;
    Eigen::MatrixXd Ac = Eigen::MatrixXd::Zero(4, 4), Bc = Eigen::MatrixXd::Zero(4, 1), Ad, Bd;
    Ac(0, 1) = 1;
    Ac(1, 1) = -kB / kJ;
    Ac(1, 2) = kKa / kJ;
    Ac(2, 3) = 1;
    Ac(3, 2) = -w * w;
    Ac(3, 3) = -2 * kZeta * w;
    Bc(3, 0) = w * w;
    zoh(Ac, Bc, kTs, Ad, Bd);
    const std::vector<double> drive = held_levels(kN, 7, -5, 5, 5, 40, 10);
    Signals s = state_record(Ad, Bd, drive, {0, 1}, {"voltage", "position", "velocity"}, kTs, "series mode truth");
    return s;
}

double worst_relative_error(bool discrete)
{
    const Signals data = truth_record();
    const NominalModel m = nominal_from_json(axis_doc(discrete), kTs);
    const ReplaySetup s = make_replay_setup(m, data, {}, {"position", "velocity"});
    const ReplayTrace t = replay(s, {{Effect::unmodelled_mode, {kF, kZeta}, Site::force_input, 0}});
    double worst = 0;
    for (Eigen::Index c = 0; c < 2; ++c) {
        const Eigen::VectorXd y = data.values.col(c + 1);
        const double sd = std::sqrt((y.array() - y.mean()).square().mean());
        worst = std::max(worst, (t.y.col(c) - y).cwiseAbs().maxCoeff() / sd);
    }
    return worst;
}

}  // namespace

TEST(GapSitesSeries, the_series_mode_replays_the_exact_path_on_a_continuous_plant)
{
    EXPECT_LT(worst_relative_error(false), 1e-8);
}

// A discrete document: the generator is log(A)/Ts, B's hold inverted.
TEST(GapSitesSeries, the_series_mode_replays_the_exact_path_on_a_discrete_plant)
{
    EXPECT_LT(worst_relative_error(true), 1e-7);
}
