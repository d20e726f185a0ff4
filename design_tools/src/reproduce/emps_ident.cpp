// emps_ident.cpp - EMPS benchmark checks: IDIM-LS on the estimation record and
// closed-loop simulation of the identified model on the validation record.
// Source: A. Janot, M. Gautier, M. Brunot, "Data Set and Reference Models of
// EMPS", 2019 (facts in data/real/emps/README.md).
#include <cstdio>

#include "fracdesign/ident/emps.hpp"
#include "fracdesign/reproduce.hpp"

namespace fracdesign {
namespace {

ident::IdimResult identify_emps()
{
    const ident::EmpsRecord r = ident::load_emps_mat(ident::emps_data_path("DATA_EMPS.mat"));
    return ident::idim_ls_servo(r.qm, r.force(), r.dt);
}

CheckOutcome check_idim()
{
    const ident::IdimResult id = identify_emps();
    CheckOutcome o;
    o.expected = {95.1089, 203.5034, 20.3935, -3.1648};
    o.got = {id.theta(0), id.theta(1), id.theta(2), id.theta(3)};
    o.tol = 0.02;
    o.relative = true;
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "[M kg, Fv N s/m, Fc N, offset N]; gtau = 35.15 N/V from the file; Butterworth 4th order 100 Hz "
                  "zero-phase, central differences, parallel decimation by 10; cond(W) = %.2f (published 25.99), "
                  "force relative error %.2f %% (published 4.08 %%)",
                  id.cond, id.rel_error);
    o.note = buf;
    return o;
}

CheckOutcome check_validation()
{
    const ident::IdimResult id = identify_emps();
    const ident::EmpsRecord r = ident::load_emps_mat(ident::emps_data_path("DATA_EMPS_PULSES.mat"));
    const double th[ident::kServoParams] = {id.theta(0), id.theta(1), id.theta(2), id.theta(3), 0.0, 1.0};
    std::vector<double> q;
    ident::simulate_servo_closed_loop(th, r.controller, r.qg, r.pulses, r.dt, 10, q);
    CheckOutcome o;
    o.expected = {0.0080248};
    o.got = {ident::relative_error_percent(r.qm, q, 50)};
    o.tol = 0.0080248;
    o.relative = false;
    o.note =
        "relative position error 100||qm - q||/||qm|| in %, first 50 samples dropped, next to the published "
        "0.0080248 %; pulses added in volts after the +-10 V saturation, one-sample delay, RK4 with 10 substeps. "
        "Tolerance: the error must stay below twice the published one (0 < got <= 0.016 %). The position loop "
        "(20 Hz) hides most model errors in q, so only the order of magnitude is meaningful: with M doubled the "
        "error is ~0.17 %, fails; our simulator is closer to qm than the authors' Simulink run (their logged "
        "training simulation also differs from our PD law on its own q_sim), so got < expected is normal.";
    return o;
}

CheckRegistrar reg_idim({"emps.idim", "EMPS description sec. 3.4 (Janot, Gautier, Brunot 2019), DATA_EMPS.mat",
                         check_idim});
CheckRegistrar reg_val({"emps.validation", "EMPS description sec. 3.5, DATA_EMPS_PULSES.mat cross-test",
                        check_validation});

}  // namespace
}  // namespace fracdesign
