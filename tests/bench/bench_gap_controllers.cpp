// bench_gap_controllers.cpp - replay cost per sample of each controller kind
// (issue 21 item 4): the closed-loop replay of one plant (mass on a spring,
// 2 states, 1 kHz) under each kind, against today's linear law (kind
// statespace) as the reference; and each kind's Controller::step alone
// against the direct libfrac calls the PLC block makes per cycle (the
// wrapper's overhead). Wall time, best of 5 runs of 200 000 samples.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>

#include "fracdesign/gap/effects.hpp"

#include "frac/fodamp.h"
#include "frac/fopid.h"

using namespace fracdesign::gap;
using nlohmann::json;

namespace {

const double kTs = 1e-3;
const Eigen::Index kN = 200000;

json doc(const json& controller)
{
    return {{"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "mass_on_spring"},
            {"time", "continuous"}, {"A", {{0.0, 1.0}, {-12.0, -1.8}}}, {"B", {{0.0}, {1.5}}},
            {"C", {{1.0, 0.0}, {0.0, 1.0}}}, {"D", {{0.0}, {0.0}}}, {"inputs", {"u"}}, {"outputs", {"x", "v"}},
            {"gap", {{"velocity", "v"}, {"force_input", "u"},
                     {"closed_loop", {{"references", {"r"}}, {"measured", {"x", "v"}}, {"controller", controller}}}}}};
}

double best_ns(const std::function<void()>& f)
{
    double best = 1e300;
    for (int i = 0; i < 5; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        best = std::min(best, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count());
    }
    return best / double(kN);
}

double ref(Eigen::Index k) { return ((k / 2000) % 2 ? 1.0 : -0.7) + 0.1 * std::sin(0.01 * double(k)); }

const json kOp = {{"method", "gl"}, {"memory", 200}};

frac_fopid_params fopid_params()
{
    frac_fopid_params p;
    std::memset(&p, 0, sizeof p);
    p.kp = 20;
    p.ki = 15;
    p.kd = 2;
    p.lambda = 0.8;
    p.mu = 0.7;
    p.tf = 0.005;
    p.b = p.c = 1;
    p.umin = -8;
    p.umax = 10;
    p.antiwindup = FRAC_FOPID_AW_BACKCALC;
    p.tt = 0.1;
    p.ts = kTs;
    p.op.method = FRAC_FO_GL;
    p.op.ts = kTs;
    p.op.memory = 200;
    return p;
}

const json kFopid = {{"kind", "fopid"}, {"kp", 20}, {"ki", 15}, {"kd", 2}, {"lambda", 0.8}, {"mu", 0.7}, {"tf", 0.005},
                     {"umin", -8}, {"umax", 10}, {"antiwindup", "backcalc"}, {"tt", 0.1}, {"op", kOp}, {"measured", "x"}};

struct Case {
    const char* name;
    json controller;
    std::function<double()> direct;  // ns per sample of the PLC's libfrac calls (0: no PLC block)
};

}  // namespace

int main()
{
    Signals s;
    s.source = "bench";
    s.names = {"r", "x", "v"};
    s.Ts = kTs;
    s.values = Eigen::MatrixXd::Zero(kN, 3);
    for (Eigen::Index k = 0; k < kN; ++k) s.values(k, 0) = ref(k);

    json cascade = {{"kind", "cascade"}, {"loops", {kFopid, kFopid}}};
    cascade["loops"][0]["divider"] = 4;
    cascade["loops"][1]["measured"] = "v";
    json stages = kFopid;
    stages["friction"] = {{"model", "linear"}, {"b1", 0.1}, {"b0", 0.3}, {"velocity", "v"}};
    stages["feedforward"] = {{{"lut1d", {{"x", {-2, -1, 0, 1, 2}}, {"y", {-24, -12, 0, 12, 24}}}}, {"input", "r"}}};
    stages["rate_limit"] = {{"output", 500}};
    stages["limits"] = {{"min", -6}, {"max", 9}};
    auto fopid_direct = [] {
        const frac_fopid_params p = fopid_params();
        std::vector<frac_real> st(frac_fopid_storage_len(&p));
        frac_fopid c;
        frac_fopid_init(&c, &p, st.data(), st.size());
        volatile double sink = 0;
        return best_ns([&] {
            frac_real u = 0;
            for (Eigen::Index k = 0; k < kN; ++k) {
                frac_fopid_step(&c, frac_real(ref(k)), frac_real(0.9 * ref(k)), &u);
                sink = sink + u;
            }
        });
    };
    auto fodamp_direct = [] {
        frac_fodamp_params p;
        std::memset(&p, 0, sizeof p);
        p.kc = 3;
        p.alpha = 0.7;
        p.n1 = 0.005;
        p.d1 = 0.02;
        p.fa = 0.3;
        p.fbeta = 0.6;
        p.fb = 0.05;
        p.ts = kTs;
        p.op.method = FRAC_FO_GL;
        p.op.ts = kTs;
        p.op.memory = 200;
        std::vector<frac_real> st(frac_fodamp_storage_len(&p));
        frac_fodamp c;
        frac_fodamp_init(&c, &p, st.data(), st.size());
        volatile double sink = 0;
        return best_ns([&] {
            frac_real u = 0;
            for (Eigen::Index k = 0; k < kN; ++k) {
                frac_fodamp_step(&c, frac_real(ref(k)), frac_real(0.9 * ref(k)), &u);
                sink = sink + u;
            }
        });
    };
    const std::vector<Case> cases = {
        {"statespace (PD, reference)", {{"time", "discrete"}, {"Ts", kTs}, {"D", {{20.0, -20.0, -2.0}}}}, nullptr},
        {"fopid (GL 200, backcalc)", kFopid, fopid_direct},
        {"collocated (GL 200, prefilter)",
         {{"kind", "collocated"}, {"kc", 3}, {"alpha", 0.7}, {"m", 0}, {"n1", 0.005}, {"d1", 0.02}, {"fa", 0.3},
          {"fbeta", 0.6}, {"fb", 0.05}, {"op", kOp}, {"measured", "x"}},
         fodamp_direct},
        {"cascade (2 fopid, outer divider 4)", cascade, nullptr},
        {"fopid + friction, LUT1D, limits, ramp", stages, nullptr},
    };
    std::printf("replay cost per sample, 1 kHz closed loop, %ld samples (best of 5)\n", long(kN));
    std::printf("%-40s %12s %12s %8s %14s %14s %8s\n", "controller kind", "replay ns", "statespace", "ratio", "step ns",
                "libfrac ns", "ratio");
    double ref_ns = 0;
    for (const Case& c : cases) {
        const NominalModel m = nominal_from_json(doc(c.controller), kTs);
        const ReplaySetup setup = make_replay_setup(m, s, {}, {"x", "v"});
        volatile double sink = 0;
        const double rep = best_ns([&] { sink = sink + replay(setup, {}).y(kN - 1, 0); });
        if (ref_ns == 0) ref_ns = rep;
        std::unique_ptr<Controller> ctl = m.loop.controller->clone();
        const double r0 = ref(0), y0[2] = {0, 0};
        ctl->start(&r0, y0);
        const double step = best_ns([&] {
            double u = 0;
            for (Eigen::Index k = 0; k < kN; ++k) {
                const double r = ref(k), y[2] = {0.9 * r, 0.0};
                ctl->step(&r, y, &u);
                sink = sink + u;
            }
        });
        std::printf("%-40s %12.1f %12.1f %8.2f %14.1f", c.name, rep, ref_ns, rep / ref_ns, step);
        if (c.direct) {
            const double d = c.direct();
            std::printf(" %14.1f %8.2f\n", d, step / d);
        } else {
            std::printf(" %14s %8s\n", "-", "-");
        }
    }
    return 0;
}
