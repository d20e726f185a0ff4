// armctrl_controller.cpp - controller kind "armctrl" (armctrl_controller.hpp):
// the ArmCtrl program of plc_blocks in the plc_rt task runtime, lockstep.
//
// The runtime is configured as the PLC and the HIL controller node run it
// (Table 2.3 task classes, hil/plc/plc_law.c): system tick 100 us (400 us
// interface cycle x 0.25), ArmCtrl in Cyclic #1 with the table's cycle time
// T, ImuRead in Cyclic #2 with T/2 (the IMU rate reaches ArmCtrl through
// ImuRead's output image, so ArmCtrl sees it one ImuRead cycle late, as on
// the PLC), simulated CPU times 300 us and 50 us. One record sample is one
// Cyclic #1 cycle: the sample's inputs go into the process image, the
// runtime advances T / tick ticks (ArmCtrl latches at its release and
// publishes after its CPU time), and the published TorqueSetpoint is the
// sample's output (0 while TorqueEnable is FALSE, as the drive then applies
// no torque). DriveCounter and the IMU frame counter advance every sample:
// a replayed sensor is never stale, so the watchdogs never trip.
//
// State and clone(): plc_rt holds pointers to the program descriptors, the
// programs hold pointers to their I/O images, to the table storage and into
// their own blocks (ParTable's handle, libfrac objects in IEC storage), so a
// byte copy of the runtime would point into the original. clone() instead
// rebuilds the runtime from the (shared, immutable) table bytes, runs _INIT
// and replays every sample this controller has stepped since start(): the
// program is deterministic (simulated clock, no I/O), so the copy's state
// equals the original's bit for bit (test plc_replay_armctrl). The replay
// clones controllers at their start state, where this costs one _INIT.
#include "fracbench/armctrl_controller.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "fracdesign/gap/controller.hpp"

extern "C" {
#include "ArmCtrl.h"
#include "ImuRead.h"
#include "frac/ptable.h"
#include "plc_rt.h"
}

