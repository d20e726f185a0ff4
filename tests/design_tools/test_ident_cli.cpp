// Tests of `fracdesign ident` end to end: files in, JSON out, bad input and
// non-converged fits reported with the right exit status.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fracdesign/ident/haro_synthetic.hpp"
#include "fracdesign/ident/time_domain.hpp"
#include "fracdesign/io/frf_csv.hpp"
#include "fracdesign/io/signal_csv.hpp"

using namespace fracdesign;

namespace {

const std::string kDir = FRAC_BINARY_DIR;

struct CliRun {
    int rc;
    std::string out, err;
};

CliRun run(const std::string& args)
{
    const std::string o = kDir + "/test_ident_cli.out", e = kDir + "/test_ident_cli.err";
    const int st = std::system((std::string(FRACDESIGN_EXE) + " ident " + args + " >" + o + " 2>" + e).c_str());
    auto slurp = [](const std::string& p) {
        std::ifstream f(p);
        std::stringstream ss;
        ss << f.rdbuf();
        return ss.str();
    };
    return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, slurp(o), slurp(e)};
}

std::string write_vi_frf()
{
    std::vector<double> w;
    const auto g = ident::haro_grid(94, 8000);
    for (std::size_t i = 0; i < g.size(); i += 16) w.push_back(g[i]);
    const ident::Frf f = ident::haro_synthetic_frf({7.1e-5, 0.996, 0.055, 0.594}, w, 0.0, 1);
    const std::string path = kDir + "/test_ident_cli_frf.csv";
    io::write_frf_csv(path, {f.w, f.G});
    return path;
}

std::string write_process_csv(bool with_nan)
{
    const double th[4] = {1.0, 1.0 / (5.8434 * 5.8434), 1.92, 0.1613};
    const double h = 0.01;
    io::SignalTable t;
    t.names = {"u", "y"};
    std::vector<double> u(500, 1.0);
    const auto y = ident::simulate_fo_process(th, u, h);
    for (std::size_t k = 0; k < u.size(); ++k) t.t.push_back(k * h);
    t.columns = {u, y};
    const std::string path = kDir + "/test_ident_cli_process.csv";
    std::string text = io::format_signal_csv(t);
    if (with_nan) {  // the time stamp of data row 2 (file row 3)
        const std::size_t b = text.find("\n", text.find("\n") + 1) + 1;
        text.replace(b, text.find(',', b) - b, "nan");
    }
    std::ofstream(path) << text;
    return path;
}

}  // namespace

TEST(IdentCli, frf_fit_recovers_type_vi_as_json)
{
    const CliRun r = run("frf --frf " + write_vi_frf() + " --structure VI --weighting 1/w --starts 3 --json");
    ASSERT_EQ(r.rc, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["schema"], "frac.ident.frf");
    ASSERT_EQ(j["fits"].size(), 1u);
    EXPECT_NEAR(j["fits"][0]["params"]["lambda"].get<double>(), 0.594, 1e-6);
    EXPECT_NEAR(j["fits"][0]["params"]["zeta"].get<double>(), 7.1e-5, 1e-10);
    EXPECT_TRUE(j["fits"][0]["converged"].get<bool>());
}

TEST(IdentCli, non_converged_fit_exits_3_with_the_ceres_report)
{
    const CliRun r = run("frf --frf " + write_vi_frf() + " --structure VI --weighting const --starts 1 --max-iter 1");
    EXPECT_EQ(r.rc, 3);
    EXPECT_NE(r.err.find("did NOT converge"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("Termination"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("NOT CONVERGED"), std::string::npos) << r.out;
}

TEST(IdentCli, process_fit_from_step_csv)
{
    const CliRun r = run("process --csv " + write_process_csv(false) + " --init 0.8,0.05,1.7,0.12 --json");
    ASSERT_EQ(r.rc, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(j["lambda"].get<double>(), 1.92, 1e-6);
    EXPECT_NEAR(j["tau"].get<double>(), 0.1613, 1e-6);
}

TEST(IdentCli, nan_in_csv_is_refused_naming_row_and_column)
{
    const CliRun r = run("process --csv " + write_process_csv(true));
    EXPECT_EQ(r.rc, 1);
    EXPECT_NE(r.err.find("row 3, column 't'"), std::string::npos) << r.err;
}

TEST(IdentCli, servo_idim_on_emps_and_usage_errors)
{
    const std::string mat = std::string(FRAC_SHARED_DIR) + "/data/real/emps/DATA_EMPS.mat";
    const CliRun r = run("servo --mat " + mat + " --method idim --json");
    ASSERT_EQ(r.rc, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(j["idim"]["theta"][0].get<double>(), 95.1089, 0.02 * 95.1089);
    EXPECT_EQ(run("servo").rc, 2);
    EXPECT_EQ(run("frf --frf x.csv --weighting log").rc, 2);
    EXPECT_EQ(run("bogus").rc, 2);
    EXPECT_EQ(run("servo --mat " + mat + " --method oe").rc, 2);  // oe alone needs --init
}

TEST(IdentCli, frf_from_time_data_goes_through_welch)
{
    // y = 0.5 x: a flat FRF of 0.5 the antenna model cannot follow; the point
    // is the time-data path (Welch grid, wmin/wmax band), not the fit quality.
    io::SignalTable t;
    t.names = {"theta_m", "torque"};
    std::vector<double> x(4000), y(4000);
    for (std::size_t k = 0; k < x.size(); ++k) {
        t.t.push_back(k * 1e-3);
        x[k] = std::sin(0.37 * k) + std::sin(0.011 * k * k * 1e-3);
        y[k] = 0.5 * x[k];
    }
    t.columns = {x, y};
    const std::string path = kDir + "/test_ident_cli_time.csv";
    io::write_signal_csv(path, t);
    const CliRun r = run("frf --time " + path + " --structure I --weighting 1/w --starts 1 --wmax 300 --json");
    ASSERT_NE(r.out.find("frac.ident.frf"), std::string::npos) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    // 8 segments of floor(4000/(8 - 7*0.15)) = 575 samples: bins 1..27 lie below 300 rad/s
    EXPECT_EQ(j["points"].get<int>(), int(std::floor(300.0 / (2 * M_PI * 1000.0 / 575))));
    EXPECT_EQ(run("frf --time " + path + " --frf x.csv").rc, 2);
}
