// friction.cpp - the "friction" stage (kinds.hpp): static friction
// compensation as the FrictionComp block computes it
// (plc_blocks/FracCtrl/FrictionComp.c): frac_friction_init with the block's
// parameter struct, frac_friction_eval(velocity) added to a plant input
// (seed 004 (5.1): Exp. A/B add it to the PD torque). The velocity is a
// named signal of the loop, the measured one or a reference (notes 004b
// erratum 18: the caller's choice).
#include <cstring>

#include "kinds.hpp"

namespace fracdesign {
namespace gap {

FrictionTerm::FrictionTerm(const json& doc, const ControllerContext& ctx, const std::string& where)
{
    if (!doc.is_object()) throw std::runtime_error(where + ": " + shown(doc) + " is not allowed (an object)");
    static const char* const keys[] = {"model", "k", "b1", "b0", "b1n", "b1p", "b0n", "b0p", "b1s", "b2s", "b3s",
                                       "v_s", "delta", "velocity", "output"};
    for (auto it = doc.begin(); it != doc.end(); ++it) {
        bool known = false;
        for (const char* k : keys) known = known || it.key() == k;
        if (!known)
            throw std::runtime_error(field(where, it.key()) + ": unknown field of friction compensation (fields: model, k, "
                                     "b1, b0, b1n, b1p, b0n, b0p, b1s, b2s, b3s, v_s, delta, velocity, output)");
    }
    frac_friction_params p;
    std::memset(&p, 0, sizeof p);
    p.model = choice(doc, "model", where, 0, {"linear", "asymmetric", "stribeck"});
    p.k = frac_real(number(doc, "k", where, 60.0));
    if (!(p.k > 0)) refuse(where, "k", doc.at("k"), "a tanh gain > 0 s/rad");
    p.b1 = frac_real(number(doc, "b1", where, 0.0));
    p.b0 = frac_real(number(doc, "b0", where, 0.0));
    p.b1n = frac_real(number(doc, "b1n", where, 0.0));
    p.b1p = frac_real(number(doc, "b1p", where, 0.0));
    p.b0n = frac_real(number(doc, "b0n", where, 0.0));
    p.b0p = frac_real(number(doc, "b0p", where, 0.0));
    p.b1s = frac_real(number(doc, "b1s", where, 0.0));
    p.b2s = frac_real(number(doc, "b2s", where, 0.0));
    p.b3s = frac_real(number(doc, "b3s", where, 0.0));
    p.v_s = frac_real(number(doc, "v_s", where, 1.0));
    p.delta = frac_real(number(doc, "delta", where, 2.0));
    if (p.model == FRAC_FRICTION_STRIBECK) {
        if (!(p.v_s > 0)) refuse(where, "v_s", doc.at("v_s"), "a Stribeck velocity > 0");
        if (!(p.delta > 0)) refuse(where, "delta", doc.at("delta"), "a Stribeck exponent > 0");
    }
    ControllerContext c = ctx;
    c.where = where;
    velocity_ = signal_index(doc, "velocity", c, -1);
    output_ = output_index(doc, "output", c);
    check_status(frac_friction_init(&f_, &p), where, "the friction parameters");
}

void FrictionTerm::add(const double* w, double* u)
{
    frac_real tau = 0;
    frac_friction_eval(&f_, frac_real(w[velocity_]), &tau);
    u[output_] += double(tau);
}

}  // namespace gap
}  // namespace fracdesign
