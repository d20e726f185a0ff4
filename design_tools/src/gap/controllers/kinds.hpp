// kinds.hpp - the controller kinds built into design_tools (controller.hpp);
// one file per kind or stage in this folder, each kind listed in
// builtin_controller_kinds() (kinds.cpp).
#pragma once
#include <memory>
#include <vector>

#include "document.hpp"
#include "fracdesign/gap/controller.hpp"

#include "frac/friction.h"
#include "frac/lut.h"
#include "frac/trajlut.h"

namespace fracdesign {
namespace gap {

struct BuiltinKind {
    const char* kind;
    ControllerFactory make;
};
const std::vector<BuiltinKind>& builtin_controller_kinds();

// statespace.cpp: the linear discrete state space of the first document version.
std::unique_ptr<Controller> make_statespace_controller(const nlohmann::json& doc, const ControllerContext& ctx);
// fopid.cpp: the FOPID block (frac/fopid.h).
std::unique_ptr<Controller> make_fopid_controller(const nlohmann::json& doc, const ControllerContext& ctx);
// collocated.cpp: the seed 002 collocated law with its prefilter (frac/fodamp.h).
std::unique_ptr<Controller> make_collocated_controller(const nlohmann::json& doc, const ControllerContext& ctx);
// cascade.cpp: loops in series, each a controller document.
std::unique_ptr<Controller> make_cascade_controller(const nlohmann::json& doc, const ControllerContext& ctx);

// The stages every kind may have (controller_common_fields(), pipeline.cpp).

// ratelimit.cpp: "rate_limit" - frac_ramp_step (frac/ramp.h), the bounded-rate
// ramp the PLC applies to a command: y = x + clamp(target - x, -rate Ts, rate Ts).
class RateLimit {
public:
    RateLimit(double rate, double Ts) : rate_(rate), Ts_(Ts) {}
    void reset(double x) { x_ = x, started_ = true; }
    void unstart() { started_ = false; }
    // The first call after unstart() passes the target through.
    double step(double target);

private:
    double rate_, Ts_, x_ = 0.0;
    bool started_ = false;
};
// A rate > 0 (units per second) at doc[key]; 0 when absent.
double read_rate(const json& doc, const char* key, const std::string& where);

// friction.cpp: "friction" - the FrictionComp block (frac/friction.h):
// tau = frac_friction_eval(v) added to a plant input.
class FrictionTerm {
public:
    FrictionTerm(const json& doc, const ControllerContext& ctx, const std::string& where);
    // w = [references; measured] as the law saw them; adds to u[output].
    void add(const double* w, double* u);

private:
    frac_friction f_;
    int velocity_, output_;
};

// tables.cpp: LUT1D and TrajLUT (frac/lut.h, frac/trajlut.h) as the PLC
// blocks use them; the table data are shared read-only between copies.
struct LutData;
struct TrajData;
class Lut1Term {  // "feedforward": [{"lut1d": {...}, "input": name, "output": name}]
public:
    Lut1Term(const json& doc, const ControllerContext& ctx, const std::string& where);
    void add(const double* w, double* u);

private:
    std::shared_ptr<const LutData> data_;
    frac_lut1 lut_;
    int input_, output_;
};
class TrajTable {  // "feedforward": [{"trajlut": {...}, "channel": c, "output": name}] and "reference_table"
public:
    TrajTable(const json& doc, const ControllerContext& ctx, const std::string& where);
    size_t channels() const { return tl_.channels; }
    void seek0() { frac_trajlut_seek(&tl_, 0); }
    // Values of the current cycle (frac_trajlut_eval) or of the current cycle, then advance (frac_trajlut_step).
    void eval(double* out);
    void step(double* out);

private:
    std::shared_ptr<const TrajData> data_;
    frac_trajlut tl_;
};

// pipeline.cpp: the law with its common stages; `divider` >= 1 (the law's
// ctx.Ts is already divider times the record's).
std::unique_ptr<Controller> with_common_stages(std::unique_ptr<Controller> law, const json& doc,
                                               const ControllerContext& ctx, int divider);

}  // namespace gap
}  // namespace fracdesign