namespace fracbench {

namespace {

using fracdesign::gap::Controller;
using fracdesign::gap::ControllerContext;

constexpr unsigned kTickUs = 100;          // Table 2.3: 400 us x 0.25
constexpr double kTMin = 4e-4, kTMax = 0.1;  // Cyclic #1 = T, Cyclic #2 = T/2 on the tick (as hil/plc/plc_law.h)

// Ticks per Cyclic #1 cycle for cycle time T, 0 when T is not a whole
// multiple of 2 ticks in [kTMin, kTMax].
unsigned ticks_for(double T)
{
    const double us = T * 1e6, k = std::floor(us / (2.0 * kTickUs) + 0.5);
    if (!(T >= kTMin && T <= kTMax) || std::fabs(k * 2.0 * kTickUs - us) > 1e-3) return 0;
    return unsigned(2.0 * k);
}

// The task runtime with ArmCtrl (from the table) and ImuRead, started
// (_INIT run). Not copyable: the runtime and the programs point into it.
struct Machine {
    armctrl a;
    imuread m;
    plc_program pa, pm;
    plc_rt rt;
    armctrl_table_storage store;
    armctrl_inputs drive_img;
    armctrl_outputs ctrl_img;
    imuread_inputs can_img;
    imuread_outputs imu_img;
    unsigned ticks = 0;
    bool tasks = false;  // the tasks have started cycling (Run)
    Machine() = default;
    Machine(const Machine&) = delete;
    Machine& operator=(const Machine&) = delete;
};

// Builds and starts the machine on `table` (must outlive it). Returns "" or
// the runtime's refusal of its configuration; ArmCtrl's refusal of the table
// shows as m.a.fault.
std::string start_machine(Machine& m, const std::vector<std::uint8_t>& table, unsigned ticks)
{
    std::memset(static_cast<void*>(&m), 0, sizeof m);
    m.ticks = ticks;
    char cfg_text[512], err[256] = "";
    std::snprintf(cfg_text, sizeof cfg_text,
                  "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = continue\n"
                  "[cyclic1]\nduration_us = %u\nsim_cost_us = 300\nprograms = ArmCtrl\n"
                  "[cyclic2]\nduration_us = %u\nsim_cost_us = 50\nprograms = ImuRead\n",
                  ticks * kTickUs, ticks * kTickUs / 2u);
    armctrl_program_table(&m.a, &m.pa, table.data(), UDINT(table.size()), &m.store, &m.drive_img, &m.imu_img, &m.ctrl_img);
    imuread_program(&m.m, &m.pm, 1.0f, &m.can_img, &m.imu_img);
    const plc_program* reg[2] = {&m.pa, &m.pm};
    plc_rt_config cfg;
    if (plc_rt_config_parse(&cfg, cfg_text, "table_2_3", err, sizeof err) != PLC_RT_OK ||
        plc_rt_init(&m.rt, &cfg, reg, 2, err, sizeof err) != PLC_RT_OK || plc_rt_start(&m.rt) != PLC_RT_OK)
        return std::string("the task runtime refused its configuration: ") + err;
    return "";
}

// The refusal of a table ArmCtrl's _INIT faulted on (hil/plc/plc_law.c
// describes it the same way): which FRPT field, else which layout entry,
// else which block's StatusID.
std::string describe_refusal(const Machine& m, const std::vector<std::uint8_t>& b)
{
    frac_ptable t;
    const unsigned sid = unsigned(m.a.out.StatusID);
    char msg[320];
    const int st = frac_ptable_open(&t, b.data(), b.size());
    if (st != FRAC_OK) {
        char ename[FRAC_PTABLE_NAME_LEN + 1] = "";
        if (t.fail_entry >= 0 &&
            FRAC_PTABLE_HEADER_SIZE + std::size_t(t.fail_entry + 1) * FRAC_PTABLE_ENTRY_SIZE <= b.size())
            std::memcpy(ename, b.data() + FRAC_PTABLE_HEADER_SIZE + std::size_t(t.fail_entry) * FRAC_PTABLE_ENTRY_SIZE,
                        FRAC_PTABLE_NAME_LEN);
        if (t.fail_entry >= 0)
            std::snprintf(msg, sizeof msg, "ParTable refuses the data object: %s (field %s of entry %ld '%s'; ArmCtrl StatusID %u)",
                          frac_status_str(st), t.fail_field, t.fail_entry, ename, sid);
        else
            std::snprintf(msg, sizeof msg, "ParTable refuses the data object: %s (field %s; ArmCtrl StatusID %u)",
                          frac_status_str(st), t.fail_field, sid);
        return msg;
    }
    static armctrl_table_storage scratch;  // 200 kB: not on the stack
    static std::mutex scratch_lock;
    std::lock_guard<std::mutex> g(scratch_lock);
    const int pst = armctrl_params_from_table(&scratch, &t);
    if (pst != FRAC_OK)
        std::snprintf(msg, sizeof msg,
                      "ArmCtrl's layout refuses the table: %s (entry '%s': missing, of the wrong size or out of range, "
                      "plc_blocks/programs/ArmCtrl.h; ArmCtrl StatusID %u)",
                      frac_status_str(pst), scratch.fail_entry, sid);
    else
        std::snprintf(msg, sizeof msg,
                      "a block refused a value at ArmCtrl's _INIT (ArmCtrl StatusID %u; FracCtrl.var names the codes)", sid);
    return msg;
}

std::vector<std::uint8_t> read_bytes(const std::string& path, const std::string& where)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(where + ": cannot open the ArmCtrl table '" + path + "'");
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Where an ArmCtrl input comes from: the r (reference column) or y
// (measured model output) vector of step(), or nowhere (-1).
struct Source {
    bool reference = false;
    int index = -1;
    double get(const double* r, const double* y) const { return index < 0 ? 0.0 : (reference ? r : y)[index]; }
};

// One sample's inputs, as logged for clone().
struct Sample {
    double angle, velocity, tip;
    bool start, run;
};

class ArmCtrlLaw final : public Controller {
public:
    ArmCtrlLaw(std::shared_ptr<const std::vector<std::uint8_t>> table, unsigned ticks, Source angle, Source velocity,
               Source tip, Source start, Source run, int output, int outputs, double limit)
        : table_(std::move(table)), ticks_(ticks), angle_(angle), velocity_(velocity), tip_(tip), start_(start),
          run_(run), output_(output), outputs_(outputs), limit_(limit)
    {
    }
    std::unique_ptr<Controller> clone() const override
    {
        auto c = std::make_unique<ArmCtrlLaw>(table_, ticks_, angle_, velocity_, tip_, start_, run_, output_, outputs_, limit_);
        if (m_) {
            c->boot();
            for (const Sample& s : log_) c->cycle(s);
            c->log_ = log_;
        }
        return c;
    }
    std::string kind() const override { return "armctrl"; }
    // _INIT (at rest): the program's state at power-on, which the record's
    // first sample follows.
    void start(const double*, const double*) override
    {
        boot();
        log_.clear();
    }
    void step(const double* r, const double* y, double* u) override
    {
        if (!m_) boot();
        Sample s;
        s.angle = angle_.get(r, y);
        s.velocity = velocity_.get(r, y);
        s.tip = tip_.get(r, y);
        s.start = start_.index >= 0 && start_.get(r, y) != 0.0;
        s.run = run_.index < 0 || run_.get(r, y) != 0.0;
        const double tau = cycle(s);
        log_.push_back(s);
        for (int i = 0; i < outputs_; ++i) u[i] = i == output_ ? tau : 0.0;
    }
    double output_limit() const override { return limit_; }
    // ArmCtrl computes in REAL (float), as on the PLC.
    double arithmetic_epsilon() const override { return double(std::numeric_limits<float>::epsilon()); }

private:
    void boot()
    {
        m_ = std::make_unique<Machine>();
        const std::string e = start_machine(*m_, *table_, ticks_);
        if (!e.empty()) throw std::runtime_error(e);  // configuration checked by the factory: cannot happen
    }
    // One Cyclic #1 cycle on the sample's inputs (hil/plc/plc_law.c
    // hil_plc_law_step without the bus: fresh drive values and an IMU
    // reading every cycle). Start: the column, else TRUE from the second
    // cycle the tasks run (a Start TRUE at the first is no edge).
    double cycle(const Sample& s)
    {
        Machine& m = *m_;
        if (!m.tasks && !s.run) return 0.0;
        const bool first = !m.tasks;
        m.tasks = true;
        m.drive_img.MotorAngle = REAL(s.angle);
        m.drive_img.MotorVelocity = REAL(s.velocity);
        m.drive_img.DriveCounter++;
        m.drive_img.Start = start_.index >= 0 ? BOOL(s.start) : BOOL(!first || m.drive_img.Start);
        m.drive_img.Acknowledge = 0;
        m.can_img.RawRate = REAL(s.tip);
        m.can_img.FrameCounter++;
        plc_rt_run_sim(&m.rt, m.ticks);
        return m.ctrl_img.TorqueEnable ? double(m.ctrl_img.TorqueSetpoint) : 0.0;
    }
    std::shared_ptr<const std::vector<std::uint8_t>> table_;
    unsigned ticks_;
    Source angle_, velocity_, tip_, start_, run_;
    int output_, outputs_;
    double limit_;
    std::unique_ptr<Machine> m_;
    std::vector<Sample> log_;
};

Source source_of(const nlohmann::json& inputs, const char* key, bool required, const ControllerContext& ctx)
{
    const std::string w = ctx.where + ".inputs." + key;
    Source s;
    if (!inputs.contains(key)) {
        if (required) throw std::runtime_error(w + ": missing (the column or model output ArmCtrl's " + key + " reads)");
        return s;
    }
    if (!inputs.at(key).is_string()) throw std::runtime_error(w + ": must be a string (a column or model output name)");
    const std::string name = inputs.at(key).get<std::string>();
    for (size_t i = 0; i < ctx.measured.size(); ++i)
        if (ctx.measured[i] == name) {
            s.index = int(i);
            return s;
        }
    for (size_t i = 0; i < ctx.references.size(); ++i)
        if (ctx.references[i] == name) {
            s.reference = true;
            s.index = int(i);
            return s;
        }
    std::string m, r;
    for (const std::string& x : ctx.measured) m += (m.empty() ? "" : ", ") + x;
    for (const std::string& x : ctx.references) r += (r.empty() ? "" : ", ") + x;
    throw std::runtime_error(w + ": '" + name + "' is neither a closed_loop.measured model output (" + m +
                             ") nor a closed_loop.references column (" + r + ")");
}

std::unique_ptr<Controller> make_armctrl(const nlohmann::json& doc, const ControllerContext& ctx)
{
    for (auto it = doc.begin(); it != doc.end(); ++it)
        if (it.key() != "kind" && it.key() != "table" && it.key() != "inputs" && it.key() != "output")
            throw std::runtime_error(ctx.where + "." + it.key() + ": unknown field (allowed: kind, table, inputs, output)");
    if (!doc.contains("table") || !doc.at("table").is_string())
        throw std::runtime_error(ctx.where + ".table: missing string (the ArmCtrl parameter table file, relative to the model document)");
    const std::string rel = doc.at("table").get<std::string>();
    const std::string path = !rel.empty() && rel[0] == '/' ? rel : (ctx.base_dir.empty() ? "." : ctx.base_dir) + "/" + rel;
    const std::string tw = ctx.where + ".table";
    auto bytes = std::make_shared<const std::vector<std::uint8_t>>(read_bytes(path, tw));
    double ts = 0.0;
    const std::string refusal = armctrl_table_refusal(*bytes, &ts);
    if (!refusal.empty()) throw std::runtime_error(tw + ": '" + path + "': " + refusal);
    // "ts" is a REAL on the PLC (float): equal to the record's Ts to its precision.
    if (!(std::fabs(ts - ctx.Ts) <= 1e-6 * ctx.Ts)) {
        char b[256];
        std::snprintf(b, sizeof b, ": the table's cycle time 'ts' = %.7g s is not the record's sample time Ts = %.9g s "
                      "(one ArmCtrl cycle per sample)", ts, ctx.Ts);
        throw std::runtime_error(tw + b);
    }
    const unsigned ticks = ticks_for(ctx.Ts);
    if (!ticks) {
        char b[256];
        std::snprintf(b, sizeof b, ": the table's cycle time 'ts' = %.7g s is no task-class duration: a whole multiple "
                      "of 200 us in [%g, %g] s (Cyclic #1 = ts, Cyclic #2 = ts/2 on the 100 us tick)", ts, kTMin, kTMax);
        throw std::runtime_error(tw + b);
    }
    if (!doc.contains("inputs") || !doc.at("inputs").is_object())
        throw std::runtime_error(ctx.where + ".inputs: missing object {\"MotorAngle\": .., \"MotorVelocity\": .., \"TipRate\": ..}");
    const nlohmann::json& in = doc.at("inputs");
    for (auto it = in.begin(); it != in.end(); ++it)
        if (it.key() != "MotorAngle" && it.key() != "MotorVelocity" && it.key() != "TipRate" && it.key() != "Start" &&
            it.key() != "Run")
            throw std::runtime_error(ctx.where + ".inputs." + it.key() +
                                     ": not an ArmCtrl input (allowed: MotorAngle, MotorVelocity, TipRate, Start, Run)");
    const Source angle = source_of(in, "MotorAngle", true, ctx), velocity = source_of(in, "MotorVelocity", true, ctx),
                 tip = source_of(in, "TipRate", true, ctx), start = source_of(in, "Start", false, ctx),
                 run = source_of(in, "Run", false, ctx);
    int output = 0;
    if (doc.contains("output")) {
        if (!doc.at("output").is_string()) throw std::runtime_error(ctx.where + ".output: must be a string (a plant input)");
        const std::string o = doc.at("output").get<std::string>();
        output = -1;
        for (size_t i = 0; i < ctx.inputs.size(); ++i)
            if (ctx.inputs[i] == o) output = int(i);
        if (output < 0) {
            std::string l;
            for (const std::string& x : ctx.inputs) l += (l.empty() ? "" : ", ") + x;
            throw std::runtime_error(ctx.where + ".output: '" + o + "' is not a plant input (" + l + ")");
        }
    }
    if (ctx.outputs < 1) throw std::runtime_error(ctx.where + ": the plant has no input for TorqueSetpoint");
    auto probe = std::make_unique<Machine>();
    start_machine(*probe, *bytes, ticks);
    const double limit = double(probe->store.par.TorqueLimit);
    return std::make_unique<ArmCtrlLaw>(bytes, ticks, angle, velocity, tip, start, run, output, ctx.outputs, limit);
}

}  // namespace

std::string armctrl_table_refusal(const std::vector<std::uint8_t>& bytes, double* ts)
{
    if (bytes.size() > 0xFFFFFFFFul) return "the data object is larger than a UDINT size";
    // _INIT at any valid cycle time: the runtime's configuration does not
    // reach ArmCtrl's checks of the table.
    auto m = std::make_unique<Machine>();
    const std::string e = start_machine(*m, bytes, 12);
    if (!e.empty()) return e;
    if (m->a.fault) return describe_refusal(*m, bytes);
    if (ts) *ts = double(m->store.par.CycleTime);
    return "";
}

void register_armctrl_controller()
{
    static std::once_flag once;
    std::call_once(once, [] { fracdesign::gap::register_controller_kind("armctrl", make_armctrl); });
}

}  // namespace fracbench
