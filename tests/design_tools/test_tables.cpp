// Parameter tables: schema validation, emitters, and the round trip
// emit -> load in C (libfrac's frac_ptable, and a compiled C program) -> identical values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "frac/ptable.h"
#include "fracdesign/tables/ptable.hpp"
#include "run_command.hpp"

using namespace fracdesign::tables;

namespace {

ParamTable sample(RealType r)
{
    std::mt19937 rng(42);
    std::normal_distribution<double> g(0.0, 1.0);
    ParamTable t;
    t.name = "lqg_expD";
    t.real = r;
    t.meta = {{"source", "test */ *) comment closers must not leak"}};
    Eigen::MatrixXd K(1, 23), L(24, 3);
    for (int j = 0; j < 23; ++j) K(0, j) = g(rng) * std::pow(10.0, j % 7 - 3);
    for (int i = 0; i < 24; ++i)
        for (int j = 0; j < 3; ++j) L(i, j) = g(rng) / 3.0;
    t.add("K", K, "state feedback gain");
    t.add("L_e", L, "observer gain");
    t.add("Ts", 1.2e-3, "sample time [s]");
    t.add("d_i", 4.0);
    t.add("tiny", 4.9406564584124654e-300);
    return t;
}

std::string run(const std::string& cmd, int* status) { return run_command(cmd, status); }

std::string tmpdir()
{
    char tmpl[] = "/tmp/frac_tables_XXXXXX";
    const char* d = mkdtemp(tmpl);
    return d ? d : "/tmp";
}

}  // namespace

TEST(Tables, BinaryRoundTripThroughLibfracIsBitIdenticalInFloat64)
{
    const ParamTable t = sample(RealType::F64);
    const ParamTable back = table_from_binary(to_binary(t));
    EXPECT_EQ(back.name, t.name);
    ASSERT_EQ(back.entries.size(), t.entries.size());
    for (size_t i = 0; i < t.entries.size(); ++i) {
        EXPECT_EQ(back.entries[i].name, t.entries[i].name);
        EXPECT_EQ(back.entries[i].rows, t.entries[i].rows);
        EXPECT_EQ(back.entries[i].cols, t.entries[i].cols);
        ASSERT_EQ(back.entries[i].values.size(), t.entries[i].values.size());
        for (size_t k = 0; k < t.entries[i].values.size(); ++k)
            EXPECT_EQ(std::memcmp(&back.entries[i].values[k], &t.entries[i].values[k], sizeof(double)), 0);
    }
}

TEST(Tables, Float32TableHoldsTheFloatRoundedValues)
{
    ParamTable t = sample(RealType::F32);
    t.entries.pop_back();  // 4.9e-300 underflows to 0 in float32, still finite: keep the test about rounding
    const ParamTable back = table_from_binary(to_binary(t));
    for (size_t i = 0; i < t.entries.size(); ++i)
        for (size_t k = 0; k < t.entries[i].values.size(); ++k)
            EXPECT_EQ(back.entries[i].values[k], static_cast<double>(static_cast<float>(t.entries[i].values[k])));
}

TEST(Tables, JsonRoundTripPreservesEveryValue)
{
    const ParamTable t = sample(RealType::F64);
    const ParamTable back = table_from_json(nlohmann::json::parse(to_json(t).dump()));
    for (size_t i = 0; i < t.entries.size(); ++i) EXPECT_EQ(back.entries[i].values, t.entries[i].values);
    EXPECT_EQ(back.entries[0].doc, "state feedback gain");
}

