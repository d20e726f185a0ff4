// pipeline.cpp - the stages every controller kind may have around its law
// (controller_common_fields(); docs/gap.md "Controller kinds"), composed as
// the PLC programs compose their blocks in one task cycle (ArmCtrl, FoLoop):
//   1. "reference_table": a TrajLUT replaces named references by its channels;
//   2. "rate_limit".reference: each reference ramped by frac_ramp_step;
//   3. the law (its own limits and anti-windup inside, e.g. fopid's umin/umax);
//   4. "friction" (FrictionComp) and "feedforward" (LUT1D, TrajLUT) added to plant inputs;
//   5. "limits": the kind's output clamp, {"min", "max"} or a symmetric number;
//   6. "rate_limit".output: each output ramped by frac_ramp_step.
// "divider" n: the whole task runs on samples 0, n, 2n, ... at Ts n, its
// outputs held in between (a slower task class, ARCHITECTURE.md task model).
// Start: the table at cycle 0, the reference ramps at that first reference,
// the law by its own rule, the output ramps pass their first value.
#include <algorithm>
#include <optional>
#include <stdexcept>

#include "kinds.hpp"

namespace fracdesign {
namespace gap {

namespace {

struct TrajTerm {
    TrajTable table;
    int channel, output;
};

class Pipeline final : public Controller {
public:
    Pipeline(std::unique_ptr<Controller> law, const ControllerContext& ctx) : law_(std::move(law)), nr_(int(ctx.references.size())),
          ny_(int(ctx.measured.size())), nu_(ctx.outputs), w_(size_t(nr_ + ny_)), u_(size_t(nu_), 0.0), tab_(FRAC_TRAJLUT_MAX_CH)
    {
    }
    Pipeline(const Pipeline& o)
        : Controller(o), law_(o.law_->clone()), nr_(o.nr_), ny_(o.ny_), nu_(o.nu_), divider_(o.divider_), count_(o.count_),
          limits_(o.limits_), ref_table_(o.ref_table_), ref_map_(o.ref_map_), ref_rate_(o.ref_rate_), out_rate_(o.out_rate_),
          friction_(o.friction_), lut_(o.lut_), traj_(o.traj_), w_(o.w_), u_(o.u_), tab_(o.tab_)
    {
    }
    std::unique_ptr<Controller> clone() const override { return std::make_unique<Pipeline>(*this); }
    std::string kind() const override { return law_->kind(); }
    void start(const double* r0, const double* y0) override
    {
        load(r0, y0);
        if (ref_table_) {
            ref_table_->seek0();
            ref_table_->eval(tab_.data());
            for (size_t c = 0; c < ref_map_.size(); ++c) w_[size_t(ref_map_[c])] = tab_[c];
        }
        for (size_t j = 0; j < ref_rate_.size(); ++j) ref_rate_[j].reset(w_[j]);
        for (RateLimit& l : out_rate_) l.unstart();
        for (TrajTerm& t : traj_) t.table.seek0();
        law_->start(w_.data(), w_.data() + nr_);
        count_ = 0;
    }
    void step(const double* r, const double* y, double* u) override
    {
        if (count_++ % divider_ == 0) run(r, y);
        std::copy(u_.begin(), u_.end(), u);
    }
    double output_limit() const override { return std::min(law_->output_limit(), limits_.scale()); }
    bool small_signal(Eigen::MatrixXd& A, Eigen::MatrixXd& B, Eigen::MatrixXd& C, Eigen::MatrixXd& D) const override
    {
        // Rate limits and clamps do not act on small signals; tables,
        // friction compensation and a slower task change the law.
        if (divider_ != 1 || ref_table_ || !friction_.empty() || !lut_.empty() || !traj_.empty()) return false;
        return law_->small_signal(A, B, C, D);
    }

