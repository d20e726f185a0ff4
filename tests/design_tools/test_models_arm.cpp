// test_models_arm.cpp - Krylov reduction, 2-mass drive and the coupled arm (3.103) of seed 004.
#include <gtest/gtest.h>

#include <cmath>

#include "fracdesign/models/arm.hpp"
#include "fracdesign/models/krylov.hpp"

using namespace fracdesign;

TEST(Krylov, reduced_beam_is_port_hamiltonian_and_matches_the_moments)
{
    const PsBeam b = build_ps_beam(wang_steel_beam(), 9);
    const PhSystem r = krylov_reduce(b.ph, wang_krylov_shifts());
    ASSERT_EQ(r.J.rows(), 12);
    EXPECT_LT(r.skew_residual(), 1e-12);
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(r.Q).info(), Eigen::Success);
    EXPECT_EQ(r.D, b.ph.D);
    const StateSpace f = b.ph.state_space(), rs = r.state_space();
    for (double s : wang_krylov_shifts()) EXPECT_LT((f.transfer(s) - rs.transfer(s)).norm() / f.transfer(s).norm(), 1e-9);
    // first mode kept (notes 004a R14: 2.9343 Hz)
    EXPECT_NEAR(rs.natural_frequencies_hz()[0], 2.9343, 1e-4);
}

TEST(Krylov, bad_shift_lists_are_refused)
{
    const PsBeam b = build_ps_beam(wang_steel_beam(), 3);
    EXPECT_THROW(krylov_reduce(b.ph, {}), std::invalid_argument);
    EXPECT_THROW(krylov_reduce(b.ph, {1.0, NAN}), std::invalid_argument);
    EXPECT_THROW(krylov_reduce(b.ph, {1, 2, 3, 4}), std::invalid_argument);  // 16 > 12 states
    EXPECT_THROW(krylov_reduce(b.ph, {5.0, 5.0}), std::runtime_error);        // repeated: rank loss
}

TEST(Drive, two_mass_drive_has_the_free_free_gear_frequency)
{
    const DriveParams d = wang_drive();
    EXPECT_NEAR(d.I_M, 5.8624, 1e-12);
    const StateSpace s = drive_model(d).state_space();
    const double w = std::sqrt(d.c_s * (1 / d.I_M + 1 / d.I_h));
    ASSERT_EQ(s.natural_frequencies_hz().size(), 1u);
    EXPECT_NEAR(s.natural_frequencies_hz()[0], w / (2 * M_PI), 1e-9 * w);
    DriveParams bad = d;
    bad.c_s = -1;
    EXPECT_THROW(drive_model(bad), std::invalid_argument);
}

TEST(Arm, first_flexible_mode_is_about_3_hz_with_the_load_side_inertia)
{
    const ArmModel red = build_arm(wang_steel_beam(), wang_drive(), ArmOptions());
    ASSERT_EQ(red.arm.J.rows(), 16);
    EXPECT_LT(red.arm.skew_residual(), 1e-12);
    EXPECT_NEAR(red.arm.state_space().natural_frequencies_hz(1e-3)[0], 3.0959, 1e-4);
    // notes 004a sec. 4: with the printed motor-side I_M = 2.29e-4 the first mode would be 12.3152 Hz
    DriveParams motor_side = wang_drive();
    motor_side.I_M = 2.29e-4;
    ArmOptions full;
    full.reduce = false;
    const ArmModel m = build_arm(wang_steel_beam(), motor_side, full);
    EXPECT_NEAR(m.arm.state_space().natural_frequencies_hz(1e-3)[0], 12.3152, 1e-4);
}

TEST(Arm, coupling_uses_the_feedthrough_sign_so_even_and_odd_n_agree)
{
    // (3.103) as printed assumes sigma = +1; for even N the coupling must use sigma = -1, else the
    // tip outputs would differ between N = 9 and N = 12 at low frequency.
    ArmOptions o9, o12;
    o9.reduce = o12.reduce = false;
    o12.N = 12;
    const StateSpace a9 = build_arm(wang_steel_beam(), wang_drive(), o9).arm.state_space();
    const StateSpace a12 = build_arm(wang_steel_beam(), wang_drive(), o12).arm.state_space();
    for (double w : {2.0, 20.0, 60.0}) {
        const Eigen::MatrixXcd h9 = a9.frequency_response(w), h12 = a12.frequency_response(w);
        EXPECT_LT((h9 - h12).norm() / h9.norm(), 1e-3) << w;
    }
    // and the arm is passive: dH/dt = u^T y for the undamped model
    const PhSystem arm = build_arm(wang_steel_beam(), wang_drive(), o12).arm;
    const Eigen::VectorXd x = Eigen::VectorXd::Random(arm.J.rows()), u = Eigen::VectorXd::Random(3);
    const Eigen::VectorXd e = arm.Q * x;
    const double dH = e.dot(arm.J * e + arm.B * u), uy = u.dot(arm.B.transpose() * e);
    EXPECT_NEAR(dH, uy, 1e-9 * std::fabs(uy));
}

TEST(Arm, outputs_and_inputs_are_named_after_3_104)
{
    const ArmModel m = build_arm(wang_steel_beam(), wang_drive(), ArmOptions());
    EXPECT_EQ(m.arm.inputs[0], "tau_M [N m]");
    EXPECT_EQ(m.arm.outputs[1], "w_dot(L) [m/s]");  // (3.104) prints psi_dot(L) twice
    EXPECT_EQ(m.arm.outputs[2], "psi_dot(L) [rad/s]");
    EXPECT_THROW(couple_arm(drive_model(wang_drive()), m.beam_used, 0.5), std::invalid_argument);
}
