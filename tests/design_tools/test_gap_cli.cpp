// test_gap_cli.cpp - `fracdesign gap` end to end: the happy path writes
// result.json and report.html; each bad input gives one clear message on
// stderr, a non-zero exit, and no output directory.
#include <gtest/gtest.h>

#include "cli_scratch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using cli_scratch::Outcome;
using cli_scratch::write;

fs::path workdir() { return cli_scratch::dir("fracdesign_gap_cli"); }

const char* kModel = R"({"schema": "frac.model", "version": 1, "kind": "statespace", "name": "msd",
  "time": "continuous", "A": [[0, 1], [-20, -2]], "B": [[0], [1]], "C": [[1, 0], [0, 1]], "D": [[0], [0]],
  "inputs": ["u"], "outputs": ["x", "v"], "gap": {"velocity": "v", "force_input": "u"}})";

// t,u,x,v with x, v from a crude Euler replay of the model (the content only needs to be plausible).
std::string csv(const std::string& header, int rows, double jump_at = -1, bool nan = false)
{
    std::ostringstream o;
    o.precision(10);
    o << header << "\n";
    double x = 0, v = 0, t = 0;
    for (int k = 0; k < rows; ++k) {
        const double u = std::sin(0.7 * t) + 0.5 * std::sin(2.3 * t);
        o << t << "," << u << "," << x << "," << ((nan && k == rows / 2) ? std::string("nan") : std::to_string(v)) << "\n";
        const double a = u - 20 * x - 2 * v;
        x += 0.01 * v;
        v += 0.01 * a;
        t += (k == int(jump_at)) ? 0.02 : 0.01;
    }
    return o.str();
}

Outcome run(const std::string& args)
{
    return cli_scratch::run(std::string(FRACDESIGN_EXE) + " gap " + args, workdir() / "stderr.txt");
}

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

