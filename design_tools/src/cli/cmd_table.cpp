// cmd_table.cpp - `fracdesign table emit|check`: parameter tables for the PLC.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "frac/ptable.h"
#include "fracdesign/cli.hpp"
#include "fracdesign/tables/ptable.hpp"

namespace fracdesign {
namespace {

using tables::ParamTable;

std::vector<std::uint8_t> read_bytes(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot open '" + path + "'");
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// Reports a refused table on stderr naming the field; exit status 1.
int refuse(const std::string& what, const tables::TableError& e)
{
    std::cerr << "fracdesign table " << what << ": table refused: field " << e.field << ": " << e.what() << "\n";
    return 1;
}

int run_emit(const Args& args)
{
    args.check_known({"json", "in", "format", "real", "out", "name"});
    const std::string in = args.str("in"), format = args.str("format"), out = args.str("out");
    if (!tables::is_emit_format(format)) throw UsageError("--format must be json, c, var or bin");
    nlohmann::json doc;
    {
        std::ifstream f(in);
        if (!f) throw std::runtime_error("cannot open '" + in + "'");
        try {
            f >> doc;
        } catch (const nlohmann::json::exception& e) {
            throw std::runtime_error("'" + in + "' is not JSON: " + e.what());
        }
    }
    ParamTable t;
    try {
        t = tables::table_from_document(doc);
        if (args.has("real")) t.real = tables::real_type_from_string(args.str("real"));
        if (args.has("name")) t.name = args.str("name");
        t.validate();
    } catch (const tables::TableError& e) {
        return refuse("emit", e);
    }
    const std::string data = tables::emit(t, format);
    write_file(out, data);
    const size_t bytes = data.size();
    if (args.has("json")) {
        nlohmann::json j = {{"schema", "frac.table.emit"}, {"version", 1},     {"table", t.name},
                            {"format", format},          {"real", tables::to_string(t.real)},
                            {"out", out},                {"bytes", bytes},  {"entries", t.entries.size()}};
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << "table '" << t.name << "' (" << t.entries.size() << " entries, " << tables::to_string(t.real)
                  << ") -> " << out << " [" << format << ", " << bytes << " bytes]\n";
    }
    return 0;
}

int run_check(const Args& args)
{
    args.check_known({"json"});
    if (args.positional().size() != 2) throw UsageError("usage: fracdesign table check FILE.bin");
    const std::string path = args.positional()[1];
    ParamTable t;
    try {
        t = tables::table_from_binary(read_bytes(path));
    } catch (const tables::TableError& e) {
        return refuse("check", e);
    }
    if (args.has("json")) {
        nlohmann::json j = tables::to_json(t);
        j["valid"] = true;
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << path << ": valid FRPT v" << FRAC_PTABLE_VERSION << " table '" << t.name << "', "
                  << tables::to_string(t.real) << ", " << t.entries.size() << " entries\n";
        for (const auto& e : t.entries) {
            std::printf("  %-23s %5d x %-5d", e.name.c_str(), e.rows, e.cols);
            for (size_t k = 0; k < e.values.size() && k < 4; ++k) std::printf(" %.10g", e.values[k]);
            std::printf("%s\n", e.values.size() > 4 ? " ..." : "");
        }
    }
    return 0;
}

int run_table(const std::vector<std::string>& argv)
{
    Args args(argv, {"json"});
    if (args.positional().empty()) throw UsageError("expected a verb: emit or check");
    const std::string verb = args.positional()[0];
    if (verb == "emit") {
        if (args.positional().size() != 1) throw UsageError("emit takes no positional arguments");
        return run_emit(args);
    }
    if (verb == "check") return run_check(args);
    throw UsageError("unknown verb '" + verb + "' (emit, check)");
}

CommandRegistrar reg({"table", "emit and check the parameter tables the PLC loads",
                      "usage: fracdesign table emit --in DOC.json --format json|c|var|bin --out FILE\n"
                      "                             [--real float64|float32] [--name NAME] [--json]\n"
                      "       fracdesign table check FILE.bin [--json]\n\n"
                      "emit: DOC is a parameter table (schema frac.ptable v1) or a design document\n"
                      "(frac.design.fopi, fopd, collocated, lqg); writes it as JSON, a C header of const\n"
                      "arrays (plus the binary object as bytes), a B&R .var file of IEC 61131-3\n"
                      "initializers, or the binary data object FRPT (docs/param_table_format.md).\n"
                      "check: validates a binary table with libfrac's frac_ptable_open (the PLC's\n"
                      "reader: magic, version, CRC32, dimensions, finiteness) and lists it.\n"
                      "A table that fails validation is refused naming the field, exit status 1.\n",
                      run_table});

}  // namespace
}  // namespace fracdesign
