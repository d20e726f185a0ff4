// cascade.cpp - controller kind "cascade": loops in series, as the drives'
// position / velocity / current cascades run: "loops" lists them outer
// first, each a controller document of any kind (its own limits,
// anti-windup, stages and "divider"); loop i's output is loop i+1's only
// reference, every loop sees all measured outputs (and picks its own, e.g.
// fopid's "measured"), the outer loop all references. The innermost loop
// drives the plant input "output" (default the first), the others get 0.
//
// Start rule: the outer loop by its rule at the first sample; each inner
// loop by its rule with, as reference, what the loop outside it commands
// at the first sample (a copy of that loop stepped once). small_signal:
// none (the loops' limits are what a cascade is about; the closed-loop
// modes are left to the plant's).
#include <stdexcept>

#include "kinds.hpp"

namespace fracdesign {
namespace gap {

namespace {

class Cascade final : public Controller {
public:
    Cascade(std::vector<std::unique_ptr<Controller>> loops, int nr, int ny, int out, int nu)
        : loops_(std::move(loops)), nr_(nr), ny_(ny), out_(out), nu_(nu), link_(loops_.size() + 1, 0.0)
    {
    }
    Cascade(const Cascade& o) : Controller(o), nr_(o.nr_), ny_(o.ny_), out_(o.out_), nu_(o.nu_), link_(o.link_)
    {
        for (const auto& l : o.loops_) loops_.push_back(l->clone());
    }
    std::unique_ptr<Controller> clone() const override { return std::make_unique<Cascade>(*this); }
    std::string kind() const override { return "cascade"; }
    void start(const double* r0, const double* y0) override
    {
        const double* r = r0;
        for (size_t i = 0; i < loops_.size(); ++i) {
            loops_[i]->start(r, y0);
            std::unique_ptr<Controller> probe = loops_[i]->clone();
            probe->step(r, y0, &link_[i]);
            r = &link_[i];
        }
    }
    void step(const double* r, const double* y, double* u) override
    {
        const double* ri = r;
        for (size_t i = 0; i < loops_.size(); ++i) {
            loops_[i]->step(ri, y, &link_[i]);
            ri = &link_[i];
        }
        for (int i = 0; i < nu_; ++i) u[i] = 0.0;
        u[out_] = link_[loops_.size() - 1];
    }
    double output_limit() const override { return loops_.back()->output_limit(); }

private:
    std::vector<std::unique_ptr<Controller>> loops_;
    int nr_, ny_, out_, nu_;
    std::vector<double> link_;
};

}  // namespace

std::unique_ptr<Controller> make_cascade_controller(const json& doc, const ControllerContext& ctx)
{
    const std::string& w = ctx.where;
    check_fields(doc, w, "cascade", {"loops", "output"});
    if (!doc.contains("loops") || !doc.at("loops").is_array() || doc.at("loops").size() < 2)
        refuse(w, "loops", doc.value("loops", json()), "an array of at least 2 controller documents, outer loop first");
    const json& loops = doc.at("loops");
    const int out = output_index(doc, "output", ctx);
    std::vector<std::unique_ptr<Controller>> built;
    for (size_t i = 0; i < loops.size(); ++i) {
        ControllerContext c = ctx;
        c.where = field(w, "loops[" + std::to_string(i) + "]");
        if (i > 0) c.references = {"loops[" + std::to_string(i - 1) + "] output"};
        c.outputs = 1;
        c.inputs = {i + 1 < loops.size() ? "loops[" + std::to_string(i + 1) + "] reference"
                                          : (ctx.inputs.empty() ? std::to_string(out) : ctx.inputs[size_t(out)])};
        built.push_back(make_controller(loops[i], c));
    }
    return std::make_unique<Cascade>(std::move(built), int(ctx.references.size()), int(ctx.measured.size()), out, ctx.outputs);
}

}  // namespace gap
}  // namespace fracdesign
