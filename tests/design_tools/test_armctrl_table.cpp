// `fracdesign armctrl`: the ArmCtrl parameter tables of seed 004 Exp. A-D are read back by the
// PLC's own code (libfrac's frac_ptable_open and plc_blocks' armctrl_params_from_table) with the
// values of the design, bit for bit in float64; the LQG entries drive frac_lqg_step exactly like
// the design's dense predictor; bad requests are refused with a message naming the option.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "ArmCtrl.h"
#include "frac/lqg.h"
#include "frac/ptable.h"
#include "fracdesign/design/arm_design.hpp"
#include "fracdesign/design/armctrl.hpp"
#include "fracdesign/tables/ptable.hpp"
#include <nlohmann/json.hpp>
#include "run_command.hpp"

// design_tools may not include plc_blocks, so arm_design.hpp states the PLC
// program's LQG state capacity itself; this is where the two meet.
static_assert(fracdesign::design::kArmctrlLqgNmax == ARMCTRL_LQG_NMAX,
              "arm_design.hpp's kArmctrlLqgNmax must equal ArmCtrl.h's ARMCTRL_LQG_NMAX");

using namespace fracdesign;

namespace {

std::string run(const std::string& cmd, int* status) { return run_command(cmd, status); }

std::string tmpdir()
{
    static std::string dir;
    if (dir.empty()) {
        char tmpl[] = "/tmp/frac_armctrl_XXXXXX";
        const char* d = mkdtemp(tmpl);
        dir = d ? d : "/tmp";
    }
    return dir;
}

std::vector<std::uint8_t> read_bytes(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// One design per experiment, shared by the tests (the design takes about a second).
const design::ArmctrlDesign& designed(char exp)
{
    static std::map<char, std::unique_ptr<design::ArmctrlDesign>> cache;
    auto& d = cache[exp];
    if (!d) {
        design::ArmctrlSpec s;
        s.exp = exp;
        d = std::make_unique<design::ArmctrlDesign>(design::design_armctrl(s));
    }
    return *d;
}

// The CLI's binary table of one experiment (cached per experiment).
const std::vector<std::uint8_t>& emitted(char exp)
{
    static std::map<char, std::vector<std::uint8_t>> cache;
    auto& b = cache[exp];
    if (b.empty()) {
        const std::string out = tmpdir() + "/exp" + exp + ".bin";
        int st = -1;
        const std::string log =
            run(std::string(FRACDESIGN_EXE) + " armctrl --exp " + exp + " --format bin --out " + out, &st);
        EXPECT_EQ(st, 0) << log;
        b = read_bytes(out);
    }
    return b;
}

class ArmctrlTable : public ::testing::TestWithParam<char> {};

TEST_P(ArmctrlTable, LibfracReadsTheDesignBitForBit)
{
    const char exp = GetParam();
    const auto& d = designed(exp);
    const auto& bytes = emitted(exp);
    ASSERT_FALSE(bytes.empty());
    frac_ptable pt;
    ASSERT_EQ(frac_ptable_open(&pt, bytes.data(), static_cast<unsigned long>(bytes.size())), FRAC_OK);
    ASSERT_EQ(pt.n_entries, d.table.entries.size());
    for (const auto& e : d.table.entries) {
        std::vector<frac_real> v(e.values.size());
        ASSERT_EQ(frac_ptable_get(&pt, e.name.c_str(), e.rows, e.cols, v.data()), FRAC_OK) << e.name;
        for (size_t k = 0; k < v.size(); ++k)
            ASSERT_TRUE(same_bits(v[k], e.values[k])) << e.name << "[" << k << "]: " << v[k] << " vs " << e.values[k];
    }
    // The order and names of ArmCtrl.h.
    std::vector<std::string> names = {"variant", "ts", "ff", "ff_grid", "ff_lead", "torque_limit", "watchdog"};
    if (exp <= 'B') {
        names.insert(names.end(), {"pd", "friction"});
    } else {
        names.insert(names.end(), {"lqg_dims", "A", "B", "C", "K", "L"});
    }
    ASSERT_EQ(names.size(), d.table.entries.size());
    for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(d.table.entries[i].name, names[i]);
}

TEST_P(ArmctrlTable, ArmCtrlReaderFillsItsParametersFromTheTable)
{
    const char exp = GetParam();
    const auto& d = designed(exp);
    const auto& bytes = emitted(exp);
    frac_ptable pt;
    ASSERT_EQ(frac_ptable_open(&pt, bytes.data(), static_cast<unsigned long>(bytes.size())), FRAC_OK);
    static armctrl_table_storage s;
    ASSERT_EQ(armctrl_params_from_table(&s, &pt), FRAC_OK);
    const armctrl_params& p = s.par;
    EXPECT_EQ(static_cast<int>(p.Variant), exp - 'A');
    EXPECT_EQ(p.CycleTime, static_cast<REAL>(1.2e-3));
    const size_t n = d.ff[0].size();
    ASSERT_EQ(p.Ff.Channels, static_cast<decltype(p.Ff.Channels)>(ARMCTRL_FF_N));
    ASSERT_EQ(p.Ff.N, n);
    ASSERT_LE(n, static_cast<size_t>(ARMCTRL_FF_MAX));
    for (int c = 0; c < ARMCTRL_FF_N; ++c)
        for (size_t k = 0; k < n; ++k) ASSERT_TRUE(same_bits(p.Ff.pData[c][k], d.ff[c][k])) << c << "," << k;
    EXPECT_TRUE(same_bits(p.Ff.T0, d.t0));
    EXPECT_TRUE(same_bits(p.Ff.Dt, d.dt));
    EXPECT_TRUE(same_bits(p.Ff.TMotionStart, 0.5));  // Table 8.5
    EXPECT_TRUE(same_bits(p.Ff.TMotionEnd, 2.0));
    const long lead_d[4] = {0, 0, -3, 4};  // Sec. 8.6, Table 8.8
    for (int c = 0; c < 4; ++c) EXPECT_EQ(p.Ff.Lead[c], exp == 'D' ? lead_d[c] : 0) << c;
    EXPECT_EQ(p.TorqueLimit, static_cast<REAL>(d.spec.torque_limit));
    EXPECT_GE(p.WdDrive.MaxStaleCycles, 1u);
    if (exp <= 'B') {
        EXPECT_EQ(p.Kp, static_cast<REAL>(320.0));  // Table 8.6
        EXPECT_EQ(p.Kd, static_cast<REAL>(200.0));
        EXPECT_EQ(p.Friction.B1, static_cast<REAL>(3.04));
        EXPECT_EQ(p.Friction.B0, static_cast<REAL>(7.684));
        EXPECT_EQ(p.Friction.K, static_cast<REAL>(60.0));
        return;
    }
    ASSERT_TRUE(d.lqg.has_value());
    const long nx = d.A.rows(), nb = d.K.cols();
    EXPECT_EQ(nx, 16);  // 4 drive + 12 reduced beam states (notes 004b 6.3)
    EXPECT_EQ(nb, exp == 'D' ? 23 : 16);
    EXPECT_EQ(p.Lqg.N, static_cast<UDINT>(nx));
    EXPECT_EQ(p.Lqg.Di, exp == 'D' ? 4u : 0u);
    EXPECT_EQ(p.Lqg.Do[0], 0u);
    EXPECT_EQ(p.Lqg.Do[1], 0u);
    EXPECT_EQ(p.Lqg.Do[2], exp == 'D' ? 3u : 0u);
    for (long i = 0; i < nx; ++i) {
        for (long j = 0; j < nx; ++j) ASSERT_TRUE(same_bits(p.Lqg.pA[i * nx + j], d.A(i, j)));
        ASSERT_TRUE(same_bits(p.Lqg.pB[i], d.B(i, 0)));
        for (long r = 0; r < 3; ++r) ASSERT_TRUE(same_bits(p.Lqg.pC[r * nx + i], d.C(r, i)));
    }
    for (long j = 0; j < nb; ++j) ASSERT_TRUE(same_bits(p.Lqg.pK[j], d.K(0, j)));
    for (long i = 0; i <= nb; ++i)
        for (long r = 0; r < 3; ++r) ASSERT_TRUE(same_bits(p.Lqg.pL[i * 3 + r], d.L(i, r)));
    // The same gains as `fracdesign lqg --exp C|D` writes (its design document, JSON doubles
    // round-trip exactly).
    const std::string doc = tmpdir() + "/lqg_" + exp + ".json";
    int st = -1;
    const std::string log = run(std::string(FRACDESIGN_EXE) + " lqg --exp " + exp + " --out " + doc, &st);
    ASSERT_EQ(st, 0) << log;
    std::ifstream jf(doc);
    const auto ref = nlohmann::json::parse(jf);
    ASSERT_EQ(ref["K"][0].size(), static_cast<size_t>(nb));
    ASSERT_EQ(ref["Le"].size(), static_cast<size_t>(nb + 1));
    for (long j = 0; j < nb; ++j) EXPECT_TRUE(same_bits(ref["K"][0][j].get<double>(), d.K(0, j))) << j;
    for (long i = 0; i <= nb; ++i)
        for (long r = 0; r < 3; ++r) EXPECT_TRUE(same_bits(ref["Le"][i][r].get<double>(), d.L(i, r))) << i << "," << r;
}

// frac_lqg_step with the table's A', B', C', K, L computes what the design's dense predictor
// (A_e, B_e, C_e, L_e of (7.26)-(7.27)) computes: the matrices are in libfrac's convention.
TEST_P(ArmctrlTable, LqgEntriesDriveFracLqgLikeTheDesign)
{
    const char exp = GetParam();
    const auto& d = designed(exp);
    if (exp <= 'B') {  // PD variants carry no LQG entries
        EXPECT_FALSE(d.lqg.has_value());
        EXPECT_THROW(d.table.at("K"), tables::TableError);
        return;
    }
    const auto& g = *d.lqg;
    const long nx = d.A.rows(), nb = d.K.cols(), ne = nb + 1;
    std::vector<frac_real> A(d.A.size()), B(nx), C(3 * nx), K(nb), L(ne * 3);
    for (long i = 0; i < nx; ++i) {
        for (long j = 0; j < nx; ++j) A[i * nx + j] = d.A(i, j);
        B[i] = d.B(i, 0);
        for (long r = 0; r < 3; ++r) C[r * nx + i] = d.C(r, i);
    }
    for (long j = 0; j < nb; ++j) K[j] = d.K(0, j);
    for (long i = 0; i < ne; ++i)
        for (long r = 0; r < 3; ++r) L[i * 3 + r] = d.L(i, r);
    const size_t d_o[3] = {0, 0, static_cast<size_t>(d.spec.dout)};
    frac_lqg_params prm{static_cast<size_t>(nx), static_cast<size_t>(d.spec.di), 3, d_o, A.data(), B.data(),
                        C.data(), K.data(), L.data()};
    frac_lqg c;
    std::vector<frac_real> storage(FRAC_LQG_STORAGE(ne, 3));
    ASSERT_EQ(frac_lqg_init(&c, &prm, storage.data(), storage.size()), FRAC_OK);
    std::mt19937 rng(7);
    std::normal_distribution<double> n01(0.0, 1.0);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(ne);
    double worst = 0.0;
    for (int k = 0; k < 200; ++k) {
        const double ustar = 5.0 * n01(rng);
        frac_real yref[3], y[3], u;
        Eigen::Vector3d ey;
        for (int j = 0; j < 3; ++j) {
            yref[j] = 0.1 * n01(rng);
            y[j] = 0.1 * n01(rng);
            ey(j) = yref[j] - y[j];
        }
        ASSERT_EQ(frac_lqg_step(&c, ustar, yref, y, &u), FRAC_OK);
        const double fb = (g.K * e.head(nb))(0) - e(nb);  // (7.21)
        const Eigen::VectorXd eu = Eigen::VectorXd::Constant(1, -fb);
        e = g.Ae * e + g.Be * eu + g.Le * (ey - g.Ce * e);  // (7.27)
        worst = std::max(worst, std::fabs(u - (ustar + fb)) / (1.0 + std::fabs(ustar + fb)));
    }
    EXPECT_LT(worst, 1e-9);
}

// The feedforward starts at rest before the motion; Exp. B-D hold the pre-actuation of the
// stable inversion (torque before the nominal start at 0.5 s) and the model tracks the tip rate.
TEST_P(ArmctrlTable, FeedforwardStartsAtRestWithPreActuation)
{
    const char exp = GetParam();
    const auto& d = designed(exp);
    const size_t n = d.ff[0].size();
    EXPECT_LT(d.t0, d.t_motion_start);
    EXPECT_LE(d.t0, 0.0);
    for (int c = 0; c < 3; ++c) EXPECT_LT(std::fabs(d.ff[c][0]), 1e-6) << "row " << c << " not at rest at sample 0";
    EXPECT_LE(std::fabs(d.ff[3][0]), design::kArmctrlRestTol * d.tau_max) << "torque not at rest at sample 0";
    EXPECT_LE(d.start_tau, design::kArmctrlRestTol * d.tau_max);
    // reaches q_e = pi/2 and rests at the end
    EXPECT_NEAR(d.ff[2][n - 1], 0.0, 1e-9);
    EXPECT_NEAR(d.ff[0][n - 1], 1.5707963267948966, 1e-3);
    EXPECT_LT(d.tail_step, 1e-4);
    double pre = 0.0;
    for (size_t k = 0; k < n; ++k)
        if (d.t0 + k * d.dt < d.t_motion_start) pre = std::max(pre, std::fabs(d.ff[3][k]));
    if (exp == 'A') {
        EXPECT_EQ(pre, 0.0);  // the rigid-body feedforward starts with the motion
    } else {
        EXPECT_GT(pre, 1e-3 * d.tau_max) << "no pre-actuation in the table";
        EXPECT_LT(d.pre_actuation_start, d.t_motion_start);
        ASSERT_TRUE(d.ibffc.has_value());
        EXPECT_LT(d.ibffc->rel_rms, 1e-6);
    }
}

TEST_P(ArmctrlTable, EmittedTablePassesTableCheck)
{
    const char exp = GetParam();
    emitted(exp);
    int st = -1;
    const std::string out =
        run(std::string(FRACDESIGN_EXE) + " table check " + tmpdir() + "/exp" + exp + ".bin", &st);
    EXPECT_EQ(st, 0) << out;
    EXPECT_NE(out.find("valid FRPT"), std::string::npos) << out;
    EXPECT_NE(out.find("'armctrl'"), std::string::npos) << out;
}

INSTANTIATE_TEST_SUITE_P(ExpAtoD, ArmctrlTable, ::testing::Values('A', 'B', 'C', 'D'));

TEST(ArmctrlCli, OtherFormatsAndFloat32)
{
    int st = -1;
    const std::string dir = tmpdir();
    for (const char* f : {"json", "c", "var"}) {
        const std::string out = run(std::string(FRACDESIGN_EXE) + " armctrl --exp A --format " + f + " --out " + dir +
                                        "/a." + f, &st);
        EXPECT_EQ(st, 0) << out;
    }
    std::ifstream j(dir + "/a.json");
    const auto doc = nlohmann::json::parse(j);
    const auto t = tables::table_from_json(doc);
    EXPECT_EQ(t.name, "armctrl");
    const std::string out =
        run(std::string(FRACDESIGN_EXE) + " armctrl --exp A --real float32 --out " + dir + "/a32.bin", &st);
    EXPECT_EQ(st, 0) << out;
    const auto b = read_bytes(dir + "/a32.bin");
    frac_ptable pt;
    ASSERT_EQ(frac_ptable_open(&pt, b.data(), static_cast<unsigned long>(b.size())), FRAC_OK);
    EXPECT_EQ(pt.elem_type, static_cast<unsigned>(FRAC_PTABLE_F32));
    static armctrl_table_storage s;
    EXPECT_EQ(armctrl_params_from_table(&s, &pt), FRAC_OK);
}

TEST(ArmctrlCli, BadRequestsAreRefusedNamingTheOption)
{
    struct Case {
        const char* args;
        const char* says;
    } cases[] = {
        {"--exp E", "--exp"},
        {"", "exp"},
        {"--exp D --di -1", "--di"},
        {"--exp D --do -2", "--do"},
        {"--exp C --di 4", "Exp. C has no delay model"},
        {"--exp B --N 4", "--N"},
        {"--exp B --N 100", "--N"},
        {"--exp A --format xml", "--format"},
        {"--exp A --real float16", "--real"},
        {"--exp D --di 60", "--di"},
        {"--exp D --di 40 --do 8", "FRAC_MAT_MAX"},
    };
    for (const auto& c : cases) {
        int st = -1;
        const std::string out =
            run(std::string(FRACDESIGN_EXE) + " armctrl " + c.args + " --out " + tmpdir() + "/bad.bin", &st);
        EXPECT_NE(st, 0) << c.args;
        EXPECT_NE(out.find(c.says), std::string::npos) << c.args << ": " << out;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << "one clear message: " << out;
    }
    EXPECT_THROW(
        [] {
            design::ArmctrlSpec s;
            s.exp = 'Q';
            design::design_armctrl(s);
        }(),
        std::invalid_argument);
}

}  // namespace

namespace {

TEST(ArmctrlDesign, FeedforwardCapacityIsArmCtrlsFfMax)
{
    // The table fills ArmCtrl's storage exactly up to ARMCTRL_FF_MAX samples and refuses one more.
    design::ArmctrlSpec s;
    s.exp = 'A';
    s.post = (ARMCTRL_FF_MAX - 1) * s.T - 2.0 - 1e-7;
    EXPECT_EQ(design::design_armctrl(s).ff[0].size(), static_cast<size_t>(ARMCTRL_FF_MAX));
    s.post = ARMCTRL_FF_MAX * s.T - 2.0 - 1e-7;
    EXPECT_THROW(design::design_armctrl(s), std::invalid_argument);
}

}  // namespace
