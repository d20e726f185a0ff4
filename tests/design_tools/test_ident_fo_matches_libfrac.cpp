// The identification's fractional-process simulator (ident/time_domain.hpp,
// templated so Ceres can differentiate through it) must be the same
// numerical scheme as what runs on the PLC and the HIL rig: libfrac's
// frac_foprocess with the Grünwald–Letnikov operator at full memory
// (implicit GL, seed 001 note section 7, linear interpolation of the
// fractional delay). Both are run on the same inputs here.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "frac/foprocess.h"
#include "fracdesign/ident/time_domain.hpp"

namespace {

std::vector<double> run_libfrac(const double th[4], const std::vector<double>& u, double h)
{
    frac_foprocess_params p{};
    p.k = th[0];
    p.t = th[1];
    p.lambda = th[2];
    p.tau = th[3];
    p.ts = h;
    p.op.method = FRAC_FO_GL;
    p.op.memory = u.size();  // full memory, as the identification's simulator
    std::vector<double> storage(frac_foprocess_storage_len(&p));
    frac_foprocess g;
    EXPECT_EQ(frac_foprocess_init(&g, &p, storage.data(), storage.size()), FRAC_OK);
    std::vector<double> y(u.size());
    for (size_t k = 0; k < u.size(); ++k) EXPECT_EQ(frac_foprocess_step(&g, u[k], &y[k]), FRAC_OK);
    return y;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b)
{
    double m = 0.0;
    for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::fabs(a[i] - b[i]));
    return m;
}

// Seed 001 robot (notes 001): lambda = 1.92, w0 = 5.8434 rad/s (T = 1/w0^2),
// tau = 0.1613 s (not a multiple of Ts: exercises the interpolated delay).
TEST(IdentFoProcess, StepResponseEqualsLibfracFoprocess)
{
    const double h = 2e-3;
    const double th[4] = {1.3, 1.0 / (5.8434 * 5.8434), 1.92, 0.1613};
    std::vector<double> u(1500, 1.0);
    const auto y_ident = fracdesign::ident::simulate_fo_process(th, u, h);
    const auto y_frac = run_libfrac(th, u, h);
    EXPECT_LT(max_abs_diff(y_ident, y_frac), 1e-10);
    EXPECT_GT(*std::max_element(y_frac.begin(), y_frac.end()), 1.3);  // underdamped: overshoot above K
}

TEST(IdentFoProcess, ChirpResponseEqualsLibfracFoprocess)
{
    const double h = 1e-3;
    const double th[4] = {0.8, 0.05, 1.2, 0.0125};
    std::vector<double> u(2000);
    for (size_t k = 0; k < u.size(); ++k) {
        const double t = k * h;
        u[k] = std::sin(2.0 * M_PI * (0.2 + 2.0 * t) * t);
    }
    const auto y_ident = fracdesign::ident::simulate_fo_process(th, u, h);
    const auto y_frac = run_libfrac(th, u, h);
    EXPECT_LT(max_abs_diff(y_ident, y_frac), 1e-10);
}

}  // namespace
