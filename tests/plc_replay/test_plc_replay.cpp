// The gap replay's controller kind "armctrl" (bench/src/plc_replay, issue 21
// items 2, 3 and 5): its TorqueSetpoint sequence is bit-identical to the
// ArmCtrl program run directly in the plc_rt lockstep on the same inputs
// (Exp. A: PD + friction compensation, Exp. D: LQG with delays; both through
// the torque limit), a clone taken mid-record continues bit-identically, and
// a table is refused with the field ParTable / ArmCtrl's layout names.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "fracbench/armctrl_controller.hpp"
#include "fracdesign/gap/controller.hpp"
#include "fracdesign/gap/nominal.hpp"
#include "fracdesign/tables/ptable.hpp"

extern "C" {
#include "ArmCtrl.h"
#include "FracCtrl.h"
#include "ImuRead.h"
#include "frac/ptable.h"
#include "plc_rt.h"
}

namespace {

using fracdesign::gap::Controller;
using fracdesign::gap::ControllerContext;

std::vector<std::uint8_t> read_bytes(const std::string& p)
{
    std::ifstream in(p, std::ios::binary);
    EXPECT_TRUE(bool(in)) << p;
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& p, const std::vector<std::uint8_t>& b)
{
    std::ofstream o(p, std::ios::binary);
    o.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

std::string table_path(char exp) { return std::string(PLC_REPLAY_TABLES) + "/armctrl_" + exp + ".bin"; }

struct In {
    double angle, velocity, tip;
};

// Inputs that sweep the controller through its torque limit: a motor angle
// far from the feedforward's (a 2 rad tone) and a tip rate with a 7 Hz part.
std::vector<In> inputs(int n, double T)
{
    std::vector<In> v(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        const double t = k * T, w = 2 * M_PI * 0.9;
        v[size_t(k)] = {2.0 * std::sin(w * t), 2.0 * w * std::cos(w * t),
                        0.8 * std::cos(2 * M_PI * 7.0 * t) + 0.3 * std::sin(w * t)};
    }
    return v;
}

// The reference: ArmCtrl (from the table) and ImuRead in the plc_rt task
// runtime with the PLC's Table 2.3 classes (100 us tick, Cyclic #1 = T,
// Cyclic #2 = T/2), driven by hand as tests/plc_blocks and hil/plc run it;
// Start TRUE from the second cycle.
struct Direct {
    armctrl a;
    imuread m;
    plc_program pa, pm;
    plc_rt rt;
    armctrl_table_storage store;
    armctrl_inputs di;
    armctrl_outputs dout;
    imuread_inputs ci;
    imuread_outputs co;
};

std::vector<double> run_direct(const std::vector<std::uint8_t>& table, const std::vector<In>& in, double T)
{
    auto d = std::make_unique<Direct>();
    std::memset(static_cast<void*>(d.get()), 0, sizeof *d);
    const unsigned us = unsigned(std::lround(T * 1e6));
    const std::string cfg_text = "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n"
                                 "violation_reaction = continue\n[cyclic1]\nduration_us = " + std::to_string(us) +
                                 "\nsim_cost_us = 300\nprograms = ArmCtrl\n[cyclic2]\nduration_us = " +
                                 std::to_string(us / 2) + "\nsim_cost_us = 50\nprograms = ImuRead\n";
    armctrl_program_table(&d->a, &d->pa, table.data(), UDINT(table.size()), &d->store, &d->di, &d->co, &d->dout);
    imuread_program(&d->m, &d->pm, 1.0f, &d->ci, &d->co);
    const plc_program* reg[2] = {&d->pa, &d->pm};
    plc_rt_config cfg;
    char err[256];
    EXPECT_EQ(plc_rt_config_parse(&cfg, cfg_text.c_str(), "t", err, sizeof err), PLC_RT_OK) << err;
    EXPECT_EQ(plc_rt_init(&d->rt, &cfg, reg, 2, err, sizeof err), PLC_RT_OK) << err;
    EXPECT_EQ(plc_rt_start(&d->rt), PLC_RT_OK);
    EXPECT_FALSE(d->a.fault);
    std::vector<double> tau;
    for (size_t k = 0; k < in.size(); ++k) {
        d->di.MotorAngle = REAL(in[k].angle);
        d->di.MotorVelocity = REAL(in[k].velocity);
        d->di.DriveCounter++;
        d->di.Start = k >= 1;
        d->ci.RawRate = REAL(in[k].tip);
        d->ci.FrameCounter++;
        plc_rt_run_sim(&d->rt, us / 100u);
        tau.push_back(d->dout.TorqueEnable ? double(d->dout.TorqueSetpoint) : 0.0);
    }
    plc_rt_stop(&d->rt);
    return tau;
}

ControllerContext context(double T)
{
    ControllerContext c;
    c.Ts = T;
    c.measured = {"motor_angle", "motor_velocity", "imu_rate"};
    c.outputs = 1;
    c.inputs = {"torque_cmd"};
    c.where = "model gap.closed_loop.controller";
    c.base_dir = "/";
    return c;
}

nlohmann::json doc(const std::string& table)
{
    return {{"kind", "armctrl"},
            {"table", table},
            {"inputs", {{"MotorAngle", "motor_angle"}, {"MotorVelocity", "motor_velocity"}, {"TipRate", "imu_rate"}}},
            {"output", "torque_cmd"}};
}

std::unique_ptr<Controller> make(const nlohmann::json& d, double T)
{
    fracbench::register_armctrl_controller();
    return fracdesign::gap::make_controller(d, context(T));
}

std::vector<double> run_kind(Controller& proto, const std::vector<In>& in, size_t clone_at, std::vector<double>* from_clone)
{
    std::unique_ptr<Controller> c = proto.clone();
    const double y0[3] = {in[0].angle, in[0].velocity, in[0].tip};
    c->start(nullptr, y0);
    std::unique_ptr<Controller> copy;
    std::vector<double> tau;
    for (size_t k = 0; k < in.size(); ++k) {
        if (k == clone_at) copy = c->clone();
        const double y[3] = {in[k].angle, in[k].velocity, in[k].tip};
        double u = 0;
        c->step(nullptr, y, &u);
        tau.push_back(u);
        if (copy && from_clone) {
            copy->step(nullptr, y, &u);
            from_clone->push_back(u);
        }
    }
    return tau;
}

std::string message_of(const nlohmann::json& d, double T)
{
    try {
        make(d, T);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

class Exp : public ::testing::TestWithParam<char> {};

TEST_P(Exp, torque_setpoints_are_bit_identical_to_the_program_in_the_lockstep_runtime)
{
    const double T = 1.2e-3;
    const std::vector<std::uint8_t> table = read_bytes(table_path(GetParam()));
    const std::vector<In> in = inputs(2500, T);  // 3 s: the Table 8.5 move (0.5 .. 2 s) and after
    const std::vector<double> ref = run_direct(table, in, T);
    auto proto = make(doc(table_path(GetParam())), T);
    std::vector<double> tail;
    const size_t at = 1234;
    const std::vector<double> got = run_kind(*proto, in, at, &tail);
    ASSERT_EQ(got.size(), ref.size());
    size_t limited = 0, differ = 0;
    const double lim = proto->output_limit();
    for (size_t k = 0; k < ref.size(); ++k) {
        differ += got[k] != ref[k];
        limited += std::fabs(ref[k]) >= lim;
    }
    EXPECT_EQ(differ, 0u);
    // the inputs drive the law into its limit for a good part of the record
    EXPECT_GT(double(limited), 0.1 * double(ref.size())) << "limit " << lim;
    EXPECT_GT(lim, 0.0);
    ASSERT_EQ(tail.size(), ref.size() - at);
    for (size_t k = 0; k < tail.size(); ++k) ASSERT_EQ(tail[k], ref[at + k]) << "clone, sample " << at + k;
}

INSTANTIATE_TEST_SUITE_P(ArmCtrl, Exp, ::testing::Values('A', 'D'));

TEST(ArmCtrlKind, a_missing_table_file_is_refused_naming_the_field)
{
    const std::string m = message_of(doc("/nonexistent/ctrl.bin"), 1.2e-3);
    EXPECT_NE(m.find("gap.closed_loop.controller.table"), std::string::npos) << m;
    EXPECT_NE(m.find("cannot open"), std::string::npos) << m;
}

// The field ParTable's validation names for these bytes (frac_ptable_open,
// the check ParTable runs), and that the PLC's ParTable block refuses them.
std::string partable_field(const std::vector<std::uint8_t>& b)
{
    struct ParTable pt;
    std::memset(&pt, 0, sizeof pt);
    pt.pData = const_cast<USINT*>(b.data());
    pt.Size = UDINT(b.size());
    pt.Enable = 1;
    ParTable(&pt);
    EXPECT_TRUE(pt.Error);
    frac_ptable t;
    EXPECT_NE(frac_ptable_open(&t, b.data(), b.size()), FRAC_OK);
    return t.fail_field;
}

TEST(ArmCtrlKind, a_table_failing_its_crc_or_truncated_is_refused_with_partables_field)
{
    std::vector<std::uint8_t> b = read_bytes(table_path('D'));
    const std::string dir = ::testing::TempDir();
    std::vector<std::uint8_t> crc = b;
    crc[crc.size() / 2] ^= 0x40;
    write_bytes(dir + "/crc.bin", crc);
    std::string m = message_of(doc(dir + "/crc.bin"), 1.2e-3);
    const std::string f = partable_field(crc);
    EXPECT_EQ(f, "crc32");
    EXPECT_NE(m.find("field " + f), std::string::npos) << m;
    EXPECT_NE(m.find("gap.closed_loop.controller.table"), std::string::npos) << m;
    std::vector<std::uint8_t> cut(b.begin(), b.begin() + long(b.size() / 3));
    write_bytes(dir + "/cut.bin", cut);
    m = message_of(doc(dir + "/cut.bin"), 1.2e-3);
    const std::string fc = partable_field(cut);
    EXPECT_FALSE(fc.empty());
    EXPECT_NE(m.find("field " + fc), std::string::npos) << m;
}

TEST(ArmCtrlKind, a_table_of_the_wrong_layout_is_refused_naming_armctrls_entry)
{
    fracdesign::tables::ParamTable t = fracdesign::tables::table_from_binary(read_bytes(table_path('A')));
    for (auto& e : t.entries)
        if (e.name == "ff_lead") {  // 1 x 4 in ArmCtrl's layout: make it 1 x 3
            e.cols = 3;
            e.values.resize(3);
        }
    const std::string p = ::testing::TempDir() + "/dims.bin";
    write_bytes(p, fracdesign::tables::to_binary(t));
    const std::string m = message_of(doc(p), 1.2e-3);
    EXPECT_NE(m.find("entry 'ff_lead'"), std::string::npos) << m;
    EXPECT_NE(m.find("layout"), std::string::npos) << m;
}

TEST(ArmCtrlKind, a_record_whose_sample_time_is_not_the_tables_cycle_is_refused)
{
    const std::string m = message_of(doc(table_path('D')), 1e-3);
    EXPECT_NE(m.find("gap.closed_loop.controller.table"), std::string::npos) << m;
    EXPECT_NE(m.find("'ts'"), std::string::npos) << m;
}

TEST(ArmCtrlKind, an_input_mapped_to_no_column_or_output_is_refused_naming_it)
{
    nlohmann::json d = doc(table_path('D'));
    d["inputs"]["TipRate"] = "gyro";
    std::string m = message_of(d, 1.2e-3);
    EXPECT_NE(m.find("gap.closed_loop.controller.inputs.TipRate: 'gyro'"), std::string::npos) << m;
    d = doc(table_path('D'));
    d["inputs"]["Torque"] = "imu_rate";
    m = message_of(d, 1.2e-3);
    EXPECT_NE(m.find("inputs.Torque: not an ArmCtrl input"), std::string::npos) << m;
    d = doc(table_path('D'));
    d["output"] = "voltage";
    m = message_of(d, 1.2e-3);
    EXPECT_NE(m.find("controller.output: 'voltage'"), std::string::npos) << m;
}

}  // namespace
