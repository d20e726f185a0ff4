// Tests of the time-domain output-error fits (fracdesign/ident/time_domain.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "fracdesign/ident/emps.hpp"
#include "fracdesign/ident/time_domain.hpp"

using namespace fracdesign::ident;

namespace {

// Seed 001 Sec. 5, eq. (51): the teleoperated robot, K = 1, T = 1/w0^2,
// w0 = 5.8434 rad/s, lambda = 1.92, tau = 0.1613 s.
const double kRobot[4] = {1.0, 1.0 / (5.8434 * 5.8434), 1.92, 0.1613};

std::vector<double> step(std::size_t n) { return std::vector<double>(n, 1.0); }

std::vector<double> chirp(std::size_t n, double h)
{
    std::vector<double> u(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double t = k * h;
        u[k] = std::sin(2.0 * M_PI * (0.1 * t + 0.15 * t * t));
    }
    return u;
}

}  // namespace

TEST(FoProcessSim, gl_step_response_of_first_order_matches_exponential)
{
    // lambda = 1: T y' + y = K u, step response K (1 - exp(-t/T)). GL with
    // lambda = 1 has w = (1, -1, 0, 0, ...): exactly the backward Euler
    // recursion, first-order accurate.
    const double th[4] = {2.0, 0.5, 1.0, 0.0};
    const double h = 1e-3;
    const auto y = simulate_fo_process(th, step(3000), h);
    double yb = 0.0;
    for (std::size_t k = 0; k < 3000; ++k) {
        yb = (0.5 / h * yb + 2.0) / (0.5 / h + 1.0);
        EXPECT_NEAR(y[k], yb, 1e-12);
    }
    for (std::size_t k = 100; k < 3000; k += 500)
        EXPECT_NEAR(y[k], 2.0 * (1.0 - std::exp(-double(k) * h / 0.5)), 2.0 * h / 0.5);
}

TEST(FoProcessSim, delay_shifts_the_response)
{
    const double h = 0.01;
    const double th0[4] = {1.0, 0.1, 1.5, 0.0}, th1[4] = {1.0, 0.1, 1.5, 0.2};
    const auto y0 = simulate_fo_process(th0, step(200), h);
    const auto y1 = simulate_fo_process(th1, step(200), h);
    for (std::size_t k = 0; k < 20; ++k) EXPECT_EQ(y1[k], 0.0);
    for (std::size_t k = 20; k < 200; ++k) EXPECT_NEAR(y1[k], y0[k - 20], 1e-12);
}

TEST(ProcessFit, recovers_seed001_robot_from_step_and_from_chirp)
{
    const double h = 0.01;
    for (int input = 0; input < 2; ++input) {
        const auto u = input ? chirp(800, h) : step(600);
        const auto y = simulate_fo_process(kRobot, u, h);
        ProcessFitOptions o;
        o.initial = {0.8, 0.05, 1.7, 0.12};
        const ProcessFitResult r = fit_fo_process(u, y, h, o);
        EXPECT_TRUE(r.converged) << r.full_report;
        EXPECT_NEAR(r.process.K, kRobot[0], 1e-6 * kRobot[0]) << input;
        EXPECT_NEAR(r.process.T, kRobot[1], 1e-6 * kRobot[1]);
        EXPECT_NEAR(r.process.lambda, kRobot[2], 1e-6 * kRobot[2]);
        EXPECT_NEAR(r.process.tau, kRobot[3], 1e-6 * kRobot[3]);
        EXPECT_GT(r.fit_percent, 99.99);
    }
}

TEST(ProcessFit, refuses_bad_records)
{
    const double h = 0.01;
    auto u = step(100), y = simulate_fo_process(kRobot, u, h);
    EXPECT_THROW(fit_fo_process(u, std::vector<double>(99, 0.0), h), std::invalid_argument);
    EXPECT_THROW(fit_fo_process(step(10), std::vector<double>(10, 0.0), h), std::invalid_argument);
    EXPECT_THROW(fit_fo_process(u, y, 0.0), std::invalid_argument);
    EXPECT_THROW(fit_fo_process(std::vector<double>(100, 0.0), y, h), std::invalid_argument);
    y[50] = NAN;
    try {
        fit_fo_process(u, y, h);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("index 50"), std::string::npos) << e.what();
    }
}

