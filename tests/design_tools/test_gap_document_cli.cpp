// test_gap_document_cli.cpp - `fracdesign gap` on the document's new fields
// (docs/gap.md "What the document states"): a foprocess nominal runs end to
// end, and each bad value gives one line on stderr naming the field, the
// value and what is allowed, a non-zero exit and no output directory.
#include <gtest/gtest.h>

#include "cli_scratch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using cli_scratch::write;

fs::path workdir() { return cli_scratch::dir("fracdesign_gap_document_cli"); }

// t,u,y: a first-order lag y' = -2 y + 3 u (Euler; the content only needs to be plausible).
std::string csv(int rows)
{
    std::ostringstream o;
    o.precision(10);
    o << "t,u,y\n";
    double y = 0;
    for (int k = 0; k < rows; ++k) {
        const double t = 0.01 * k, u = std::sin(0.9 * t) + 0.4 * std::sin(3.1 * t);
        o << t << "," << u << "," << y << "\n";
        y += 0.01 * (-2 * y + 3 * u);
    }
    return o.str();
}

nlohmann::json lag(const nlohmann::json& gap)
{
    return {{"schema", "frac.model"}, {"version", 1},    {"kind", "statespace"}, {"time", "continuous"},
            {"A", {{-2.0}}},          {"B", {{3.0}}},    {"C", {{1.0}}},         {"D", {{0.0}}},
            {"inputs", {"u"}},        {"outputs", {"y"}}, {"gap", gap}};
}

struct Outcome {
    int status;
    std::string err;
    fs::path out;
};

Outcome run(const nlohmann::json& model, const std::string& tag)
{
    const fs::path d = workdir();
    write(d / (tag + ".json"), model.dump());
    write(d / "data.csv", csv(600));
    const fs::path out = d / ("out_" + tag), err = d / ("err_" + tag);
    const cli_scratch::Outcome r =
        cli_scratch::run(std::string(FRACDESIGN_EXE) + " gap --model " + (d / (tag + ".json")).string() + " --data " +
                             (d / "data.csv").string() + " --effects gain_error,sensor_offset --out " + out.string(),
                         err);
    return {r.status, r.err, out};
}

// One line naming each of `words` (the field, the value, what is allowed).
void expect_refused(const nlohmann::json& model, const std::string& tag, const std::vector<std::string>& words)
{
    const Outcome r = run(model, tag);
    EXPECT_NE(r.status, 0) << tag;
    for (const std::string& w : words) EXPECT_NE(r.err.find(w), std::string::npos) << tag << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << tag << ": " << r.err;
    EXPECT_FALSE(fs::exists(r.out)) << tag;
}

}  // namespace