TEST(Tables, EmittedCHeaderCompilesAndItsArraysAndBlobAgreeInC)
{
    // The generated header is compiled by the C compiler together with libfrac;
    // the program validates the embedded FRPT blob with frac_ptable_open and
    // compares every frac_ptable_get value with the const arrays, bit for bit.
    const ParamTable t = sample(RealType::F64);
    const std::string dir = tmpdir();
    std::ofstream(dir + "/lqg_expD.h") << to_c_header(t);
    std::ostringstream prog;
    prog << "#include <stdio.h>\n#include <string.h>\n#include \"frac/ptable.h\"\n#include \"lqg_expD.h\"\n"
         << "static int same(const char *n, const double *a, unsigned r, unsigned c, const frac_ptable *t) {\n"
         << "  double v[128]; unsigned i;\n"
         << "  if (frac_ptable_get(t, n, r, c, v) != FRAC_OK) return 0;\n"
         << "  for (i = 0; i < r * c; i++) if (memcmp(&v[i], &a[i], sizeof(double)) != 0) return 0;\n"
         << "  return 1; }\n"
         << "int main(void) { frac_ptable t; int ok;\n"
         << "  if (frac_ptable_open(&t, lqg_expD_frpt, sizeof lqg_expD_frpt) != FRAC_OK) { puts(\"invalid\"); return 1; }\n"
         << "  ok = same(\"K\", lqg_expD_K, LQG_EXPD_K_ROWS, LQG_EXPD_K_COLS, &t)"
         << " && same(\"L_e\", lqg_expD_L_e, LQG_EXPD_L_E_ROWS, LQG_EXPD_L_E_COLS, &t)"
         << " && same(\"Ts\", lqg_expD_Ts, 1, 1, &t) && same(\"d_i\", lqg_expD_d_i, 1, 1, &t)"
         << " && same(\"tiny\", lqg_expD_tiny, 1, 1, &t);\n"
         << "  puts(ok ? \"identical\" : \"different\"); return ok ? 0 : 1; }\n";
    std::ofstream(dir + "/main.c") << prog.str();
    int st = 0;
    const std::string inc = std::string(FRAC_SOURCE_DIR) + "/libfrac/include";
    const std::string lib = std::string(FRAC_BINARY_DIR) + "/libfrac/libfrac.a";
    std::string out = run("cc -std=c89 -pedantic -Wall -Wextra -Werror -Wno-unused-variable -I" + inc + " -I" + dir +
                              " " + dir + "/main.c " + lib + " -lm -o " + dir + "/roundtrip",
                          &st);
    ASSERT_EQ(st, 0) << out;
    out = run(dir + "/roundtrip", &st);
    EXPECT_EQ(st, 0);
    EXPECT_EQ(out, "identical\n");
}

TEST(Tables, VarFileHoldsOneInitializerPerEntryWithExactLiterals)
{
    const ParamTable t = sample(RealType::F64);
    const std::string var = to_var(t);
    EXPECT_EQ(var.find("VAR\n"), var.find("VAR"));
    EXPECT_NE(var.find("END_VAR\n"), std::string::npos);
    EXPECT_NE(var.find("lqg_expD_K : ARRAY[0..0,0..22] OF LREAL := ["), std::string::npos);
    EXPECT_NE(var.find("lqg_expD_L_e : ARRAY[0..23,0..2] OF LREAL := ["), std::string::npos);
    EXPECT_NE(var.find("lqg_expD_d_i : LREAL := 4.0;"), std::string::npos);
    EXPECT_EQ(var.find("*/"), std::string::npos);
    // Every literal of K reads back to the same double.
    const size_t a = var.find(":= [", var.find("lqg_expD_K")) + 4, b = var.find("]", a);
    std::stringstream ss(var.substr(a, b - a));
    std::string tok;
    size_t k = 0;
    while (std::getline(ss, tok, ',')) {
        EXPECT_NE(tok.find_first_of(".eE"), std::string::npos) << tok;  // IEC real literal
        EXPECT_EQ(std::strtod(tok.c_str(), nullptr), t.at("K").values[k++]);
    }
    EXPECT_EQ(k, 23u);
    EXPECT_EQ(to_var(sample(RealType::F32)).find("LREAL"), std::string::npos);
}

TEST(Tables, InvalidTablesAreRefusedNamingTheField)
{
    auto field_of = [](const ParamTable& t) {
        try {
            t.validate();
        } catch (const TableError& e) {
            return e.field;
        }
        return std::string("(accepted)");
    };
    ParamTable t = sample(RealType::F64);
    t.entries[1].values[7] = NAN;
    EXPECT_EQ(field_of(t), "entries[1].values[7]");
    t = sample(RealType::F32);
    t.entries[2].values[0] = 1e39;
    EXPECT_EQ(field_of(t), "entries[2].values[0]");
    t = sample(RealType::F64);
    t.entries[0].name = "2K";
    EXPECT_EQ(field_of(t), "entries[0].name");
    t.entries[0].name = "K__x";
    EXPECT_EQ(field_of(t), "entries[0].name");
    t.entries[0].name = "Ts";
    EXPECT_EQ(field_of(t), "entries[2].name");
    t = sample(RealType::F64);
    t.entries[0].values.pop_back();
    EXPECT_EQ(field_of(t), "entries[0].values");
    t = sample(RealType::F64);
    t.name = "a_name_that_is_much_too_long_for_the_header";
    EXPECT_EQ(field_of(t), "name");

    nlohmann::json j = to_json(sample(RealType::F64));
    j["version"] = 2;
    EXPECT_THROW(table_from_json(j), TableError);
    j = to_json(sample(RealType::F64));
    j["entries"][1]["rows"] = 0;
    try {
        table_from_json(j);
        FAIL();
    } catch (const TableError& e) {
        EXPECT_EQ(e.field, "entries[1].rows");
    }
}

