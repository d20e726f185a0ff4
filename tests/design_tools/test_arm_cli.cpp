// The --arm paths of fracdesign model/lqg/armctrl/traj: a bad document or option is one line naming
// the field, exit 2, and nothing is written; a good one writes every output it was asked for.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "run_command.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kExe = FRACDESIGN_EXE;
const std::string kArmB = std::string(FRAC_SOURCE_DIR) + "/docs/examples/arm_b/arm.json";

fs::path scratch(const std::string& name)
{
    const fs::path d = fs::path(FRAC_BINARY_DIR) / "test-arm-cli" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string write_doc(const fs::path& dir, const json& j)
{
    const std::string p = (dir / "arm.json").string();
    std::ofstream(p) << j.dump();
    return p;
}

}  // namespace

TEST(ArmCli, bad_document_is_refused_naming_the_field_and_writes_nothing)
{
    const fs::path d = scratch("bad");
    json j = json::parse(std::ifstream(kArmB));
    j["drive"]["torque_peak"] = 10.0;  // below the rated 60 N m
    const std::string doc = write_doc(d, j);
    const std::string outs = " --save-plant " + (d / "p.bin").string() + " --gap-nominal " + (d / "n.json").string();
    int st = 0;
    std::string out = run_command(kExe + " model --arm " + doc + outs, &st);
    EXPECT_EQ(st, 2) << out;
    EXPECT_NE(out.find("arm: field 'drive.torque_peak': value 10 out of range: allowed [60, 1e+06]"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(d / "p.bin"));
    EXPECT_FALSE(fs::exists(d / "n.json"));
    out = run_command(kExe + " armctrl --arm " + doc + " --move 0:1@1+1.5 --out " + (d / "c.bin").string(), &st);
    EXPECT_EQ(st, 2) << out;
    EXPECT_FALSE(fs::exists(d / "c.bin"));
    out = run_command(kExe + " lqg --arm " + (d / "missing.json").string(), &st);
    EXPECT_EQ(st, 2) << out;
    EXPECT_NE(out.find("cannot read the file"), std::string::npos) << out;
}

TEST(ArmCli, a_document_the_hil_rig_cannot_emulate_gets_no_scenario_and_no_file)
{
    const fs::path d = scratch("rig");
    const std::string outs = " --save-plant " + (d / "p.bin").string() + " --save-scenario " + (d / "s.txt").string();
    struct Case {
        const char* section;
        const char* key;
        long value;
        const char* message;
    };
    for (const Case& c : {Case{"delays", "output", 6, "arm: field 'delays.output': value 6: the HIL rig's IMU node models only [2, 5] samples"},
                          Case{"delays", "output", 1, "arm: field 'delays.output': value 1: the HIL rig's IMU node models only [2, 5] samples"},
                          Case{"sensors", "encoder_counts_per_rev", 1000000,
                               "arm: field 'sensors.encoder_counts_per_rev': value 1000000: the HIL rig's drive counts 2^bits per "
                               "revolution, bits in [1, 20] (2 .. 1048576, a power of 2)"},
                          Case{"sensors", "encoder_counts_per_rev", 1L << 21,
                               "arm: field 'sensors.encoder_counts_per_rev': value 2097152: the HIL rig's drive counts"}}) {
        json j = json::parse(std::ifstream(kArmB));
        j[c.section][c.key] = c.value;
        const std::string doc = write_doc(d, j);
        int st = 0;
        std::string out = run_command(kExe + " model --arm " + doc + outs, &st);
        EXPECT_EQ(st, 2) << out;
        EXPECT_NE(out.find(c.message), std::string::npos) << out;
        EXPECT_FALSE(fs::exists(d / "s.txt"));
        EXPECT_FALSE(fs::exists(d / "p.bin"));  // nothing written, also not the outputs the rig does not limit
        // the design itself is not limited by the rig: the plant table alone is written
        out = run_command(kExe + " model --arm " + doc + " --save-plant " + (d / "p.bin").string(), &st);
        EXPECT_EQ(st, 0) << out;
        EXPECT_TRUE(fs::exists(d / "p.bin"));
        fs::remove(d / "p.bin");
    }
}

TEST(ArmCli, bad_moves_and_mixed_options_are_refused)
{
    const fs::path d = scratch("moves");
    int st = 0;
    const std::string c = " --out " + (d / "c.bin").string();
    std::string out = run_command(kExe + " armctrl --arm " + kArmB + " --move 0:1@1" + c, &st);
    EXPECT_EQ(st, 2) << out;
    EXPECT_NE(out.find("is not Q@T+DUR"), std::string::npos) << out;
    out = run_command(kExe + " armctrl --arm " + kArmB + " --exp D --move 0:1@1+1.5" + c, &st);
    EXPECT_EQ(st, 2) << out;
    EXPECT_NE(out.find("--exp does not go with --arm"), std::string::npos) << out;
    // a move starting too early for the inversion's pre-actuation: exit 1, cause named, nothing written
    out = run_command(kExe + " armctrl --arm " + kArmB + " --move 0:1@0.1+1.5" + c, &st);
    EXPECT_EQ(st, 1) << out;
    EXPECT_NE(out.find("not at rest"), std::string::npos) << out;
    // ... it states the lead the pre-actuation needs, and that lead is enough: the same move started
    // 50 ms after it (the playback's first d_i cycles at rest) is accepted
    const size_t at = out.find("the pre-actuation needs ");
    ASSERT_NE(at, std::string::npos) << out;
    const double lead = std::stod(out.substr(at + std::strlen("the pre-actuation needs ")));
    EXPECT_GT(lead, 0.1) << out;
    EXPECT_LT(lead, 2.0) << out;
    {
        const std::string ok = run_command(kExe + " armctrl --arm " + kArmB + " --move 0:1@" + std::to_string(lead + 0.05) +
                                               "+1.5 --post 0.2 --out " + (d / "later.bin").string(), &st);
        EXPECT_EQ(st, 0) << ok;
        EXPECT_TRUE(fs::exists(d / "later.bin"));
    }
    // a move faster than the drive's peak torque allows
    out = run_command(kExe + " armctrl --arm " + kArmB + " --move 0:20@1+0.3" + c, &st);
    EXPECT_EQ(st, 1) << out;
    EXPECT_NE(out.find("more than drive.torque_peak"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(d / "c.bin"));
}

TEST(ArmCli, one_document_gives_plant_table_gap_nominal_scenario_and_feedforward)
{
    const fs::path d = scratch("good");
    int st = 0;
    std::string out = run_command(kExe + " model --arm " + kArmB + " --json --save-plant " + (d / "p.bin").string() +
                                      " --gap-nominal " + (d / "n.json").string() + " --save-scenario " + (d / "s.txt").string(),
                                  &st);
    ASSERT_EQ(st, 0) << out;
    const json m = json::parse(out);
    EXPECT_EQ(m["full_states"], 4 + 36 + 2);  // drive, beam N = 9, payload mass (no rotary inertia)
    const json n = json::parse(std::ifstream(d / "n.json"));
    // + torque_prev (first-order hold) + the IMU ages 1 .. 2h - 1, h = max(1, d_o - 1) = 4 for d_o = 5
    EXPECT_EQ(n["A"].size(), 42u + 1u + (2u * 4u - 1u));
    EXPECT_EQ(n["outputs"], json({"motor_velocity", "imu_rate"}));
    out = run_command(kExe + " table check " + (d / "p.bin").string(), &st);
    EXPECT_EQ(st, 0) << out;
    out = run_command(kExe + " traj --arm " + kArmB + " --move 0:1@1+1.5 --json --out " + (d / "ff.csv").string(), &st);
    ASSERT_EQ(st, 0) << out;
    const json t = json::parse(out);
    EXPECT_LT(t["inverse_tracking_rel_rms"].get<double>(), 1e-6);
    EXPECT_TRUE(fs::exists(d / "ff.csv"));
}
