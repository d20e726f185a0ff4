// document.hpp - reading a controller kind's document object
// (docs/model_format.md "Closed-loop controller kinds"): every refusal is one
// std::runtime_error naming the field (ctx.where + ".field"), its value and
// what is allowed (issue 21 item 5), raised before any libfrac init, so
// libfrac's own checks only back these up.
#pragma once
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "fracdesign/gap/controller.hpp"
#include "frac/fo_op.h"

namespace fracdesign {
namespace gap {

using json = nlohmann::json;

// "where.key"
std::string field(const std::string& where, const std::string& key);
// The JSON text of a value, for messages.
std::string shown(const json& v);
[[noreturn]] void refuse(const std::string& where, const std::string& key, const json& v, const std::string& allowed);

// Refuses a key that is neither one of the kind's own nor a common field
// (controller_common_fields()).
void check_fields(const json& doc, const std::string& where, const std::string& kind, std::initializer_list<const char*> own);

// A finite number; `def` when absent (NaN default: the field is required).
double number(const json& doc, const char* key, const std::string& where,
              double def = std::numeric_limits<double>::quiet_NaN());
// An integer >= lo (a number with no fractional part).
long integer(const json& doc, const char* key, const std::string& where, long def, long lo);
// One of `allowed`; returns its index.
int choice(const json& doc, const char* key, const std::string& where, int def, std::initializer_list<const char*> allowed);

// Output limits: a number L > 0 (symmetric, [-L, L]) or {"min": a, "max": b}
// (either may be absent: -inf / +inf), min < max.
struct Limits {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    double scale() const;  // max(|lo|, |hi|)
};
Limits read_limits(const json& v, const std::string& where);

// The fractional operators' realization ("op": {"method", "memory", "wb", "wh", "n"}),
// order 0 (the laws set it), sampling time Ts.
frac_fo_params read_realization(const json& doc, const std::string& where, double Ts);

// A signal the law reads, by name: a reference (index j) or a measured
// output (index nr + j) of ctx; absent: `def` (-1: required).
int signal_index(const json& doc, const char* key, const ControllerContext& ctx, int def);
// A reference (index into ctx.references), a measured output (index into
// ctx.measured) or a plant input (index into ctx.inputs, or into 0..outputs-1
// when ctx.inputs is empty); absent: 0.
int reference_index(const json& doc, const char* key, const ControllerContext& ctx);
int measured_index(const json& doc, const char* key, const ControllerContext& ctx);
int output_index(const json& doc, const char* key, const ControllerContext& ctx);

// A libfrac init's refusal (a backstop: the fields were checked above).
void check_status(int status, const std::string& where, const std::string& what);

}  // namespace gap
}  // namespace fracdesign