TEST(Tables, CorruptedBinaryIsRefusedNamingTheField)
{
    auto bin = to_binary(sample(RealType::F64));
    bin[200] ^= 0x40;
    try {
        table_from_binary(bin);
        FAIL();
    } catch (const TableError& e) {
        EXPECT_EQ(e.field, "crc32");
    }
    bin = to_binary(sample(RealType::F64));
    bin[4] = 9;
    try {
        table_from_binary(bin);
        FAIL();
    } catch (const TableError& e) {
        EXPECT_EQ(e.field, "version");
    }
    bin.resize(30);
    EXPECT_THROW(table_from_binary(bin), TableError);
}

TEST(Tables, CliEmitsEveryFormatAndRefusesACorruptTable)
{
    const std::string dir = tmpdir(), exe = FRACDESIGN_EXE;
    std::ofstream(dir + "/t.json") << to_json(sample(RealType::F64)).dump();
    int st = 0;
    for (const char* f : {"json", "c", "var", "bin"}) {
        const std::string out = run(exe + " table emit --in " + dir + "/t.json --format " + f + " --out " + dir + "/t." + f, &st);
        EXPECT_EQ(st, 0) << out;
    }
    std::string out = run(exe + " table check " + dir + "/t.bin", &st);
    EXPECT_EQ(st, 0) << out;
    EXPECT_NE(out.find("valid FRPT v1"), std::string::npos) << out;
    {
        std::fstream f(dir + "/t.bin", std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(0);
        f.put('X');
    }
    out = run(exe + " table check " + dir + "/t.bin", &st);
    EXPECT_EQ(st, 1);
    EXPECT_NE(out.find("field magic"), std::string::npos) << out;
    run(exe + " table emit --in " + dir + "/t.json --format yaml --out " + dir + "/t.y", &st);
    EXPECT_EQ(st, 2);
}

TEST(Tables, DesignDocumentsMapToTheirEntries)
{
    const nlohmann::json fopi = {{"schema", "frac.design.fopi"},
                                 {"source", "seed 001"},
                                 {"controller", {{"Kp", 0.1218565}, {"Ki", 0.1255097}, {"alpha", 0.88}}}};
    const ParamTable t = table_from_document(fopi);
    EXPECT_EQ(t.name, "fopi");
    EXPECT_EQ(t.at("Ki").values[0], 0.1255097);
    const nlohmann::json lqg = {{"schema", "frac.design.lqg"}, {"T", 1.2e-3}, {"di", 4}, {"do", 3},
                                {"K", {{1.0, 2.0}}},          {"Le", {{1.0}, {2.0}, {3.0}}},
                                {"Ae", {{1.0, 0.0}, {0.0, 1.0}}}, {"Be", {{0.0}, {1.0}}},
                                {"Ce", {{1.0, 0.0}}}};
    const ParamTable l = table_from_document(lqg);
    EXPECT_EQ(l.at("Le").rows, 3);
    EXPECT_EQ(l.at("K").cols, 2);
    EXPECT_EQ(l.at("d_o").values[0], 3.0);
    nlohmann::json bad = lqg;
    bad["Ae"][1] = {1.0};
    try {
        table_from_document(bad);
        FAIL();
    } catch (const TableError& e) {
        EXPECT_EQ(e.field, "Ae[1]");
    }
    EXPECT_THROW(table_from_document({{"schema", "frac.design.unknown"}}), TableError);
    EXPECT_THROW(table_from_document({{"schema", "frac.design.fopi"}, {"controller", {{"Kp", 1.0}}}}), TableError);
}
