// feliu_models.cpp - reproduction checks of the models of seed 002 (Feliu-Batlle, Feliu-Talegon,
// San-Millan 2020; file 002_0c080d042df814b5.txt) and of seed 001's normalised fractional process
// (file 001_73fc104b23173f00.txt).
#include <algorithm>
#include <cmath>

#include "fracdesign/models/collocated.hpp"
#include "fracdesign/models/foprocess.hpp"
#include "fracdesign/reproduce.hpp"

namespace fracdesign {
namespace {

CheckRegistrar nominal({"feliu.nominal", "seed 002 Sec. 5.1 after (43): nominal modal data, m2 = 0.12 lb", [] {
    CheckOutcome o;
    const CollocatedPlant p = collocated_plant(kFeliuM2Nominal);
    o.expected = {6.014, 28.21, 40.011, 4.11};
    o.got = {p.a1, p.z1, p.a2, p.b};
    o.tol = 1e-4;
    o.relative = true;
    o.note = "a10, z10, a20 [rad/s], b0 from (42); the paper truncates (a20 = 40.0119 prints 40.011)";
    return o;
}});

CheckRegistrar ranges({"feliu.ranges", "seed 002 Sec. 5.1: ranges of z1, a1, a2 over m2 in [0.01, 0.23] lb", [] {
    CheckOutcome o;
    const CollocatedPlant lo = collocated_plant(kFeliuM2Max), hi = collocated_plant(kFeliuM2Min);
    o.expected = {26.83, 50.46, 4.44, 14.22, 39.12, 58.62};
    o.got = {lo.z1, hi.z1, lo.a1, hi.a1, lo.a2, hi.a2};
    o.tol = 5e-3;
    o.note = "rad/s, [min, max] of z1, a1, a2 (all decrease with m2)";
    return o;
}});

CheckRegistrar damping({"feliu.damping_max", "seed 002 Sec. 5.2 end and (44): eps_bar = 0.007", [] {
    CheckOutcome o;
    double mx = 0.0;
    for (int i = 0; i <= 220; ++i) {
        const CollocatedPlant p = collocated_plant(kFeliuM2Min + (kFeliuM2Max - kFeliuM2Min) * i / 220.0);
        mx = std::max({mx, p.zeta1, p.zeta2, p.xi1});
    }
    o.expected = {0.007};
    o.got = {mx};
    o.tol = 5e-4;
    o.note = "largest Rayleigh damping ratio of a1, a2, z1 over m2 (notes 002: 0.006704, printed rounded up)";
    return o;
}});

CheckRegistrar fo({"feliu.fo.normalisation", "seed 001 (4), (10), Sec. 5 robot; tau_n with erratum E1 (notes 001)", [] {
    CheckOutcome o;
    const FoProcess p = feliu_benftima_robot();
    o.expected = {0.1589974, 1.014482, 1.011223};
    o.got = {p.time_scale(), p.normalised_delay(), p.normalised_frequency(6.36)};
    o.tol = 5e-6;  // the notes print 7 significant digits
    o.relative = true;
    o.note = "T^(1/lambda) [s], tau_n = tau/T^(1/lambda), w_cn at w_c = 6.36 rad/s (notes 001 C5)";
    return o;
}});

}  // namespace
}  // namespace fracdesign