TEST(ProcessFit, non_converged_fit_says_so_with_the_ceres_report)
{
    const double h = 0.01;
    const auto u = step(300);
    const auto y = simulate_fo_process(kRobot, u, h);
    ProcessFitOptions o;
    o.initial = {0.5, 0.2, 1.2, 0.0};
    o.max_iterations = 1;
    int calls = 0;
    o.on_iteration = [&calls](int, double J) {
        EXPECT_GT(J, 0.0);
        ++calls;
    };
    const ProcessFitResult r = fit_fo_process(u, y, h, o);
    EXPECT_GE(calls, 1);  // the progress hook sees the iterations
    EXPECT_FALSE(r.converged);
    EXPECT_NE(r.summary.find("NO_CONVERGENCE"), std::string::npos) << r.summary;
    EXPECT_NE(r.full_report.find("Termination"), std::string::npos);
}

TEST(ServoFit, open_loop_recovers_inertia_friction_and_stribeck)
{
    const double dt = 1e-3;
    const double truth[kServoParams] = {95.0, 200.0, 20.0, -3.0, 8.0, 0.1};
    std::vector<double> F(4000);
    for (std::size_t k = 0; k < F.size(); ++k)
        F[k] = 300.0 * std::sin(2.0 * M_PI * 1.0 * k * dt) + 80.0 * std::sin(2.0 * M_PI * 4.3 * k * dt);
    ServoRecord rec;
    rec.dt = dt;
    rec.force = F;
    rec.q = simulate_servo_open_loop(truth, F, dt, 4);
    ServoFitOptions o;
    o.stribeck = true;
    o.skip = 0;
    o.initial = {90.0, 180.0, 18.0, -2.0, 6.0, 0.12};
    const ServoFitResult r = fit_servo(rec, o);
    EXPECT_TRUE(r.converged) << r.full_report;
    for (int i = 0; i < kServoParams; ++i) EXPECT_NEAR(r.theta[i], truth[i], 1e-4 * std::fabs(truth[i])) << i;
    EXPECT_LT(r.q_error_percent, 1e-6);
}

TEST(ServoFit, closed_loop_with_known_emps_controller_recovers_the_model)
{
    const EmpsRecord e = load_emps_mat(emps_data_path("DATA_EMPS.mat"));
    ServoRecord rec;
    rec.dt = e.dt;
    rec.closed_loop = true;
    rec.controller = e.controller;
    rec.qr.assign(e.qg.begin(), e.qg.begin() + 6000);
    const double truth[kServoParams] = {95.1, 203.5, 20.4, -3.16, 0.0, 0.01};
    std::vector<double> q, u;
    simulate_servo_closed_loop(truth, rec.controller, rec.qr, {}, rec.dt, 4, q, &u);
    rec.q = q;
    rec.u = u;
    ServoFitOptions o;
    o.initial = {80.0, 150.0, 15.0, 0.0, 0.0, 0.01};
    const ServoFitResult r = fit_servo(rec, o);
    EXPECT_TRUE(r.converged) << r.full_report;
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(r.theta[i], truth[i], 1e-4 * std::fabs(truth[i])) << i;
    EXPECT_EQ(r.theta[4], 0.0);  // Stribeck held at zero
}

TEST(ServoFit, refuses_bad_records_naming_the_problem)
{
    ServoRecord rec;
    rec.dt = 1e-3;
    rec.force.assign(60, 1.0);
    rec.q.assign(60, 0.1);
    try {
        fit_servo(rec);  // 60 samples < skip 50 + 20
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("too short"), std::string::npos) << e.what();
    }
    rec.force.assign(100, 1.0);
    rec.q.assign(100, 0.1);
    ServoFitOptions o;
    o.skip = 0;
    rec.force.resize(90);
    EXPECT_THROW(fit_servo(rec, o), std::invalid_argument);  // length mismatch
    rec.force.assign(100, 1.0);
    rec.q[7] = INFINITY;
    try {
        fit_servo(rec, o);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("index 7"), std::string::npos) << e.what();
    }
    rec.q[7] = 0.1;
    o.initial[0] = -1.0;
    EXPECT_THROW(fit_servo(rec, o), std::invalid_argument);  // initial mass outside bounds
    rec.dt = 0.0;
    EXPECT_THROW(fit_servo(rec), std::invalid_argument);
}
