// Tests of the MAT v5 reader (fracdesign/io/matv5.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "fracdesign/io/matv5.hpp"
#include "fracdesign/io/signal_csv.hpp"

using fracdesign::io::MatError;
using fracdesign::io::parse_mat_v5;

namespace {

const std::string kEmps = std::string(FRAC_SHARED_DIR) + "/data/real/emps/";

void put32(std::vector<unsigned char>& b, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) b.push_back((v >> (8 * i)) & 0xff);
}

// A hand-built uncompressed level-5 file holding one 2x1 double matrix `x`
// (MAT-File Format: header, miMATRIX with flags, dims, small-element name, data).
std::vector<unsigned char> tiny_mat()
{
    std::vector<unsigned char> b(116, ' ');
    const char* text = "MATLAB 5.0 MAT-file, test";
    std::memcpy(b.data(), text, std::strlen(text));
    b.resize(124, 0);
    b.push_back(0x00); b.push_back(0x01); b.push_back('I'); b.push_back('M');
    put32(b, 14); put32(b, 16 + 16 + 8 + 24);    // miMATRIX
    put32(b, 6); put32(b, 8); put32(b, 6); put32(b, 0);  // flags: class double
    put32(b, 5); put32(b, 8); put32(b, 2); put32(b, 1);  // dims 2x1
    put32(b, (1u << 16) | 1u); b.push_back('x'); b.push_back(0); b.push_back(0); b.push_back(0);
    put32(b, 9); put32(b, 16);
    const double v[2] = {1.5, -2.25};
    const unsigned char* p = reinterpret_cast<const unsigned char*>(v);
    b.insert(b.end(), p, p + 16);
    return b;
}

}  // namespace

TEST(MatV5, reads_uncompressed_double_matrix)
{
    const auto f = parse_mat_v5(tiny_mat(), "tiny.mat");
    const auto& x = f.at("x");
    EXPECT_EQ(x.rows, 2u);
    EXPECT_EQ(x.cols, 1u);
    EXPECT_EQ(x.data, (std::vector<double>{1.5, -2.25}));
    EXPECT_EQ(f.header, "MATLAB 5.0 MAT-file, test");
}

TEST(MatV5, refuses_truncated_file_naming_the_problem)
{
    auto b = tiny_mat();
    b.resize(b.size() - 9);
    try {
        parse_mat_v5(b, "tiny.mat");
        FAIL();
    } catch (const MatError& e) {
        EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    }
}

TEST(MatV5, refuses_non_mat_and_short_input)
{
    EXPECT_THROW(parse_mat_v5(std::vector<unsigned char>(10, 0), "a"), MatError);
    std::vector<unsigned char> b = tiny_mat();
    b[126] = 'X';
    EXPECT_THROW(parse_mat_v5(b, "a"), MatError);
}

TEST(MatV5, missing_variable_lists_available_ones)
{
    const auto f = parse_mat_v5(tiny_mat(), "tiny.mat");
    try {
        f.at("y");
        FAIL();
    } catch (const MatError& e) {
        EXPECT_NE(std::string(e.what()).find("has: x"), std::string::npos) << e.what();
    }
    EXPECT_THROW(f.at("x").scalar(), MatError);
}

TEST(MatV5, reads_compressed_emps_file_matching_its_csv_export)
{
    const auto f = fracdesign::io::read_mat_v5(kEmps + "DATA_EMPS_PULSES.mat");
    const auto qm = f.vector("qm");
    const auto p = f.vector("pulses_N");
    ASSERT_EQ(qm.size(), 24841u);
    // MATLAB class double, stored as miUINT8 (MATLAB narrows the storage type
    // of integer-valued doubles): exercises the type conversion path.
    EXPECT_EQ(f.at("pulses_N").mclass, "double");
    EXPECT_NEAR(f.at("gtau").scalar(), 35.15065188248547, 1e-12);
    const auto csv = fracdesign::io::read_signal_csv(kEmps + "emps_pulses.csv");
    const auto& cq = csv.column("qm_m");
    const auto& cp = csv.column("pulses_N");
    for (std::size_t k = 0; k < qm.size(); k += 997) {
        EXPECT_NEAR(qm[k], cq[k], 1e-9 * (1.0 + std::fabs(cq[k])));
        EXPECT_EQ(p[k], cp[k]);
    }
}
