// The frac.arm document: validation messages, the model from it (payload, IMU rows), the automatic
// reduction and the LQG on an arm the seeds do not print (derived here), and the seed arm's document.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "fracdesign/design/arm_design.hpp"
#include "fracdesign/models/arm_document.hpp"

using namespace fracdesign;
using nlohmann::json;

namespace {

// An aluminium strip arm derived for this test: no seed prints it.
json alu_doc()
{
    return {{"schema", "frac.arm"},
            {"version", 1},
            {"name", "alu_test"},
            {"link",
             {{"length", 0.7},
              {"material", {{"E", 70e9}, {"poisson", 0.33}, {"rho", 2700}}},
              {"section", {{"shape", "rectangular"}, {"width", 0.05}, {"thickness", 0.004}}},
              {"damping", {{"r_t", 0.3}}}}},
            {"payload", {{"mass", 0.4}, {"inertia", 2e-4}}},
            {"hub", {{"inertia", 2e-3}, {"radius", 0.02}}},
            {"drive", {{"I_M", 1.2}, {"gear_stiffness", 3e4}, {"torque_rated", 30}, {"torque_peak", 80}}},
            {"sample_time", 1e-3},
            {"delays", {{"input", 1}, {"output", 2}}}};
}

std::string error_of(const json& j)
{
    try {
        arm_from_json(j);
    } catch (const ArmDocumentError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ArmDocument, every_bad_field_is_refused_naming_field_value_and_range)
{
    struct Case {
        const char* path;
        json value;
        const char* expect;
    };
    const Case cases[] = {
        {"/link/length", -0.7, "arm: field 'link.length': value -0.7 out of range: allowed (0, 100] m"},
        {"/link/material/E", "steel", "arm: field 'link.material.E': value \"steel\" is not a number"},
        {"/link/section/width", 0.0, "arm: field 'link.section.width': value 0 out of range: allowed (0, 10] m"},
        {"/payload/mass", -1.0, "arm: field 'payload.mass': value -1 out of range: allowed [0, 100000] kg"},
        {"/hub/inertia", 0.0, "arm: field 'hub.inertia': value 0 out of range"},
        {"/drive/torque_peak", 10.0, "arm: field 'drive.torque_peak': value 10 out of range: allowed [30, 1e+06]"},
        {"/sample_time", 1.0, "arm: field 'sample_time': value 1 out of range: allowed [1e-05, 0.1] s"},
        {"/delays/input", 3000000000LL, "arm: field 'delays.input': value 3000000000 out of range: allowed integer in [0, 40]"},
        {"/delays/output", 1.5, "arm: field 'delays.output': value 1.5 is not an integer"},
        {"/design", json{{"N", 201}}, "arm: field 'design.N': value 201 out of range: allowed integer in [4, 200]"},
        {"/design", json{{"N", 3000000000LL}}, "arm: field 'design.N': value 3000000000 out of range"},
        {"/design", json{{"bandwidth_hz", 600.0}}, "arm: field 'design.bandwidth_hz': value 600 out of range: allowed (0, 500)"},
        {"/sensors", json{{"imu_position", 0.8}}, "arm: field 'sensors.imu_position': value 0.8 out of range: allowed (0, 0.7] m"},
        {"/link/model", "bernoulli", "arm: field 'link.model': value \"bernoulli\": allowed \"timoshenko\", \"euler-bernoulli\""},
        {"/drive/gear_stifness", 1.0, "arm: field 'drive.gear_stifness': is not a field of this section"},
        {"/schema", "frac.model", "arm: field 'schema': value \"frac.model\": allowed \"frac.arm\""},
    };
    for (const Case& c : cases) {
        json j = alu_doc();
        j[json::json_pointer(c.path)] = c.value;
        const std::string e = error_of(j);
        EXPECT_NE(e.find(c.expect), std::string::npos) << c.path << ": " << e;
    }
    json j = alu_doc();
    j["link"].erase("length");
    EXPECT_NE(error_of(j).find("'link.length': is missing"), std::string::npos);
    j = alu_doc();
    j["link"]["per_length"] = {{"EI", 1.0}, {"GA", 1e6}, {"rhoA", 1.0}, {"rhoI", 1e-6}};
    EXPECT_NE(error_of(j).find("not both"), std::string::npos);
}

TEST(ArmDocument, round_trips_through_its_per_length_form)
{
    const ArmDocument a = arm_from_json(alu_doc());
    const ArmDocument b = arm_from_json(arm_to_json(a));
    EXPECT_DOUBLE_EQ(a.beam.K_b, b.beam.K_b);
    EXPECT_DOUBLE_EQ(a.beam.K_s, b.beam.K_s);
    EXPECT_DOUBLE_EQ(a.mount_k_w, b.mount_k_w);
    EXPECT_EQ(a.dout, b.dout);
    // E I = E w t^3 / 12, kappa G A with G = E / (2 (1 + nu)), kappa 5/6
    EXPECT_NEAR(a.beam.K_b, 70e9 * 0.05 * std::pow(0.004, 3) / 12.0, 1e-9);
    EXPECT_NEAR(a.beam.K_s, 5.0 / 6.0 * 70e9 / 2.66 * 0.05 * 0.004, 1e-3);
}

TEST(ArmDocument, tip_rate_reconstruction_equals_the_port_output_and_integrates_the_angle)
{
    const ArmDocument a = arm_from_json(alu_doc());
    const ArmBuild b = build_arm_from_document(a, 10, false, {});
    EXPECT_EQ(b.arm.J.rows(), 4 + 40 + 4);
    const StateSpace m = arm_document_measured(a, b);
    const Eigen::RowVectorXd rate = arm_rate_row(b, a.beam.L);
    EXPECT_LT((rate - m.C.row(2)).cwiseAbs().maxCoeff(), 1e-9 * m.C.row(2).cwiseAbs().maxCoeff());
    for (double z : {0.2, 0.45, 0.7}) {
        const Eigen::RowVectorXd d = arm_angle_row(b, z) * b.arm.A() - arm_rate_row(b, z);
        EXPECT_LT(d.cwiseAbs().maxCoeff(), 1e-8 * (arm_rate_row(b, z).cwiseAbs().maxCoeff() + 1.0)) << z;
    }
}

TEST(ArmDocument, payload_lowers_the_first_mode_as_a_lumped_tip_mass_does)
{
    // Rayleigh: a clamped-free beam with a tip mass m has w1^2 ~ 3 EI / (L^3 (m + 0.2357 rho A L)).
    json j = alu_doc();
    j["payload"] = {{"mass", 0.4}, {"inertia", 0}};
    j["hub"]["inertia"] = 1e3;  // hub nearly clamped by a huge inertia
    j["drive"]["I_M"] = 1e3;
    j["drive"]["gear_stiffness"] = 1e10;
    const ArmDocument a = arm_from_json(j);
    const ArmBuild b = build_arm_from_document(a, 10, false, {});
    const double f1 = b.arm.state_space().natural_frequencies_hz(1e-3).front();
    const double L = a.beam.L, EI = a.beam.K_b, rA = a.beam.rho;
    const double f_rayleigh = std::sqrt(3.0 * EI / (L * L * L * (0.4 + 0.2357 * rA * L))) / (2.0 * M_PI);
    EXPECT_NEAR(f1, f_rayleigh, 0.02 * f_rayleigh);
}

TEST(ArmDocument, euler_bernoulli_limit_matches_the_clamped_free_roots)
{
    json j = alu_doc();
    j["link"]["model"] = "euler-bernoulli";
    const ArmDocument a = arm_from_json(j);
    const PsBeam b = build_ps_beam(a.beam, 14);
    const auto f = clamped_free_frequencies_hz(b, 2);
    const double c = std::sqrt(a.beam.K_b / a.beam.rho) / (a.beam.L * a.beam.L) / (2.0 * M_PI);
    EXPECT_NEAR(f[0], 1.875104068711961 * 1.875104068711961 * c, 1e-4 * f[0]);
    // shear-rigid limit: relative error about (beta_i L)^2 / (2 kEbShear), 1.1e-4 for the second mode
    EXPECT_NEAR(f[1], 4.694091132974175 * 4.694091132974175 * c, 3e-4 * f[1]);
}

TEST(ArmDesign, reduction_keeps_the_modes_below_the_bandwidth_and_refuses_a_tight_bound)
{
    const ArmDocument a = arm_from_json(alu_doc());
    const design::ArmReduction r = design::choose_reduction(a);
    ASSERT_GE(r.retained.size(), 2u);
    EXPECT_LE(r.max_error_below_bandwidth, a.design.mode_error_max);
    EXPECT_DOUBLE_EQ(r.bandwidth_hz, r.full_hz.front());
    EXPECT_EQ(r.shifts.size(), r.beam_modes_rad_s.size() + 1);
    EXPECT_EQ(r.reduced_states, 4 + 4 * static_cast<int>(r.shifts.size()) + 4);
    // a bound below the error actually reached on the first mode must be refused
    json j = alu_doc();
    j["design"] = {{"mode_error_max", std::max(1e-12, 0.5 * r.max_error_below_bandwidth)}};
    EXPECT_THROW(design::choose_reduction(arm_from_json(j)), design::ArmDesignError);
}

TEST(ArmDesign, lqg_from_the_document_is_stable_on_the_unreduced_arm_with_its_delays)
{
    const ArmDocument a = arm_from_json(alu_doc());
    const design::ArmLqg r = design::design_arm_lqg(a);
    EXPECT_EQ(r.check_unreduced.plant_di, a.di);
    EXPECT_EQ(r.check_unreduced.plant_do, a.dout);
    EXPECT_EQ(r.check_unreduced.plant_states, static_cast<int>(r.full.nx()) + a.di + a.dout);
    EXPECT_LT(r.check_unreduced.spectral_radius, 1.0);
    EXPECT_GT(r.check_unreduced.gain_margin_db, 0.0);
    // the default rule scales Table 8.8 by (tau_rated / 95.7)^2
    EXPECT_DOUBLE_EQ(r.lqg.params.q_low, 5e3 * std::pow(30.0 / design::kWangRatedTorque, 2));
}

TEST(ArmDesign, seed_arm_document_gives_the_thesis_sizes_and_shifts_near_table_8_4)
{
    const ArmDocument a = read_arm_file(std::string(FRAC_SOURCE_DIR) + "/docs/examples/arm_wang/arm.json");
    const design::ArmReduction r = design::choose_reduction(a);
    EXPECT_EQ(r.full_states, 40);
    EXPECT_EQ(r.reduced_states, 16);  // n = 16 (Table 8.4: r = 12)
    ASSERT_EQ(r.shifts.size(), 3u);
    EXPECT_NEAR(r.shifts[1], 18.43, 0.02);  // Table 8.4's 18.43 and 115.6 rad/s, to 0.1 %
    EXPECT_NEAR(r.shifts[2], 115.6, 0.12);
    EXPECT_NEAR(r.full_hz.front(), 3.096, 1e-3);  // notes 004a R16
}

TEST(ArmDesign, move_segments_chain_and_a_bad_spec_is_refused)
{
    const design::Move m = design::Move::parse("0:1.0@0.5+1.5,0.2@2.5+1.0");
    EXPECT_DOUBLE_EQ(m.t_start(), 0.5);
    EXPECT_DOUBLE_EQ(m.t_end(), 3.5);
    EXPECT_NEAR(m.eval(2.0)[0], 1.0, 1e-12);
    EXPECT_NEAR(m.eval(4.0)[0], 0.2, 1e-12);
    EXPECT_NEAR(m.eval(1.25)[1], 1.5 / 1.5, 1e-9);  // cruise qd_m = 1.5 s_e / duration
    EXPECT_THROW(design::Move::parse("0:1.0@0.5+1.5,0.2@1.0+1.0"), std::invalid_argument);  // overlap
    EXPECT_THROW(design::Move::parse("0:1.0@0.5"), std::invalid_argument);
    EXPECT_THROW(design::Move::parse("0:x@0.5+1"), std::invalid_argument);
}

TEST(ArmDesign, csv_tip_reference_gives_the_derivatives_of_the_sampled_move)
{
    // the sin^2 move sampled at 1e-4 s into a CSV: q and its first two derivatives come back
    const design::Move ref = design::Move::parse("0.2:1.2@0.5+1.5");
    const std::string path = std::string(FRAC_BINARY_DIR) + "/test_arm_move.csv";
    {
        std::ofstream f(path);
        f.precision(17);
        f << "t,q\n";
        for (int k = 0; k <= 25000; ++k) f << k * 1e-4 << "," << ref.eval(k * 1e-4)[0] << "\n";
    }
    const design::Move m = design::Move::from_csv(path);
    EXPECT_DOUBLE_EQ(m.q_start(), 0.2);
    for (double t : {0.3, 0.62, 1.0, 1.37, 1.9}) {
        const auto a = m.eval(t), b = ref.eval(t);
        EXPECT_NEAR(a[0], b[0], 1e-9) << t;
        EXPECT_NEAR(a[1], b[1], 1e-6) << t;
        EXPECT_NEAR(a[2], b[2], 1e-3 * 9.0 / 2.25) << t;  // qdd_m = 9 s_e / duration^2
    }
    std::ofstream(path) << "t,angle\n0,0\n1,1\n";
    EXPECT_THROW(design::Move::from_csv(path), std::invalid_argument);
}
