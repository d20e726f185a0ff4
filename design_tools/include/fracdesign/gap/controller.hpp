// controller.hpp - the known controller of a closed-loop record, as the gap
// replay runs it (docs/gap.md "Closed loop", docs/model_format.md).
//
// A closed-loop record is explained only by a replay that runs the same
// controller as the machine did (issue 21): its limits, anti-windup, rate
// limits, tables and sample-rate dividers included. Each controller kind is
// one implementation of Controller, built from the document's
// `gap.closed_loop.controller` object by its factory; the kinds that run on
// the PLC are replayed by the libfrac calls the PLC makes (ARCHITECTURE.md:
// whatever runs on the PLC is simulated with libfrac itself).
//
// Kinds built into design_tools are listed by controller_kinds(). A layer
// above design_tools (the PLC replay, which links plc_blocks) adds its kinds
// with register_controller_kind(); design_tools itself never links
// plc_blocks, so a document naming such a kind is refused here with a
// message saying which program replays it.
//
// Invariants: a Controller is a value: clone() copies parameters and state,
// so every replay (and every thread) runs its own copy of one prototype;
// step() neither allocates unboundedly nor throws once start() succeeded.
#pragma once
#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fracdesign {
namespace gap {

// What a factory knows besides its own document object.
struct ControllerContext {
    double Ts = 0.0;                      // the record's sample time: one step() per sample
    std::vector<std::string> references;  // closed_loop.references (data columns), in order
    std::vector<std::string> measured;    // closed_loop.measured (model outputs), in order
    std::vector<std::string> inputs;      // names of the plant inputs the outputs drive (may be empty: indices)
    int outputs = 0;                      // plant inputs the controller drives
    std::string where;                    // document path of the object, e.g. "model gap.closed_loop.controller"
    std::string base_dir;                 // directory of the model document (tables named by a relative path)
};

class Controller {
public:
    virtual ~Controller() = default;
    // A copy with the same parameters and the same state.
    virtual std::unique_ptr<Controller> clone() const = 0;
    virtual std::string kind() const = 0;
    // Puts the state where it is at the record's first sample: references r0
    // (ControllerContext::references order) and measurements y0 (measured
    // order). A kind with a steady state for (r0, y0) starts in it, others at
    // rest; the kind's documentation says which.
    virtual void start(const double* r0, const double* y0) = 0;
    // One sample: u (ControllerContext::outputs values) from the references
    // r and measurements y of this sample.
    virtual void step(const double* r, const double* y, double* u) = 0;
    // The largest |u_i| the controller can command (its output limits;
    // infinity when it has none): the scale of the saturation candidate.
    virtual double output_limit() const { return std::numeric_limits<double>::infinity(); }
    // The relative precision of the law's arithmetic: a law computing in
    // REAL (float, as the PLC's programs) returns FLT_EPSILON. The fits'
    // numeric derivatives step the parameters by at least its square root
    // (diagnosis.cpp refine): a smaller step moves the loop by less than the
    // law's rounding, and the derivative is noise.
    virtual double arithmetic_epsilon() const { return std::numeric_limits<double>::epsilon(); }
    // A discrete state space at Ts with inputs [r; y] and outputs u that
    // equals the law for small signals away from its limits (used for the
    // nominal's closed-loop modes); false when the kind has none.
    virtual bool small_signal(Eigen::MatrixXd& A, Eigen::MatrixXd& B, Eigen::MatrixXd& C, Eigen::MatrixXd& D) const
    {
        (void)A, (void)B, (void)C, (void)D;
        return false;
    }
};

// Builds a controller from its document object; std::runtime_error naming
// the field (ctx.where + ".field"), its value and what is allowed.
using ControllerFactory = std::function<std::unique_ptr<Controller>(const nlohmann::json& doc, const ControllerContext& ctx)>;

// The fields every kind accepts besides its own, handled by make_controller
// around the kind's law (docs/gap.md "Controller kinds"): "divider" (the law
// runs every n-th sample at n Ts, its output held), "limits", "rate_limit",
// "friction", "feedforward", "reference_table". A factory's own check of
// unknown fields lets these pass.
const std::vector<std::string>& controller_common_fields();

// Adds (or replaces) a kind. Thread-safe; call before the documents naming it are read.
void register_controller_kind(const std::string& kind, ControllerFactory make);
// Every kind this program can replay, sorted.
std::vector<std::string> controller_kinds();
// The object's "kind" (default "statespace", the controller of the first
// document version) built by its factory, with ctx.Ts multiplied by its
// "divider", and wrapped in the common stages the object names. An unknown kind is refused with
// the list of kinds; a kind only a program above design_tools provides
// (e.g. "armctrl") is refused with the name of that program.
std::unique_ptr<Controller> make_controller(const nlohmann::json& doc, const ControllerContext& ctx);

}  // namespace gap
}  // namespace fracdesign
