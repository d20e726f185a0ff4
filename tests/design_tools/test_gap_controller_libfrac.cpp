// test_gap_controller_libfrac.cpp - the gap replay's controller kinds call
// the same libfrac functions, with the same parameter structs, as the PLC
// block bodies (plc_blocks/FracCtrl/FOPID.c, FracDamp.c, FrictionComp.c,
// LUT1D.c, TrajLUT.c; the ramp of frac/ramp.h): on a fixed input sequence
// the Controller's outputs equal the direct calls to the last bit (issue 21
// item 3). Parameters are not the seeds': each kind is checked away from
// the printed designs, with every anti-windup mode and two realizations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "fracdesign/gap/controller.hpp"

#include "frac/fodamp.h"
#include "frac/fopid.h"
#include "frac/friction.h"
#include "frac/lut.h"
#include "frac/ramp.h"
#include "frac/trajlut.h"

using namespace fracdesign::gap;
using nlohmann::json;

namespace {

const double kTs = 1e-3;
const int kN = 3000;

// A reference with steps and a measurement lagging it with a ripple: both
// large enough to drive the laws into their limits.
double ref(int k) { return (k / 500) % 2 ? 1.3 : -0.4 + 0.2 * std::sin(0.013 * k); }
double meas(int k) { return 0.8 * ref(std::max(k - 40, 0)) + 0.05 * std::sin(0.31 * k) + 0.02 * std::cos(1.7 * k); }

ControllerContext ctx1()
{
    ControllerContext c;
    c.Ts = kTs;
    c.references = {"r"};
    c.measured = {"y", "v"};
    c.inputs = {"u"};
    c.outputs = 1;
    c.where = "controller";
    return c;
}

double vel(int k) { return 30 * (meas(k + 1) - meas(k)); }

std::vector<double> run(const json& doc, const ControllerContext& ctx, int n = kN)
{
    std::unique_ptr<Controller> c = make_controller(doc, ctx);
    const double r0 = ref(0), y0[2] = {meas(0), vel(0)};
    c->start(&r0, y0);
    std::vector<double> u(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        const double r = ref(k), y[2] = {meas(k), vel(k)};
        c->step(&r, y, &u[size_t(k)]);
    }
    return u;
}

frac_fopid_params fopid_params(int aw, int method, double ts)
{
    frac_fopid_params p;
    std::memset(&p, 0, sizeof p);
    p.kp = 2.3;
    p.ki = 7.1;
    p.kd = 0.27;
    p.lambda = 0.83;
    p.mu = 0.61;
    p.tf = 0.004;
    p.b = 0.7;
    p.c = 0.4;
    p.delta = 0.15;
    p.umin = -0.9;
    p.umax = 1.6;
    p.antiwindup = aw;
    p.tt = 0.03;
    p.ts = ts;
    p.op.method = method;
    p.op.order = 0;
    p.op.ts = ts;
    p.op.memory = 300;
    p.op.wb = 0.1;
    p.op.wh = 800;
    p.op.n = 5;
    return p;
}

json fopid_doc(const char* aw, const char* method)
{
    json op = {{"method", method}};
    if (std::string(method) == "gl") op["memory"] = 300;
    else op.update({{"wb", 0.1}, {"wh", 800}, {"n", 5}});
    return {{"kind", "fopid"}, {"kp", 2.3}, {"ki", 7.1}, {"kd", 0.27}, {"lambda", 0.83}, {"mu", 0.61}, {"tf", 0.004},
            {"b", 0.7}, {"c", 0.4}, {"delta", 0.15}, {"umin", -0.9}, {"umax", 1.6}, {"antiwindup", aw}, {"tt", 0.03},
            {"op", op}};
}

struct Fopid {
    frac_fopid c;
    std::vector<frac_real> s;
    explicit Fopid(const frac_fopid_params& p) : s(frac_fopid_storage_len(&p) + 1)
    {
        EXPECT_EQ(frac_fopid_init(&c, &p, s.data(), s.size()), FRAC_OK);
    }
    double step(double r, double y)
    {
        frac_real u = 0;
        frac_fopid_step(&c, r, y, &u);
        return u;
    }
};

void expect_bits(const std::vector<double>& got, const std::vector<double>& want, const std::string& what)
{
    ASSERT_EQ(got.size(), want.size());
    int saturated = 0;
    for (size_t k = 0; k < got.size(); ++k) {
        ASSERT_EQ(std::memcmp(&got[k], &want[k], sizeof(double)), 0) << what << " sample " << k << ": " << got[k] << " vs " << want[k];
        saturated += got[k] == -0.9 || got[k] == 1.6;
    }
    EXPECT_GT(saturated, 0) << what << ": the sequence must reach the limits";
}

}  // namespace