TEST(GapDocumentCli, a_foprocess_nominal_runs_end_to_end_with_its_realization_in_result_json)
{
    const nlohmann::json m = {{"schema", "frac.model"}, {"version", 1}, {"kind", "foprocess"}, {"K", 1.5},
                              {"T", 0.5},               {"lambda", 1.0}, {"tau", 0.02}, {"gap", {{"noise", {{"y", 0.01}}}}}};
    const Outcome r = run(m, "fo_ok");
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(r.out / "result.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_NE(j["data"]["realization"].get<std::string>().find("input delay of 2 samples"), std::string::npos)
        << j["data"]["realization"];
    EXPECT_TRUE(j.contains("noise_floor"));
}

TEST(GapDocumentCli, refuses_a_bad_input_delay)
{
    expect_refused(lag({{"input_delay", -0.1}}), "delay_neg", {"gap.input_delay", "-0.1", ">= 0 in seconds"});
    expect_refused(lag({{"input_delay", "long"}}), "delay_str", {"gap.input_delay", "\"long\"", ">= 0 in seconds"});
}

TEST(GapDocumentCli, refuses_a_bad_initial_state)
{
    expect_refused(lag({{"initial_state", "warm"}}), "start_word",
                   {"gap.initial_state", "\"warm\"", "\"fitted\", \"at_rest\" or {\"given\""});
    expect_refused(lag({{"initial_state", {{"given", {1.0, 2.0}}}}}), "start_len",
                   {"gap.initial_state.given", "[1.0,2.0]", "one number per plant state (1)"});
}

TEST(GapDocumentCli, refuses_at_rest_for_a_plant_that_integrates_its_first_input)
{
    nlohmann::json m = lag({{"initial_state", "at_rest"}});
    m["A"] = {{0.0}};
    // The record's first input is 0: at rest is x0 = 0, accepted.
    EXPECT_EQ(run(m, "rest_zero").status, 0);
    nlohmann::json shifted = m;
    shifted["gap"]["input_limits"] = {{"u", {0.2, 5.0}}};  // the first input clamped to 0.2: no steady state
    expect_refused(shifted, "rest_integrator", {"gap.initial_state", "\"at_rest\"", "no steady state", "\"fitted\""});
}

TEST(GapDocumentCli, refuses_a_bad_noise)
{
    expect_refused(lag({{"noise", {{"y", 0.0}}}}), "noise_zero", {"gap.noise.y", "0.0", "noise std > 0"});
    expect_refused(lag({{"noise", {{"z", 0.1}}}}), "noise_name", {"gap.noise.z", "0.1", "no model output"});
    expect_refused(lag({{"noise", 0.1}}), "noise_num", {"gap.noise", "0.1", "{\"output\": noise std > 0}"});
}

TEST(GapDocumentCli, refuses_noise_that_leaves_out_a_compared_output)
{
    nlohmann::json m = lag({{"noise", {{"y", 0.01}}}});
    m["C"] = {{1.0}, {2.0}};
    m["D"] = {{0.0}, {0.0}};
    m["outputs"] = {"y", "u"};  // "u" is a data column too, so it is compared
    expect_refused(m, "noise_missing", {"gap.noise", "'u'", "every compared output"});
}

TEST(GapDocumentCli, refuses_bad_input_limits)
{
    expect_refused(lag({{"input_limits", {{"u", {1.0, -1.0}}}}}), "lim_order", {"gap.input_limits.u", "[1.0,-1.0]", "lo < hi"});
    expect_refused(lag({{"input_limits", {{"w", {-1.0, 1.0}}}}}), "lim_name", {"gap.input_limits.w", "no model input"});
    expect_refused(lag({{"input_limits", {{"u", 2.0}}}}), "lim_num", {"gap.input_limits.u", "2.0", "[lo, hi]"});
}

TEST(GapDocumentCli, refuses_bad_known_friction)
{
    const nlohmann::json v = {{"velocity", "y"}};
    auto with = [&](const nlohmann::json& f) { nlohmann::json g = v; g["friction"] = f; return lag(g); };
    expect_refused(lag({{"friction", {{"coulomb", 1.0}}}}), "fr_velocity", {"gap.friction", "gap.velocity"});
    expect_refused(with({{"coulomb", -1.0}}), "fr_negative", {"gap.friction.coulomb", "-1.0", ">= 0"});
    expect_refused(with({{"tanh_k", 0.0}}), "fr_k", {"gap.friction.tanh_k", "0.0", "> 0"});
    expect_refused(with({{"stiction", 2.0}}), "fr_key", {"gap.friction.stiction", "viscous, coulomb, tanh_k"});
    expect_refused(with(3.0), "fr_kind", {"gap.friction", "3.0", "\"coulomb\""});
}

TEST(GapDocumentCli, refuses_open_loop_fields_in_a_closed_loop)
{
    nlohmann::json m = lag({{"input_delay", 0.01},
                            {"closed_loop",
                             {{"references", {"u"}},
                              {"measured", {"y"}},
                              {"controller", {{"time", "discrete"}, {"Ts", 0.01}, {"A", {{0.0}}}, {"B", {{0.0, 0.0}}},
                                              {"C", {{0.0}}}, {"D", {{1.0, -1.0}}}}}}}});
    m["outputs"] = {"y"};
    expect_refused(m, "cl_delay", {"gap.input_delay", "0.01", "closed_loop.delay_samples"});
}

TEST(GapDocumentCli, refuses_a_bad_realization_and_an_improper_kind)
{
    const nlohmann::json fo = {{"schema", "frac.model"}, {"version", 1}, {"kind", "foprocess"}, {"K", 1.0},
                               {"T", 0.5},               {"lambda", 0.7}, {"tau", 0.0}};
    nlohmann::json n0 = fo;
    n0["gap"] = {{"realization", {{"N", 0}}}};
    expect_refused(n0, "real_n", {"gap.realization.N", "0", "integer in [1, 40]"});
    nlohmann::json wh = fo;
    wh["gap"] = {{"realization", {{"wb", 10.0}, {"wh", 1.0}}}};
    expect_refused(wh, "real_wh", {"gap.realization.wh", "1", "above wb"});
    nlohmann::json extra = fo;
    extra["gap"] = {{"realization", {{"order", 3}}}};
    expect_refused(extra, "real_key", {"gap.realization.order", "3", "wb, wh and N"});
    const nlohmann::json antenna = {{"schema", "frac.model"},
                                    {"version", 1},
                                    {"kind", "antenna"},
                                    {"link", {{"L", 0.7}, {"rho", 0.01}, {"E", 7e10}, {"I", 2e-12}}},
                                    {"structure", "IV"},
                                    {"damping", {{"zeta", 1e-4}, {"alpha", 0.8}, {"gamma", 0.0}, {"lambda", 0.0}}}};
    expect_refused(antenna, "antenna", {"kind 'antenna'", "improper", "statespace"});
}
