// test_model_json.cpp - the versioned JSON model format: round trips of every kind, one-line errors
// naming the field, and `fracdesign model --model FILE` on good and bad files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "fracdesign/model_json.hpp"

using namespace fracdesign;
using nlohmann::json;

namespace {

std::string error_of(const json& j)
{
    try {
        model_from_json(j);
    } catch (const ModelFormatError& e) {
        return e.what();
    }
    return "no error";
}

json beam_doc()
{
    BeamModelSpec b;
    b.beam = wang_steel_beam();
    b.N = 9;
    return model_to_json(b);
}

StateSpace small_ss(double Ts)
{
    StateSpace s;
    s.A = Eigen::MatrixXd::Identity(2, 2) * -1.0;
    s.A(0, 1) = 0.5;
    s.B = Eigen::MatrixXd::Ones(2, 1);
    s.C = Eigen::MatrixXd::Ones(1, 2);
    s.D = Eigen::MatrixXd::Zero(1, 1);
    s.inputs = {"u [N m]"};
    s.outputs = {"y [rad/s]"};
    s.Ts = Ts;
    return s;
}

}  // namespace

TEST(ModelJson, every_kind_round_trips)
{
    ArmModelSpec arm;
    arm.beam = wang_steel_beam();
    arm.drive = wang_drive();
    AntennaModelSpec ant;
    ant.damping = haro_nominal_VI();
    const std::vector<ModelSpec> specs = {BeamModelSpec{wang_steel_beam(), 5, Collocation::Equidistant},
                                          arm,
                                          ant,
                                          CollocatedModelSpec{0.23, false},
                                          FoProcessModelSpec{feliu_benftima_robot()},
                                          small_ss(0.0),
                                          small_ss(1.2e-3)};
    for (const ModelSpec& m : specs) {
        const json j = model_to_json(m);
        EXPECT_EQ(j["schema"], "frac.model");
        EXPECT_EQ(j["version"], 1);
        EXPECT_EQ(j["units"], "SI");
        EXPECT_EQ(model_to_json(model_from_json(j)), j) << j.dump();
        EXPECT_EQ(model_from_json(json::parse(j.dump())).index(), m.index());
    }
    const StateSpace back = std::get<StateSpace>(model_from_json(model_to_json(small_ss(1.2e-3))));
    EXPECT_DOUBLE_EQ(back.Ts, 1.2e-3);
    EXPECT_EQ(back.A, small_ss(0).A);
}

// Found by tests/fuzz/fuzz_model_json: a state space read without "inputs"
// or "outputs" (both optional) was written with "inputs": [], which the
// reader then refused ("must have 1 names, has 0").
TEST(ModelJson, state_space_without_signal_names_round_trips)
{
    json j = model_to_json(small_ss(0.0));
    j.erase("inputs");
    j.erase("outputs");
    const json out = model_to_json(model_from_json(j));
    EXPECT_FALSE(out.contains("inputs"));
    EXPECT_FALSE(out.contains("outputs"));
    EXPECT_EQ(model_to_json(model_from_json(out)), out);
}

TEST(ModelJson, state_space_of_rational_kinds_and_refusal_for_irrational_ones)
{
    EXPECT_EQ(model_state_space(BeamModelSpec{wang_steel_beam(), 9, Collocation::GaussLegendre}).nx(), 36);
    ArmModelSpec arm{wang_steel_beam(), wang_drive(), ArmOptions()};
    EXPECT_EQ(model_state_space(arm).nx(), 16);
    arm.options.reduce = false;
    EXPECT_EQ(model_state_space(arm).nx(), 40);
    EXPECT_EQ(model_state_space(CollocatedModelSpec{}).nx(), 4);
    EXPECT_THROW(model_state_space(AntennaModelSpec{}), std::invalid_argument);
    EXPECT_THROW(model_state_space(FoProcessModelSpec{}), std::invalid_argument);
}

TEST(ModelJson, collocation_count_is_bounded_before_it_is_narrowed)
{
    // N = 3e9 as a JSON integer wrapped around in the int it was read into; each is refused naming the
    // field, the value and the range.
    for (const json n : {json(3000000000LL), json(18446744073709551615ULL), json(-3000000000LL), json(kModelNMax + 1),
                         json(1)}) {
        json j = beam_doc();
        j["discretization"]["N"] = n;
        const std::string e = error_of(j);
        EXPECT_NE(e.find("'discretization.N': must lie in [2, 200] (got " + n.dump() + ")"), std::string::npos) << e;
    }
    json j = beam_doc();
    j["discretization"]["N"] = kModelNMax;
    EXPECT_NO_THROW(model_from_json(j));
}