TEST(GapControllerLibfrac, fopid_equals_frac_fopid_step_for_every_antiwindup_and_realization)
{
    const char* aws[] = {"none", "clamp", "backcalc"};
    const char* methods[] = {"gl", "oustaloup"};
    for (int aw = 0; aw < 3; ++aw)
        for (int m = 0; m < 2; ++m) {
            Fopid f(fopid_params(aw, m == 0 ? FRAC_FO_GL : FRAC_FO_OUSTALOUP, kTs));
            std::vector<double> want(kN);
            for (int k = 0; k < kN; ++k) want[size_t(k)] = f.step(ref(k), meas(k));
            expect_bits(run(fopid_doc(aws[aw], methods[m]), ctx1()), want, std::string(aws[aw]) + "/" + methods[m]);
        }
}

TEST(GapControllerLibfrac, a_clone_continues_with_the_same_state)
{
    // clone() copies the operators' memories (pointers moved into the copy's storage).
    ControllerContext ctx = ctx1();
    std::unique_ptr<Controller> a = make_controller(fopid_doc("backcalc", "gl"), ctx);
    const double r0 = ref(0), y0[2] = {meas(0), 0};
    a->start(&r0, y0);
    double u = 0, v = 0;
    for (int k = 0; k < 700; ++k) {
        const double r = ref(k), y[2] = {meas(k), 0};
        a->step(&r, y, &u);
    }
    std::unique_ptr<Controller> b = a->clone();
    for (int k = 700; k < 1500; ++k) {
        const double r = ref(k), y[2] = {meas(k), 0};
        a->step(&r, y, &u);
        b->step(&r, y, &v);
        ASSERT_EQ(u, v) << k;
    }
    a.reset();  // b must not point into a's storage
    const double r = ref(1500), y[2] = {meas(1500), 0};
    b->step(&r, y, &v);
    EXPECT_TRUE(std::isfinite(v));
}

TEST(GapControllerLibfrac, collocated_equals_frac_fodamp_step_and_takes_the_tune_output)
{
    frac_fodamp_params p;
    std::memset(&p, 0, sizeof p);
    p.kc = 3.7;
    p.alpha = 0.66;
    p.m = 2;
    p.n1 = 0.02;
    p.n2 = 1e-4;
    p.fa = 0.21;
    p.fbeta = 0.43;
    p.fb = 0.017;
    p.ts = kTs;
    p.op.method = FRAC_FO_GL;
    p.op.ts = kTs;
    p.op.memory = 400;
    frac_fodamp d;
    std::vector<frac_real> s(frac_fodamp_storage_len(&p) + 1);
    ASSERT_EQ(frac_fodamp_init(&d, &p, s.data(), s.size()), FRAC_OK);
    std::vector<double> want(kN);
    for (int k = 0; k < kN; ++k) {
        frac_real u = 0;
        frac_fodamp_step(&d, ref(k), meas(k), &u);
        want[size_t(k)] = u;
    }
    const json op = {{"method", "gl"}, {"memory", 400}};
    const json direct = {{"kind", "collocated"}, {"kc", 3.7}, {"alpha", 0.66}, {"m", 2}, {"n1", 0.02}, {"n2", 1e-4},
                         {"fa", 0.21}, {"fbeta", 0.43}, {"fb", 0.017}, {"op", op}};
    const std::vector<double> got = run(direct, ctx1());
    for (int k = 0; k < kN; ++k) ASSERT_EQ(got[size_t(k)], want[size_t(k)]) << k;
    // `fracdesign tune collocated --json` with its prefilter, exact form: n1 = 2 eps, n2 = eps^2.
    const json design = {{"schema", "frac.design.collocated"},
                         {"version", 1},
                         {"controller", {{"form", "C(s) = Kc (1 + eps s)^2 s^(alpha-2)"}, {"Kc", 3.7}, {"alpha", 0.66}, {"eps", 0.01}}},
                         {"prefilter", {{"fn", 0.21}, {"fd", 0.017}, {"beta", 0.43}}}};
    const std::vector<double> via_design = run({{"kind", "collocated"}, {"design", design}, {"op", op}}, ctx1());
    for (int k = 0; k < kN; ++k) ASSERT_EQ(via_design[size_t(k)], want[size_t(k)]) << k;
}

