// Seed 004 state-difference LQG with delays: augmentation, modal weights, gains, loop checks.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "fracdesign/design/lqg.hpp"

using namespace fracdesign;
using namespace fracdesign::design;
using Eigen::MatrixXd;

namespace {

StateSpace arm(bool reduce, double rt = 0.5)
{
    TimoshenkoParams b = wang_steel_beam();
    b.r_t = rt;
    ArmOptions o;
    o.reduce = reduce;
    return arm_measured_model(build_arm(b, wang_drive(), o).arm);
}

}  // namespace

TEST(DesignLqg, DelayLinesShiftTheTorqueAndTheImuSignal)
{
    // 1-state plant x+ = 0.5 x + u, outputs [x, 2x, 3x]; impulse on u_bar at k = 0:
    // the plant sees it d_i samples later (7.9), the IMU channel reports it d_o samples after that (7.14).
    MatrixXd Ad = MatrixXd::Constant(1, 1, 0.5), Bd = MatrixXd::Ones(1, 1), Cd(3, 1);
    Cd << 1, 2, 3;
    MatrixXd A, B, E, C;
    delay_augment(Ad, Bd, Cd, 4, 3, A, B, E, C);
    ASSERT_EQ(A.rows(), 8);
    Eigen::VectorXd x = B.col(0);  // state after applying u_bar[0] = 1
    int first_x = -1, first_imu = -1;
    for (int k = 1; k < 12; ++k) {
        const Eigen::VectorXd y = C * x;
        if (first_x < 0 && y(0) != 0.0) first_x = k;
        if (first_imu < 0 && y(2) != 0.0) first_imu = k;
        x = A * x;
    }
    EXPECT_EQ(first_x, 1 + 4);          // x[k] reacts to u[k-1] = u_bar[k-1-d_i]
    EXPECT_EQ(first_imu, 1 + 4 + 3);
    EXPECT_EQ(E(4, 0), -1.0);           // fictitious friction at the chain input (7.10)
}

TEST(DesignLqg, ModalBasisDiagonalisesIntoRealBlocksOrderedByFrequency)
{
    const StateSpace s = arm(true);
    const MatrixXd V = modal_basis(s.A);
    const MatrixXd Am = V.inverse() * s.A * V;
    // off-diagonal 2x2 blocks vanish
    double off = 0.0;
    for (int i = 0; i < Am.rows(); ++i)
        for (int j = 0; j < Am.cols(); ++j)
            if (std::abs(i / 2 - j / 2) > 0 && !(i < 2 && j < 2)) off = std::max(off, std::fabs(Am(i, j)));
    EXPECT_LT(off, 1e-6 * Am.norm());
    // the first flexible pair (coordinates 2, 3) is the lowest flexible mode (~3.1 Hz)
    const double w = std::sqrt(std::fabs(Am(2, 3) * Am(3, 2)));
    EXPECT_NEAR(w / (2 * 3.14159265358979), 3.1, 0.1);
    // unit eigenvectors: the two real rigid-body columns, and |a|^2 + |b|^2 = 1 for each pair a +- j b
    EXPECT_NEAR(V.col(0).norm(), 1.0, 1e-12);
    EXPECT_NEAR(V.col(1).norm(), 1.0, 1e-12);
    for (int k = 2; k + 1 < V.cols(); k += 2)
        EXPECT_NEAR(V.col(k).squaredNorm() + V.col(k + 1).squaredNorm(), 1.0, 1e-12);
}

TEST(DesignLqg, UndampedRigidBodyModeUsesAJordanChain)
{
    const StateSpace s = arm(true, 0.0);
    const MatrixXd V = modal_basis(s.A);
    Eigen::JacobiSVD<MatrixXd> sv(V);
    EXPECT_GT(sv.singularValues().minCoeff(), 1e-12);
    // A v1 = 0 and A v2 parallel to v1
    EXPECT_LT((s.A * V.col(0)).norm(), 1e-6 * s.A.norm());
    const Eigen::VectorXd Av2 = s.A * V.col(1);
    EXPECT_NEAR(std::fabs(Av2.normalized().dot(V.col(0))), 1.0, 1e-6);
}