TEST(ModelJson, bad_documents_give_one_line_errors_naming_the_field)
{
    json j = beam_doc();
    j["discretization"]["N"] = 1;
    EXPECT_NE(error_of(j).find("'discretization.N'"), std::string::npos);
    j = beam_doc();
    j["beam"]["L"] = -1.2;
    EXPECT_NE(error_of(j).find("'beam.L'"), std::string::npos);
    j = beam_doc();
    j["beam"]["K_s"] = NAN;
    EXPECT_NE(error_of(j).find("'beam.K_s': must be finite"), std::string::npos);
    j = beam_doc();
    j["beam"]["rho"] = "heavy";
    EXPECT_NE(error_of(j).find("'beam.rho': must be a number"), std::string::npos);
    j = beam_doc();
    j["beam"].erase("K_b");
    EXPECT_NE(error_of(j).find("'beam.K_b': is missing"), std::string::npos);
    j = beam_doc();
    j["version"] = 2;
    EXPECT_NE(error_of(j).find("'version'"), std::string::npos);
    j = beam_doc();
    j["schema"] = "other";
    EXPECT_NE(error_of(j).find("'schema'"), std::string::npos);
    j = beam_doc();
    j["kind"] = "robot";
    EXPECT_NE(error_of(j).find("'kind'"), std::string::npos);
    j = beam_doc();
    j["discretization"]["collocation"] = "chebyshev";
    EXPECT_NE(error_of(j).find("'discretization.collocation'"), std::string::npos);
    for (const json& d : {beam_doc()}) EXPECT_EQ(error_of(d), "no error");
}

TEST(ModelJson, inconsistent_documents_are_refused)
{
    AntennaModelSpec ant;
    ant.structure = AntennaStructure::I;
    ant.damping = {1e-4, 1.0, 0.0, 0.0};
    json j = model_to_json(ant);
    EXPECT_EQ(error_of(j), "no error");
    j["damping"]["alpha"] = 0.5;  // structure I fixes alpha = 1 (seed 000 Table 2)
    EXPECT_NE(error_of(j).find("'damping.alpha': structure I fixes it to 1"), std::string::npos);
    j = model_to_json(small_ss(0));
    j["B"] = json::array({json::array({1.0})});  // 1 row for 2 states
    EXPECT_NE(error_of(j).find("'B': must have 2 rows"), std::string::npos);
    j = model_to_json(small_ss(0));
    j["C"][0] = json::array({1.0});
    EXPECT_NE(error_of(j).find("'C[0]': must have 2 columns"), std::string::npos);
    j = model_to_json(small_ss(0));
    j["inputs"] = json::array({"a", "b"});
    EXPECT_NE(error_of(j).find("'inputs'"), std::string::npos);
    j = model_to_json(small_ss(0));
    j["time"] = "discrete";
    EXPECT_NE(error_of(j).find("'Ts'"), std::string::npos);
    ArmModelSpec arm{wang_steel_beam(), wang_drive(), ArmOptions()};
    j = model_to_json(arm);
    j["drive"]["r_h"] = -0.01;
    EXPECT_NE(error_of(j).find("'drive.r_h'"), std::string::npos);
    j = model_to_json(arm);
    j["reduction"]["shifts"] = json::array();
    EXPECT_NE(error_of(j).find("'reduction.shifts'"), std::string::npos);
    // every message is a single line
    EXPECT_EQ(error_of(j).find('\n'), std::string::npos);
}

TEST(ModelJson, cli_reads_a_model_file_and_reports_a_bad_one_in_one_line)
{
    const std::string dir = std::string(FRAC_BINARY_DIR) + "/test_model_json_tmp";
    std::system(("mkdir -p " + dir).c_str());
    write_model_file(dir + "/good.json", CollocatedModelSpec{0.12, true});
    const std::string exe = FRACDESIGN_EXE;
    EXPECT_EQ(std::system((exe + " model --model " + dir + "/good.json --json > " + dir + "/out.json").c_str()), 0);
    std::ifstream out(dir + "/out.json");
    const json r = json::parse(out);
    EXPECT_NEAR(r["result"]["a1"].get<double>(), 6.014, 1e-3);
    json bad = model_to_json(CollocatedModelSpec{0.12, true});
    bad["m2_lb"] = -0.1;
    std::ofstream(dir + "/bad.json") << bad.dump();
    std::ofstream(dir + "/broken.json") << "{\"schema\": ";
    for (const char* f : {"bad", "broken"}) {
        const int rc = std::system((exe + " model --model " + dir + "/" + f + ".json 2> " + dir + "/err.txt").c_str());
        EXPECT_NE(rc, 0) << f;
        std::ifstream e(dir + "/err.txt");
        std::stringstream ss;
        ss << e.rdbuf();
        const std::string msg = ss.str();
        EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
        EXPECT_NE(msg.find(std::string(f) == "bad" ? "'m2_lb'" : "broken.json"), std::string::npos) << msg;
    }
}

