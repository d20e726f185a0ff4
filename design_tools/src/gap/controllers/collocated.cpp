// collocated.cpp - controller kind "collocated": the seed 002 collocated
// fractional damping law with its prefilter, as the PLC runs it (FracDamp
// block, plc_blocks/FracCtrl/FracDamp.c, composed by the DampLoop program,
// plc_blocks/programs/DampLoop.c): frac_fodamp_init with the block's
// parameter struct, one frac_fodamp_step(W, X) per sample,
//   u = F(s) ref - C(s) meas,  C = Kc s^alpha N(s)/(s^m D(s)),
//   F = (1 + fa s^fbeta)/(1 + fb s)        (frac/fodamp.h; seed 002 (23), (47)-(52)).
//
// Parameters: the block's own (kc, alpha, m, n1, n2, d1, d2, fa, fbeta, fb,
// op), or "design": the document `fracdesign tune collocated --json` writes
// (schema frac.design.collocated), mapped as the PLC table is
// (tables/ptable.cpp): C = Kc (1 + 2 eps s) s^(alpha - 2) (the q_approx form,
// n1 = 2 eps) or Kc (1 + eps s)^2 s^(alpha - 2) (n1 = 2 eps, n2 = eps^2),
// m = 2, D = 1; its "prefilter" (fn, beta, fd) gives fa, fbeta, fb (none: F = 1).
// "reference", "measured", "output" pick the loop's signals as for fopid.
//
// Start rule: at rest (frac_fodamp_reset), as DampLoop resets the law
// after its evaluation at rest in _INIT. small_signal: none (s^r is
// fractional for every alpha in (0, 2) but 1, and the realization's
// memory is not a small state space).
#include <cstring>
#include <stdexcept>

#include "document.hpp"
#include "kinds.hpp"
#include "libfrac_copy.hpp"

#include "frac/fodamp.h"