void expect_refused(const std::string& data, const std::string& keyword, const std::string& model = kModel)
{
    const fs::path d = workdir();
    write(d / "model.json", model);
    write(d / "data.csv", data);
    const fs::path out = d / ("out_" + std::to_string(std::hash<std::string>()(keyword)));
    const Outcome r = run("--model " + (d / "model.json").string() + " --data " + (d / "data.csv").string() + " --out " + out.string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(lower(r.err).find(keyword), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

}  // namespace

TEST(GapCli, writes_result_json_and_report)
{
    const fs::path d = workdir();
    write(d / "model.json", kModel);
    write(d / "data.csv", csv("t,u,x,v", 600));
    const fs::path out = d / "ok";
    const Outcome r = run("--model " + (d / "model.json").string() + " --data " + (d / "data.csv").string() +
                      " --effects viscous_friction,gain_error --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(out / "result.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["schema"], "frac.gap");
    EXPECT_EQ(j["version"], 1);
    EXPECT_TRUE(j.contains("verdict") && j.contains("candidates") && j.contains("where"));
    // The verdict's status is one of the documented six, with its sentence.
    const std::string st = j["verdict"]["confidence"]["status"];
    EXPECT_TRUE(st == "at_noise_floor" || st == "explained" || st == "partly_explained" || st == "unexplained" ||
                st == "no_candidate" || st == "fit_part_only" || st == "beyond_noise") << st;
    EXPECT_FALSE(j["verdict"]["confidence"]["explanation"].get<std::string>().empty());
    std::ifstream html(out / "report.html");
    std::stringstream ss;
    ss << html.rdbuf();
    EXPECT_NE(ss.str().find("<svg"), std::string::npos);
    EXPECT_EQ(ss.str().find("http://cdn"), std::string::npos);
    for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename().string().rfind(".gap-tmp", 0), std::string::npos);
}

TEST(GapCli, refuses_mismatched_column_names)
{
    expect_refused(csv("t,u,pos,vel", 300), "model/data mismatch");
}

TEST(GapCli, refuses_non_uniform_time) { expect_refused(csv("t,u,x,v", 300, 100), "uniform"); }

TEST(GapCli, refuses_nan)
{
    expect_refused(csv("t,u,x,v", 300, -1, true), "finite");
}

TEST(GapCli, refuses_a_model_whose_input_is_not_in_the_data)
{
    std::string m = kModel;
    m.replace(m.find("\"inputs\": [\"u\"]"), 15, "\"inputs\": [\"tau\"]");
    m.replace(m.find("\"force_input\": \"u\""), 18, "\"force_input\": \"tau\"");
    expect_refused(csv("t,u,x,v", 300), "model/data mismatch", m);
}

TEST(GapCli, refuses_a_malformed_coupling)
{
    std::string m = kModel;
    m.replace(m.find("\"force_input\": \"u\""), 18,
              "\"force_input\": \"u\", \"coupling\": {\"twist\": [1, 0], \"torque\": [0, 1], \"stiffness\": 0}");
    expect_refused(csv("t,u,x,v", 300), "'stiffness' must be a finite number > 0", m);
}

TEST(GapCli, refuses_a_threads_count_that_is_not_a_whole_number)
{
    const fs::path d = workdir();
    write(d / "model.json", kModel);
    write(d / "data.csv", csv("t,u,x,v", 300));
    for (const std::string bad : {"1.5", "-1", "1000"}) {
        const fs::path out = d / ("threads_" + bad);
        const Outcome r = run("--model " + (d / "model.json").string() + " --data " + (d / "data.csv").string() +
                              " --threads " + bad + " --out " + out.string());
        EXPECT_NE(r.status, 0) << bad;
        EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << bad;
    }
}

TEST(GapCli, refuses_a_loop_feedback_that_is_not_auto_model_or_measured)
{
    const fs::path d = workdir();
    write(d / "model.json", kModel);
    write(d / "data.csv", csv("t,u,x,v", 300));
    const fs::path out = d / "loop_feedback_bad";
    const Outcome r = run("--model " + (d / "model.json").string() + " --data " + (d / "data.csv").string() +
                          " --loop-feedback simulated --out " + out.string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("--loop-feedback must be auto, model or measured, got 'simulated'"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

// --loop-feedback measured feeds the replayed controller the record's
// columns of the outputs it reads: a record without one is refused naming
// it, and nothing is written.
TEST(GapCli, refuses_measured_loop_feedback_without_the_outputs_the_controller_reads)
{
    const fs::path d = workdir();
    // The mass-spring-damper under a PD on x and v (a discrete static gain).
    nlohmann::json m = nlohmann::json::parse(kModel);
    m["gap"]["closed_loop"] = {{"references", {"r"}}, {"measured", {"x", "v"}},
                               {"controller", {{"time", "discrete"}, {"Ts", 0.01}, {"A", {{0.0}}}, {"B", {{0.0, 0.0, 0.0}}},
                                               {"C", {{0.0}}}, {"D", {{40.0, -40.0, -4.0}}}}}};
    write(d / "loop_model.json", m.dump());
    std::ostringstream o;
    o << "t,r,x\n";
    for (int k = 0; k < 300; ++k) o << 0.01 * k << "," << (k >= 20 ? 1.0 : 0.0) << "," << (k >= 20 ? 0.6 : 0.0) + 0.01 * std::sin(0.3 * k) << "\n";
    write(d / "loop.csv", o.str());
    const fs::path out = d / "loop_feedback_measured";
    const Outcome r = run("--model " + (d / "loop_model.json").string() + " --data " + (d / "loop.csv").string() +
                          " --loop-feedback measured --out " + out.string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("the controller reads the output 'v', which is not a column of"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out));
    // The default (auto) simulates the loop, which needs no column of v.
    const fs::path out2 = d / "loop_feedback_auto";
    const Outcome a = run("--model " + (d / "loop_model.json").string() + " --data " + (d / "loop.csv").string() +
                          " --effects gain_error --out " + out2.string());
    EXPECT_EQ(a.status, 0) << a.err;
    EXPECT_TRUE(fs::exists(out2 / "result.json"));
}

TEST(GapCli, one_worker_and_two_give_the_same_result_json)
{
    const fs::path d = workdir();
    write(d / "model.json", kModel);
    write(d / "data.csv", csv("t,u,x,v", 600));
    nlohmann::json j[2];
    for (int w = 1; w <= 2; ++w) {
        const fs::path out = d / ("threads_ok_" + std::to_string(w));
        const Outcome r = run("--model " + (d / "model.json").string() + " --data " + (d / "data.csv").string() +
                              " --effects viscous_friction,gain_error,input_delay --threads " + std::to_string(w) +
                              " --out " + out.string());
        ASSERT_EQ(r.status, 0) << r.err;
        std::ifstream in(out / "result.json");
        j[w - 1] = nlohmann::json::parse(in);
        j[w - 1].erase("seconds");
        j[w - 1].erase("command");  // names the --threads given
    }
    EXPECT_EQ(j[0].dump(), j[1].dump());
}