    std::unique_ptr<Controller> law_;
    int nr_, ny_, nu_;
    long divider_ = 1, count_ = 0;
    Limits limits_;
    std::optional<TrajTable> ref_table_;  // a value: each clone plays its own cycle counter
    std::vector<int> ref_map_;
    std::vector<RateLimit> ref_rate_, out_rate_;
    std::vector<FrictionTerm> friction_;
    std::vector<Lut1Term> lut_;
    std::vector<TrajTerm> traj_;

private:
    void load(const double* r, const double* y)
    {
        std::copy(r, r + nr_, w_.begin());
        std::copy(y, y + ny_, w_.begin() + nr_);
    }
    void run(const double* r, const double* y)
    {
        load(r, y);
        if (ref_table_) {
            ref_table_->step(tab_.data());
            for (size_t c = 0; c < ref_map_.size(); ++c) w_[size_t(ref_map_[c])] = tab_[c];
        }
        for (size_t j = 0; j < ref_rate_.size(); ++j) w_[j] = ref_rate_[j].step(w_[j]);
        law_->step(w_.data(), w_.data() + nr_, u_.data());
        for (FrictionTerm& f : friction_) f.add(w_.data(), u_.data());
        for (Lut1Term& l : lut_) l.add(w_.data(), u_.data());
        for (TrajTerm& t : traj_) {
            t.table.step(tab_.data());
            u_[size_t(t.output)] += tab_[size_t(t.channel)];
        }
        for (double& v : u_) v = std::min(std::max(v, limits_.lo), limits_.hi);
        for (size_t i = 0; i < out_rate_.size(); ++i) u_[i] = out_rate_[i].step(u_[i]);
    }
    std::vector<double> w_, u_, tab_;
};

}  // namespace

const std::vector<std::string>& controller_common_fields()
{
    static const std::vector<std::string> f = {"divider", "limits", "rate_limit", "friction", "feedforward", "reference_table"};
    return f;
}

std::unique_ptr<Controller> with_common_stages(std::unique_ptr<Controller> law, const json& doc, const ControllerContext& ctx,
                                               int divider)
{
    bool any = divider != 1;
    for (const std::string& f : controller_common_fields()) any = any || (f != "divider" && doc.contains(f));
    if (!any) return law;
    const std::string& w = ctx.where;
    auto p = std::make_unique<Pipeline>(std::move(law), ctx);
    p->divider_ = divider;
    if (doc.contains("limits")) p->limits_ = read_limits(doc.at("limits"), field(w, "limits"));
    if (doc.contains("rate_limit")) {
        const json& rl = doc.at("rate_limit");
        const std::string rw = field(w, "rate_limit");
        if (!rl.is_object()) refuse(w, "rate_limit", rl, "{\"reference\": rate, \"output\": rate}, per second");
        for (auto it = rl.begin(); it != rl.end(); ++it)
            if (it.key() != "reference" && it.key() != "output")
                throw std::runtime_error(field(rw, it.key()) + ": unknown field of a rate limit (fields: reference, output)");
        if (const double rr = read_rate(rl, "reference", rw); rr > 0)
            p->ref_rate_.assign(ctx.references.size(), RateLimit(rr, ctx.Ts));
        if (const double ro = read_rate(rl, "output", rw); ro > 0) p->out_rate_.assign(size_t(ctx.outputs), RateLimit(ro, ctx.Ts));
    }
    if (doc.contains("friction")) {
        const json& f = doc.at("friction");
        if (f.is_array())
            for (size_t i = 0; i < f.size(); ++i) p->friction_.emplace_back(f[i], ctx, field(w, "friction[" + std::to_string(i) + "]"));
        else
            p->friction_.emplace_back(f, ctx, field(w, "friction"));
    }
    if (doc.contains("feedforward")) {
        const json& ff = doc.at("feedforward");
        if (!ff.is_array()) refuse(w, "feedforward", ff, "an array of {\"lut1d\": ..} or {\"trajlut\": ..} terms");
        for (size_t i = 0; i < ff.size(); ++i) {
            const std::string tw = field(w, "feedforward[" + std::to_string(i) + "]");
            const json& t = ff[i];
            if (t.is_object() && t.contains("lut1d") && !t.contains("trajlut")) {
                p->lut_.emplace_back(t, ctx, tw);
            } else if (t.is_object() && t.contains("trajlut") && !t.contains("lut1d")) {
                for (auto it = t.begin(); it != t.end(); ++it)
                    if (it.key() != "trajlut" && it.key() != "channel" && it.key() != "output")
                        throw std::runtime_error(field(tw, it.key()) +
                                                 ": unknown field of a TrajLUT feedforward term (fields: trajlut, channel, output)");
                TrajTable table(t.at("trajlut"), ctx, field(tw, "trajlut"));
                const long ch = integer(t, "channel", tw, 0, 0);
                if (size_t(ch) >= table.channels())
                    refuse(tw, "channel", t.at("channel"), "a channel of the table, 0.." + std::to_string(table.channels() - 1));
                ControllerContext c = ctx;
                c.where = tw;
                p->traj_.push_back({table, int(ch), output_index(t, "output", c)});
            } else {
                refuse(w, "feedforward[" + std::to_string(i) + "]", t, "an object with one of \"lut1d\" or \"trajlut\"");
            }
        }
    }
    if (doc.contains("reference_table")) {
        const json& rt = doc.at("reference_table");
        const std::string rw = field(w, "reference_table");
        p->ref_table_.emplace(rt, ctx, rw);
        if (!rt.contains("references") || !rt.at("references").is_array() || rt.at("references").size() != p->ref_table_->channels())
            refuse(rw, "references", rt.value("references", json()),
                   "one reference name per table channel (" + std::to_string(p->ref_table_->channels()) + ")");
        for (const json& n : rt.at("references")) {
            json one = {{"references", n}};
            ControllerContext c = ctx;
            c.where = rw;
            p->ref_map_.push_back(reference_index(one, "references", c));
        }
    }
    return p;
}

}  // namespace gap
}  // namespace fracdesign
