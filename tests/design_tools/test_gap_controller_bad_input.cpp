// test_gap_controller_bad_input.cpp - a controller document whose limits,
// gains, orders, dividers or tables are inconsistent, or that names an
// unknown kind or field, is refused with one message naming the field
// (issue 21 item 5); `fracdesign gap` then exits non-zero, prints that one
// line and writes no output.
#include <gtest/gtest.h>

#include "cli_scratch.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <unistd.h>

#include "fracdesign/gap/nominal.hpp"

using namespace fracdesign::gap;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const double kTs = 0.01;

json model(const json& controller, const json& saturation = json())
{
    json d = {{"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "msd"},
              {"time", "continuous"}, {"A", {{0, 1}, {-20, -2}}}, {"B", {{0}, {1}}}, {"C", {{1, 0}, {0, 1}}},
              {"D", {{0}, {0}}}, {"inputs", {"u"}}, {"outputs", {"x", "v"}},
              {"gap", {{"velocity", "v"}, {"force_input", "u"},
                       {"closed_loop", {{"references", {"r"}}, {"measured", {"x", "v"}}, {"controller", controller}}}}}};
    if (!saturation.is_null()) d["gap"]["closed_loop"]["saturation"] = saturation;
    return d;
}

json fopid() { return {{"kind", "fopid"}, {"kp", 2.0}, {"ki", 1.0}, {"lambda", 0.8}, {"umin", -5}, {"umax", 5}}; }

json with(json d, const std::string& key, const json& v)
{
    d[key] = v;
    return d;
}

// The message of nominal_from_json on this document ("" if it is accepted).
std::string refusal(const json& doc)
{
    try {
        nominal_from_json(doc, kTs, FRAC_SOURCE_DIR "/tests/design_tools/fixtures");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

void expect_names(const json& doc, const std::string& field, const std::string& also = "")
{
    const std::string m = refusal(doc);
    EXPECT_NE(m.find("model gap.closed_loop." + field + ":"), std::string::npos) << "got: '" << m << "'";
    if (!also.empty()) EXPECT_NE(m.find(also), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

json lut(const json& x, const json& y) { return {{{"lut1d", {{"x", x}, {"y", y}}}, {"input", "r"}}}; }

}  // namespace

TEST(GapControllerBadInput, inconsistent_limits)
{
    expect_names(model(with(fopid(), "umin", 5)), "controller.umin", "umin < umax");
    expect_names(model(with(fopid(), "limits", {{"min", 3}, {"max", 1}})), "controller.limits.min", "min must be < max");
    expect_names(model(with(fopid(), "limits", -2)), "controller.limits", "> 0");
    expect_names(model(fopid(), {{"min", 2}, {"max", -1}}), "saturation.min");
    expect_names(model(fopid(), 0), "saturation");
    EXPECT_EQ(refusal(model(fopid(), {{"min", -2}, {"max", 7}})), "");
}

TEST(GapControllerBadInput, non_finite_or_malformed_gains)
{
    const double inf = std::numeric_limits<double>::infinity();
    expect_names(model(with(fopid(), "kp", inf)), "controller.kp", "a finite number");
    expect_names(model(with(fopid(), "ki", "much")), "controller.ki", "\"much\"");
    expect_names(model(with(with(fopid(), "tt", -1), "antiwindup", "backcalc")), "controller.tt");
    expect_names(model(with(fopid(), "antiwindup", "soft")), "controller.antiwindup", "\"clamp\"");
    expect_names(model({{"kind", "collocated"}, {"kc", -1}, {"alpha", 0.8}}), "controller.kc", "Kc > 0");
    expect_names(model(with(fopid(), "friction", {{"k", 0}, {"b0", 1}, {"velocity", "v"}})), "controller.friction.k");
    expect_names(model(with(fopid(), "rate_limit", {{"output", -3}})), "controller.rate_limit.output", "> 0");
}

TEST(GapControllerBadInput, orders_out_of_range)
{
    expect_names(model(with(fopid(), "lambda", 2.5)), "controller.lambda", "(0, 2)");
    expect_names(model(with(with(fopid(), "kd", 1), "mu", -0.1)), "controller.mu", "[0, 2]");
    expect_names(model({{"kind", "collocated"}, {"kc", 1}, {"alpha", 2.2}}), "controller.alpha", "(0, 2)");
    expect_names(model({{"kind", "collocated"}, {"kc", 1}, {"alpha", 0.8}, {"fbeta", 3}}), "controller.fbeta");
}

TEST(GapControllerBadInput, dividers_below_one_or_not_integer)
{
    for (const json& d : {json(0), json(2.5), json(-3), json("4")}) expect_names(model(with(fopid(), "divider", d)), "controller.divider", "an integer >= 1");
    json c = {{"kind", "cascade"}, {"loops", {fopid(), with(fopid(), "divider", 0.5)}}};
    expect_names(model(c), "controller.loops[1].divider");
    EXPECT_EQ(refusal(model(with(fopid(), "divider", 3))), "");
}

TEST(GapControllerBadInput, tables_with_bad_breakpoints_or_sizes)
{
    expect_names(model(with(fopid(), "feedforward", lut({0, 1, 1, 2}, {0, 1, 2, 3}))), "controller.feedforward[0].lut1d.x[2]",
                 "strictly increasing");
    expect_names(model(with(fopid(), "feedforward", lut({0, 1, 2}, {0, 1}))), "controller.feedforward[0].lut1d.x", "sizes must agree");
    expect_names(model(with(fopid(), "feedforward", lut({0}, {0}))), "controller.feedforward[0].lut1d.y", "at least 2");
    const json traj = {{"data", {{0, 1, 2}, {0, 1}}}, {"dt", 0.1}, {"references", {"r", "r"}}};
    expect_names(model(with(fopid(), "reference_table", traj)), "controller.reference_table.data[1]", "same number");
    const json lead = {{"data", {{0, 1, 2}}}, {"dt", 0.1}, {"lead", {1, 2}}, {"references", {"r"}}};
    expect_names(model(with(fopid(), "reference_table", lead)), "controller.reference_table.lead");
    const json file = {{{"lut1d", {{"file", "no_such_table.csv"}}}, {"input", "r"}}};
    expect_names(model(with(fopid(), "feedforward", file)), "controller.feedforward[0].lut1d.file", "no_such_table.csv");
}

TEST(GapControllerBadInput, unknown_kind_or_field)
{
    expect_names(model(with(fopid(), "kind", "lqr")), "controller.kind", "fopid");
    expect_names(model(with(fopid(), "kind", "armctrl")), "controller.kind", "gap-plc");
    expect_names(model(with(fopid(), "kpp", 1)), "controller.kpp", "unknown field of controller kind 'fopid'");
    expect_names(model(with(fopid(), "op", {{"method", "gl"}, {"memmory", 10}})), "controller.op.memmory");
    expect_names(model(with(fopid(), "measured", "q")), "controller.measured", "x, v");
    expect_names(model({{"kind", "cascade"}, {"loops", {fopid()}}}), "controller.loops", "at least 2");
    expect_names(model({{"kind", "cascade"}, {"loops", {fopid(), with(fopid(), "gain", 2)}}}), "controller.loops[1].gain");
    expect_names(model({{"time", "discrete"}, {"Ts", kTs}, {"D", {{1, -1, 0}}}, {"saturaton", 3}}), "controller.saturaton");
}

namespace {

fs::path workdir() { return cli_scratch::dir("fracdesign_gap_ctl"); }

}  // namespace

TEST(GapControllerBadInput, fracdesign_gap_exits_non_zero_with_one_line_and_no_output)
{
    const fs::path d = workdir();
    {
        std::ofstream o(d / "data.csv");
        o << "t,r,x,v\n";
        for (int k = 0; k < 400; ++k) o << k * kTs << "," << std::sin(0.05 * k) << "," << 0.1 * std::sin(0.05 * k - 0.3) << "," << 0.01 * k << "\n";
    }
    const std::vector<std::pair<json, std::string>> cases = {
        {model(with(fopid(), "umin", 9)), "controller.umin"},
        {model(with(fopid(), "divider", 0)), "controller.divider"},
        {model(with(fopid(), "feedforward", lut({0, 2, 1}, {0, 1, 2}))), "controller.feedforward[0].lut1d.x[2]"},
        {model(with(fopid(), "lambda", 3)), "controller.lambda"},
        {model(with(fopid(), "kind", "pid")), "controller.kind"},
        {model(with(fopid(), "gain", 1)), "controller.gain"},
    };
    int i = 0;
    for (const auto& c : cases) {
        const fs::path m = d / ("model" + std::to_string(i) + ".json"), out = d / ("out" + std::to_string(i)), err = d / "err.txt";
        ++i;
        std::ofstream(m) << c.first.dump(1);
        const cli_scratch::Outcome r = cli_scratch::run(std::string(FRACDESIGN_EXE) + " gap --model " + m.string() +
                                                            " --data " + (d / "data.csv").string() + " --out " + out.string(),
                                                        err);
        EXPECT_NE(r.status, 0) << c.second;
        const std::string& e = r.err;
        EXPECT_NE(e.find(c.second + ":"), std::string::npos) << e;
        EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
        EXPECT_FALSE(fs::exists(out)) << c.second;
    }
    fs::remove_all(d);
}