namespace fracdesign {
namespace gap {

namespace {

class Collocated final : public Controller {
public:
    Collocated(const frac_fodamp_params& p, int ref, int meas, int out, int nu, const std::string& where)
        : ref_(ref), meas_(meas), out_(out), nu_(nu), storage_(frac_fodamp_storage_len(&p) + 1)
    {
        check_status(frac_fodamp_init(&c_, &p, storage_.data(), storage_.size()), where, "the collocated law's parameters");
    }
    // frac_fodamp points into its own coefficient arrays and into storage_:
    // both moved to this copy (libfrac_copy.hpp).
    Collocated(const Collocated& o)
        : Controller(o), ref_(o.ref_), meas_(o.meas_), out_(o.out_), nu_(o.nu_), c_(o.c_), storage_(o.storage_)
    {
        const size_t bytes = storage_.size() * sizeof(frac_real);
        rebase_fo(c_.opc, o.storage_.data(), bytes, storage_.data());
        rebase_fo(c_.opf, o.storage_.data(), bytes, storage_.data());
        rebase(c_.rat.coeffs, &o.c_, sizeof c_, &c_);
        rebase(c_.rat.state, &o.c_, sizeof c_, &c_);
    }
    Collocated& operator=(const Collocated&) = delete;
    std::unique_ptr<Controller> clone() const override { return std::make_unique<Collocated>(*this); }
    std::string kind() const override { return "collocated"; }
    void start(const double*, const double*) override { frac_fodamp_reset(&c_); }
    void step(const double* r, const double* y, double* u) override
    {
        frac_real v = 0;
        frac_fodamp_step(&c_, frac_real(r[ref_]), frac_real(y[meas_]), &v);
        for (int i = 0; i < nu_; ++i) u[i] = 0.0;
        u[out_] = double(v);
    }

private:
    int ref_, meas_, out_, nu_;
    frac_fodamp c_;
    std::vector<frac_real> storage_;
};

double design_number(const json& d, const char* obj, const char* key, const std::string& where)
{
    if (!d.contains(obj) || !d.at(obj).is_object())
        throw std::runtime_error(field(where, obj) + ": missing (the frac.design.collocated document's '" + obj + "' object)");
    return number(d.at(obj), key, field(where, obj));
}

}  // namespace

std::unique_ptr<Controller> make_collocated_controller(const json& doc, const ControllerContext& ctx)
{
    const std::string& w = ctx.where;
    check_fields(doc, w, "collocated",
                 {"design", "kc", "alpha", "m", "n1", "n2", "d1", "d2", "fa", "fbeta", "fb", "op", "reference", "measured",
                  "output"});
    if (ctx.references.empty() || ctx.measured.empty())
        throw std::runtime_error(w + ": kind 'collocated' needs one reference and one measured output in gap.closed_loop");
    frac_fodamp_params p;
    std::memset(&p, 0, sizeof p);
    if (doc.contains("design")) {
        const json& d = doc.at("design");
        const std::string dw = field(w, "design");
        if (!d.is_object() || d.value("schema", "") != "frac.design.collocated")
            throw std::runtime_error(dw + ".schema: not a frac.design.collocated document (the output of "
                                     "`fracdesign tune collocated --json`)");
        for (const char* k : {"kc", "alpha", "m", "n1", "n2", "d1", "d2", "fa", "fbeta", "fb"})
            if (doc.contains(k))
                throw std::runtime_error(field(w, k) + ": given together with 'design' (give one of them)");
        const double eps = design_number(d, "controller", "eps", dw);
        const std::string form = d.at("controller").value("form", "");
        p.kc = frac_real(design_number(d, "controller", "Kc", dw));
        p.alpha = frac_real(design_number(d, "controller", "alpha", dw));
        p.m = 2;
        p.n1 = frac_real(2 * eps);
        p.n2 = frac_real(form.find("(1 + eps s)^2") != std::string::npos ? eps * eps : 0.0);
        if (d.contains("prefilter")) {
            p.fa = frac_real(design_number(d, "prefilter", "fn", dw));
            p.fbeta = frac_real(design_number(d, "prefilter", "beta", dw));
            p.fb = frac_real(design_number(d, "prefilter", "fd", dw));
        }
    } else {
        p.kc = frac_real(number(doc, "kc", w));
        p.alpha = frac_real(number(doc, "alpha", w));
        p.m = unsigned(integer(doc, "m", w, 2, 0));
        p.n1 = frac_real(number(doc, "n1", w, 0.0));
        p.n2 = frac_real(number(doc, "n2", w, 0.0));
        p.d1 = frac_real(number(doc, "d1", w, 0.0));
        p.d2 = frac_real(number(doc, "d2", w, 0.0));
        p.fa = frac_real(number(doc, "fa", w, 0.0));
        p.fbeta = frac_real(number(doc, "fbeta", w, 0.0));
        p.fb = frac_real(number(doc, "fb", w, 0.0));
    }
    auto bad = [&](const char* k, const std::string& allowed) {
        refuse(w, doc.contains(k) ? k : "design", doc.contains(k) ? doc.at(k) : doc.at("design"), allowed);
    };
    if (!(p.kc > 0)) bad("kc", "Kc > 0");
    if (!(p.alpha > 0 && p.alpha < 2)) bad("alpha", "an order in (0, 2)");
    if (p.m > 2) bad("m", "0, 1 or 2 zeros at the origin");
    if (p.fa < 0) bad("fa", "fa >= 0");
    if (!(p.fbeta >= 0 && p.fbeta <= 2)) bad("fbeta", "an order in [0, 2]");
    if (p.fb < 0) bad("fb", "a lag time constant >= 0 s");
    if (!(p.d1 >= 0 && p.d2 >= 0 && (p.d2 == 0 || p.d1 > 0))) bad("d1", "D(s) = 1 + d1 s + d2 s^2 Hurwitz (d1, d2 >= 0, d1 > 0 if d2 > 0)");
    p.ts = frac_real(ctx.Ts);
    p.op = read_realization(doc, w, ctx.Ts);
    return std::make_unique<Collocated>(p, reference_index(doc, "reference", ctx), measured_index(doc, "measured", ctx),
                                        output_index(doc, "output", ctx), ctx.outputs, w);
}

}  // namespace gap
}  // namespace fracdesign
