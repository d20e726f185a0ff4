// Tests of the strict signal CSV reader/writer (fracdesign/io/signal_csv.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "fracdesign/io/frf_csv.hpp"
#include "fracdesign/io/signal_csv.hpp"

using fracdesign::io::parse_signal_csv;
using fracdesign::io::SignalCsvError;
using fracdesign::io::SignalTable;

namespace {

std::string error_of(const std::string& text)
{
    try {
        parse_signal_csv(text, "x.csv");
    } catch (const SignalCsvError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(SignalCsv, reads_header_time_and_columns)
{
    const SignalTable t = parse_signal_csv("t,u,y\n0,1,2\n0.5,3,4\n1.0,5,6\n", "x.csv");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t.names, (std::vector<std::string>{"u", "y"}));
    EXPECT_DOUBLE_EQ(t.dt, 0.5);
    EXPECT_DOUBLE_EQ(t.column("y")[2], 6.0);
}

TEST(SignalCsv, accepts_t_s_header_and_crlf_and_blank_lines)
{
    const SignalTable t = parse_signal_csv("t_s,u\r\n0,1\r\n\r\n0.001,2\r\n", "x.csv");
    EXPECT_EQ(t.size(), 2u);
    EXPECT_DOUBLE_EQ(t.column("u")[1], 2.0);
}

TEST(SignalCsv, refuses_non_uniform_time_naming_row)
{
    const std::string m = error_of("t,u\n0,1\n0.001,1\n0.003,1\n0.004,1\n");
    EXPECT_NE(m.find("non-uniform time step"), std::string::npos) << m;
    EXPECT_NE(m.find("row 4"), std::string::npos) << m;
}

TEST(SignalCsv, accepts_small_jitter_like_the_emps_records)
{
    EXPECT_NO_THROW(parse_signal_csv("t,u\n0,1\n0.00100002,1\n0.00199999,1\n0.003,1\n", "x.csv"));
}

TEST(SignalCsv, refuses_decreasing_time)
{
    EXPECT_NE(error_of("t,u\n0,1\n0.001,1\n0.001,1\n").find("time not increasing"), std::string::npos);
}

TEST(SignalCsv, refuses_nan_naming_row_and_column)
{
    const std::string m = error_of("t,u,y\n0,1,2\n1,nan,3\n");
    EXPECT_NE(m.find("row 3, column 'u'"), std::string::npos) << m;
    EXPECT_NE(m.find("non-finite"), std::string::npos) << m;
}

// A subnormal cell (strtod sets ERANGE on the underflow) is a finite value;
// an overflowing one is not (found on a gap-bench arm record, case 29 of seed 1).
TEST(SignalCsv, reads_a_subnormal_value_and_refuses_an_overflowing_one)
{
    const SignalTable t = parse_signal_csv("t,u\n0,-1.32005925e-311\n1,1e-320\n", "x.csv");
    EXPECT_DOUBLE_EQ(t.column("u")[0], -1.32005925e-311);
    EXPECT_GT(t.column("u")[1], 0.0);
    const std::string m = error_of("t,u\n0,1\n1,-1e400\n");
    EXPECT_NE(m.find("row 3, column 'u'"), std::string::npos) << m;
    EXPECT_NE(m.find("non-finite"), std::string::npos) << m;
}

TEST(SignalCsv, refuses_ragged_row)
{
    const std::string m = error_of("t,u,y\n0,1,2\n1,3\n");
    EXPECT_NE(m.find("row 3"), std::string::npos) << m;
    EXPECT_NE(m.find("ragged"), std::string::npos) << m;
}

TEST(SignalCsv, refuses_empty_cell_and_text)
{
    EXPECT_NE(error_of("t,u\n0,\n1,2\n").find("missing value"), std::string::npos);
    EXPECT_NE(error_of("t,u\n0,abc\n1,2\n").find("not a number: 'abc'"), std::string::npos);
}

TEST(SignalCsv, refuses_time_in_other_units)
{
    const std::string m = error_of("t_ms,u\n0,1\n1,2\n");
    EXPECT_NE(m.find("seconds"), std::string::npos) << m;
    EXPECT_NE(error_of("time,u\n0,1\n1,2\n").find("first column must be the time"), std::string::npos);
}

TEST(SignalCsv, refuses_too_short_and_empty)
{
    EXPECT_NE(error_of("t,u\n0,1\n").find("too short"), std::string::npos);
    EXPECT_NE(error_of("").find("empty file"), std::string::npos);
    EXPECT_NE(error_of("t\n0\n1\n").find("no signal column"), std::string::npos);
}

TEST(SignalCsv, refuses_duplicate_column)
{
    EXPECT_NE(error_of("t,u,u\n0,1,1\n1,2,2\n").find("duplicate"), std::string::npos);
}

TEST(SignalCsv, missing_column_lookup_names_available_columns)
{
    const SignalTable t = parse_signal_csv("t,u\n0,1\n1,2\n", "x.csv");
    try {
        t.column("y");
        FAIL();
    } catch (const SignalCsvError& e) {
        EXPECT_NE(std::string(e.what()).find("missing column 'y' (columns: u)"), std::string::npos);
    }
}

TEST(SignalCsv, write_then_read_round_trips_exactly)
{
    SignalTable t;
    t.names = {"a", "b"};
    t.t = {0.0, 0.1, 0.2};
    t.columns = {{1.0 / 3.0, -2e-300, 5.0}, {1e10, 0.1 + 0.2, -7.0}};
    const std::string path = std::string(FRAC_BINARY_DIR) + "/test_io_signal_csv_roundtrip.csv";
    fracdesign::io::write_signal_csv(path, t);
    const SignalTable r = fracdesign::io::read_signal_csv(path);
    std::remove(path.c_str());
    EXPECT_EQ(r.names, t.names);
    EXPECT_EQ(r.t, t.t);
    EXPECT_EQ(r.columns, t.columns);
}

TEST(SignalCsv, writer_refuses_non_finite_and_ragged_tables)
{
    SignalTable t;
    t.names = {"a"};
    t.t = {0.0, 1.0};
    t.columns = {{1.0, std::nan("")}};
    EXPECT_THROW(fracdesign::io::format_signal_csv(t), SignalCsvError);
    t.columns = {{1.0}};
    EXPECT_THROW(fracdesign::io::format_signal_csv(t), SignalCsvError);
}

TEST(SignalCsv, reads_the_emps_export)
{
    const auto t = fracdesign::io::read_signal_csv(std::string(FRAC_SHARED_DIR) + "/data/real/emps/emps_train.csv");
    EXPECT_EQ(t.size(), 24841u);
    EXPECT_NEAR(t.dt, 1e-3, 1e-8);
    EXPECT_DOUBLE_EQ(t.column("vir_V")[0], 2.53862808888);
}

TEST(FrfCsv, reads_hz_or_rad_s_and_refuses_other_units_and_bad_order)
{
    using fracdesign::io::parse_frf_csv;
    const auto a = parse_frf_csv("f_hz,re,im,coh\n1,2,3,0.9\n2,4,5,0.8\n", "f.csv");
    EXPECT_NEAR(a.w[1], 4.0 * M_PI, 1e-12);
    EXPECT_EQ(a.G[1], std::complex<double>(4.0, 5.0));
    const auto b = parse_frf_csv("w_rad_s,im,re\n1,2,3\n2,4,5\n", "f.csv");
    EXPECT_EQ(b.G[0], std::complex<double>(3.0, 2.0));
    EXPECT_THROW(parse_frf_csv("f_khz,re,im\n1,2,3\n2,4,5\n", "f.csv"), SignalCsvError);
    EXPECT_THROW(parse_frf_csv("f_hz,re\n1,2\n2,4\n", "f.csv"), SignalCsvError);
    try {
        parse_frf_csv("f_hz,re,im\n1,2,3\n1,4,5\n", "f.csv");
        FAIL();
    } catch (const SignalCsvError& e) {
        EXPECT_NE(std::string(e.what()).find("row 3"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parse_frf_csv("f_hz,re,im\n-1,2,3\n1,4,5\n", "f.csv"), SignalCsvError);
}
