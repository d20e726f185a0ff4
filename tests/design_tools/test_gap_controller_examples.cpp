// test_gap_controller_examples.cpp - the worked examples of docs/gap.md
// "Controller kinds" (docs/examples/gap_controllers/*.json) load, build the
// kind they document and replay a closed loop that reaches the limits; the
// tables example reads its CSV tables relative to the document and replays
// exactly as the same tables given inline.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "fracdesign/gap/effects.hpp"

using namespace fracdesign::gap;
using nlohmann::json;

namespace {

const std::string kDir = FRAC_SOURCE_DIR "/docs/examples/gap_controllers/";
const double kTs = 0.005;

Signals steps(double amp = 1.0)
{
    Signals s;
    s.source = "steps";
    s.names = {"r", "x", "v"};
    s.Ts = kTs;
    s.values = Eigen::MatrixXd::Zero(2000, 3);
    for (Eigen::Index k = 0; k < 2000; ++k) s.values(k, 0) = amp * ((k / 300) % 2 ? 1.5 : -1.0);
    return s;
}

ReplayTrace run(const NominalModel& m, double amp = 1.0) { return replay(make_replay_setup(m, steps(amp), {}, {"x", "v"}), {}); }

}  // namespace

TEST(GapControllerExamples, every_example_builds_its_kind_and_replays_into_its_limits)
{
    const std::vector<std::pair<std::string, std::string>> ex = {
        {"fopid", "fopid"}, {"collocated", "collocated"}, {"cascade", "cascade"}, {"statespace", "statespace"}, {"tables", "fopid"}};
    for (const auto& e : ex) {
        const NominalModel m = load_nominal_model(kDir + e.first + ".json", kTs);
        ASSERT_TRUE(m.closed_loop) << e.first;
        EXPECT_EQ(m.loop.controller->kind(), e.second);
        const ReplayTrace tr = run(m, e.first == "collocated" ? 8.0 : 1.0);  // the damping law needs larger steps
        ASSERT_TRUE(tr.y.allFinite()) << e.first;
        const double lim = std::min(m.loop.saturation, m.loop.controller->output_limit());
        ASSERT_TRUE(std::isfinite(lim)) << e.first;
        int at = 0;
        for (Eigen::Index k = 0; k < tr.u.size(); ++k) at += std::fabs(tr.u(k)) >= 0.999 * std::fabs(tr.u.cwiseAbs().maxCoeff());
        EXPECT_GT(at, 20) << e.first << ": the steps should hold the command at a limit";
        EXPECT_LE(tr.u.cwiseAbs().maxCoeff(), lim + 1e-12) << e.first;
    }
}

TEST(GapControllerExamples, csv_tables_replay_as_the_same_tables_inline)
{
    std::ifstream in(kDir + "tables.json");
    json doc = json::parse(in);
    json& c = doc["gap"]["closed_loop"]["controller"];
    std::vector<double> traj;
    std::ifstream csv(kDir + "reference.csv");
    std::string line;
    std::getline(csv, line);
    while (std::getline(csv, line)) traj.push_back(std::stod(line.substr(line.find(',') + 1)));
    c["reference_table"] = {{"data", {traj}}, {"t0", 0.0}, {"dt", 0.1}, {"references", {"r"}}, {"lead", {0}}};
    c["feedforward"][0]["lut1d"] = {{"x", {-3, 0, 3}}, {"y", {-27, 0, 27}}};
    const ReplayTrace a = run(load_nominal_model(kDir + "tables.json", kTs));
    const ReplayTrace b = run(nominal_from_json(doc, kTs));
    ASSERT_EQ(a.y.rows(), b.y.rows());
    EXPECT_EQ((a.y - b.y).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_GT(a.y.col(0).cwiseAbs().maxCoeff(), 0.1) << "the table must drive the loop";
}