TEST(DesignLqg, ExpDGainsHaveTheThesisDimensionsAndSmallResiduals)
{
    const LqgDesign d = design_lqg(arm(true), LqgParams::exp_d());
    EXPECT_EQ(d.K.rows(), 1);
    EXPECT_EQ(d.K.cols(), 23);
    EXPECT_EQ(d.Le.rows(), 24);
    EXPECT_EQ(d.Le.cols(), 3);
    EXPECT_LT(d.ctrl.residual, 1e-9);
    EXPECT_LT(d.obs.residual, 1e-9);
    EXPECT_LT(d.ctrl.stability, 1.0);
    EXPECT_LT(d.obs.stability, 1.0);
    // Q_c is the modal weight brought back to physical coordinates (8.5): symmetric PSD.
    Eigen::SelfAdjointEigenSolver<MatrixXd> qe(d.Qc);
    EXPECT_GT(qe.eigenvalues().minCoeff(), -1e-9 * qe.eigenvalues().maxCoeff());
}

TEST(DesignLqg, ClosedLoopIsStableOnReducedAndUnreducedArm)
{
    const LqgDesign d = design_lqg(arm(true), LqgParams::exp_d());
    const LoopCheck r = check_closed_loop(d, arm(true));
    const LoopCheck f = check_closed_loop(d, arm(false));
    EXPECT_EQ(f.plant_states, 40 + 4 + 3);
    EXPECT_LT(r.spectral_radius, 1.0);
    EXPECT_LT(f.spectral_radius, 1.0);
    EXPECT_GT(f.modulus_margin, 0.1);
    EXPECT_GT(f.phase_margin_deg, 10.0);
}

TEST(DesignLqg, ExpCWithoutDelaysStabilisesItsDesignModel)
{
    // Table 8.7 weights, no delay model.
    const LqgDesign d = design_lqg(arm(true), LqgParams::exp_c());
    EXPECT_EQ(d.K.cols(), 16);
    EXPECT_EQ(d.Le.rows(), 17);
    EXPECT_LT(check_closed_loop(d, arm(true)).spectral_radius, 1.0);
}

TEST(DesignLqg, ExpCIsStableOnTheUnreducedArmWithTheRigDelays)
{
    // Exp. C has no delay model but ran on the rig with T_i = 4 T, T_o = 3 T (Table 8.8): the check
    // closes the loop on the plant with those delays (the controller keeps d_i = d_o = 0).
    const LqgDesign d = design_lqg(arm(true), LqgParams::exp_c());
    const LoopCheck r = check_closed_loop(d, arm(true), kRigDi, kRigDo);
    const LoopCheck f = check_closed_loop(d, arm(false), kRigDi, kRigDo);
    EXPECT_EQ(r.plant_states, 16 + 4 + 3);
    EXPECT_EQ(f.plant_states, 40 + 4 + 3);
    EXPECT_EQ(f.plant_di, 4);
    EXPECT_EQ(f.plant_do, 3);
    EXPECT_LT(r.spectral_radius, 1.0);
    EXPECT_LT(f.spectral_radius, 1.0);
    EXPECT_GT(r.gain_margin_db, 6.0);
    EXPECT_GT(r.phase_margin_deg, 20.0);
}

TEST(DesignLqg, DampedRigidBodyModeIsWeightedLikeTheUndampedJordanChain)
{
    // With r_t > 0 the rigid-body mode splits into 0 and -0.047 rad/s with nearly parallel
    // eigenvectors; weighting those directly left the angle error a controller pole at
    // -0.033 rad/s (30 s). The orthonormal basis of their span gives the undamped design's poles.
    auto slowest = [](const LqgDesign& d) {
        Eigen::EigenSolver<MatrixXd> es(d.Ad - d.Bd * d.K, false);
        double s = 1e9;
        for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i)
            s = std::min(s, std::abs(std::log(std::complex<double>(es.eigenvalues()(i)))) / d.params.T);
        return s;
    };
    const LqgDesign damped = design_lqg(arm(true, 0.5), LqgParams::exp_d());
    const LqgDesign undamped = design_lqg(arm(true, 0.0), LqgParams::exp_d());
    EXPECT_GT(slowest(damped), 0.1);
    EXPECT_NEAR(slowest(damped), slowest(undamped), 0.01 * slowest(undamped));
    const MatrixXd V = modal_basis(arm(true, 0.5).A);
    EXPECT_NEAR(V.col(0).dot(V.col(1)), 0.0, 1e-12);
}

TEST(DesignLqg, BadParametersAreRefused)
{
    LqgParams p = LqgParams::exp_d();
    p.T = 0.0;
    EXPECT_THROW(design_lqg(arm(true), p), std::invalid_argument);
    p = LqgParams::exp_d();
    p.di = -1;
    EXPECT_THROW(design_lqg(arm(true), p), std::invalid_argument);
    p = LqgParams::exp_d();
    p.s_c = -1.0;
    EXPECT_THROW(design_lqg(arm(true), p), RiccatiError);
}