TEST(GapControllerLibfrac, cascade_with_dividers_equals_the_blocks_in_series)
{
    // Outer FO-PI at 4 Ts on y (held between its runs), inner PD at Ts on v.
    frac_fopid_params po = fopid_params(FRAC_FOPID_AW_CLAMP, FRAC_FO_GL, 4 * kTs), pi = fopid_params(FRAC_FOPID_AW_BACKCALC, FRAC_FO_GL, kTs);
    po.kd = 0;
    po.umin = -3;
    po.umax = 3;
    pi.ki = 0;
    pi.mu = 1;
    Fopid outer(po), inner(pi);
    std::vector<double> want(kN);
    double held = 0;
    for (int k = 0; k < kN; ++k) {
        if (k % 4 == 0) held = outer.step(ref(k), meas(k));
        want[size_t(k)] = inner.step(held, vel(k));
    }
    json o = fopid_doc("clamp", "gl"), i = fopid_doc("backcalc", "gl");
    o["kd"] = 0;
    o["umin"] = -3;
    o["umax"] = 3;
    o["divider"] = 4;
    o["measured"] = "y";
    i["ki"] = 0;
    i["mu"] = 1;
    i["measured"] = "v";
    expect_bits(run({{"kind", "cascade"}, {"loops", {o, i}}}, ctx1()), want, "cascade");
}

TEST(GapControllerLibfrac, stages_equal_ramp_friction_lut1d_and_trajlut_calls)
{
    // FO-PD law, + FrictionComp(v) + LUT1D(r) feedforward, clamp, output ramp;
    // the reference from a TrajLUT with a lead of 3 cycles.
    frac_fopid_params pp = fopid_params(FRAC_FOPID_AW_NONE, FRAC_FO_GL, kTs);
    pp.ki = 0;
    pp.umin = -1e6;
    pp.umax = 1e6;
    Fopid law(pp);
    frac_friction_params fp;
    std::memset(&fp, 0, sizeof fp);
    fp.model = FRAC_FRICTION_LINEAR;
    fp.k = 45;
    fp.b1 = 0.03;
    fp.b0 = 0.11;
    frac_friction fr;
    ASSERT_EQ(frac_friction_init(&fr, &fp), FRAC_OK);
    const std::vector<frac_real> lx = {-1, -0.2, 0.5, 2}, ly = {-0.3, 0.05, 0.2, 0.9};
    std::vector<frac_real> ld(4);
    frac_lut1 lut;
    ASSERT_EQ(frac_lut1_init(&lut, lx.data(), ly.data(), 4, FRAC_LUT_CUBIC, FRAC_LUT_EXTRAPOLATE, ld.data()), FRAC_OK);
    std::vector<frac_real> traj(200);
    for (size_t i = 0; i < traj.size(); ++i) traj[i] = frac_real(1.2 * std::sin(0.05 * double(i)));
    const frac_real* data[1] = {traj.data()};
    const long lead[1] = {3};
    frac_trajlut_params tp;
    tp.channels = 1;
    tp.n = traj.size();
    tp.data = data;
    tp.t0 = 0;
    tp.dt = 0.01;
    tp.Ts = kTs;
    tp.lead = lead;
    tp.t_motion_start = 0;
    tp.t_motion_end = 1.99;
    tp.interp = FRAC_LUT_LINEAR;
    frac_trajlut tl;
    ASSERT_EQ(frac_trajlut_init(&tl, &tp, nullptr), FRAC_OK);
    std::vector<double> want(kN);
    double x = 0;
    for (int k = 0; k < kN; ++k) {
        frac_real r = 0, f = 0, l = 0;
        frac_trajlut_step(&tl, &r, nullptr);
        double u = law.step(r, meas(k));
        frac_friction_eval(&fr, vel(k), &f);
        frac_lut1_eval(&lut, r, &l);
        u = std::min(std::max(u + f + l, -0.9), 1.6);
        if (k == 0) x = u;
        else {
            frac_real y = 0;
            frac_ramp_step(x, u, 40.0, kTs, &y);
            x = y;
        }
        want[size_t(k)] = x;
    }
    json d = fopid_doc("none", "gl");
    d["ki"] = 0;
    d.erase("umin");
    d.erase("umax");
    d["friction"] = {{"model", "linear"}, {"k", 45}, {"b1", 0.03}, {"b0", 0.11}, {"velocity", "v"}};
    d["feedforward"] = {{{"lut1d", {{"x", lx}, {"y", ly}, {"interpolation", "cubic"}, {"range", "extrapolate"}}}, {"input", "r"}}};
    d["limits"] = {{"min", -0.9}, {"max", 1.6}};
    d["rate_limit"] = {{"output", 40.0}};
    d["reference_table"] = {{"data", {traj}}, {"dt", 0.01}, {"lead", {3}}, {"t_motion_end", 1.99}, {"references", {"r"}}};
    expect_bits(run(d, ctx1()), want, "stages");
}

