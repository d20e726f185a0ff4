// Tests of the servo-axis identification pieces: filters, the closed-loop
// simulator, IDIM-LS and their bad-input paths.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "fracdesign/ident/emps.hpp"
#include "fracdesign/ident/filters.hpp"
#include "fracdesign/ident/servo.hpp"

using namespace fracdesign::ident;

namespace {

std::complex<double> response(const std::vector<Biquad>& sos, double f, double fs)
{
    const std::complex<double> zi = std::exp(std::complex<double>(0.0, -2.0 * M_PI * f / fs));
    std::complex<double> h = 1.0;
    for (const auto& q : sos) h *= (q.b0 + q.b1 * zi + q.b2 * zi * zi) / (1.0 + q.a1 * zi + q.a2 * zi * zi);
    return h;
}

// A smooth back-and-forth force profile that excites inertia, viscous and
// Coulomb friction (both directions) on an open-loop axis. Its amplitude is
// well above Fc so the axis hardly sticks at reversals (sticking breaks the
// sign(q') model that IDIM fits).
std::vector<double> test_force(std::size_t n, double dt)
{
    std::vector<double> F(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double t = k * dt;
        F[k] = 300.0 * std::sin(2.0 * M_PI * 0.5 * t) + 80.0 * std::sin(2.0 * M_PI * 3.1 * t);
    }
    return F;
}

}  // namespace

TEST(Filters, butterworth_has_unity_dc_and_half_power_at_cutoff)
{
    for (int order : {1, 2, 4, 5, 8}) {
        const auto sos = butter_lowpass(order, 100.0, 1000.0);
        EXPECT_NEAR(std::abs(response(sos, 0.0, 1000.0)), 1.0, 1e-12);
        EXPECT_NEAR(std::abs(response(sos, 100.0, 1000.0)), std::sqrt(0.5), 1e-9) << order;
        EXPECT_LT(std::abs(response(sos, 400.0, 1000.0)), std::pow(0.3, order));
    }
    EXPECT_THROW(butter_lowpass(4, 600.0, 1000.0), std::invalid_argument);
    EXPECT_THROW(butter_lowpass(0, 10.0, 1000.0), std::invalid_argument);
}

TEST(Filters, filtfilt_passes_a_ramp_without_edge_transient_or_lag)
{
    std::vector<double> x(1000);
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = 3.0 + 0.01 * k;
    const auto sos = butter_lowpass(4, 20.0, 1000.0);
    // A padding longer than the filter's settling time: exact everywhere.
    const auto y = filtfilt(sos, x, 900);
    for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(y[k], x[k], 1e-9);
    // The short default padding: exact once the start-up transient has settled.
    const auto yd = filtfilt(sos, x);
    for (std::size_t k = 300; k + 300 < x.size(); ++k) EXPECT_NEAR(yd[k], x[k], 1e-7);
    EXPECT_THROW(filtfilt(butter_lowpass(2, 20.0, 1000.0), {1.0}), std::invalid_argument);
}

TEST(ServoSim, closed_loop_delay_and_saturation_act_on_the_command)
{
    ServoController c;
    c.kp = 10.0;
    c.kv = 100.0;
    c.gtau = 1.0;
    c.u_max = 2.0;
    const double th[kServoParams] = {1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    std::vector<double> qr(5, 1.0), q, u;
    simulate_servo_closed_loop(th, c, qr, {}, 1e-3, 4, q, &u);
    EXPECT_DOUBLE_EQ(u[0], 1000.0);  // kv kp (qr - q), logged before the delay
    EXPECT_DOUBLE_EQ(q[1], 0.0);     // nothing applied during the first sample (one-sample delay)
    // then the saturated 2 V on a 1 kg mass: q = a t^2 / 2 after one sample
    EXPECT_NEAR(q[2], 0.5 * 2.0 * 1e-6, 1e-15);
}

TEST(Idim, recovers_friction_and_inertia_from_noiseless_open_loop_data)
{
    const double dt = 1e-3;
    const double th[kServoParams] = {95.0, 200.0, 20.0, -3.0, 0.0, 1.0};
    const auto F = test_force(20000, dt);
    const auto q = simulate_servo_open_loop(th, F, dt, 10);
    const IdimResult r = idim_ls_servo(q, F, dt);
    EXPECT_NEAR(r.theta(0), 95.0, 0.01 * 95.0);
    EXPECT_NEAR(r.theta(1), 200.0, 0.01 * 200.0);
    EXPECT_NEAR(r.theta(2), 20.0, 0.02 * 20.0);
    EXPECT_NEAR(r.theta(3), -3.0, 0.02 * 3.0);
    EXPECT_LT(r.rel_error, 2.0);
}

TEST(Idim, refuses_short_nan_mismatched_and_motionless_records)
{
    std::vector<double> q(300, 0.0), F(300, 1.0);
    try {
        idim_ls_servo(q, F, 1e-3);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("too short"), std::string::npos) << e.what();
    }
    std::vector<double> q2(5000, 0.0), F2(5000, 1.0);
    EXPECT_THROW(idim_ls_servo(q2, F, 1e-3), std::invalid_argument);
    F2[17] = NAN;
    try {
        idim_ls_servo(q2, F2, 1e-3);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("index 17"), std::string::npos) << e.what();
    }
    F2[17] = 1.0;
    EXPECT_THROW(idim_ls_servo(q2, F2, 1e-3), std::invalid_argument);  // no motion: rank deficient
}

TEST(Idim, refuses_sample_time_in_wrong_units)
{
    // dt given in ms (1.0 instead of 1e-3): the 100 Hz filter is above Nyquist.
    const auto F = test_force(5000, 1e-3);
    const double th[kServoParams] = {95.0, 200.0, 20.0, -3.0, 0.0, 1.0};
    const auto q = simulate_servo_open_loop(th, F, 1e-3, 4);
    try {
        idim_ls_servo(q, F, 1.0);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("sample time in s"), std::string::npos) << e.what();
    }
}

TEST(Emps, identified_model_tracks_the_pulses_record_in_closed_loop)
{
    const EmpsRecord tr = load_emps_mat(emps_data_path("DATA_EMPS.mat"));
    const IdimResult id = idim_ls_servo(tr.qm, tr.force(), tr.dt);
    const EmpsRecord r = load_emps_mat(emps_data_path("DATA_EMPS_PULSES.mat"));
    EXPECT_EQ(r.pulses.size(), r.qm.size());
    const double th[kServoParams] = {id.theta(0), id.theta(1), id.theta(2), id.theta(3), 0.0, 1.0};
    std::vector<double> q;
    simulate_servo_closed_loop(th, r.controller, r.qg, r.pulses, r.dt, 10, q);
    EXPECT_LT(relative_error_percent(r.qm, q, 50), 0.016);
    // Without the pulses the simulated position departs from the measured one.
    simulate_servo_closed_loop(th, r.controller, r.qg, {}, r.dt, 10, q);
    EXPECT_GT(relative_error_percent(r.qm, q, 50), 0.016);
}