TEST(ModelJson, cli_refuses_bad_parameters_with_usage_errors)
{
    const std::string exe = FRACDESIGN_EXE;
    auto rc = [&](const std::string& args) {
        const int r = std::system((exe + " model " + args + " > /dev/null 2>&1").c_str());
        return WIFEXITED(r) ? WEXITSTATUS(r) : -1;
    };
    EXPECT_EQ(rc("beam --N 9 --modes 3"), 0);
    EXPECT_EQ(rc("arm --full --modes 2 --json"), 0);
    EXPECT_EQ(rc("antenna --structure V --gamma 0.04 --lambda 1.2"), 0);
    EXPECT_EQ(rc("foprocess --lambda 1.5 --w 1,2"), 0);
    EXPECT_EQ(rc("robot"), 2);                           // unknown kind
    EXPECT_EQ(rc("beam --N 1"), 2);                      // N < 2
    EXPECT_EQ(rc("beam --collocation chebyshev"), 2);    // unknown node set
    EXPECT_EQ(rc("beam --Nn 9"), 2);                     // typo in an option
    EXPECT_EQ(rc("collocated --w 10,-1"), 2);            // frequency <= 0
    EXPECT_EQ(rc("antenna --structure VII"), 2);         // unknown structure
    EXPECT_EQ(rc("antenna --structure I --alpha 0.5"), 2);  // fixed by Table 2
    EXPECT_EQ(rc("beam --L -1"), 1);                     // negative length (model validation)
    EXPECT_EQ(rc("collocated --m2 0"), 1);               // tip mass must be > 0
    EXPECT_EQ(rc("foprocess --T nan"), 2);               // not a finite number
    EXPECT_EQ(rc("arm --shifts 16,16,16"), 1);           // Krylov basis loses rank
}

namespace {
// A physical collocated arm the paper does not print (docs/model_format.md, kind collocated).
json physical_collocated()
{
    return json::parse(R"({"schema": "frac.model", "version": 1, "kind": "collocated", "units": "SI",
        "link": {"L": 0.8, "EI": 2.5},
        "masses": {"m1": 0.3, "x1": 0.35, "m2": 0.2, "m2_range": [0.05, 0.5]},
        "moment_gain": 1.0, "inner_loop": {"eps": 0.004},
        "damping": {"rayleigh_a": 0.08, "rayleigh_b": 4e-5}, "damped": true})");
}
}  // namespace

TEST(ModelJson, physical_collocated_arm_round_trips_and_each_bad_field_is_named_with_value_and_range)
{
    const ModelSpec m = model_from_json(physical_collocated());
    const auto& c = std::get<CollocatedModelSpec>(m);
    EXPECT_EQ(c.arm.form, CollocatedArm::Form::Physical);
    EXPECT_EQ(c.arm.x1, 0.35);
    EXPECT_EQ(c.arm.eps, 0.004);
    EXPECT_EQ(model_to_json(model_from_json(model_to_json(m))), model_to_json(m));
    EXPECT_EQ(model_state_space(m).nx(), 4);
    // the paper's form still reads, with its printed range by default
    const auto& p = std::get<CollocatedModelSpec>(
        model_from_json(json{{"schema", "frac.model"}, {"version", 1}, {"kind", "collocated"}, {"m2_lb", 0.05}}));
    EXPECT_EQ(p.arm.form, CollocatedArm::Form::Printed);
    EXPECT_EQ(p.arm.m2_min, 0.01);
    struct Bad {
        const char* pointer;
        json value;
        const char* expect;
    };
    const Bad bad[] = {
        {"/link/EI", -1.0, "field 'link.EI': is -1, must be finite and > 0 (N m^2)"},
        {"/link/L", "long", "field 'link.L': must be a number"},
        {"/masses/x1", 0.8, "field 'masses.x1': is 0.8, must be in (0, link.L) = (0, 0.8) m"},
        {"/masses/m2", 0.6, "field 'masses.m2': is 0.6, must be inside masses.m2_range = [0.05, 0.5] kg"},
        {"/masses/m2_range", json::array({0.05}), "field 'masses.m2_range': must be an array [lo, hi]"},
        {"/inner_loop/eps", -0.1, "field 'inner_loop.eps': is -0.1, must be in [0, 1] s"},
        {"/damping/rayleigh_a", -0.5, "field 'damping.rayleigh_a': is -0.5, must be finite and >= 0 (1/s)"},
        {"/moment_gain", 0.0, "field 'moment_gain': is 0, must be finite and > 0"},
        {"/m2_lb", 0.1, "field 'm2_lb': is the printed robot's tip mass"},
    };
    for (const Bad& b : bad) {
        json j = physical_collocated();
        j[json::json_pointer(b.pointer)] = b.value;
        const std::string msg = error_of(j);
        EXPECT_NE(msg.find(b.expect), std::string::npos) << b.pointer << ": " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos);
    }
    json j = physical_collocated();
    j.erase("masses");
    EXPECT_NE(error_of(j).find("field 'masses': is missing"), std::string::npos) << error_of(j);
    j.erase("link");
    EXPECT_NE(error_of(j).find("field 'masses': is missing (give link and masses, or m2_lb"), std::string::npos);
}