TEST(GapControllerLibfrac, fopid_small_signal_is_the_law_for_integer_orders)
{
    // PID with lambda = 1, mu = 1 (GL), no limits: the state space reproduces
    // the law on any input; fractional orders have none.
    json d = {{"kind", "fopid"}, {"kp", 1.7}, {"ki", 3.1}, {"kd", 0.2}, {"lambda", 1}, {"mu", 1}, {"tf", 0.01},
              {"b", 0.6}, {"c", 0.3}, {"delta", 0.05}, {"measured", "v"}, {"op", {{"method", "gl"}, {"memory", 10}}}};
    const ControllerContext ctx = ctx1();
    std::unique_ptr<Controller> c = make_controller(d, ctx);
    Eigen::MatrixXd A, B, C, D;
    ASSERT_TRUE(c->small_signal(A, B, C, D));
    ASSERT_EQ(B.cols(), 3);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(A.rows());
    const double r0 = 0, y0[2] = {0, 0};
    c->start(&r0, y0);
    for (int k = 0; k < 500; ++k) {
        const double r = ref(k), y[2] = {meas(k), vel(k)};
        double u = 0;
        c->step(&r, y, &u);
        const Eigen::Vector3d w(r, y[0], y[1]);
        const double us = (C * x + D * w)(0);
        x = A * x + B * w;
        ASSERT_NEAR(u, us, 1e-9 * (1 + std::fabs(u))) << k;
    }
    d["lambda"] = 0.9;
    EXPECT_FALSE(make_controller(d, ctx)->small_signal(A, B, C, D));
    d["lambda"] = 1;
    d["mu"] = 0.5;
    EXPECT_FALSE(make_controller(d, ctx)->small_signal(A, B, C, D));
}

TEST(GapControllerLibfrac, a_collocated_clone_owns_its_state)
{
    const json d = {{"kind", "collocated"}, {"kc", 2.2}, {"alpha", 0.7}, {"m", 1}, {"n1", 0.03}, {"fa", 0.1}, {"fbeta", 0.5},
                    {"fb", 0.02}, {"op", {{"method", "gl"}, {"memory", 100}}}};
    std::unique_ptr<Controller> a = make_controller(d, ctx1());
    const double r0 = 0, y0[2] = {0, 0};
    a->start(&r0, y0);
    double u = 0, v = 0;
    for (int k = 0; k < 300; ++k) {
        const double r = ref(k), y[2] = {meas(k), 0};
        a->step(&r, y, &u);
    }
    std::unique_ptr<Controller> b = a->clone();
    std::vector<double> ub;
    for (int k = 300; k < 900; ++k) {
        const double r = ref(k), y[2] = {meas(k), 0};
        b->step(&r, y, &v);
        ub.push_back(v);
    }
    a.reset();
    std::unique_ptr<Controller> fresh = make_controller(d, ctx1());
    fresh->start(&r0, y0);
    for (int k = 0; k < 900; ++k) {
        const double r = ref(k), y[2] = {meas(k), 0};
        fresh->step(&r, y, &u);
        if (k >= 300) ASSERT_EQ(u, ub[size_t(k - 300)]) << k;
    }
}
