// ptable.hpp - the parameter table: one versioned schema for everything a
// controller on the PLC loads (gains, orders, matrices), and its emitters.
//
// A table is a name and an ordered list of named real matrices. Names are
// C and IEC 61131-3 identifiers: [A-Za-z][A-Za-z0-9_]*, no "__", no trailing
// "_", at most 23 characters for entries and 31 for the table; dimensions
// 1..65535; every value finite. JSON form (schema "frac.ptable", version 1):
//   {"schema": "frac.ptable", "version": 1, "name": "fopi",
//    "real": "float64", "meta": {...},
//    "entries": [{"name": "Kp", "rows": 1, "cols": 1, "values": [0.12]}, ...]}
// Emitters: JSON, a C header of const arrays, a B&R-style .var file of
// IEC 61131-3 initializers, and the binary data object "FRPT" whose layout is
// docs/param_table_format.md and whose reader is libfrac's frac/ptable.h (the
// same code the PLC runs; from_binary uses it).
#pragma once
#include <Eigen/Dense>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fracdesign::tables {

// A table or document that fails validation; `field` names what failed
// (e.g. "entries[2].values[5]", "crc32", "magic").
struct TableError : std::runtime_error {
    std::string field;
    TableError(const std::string& f, const std::string& what) : std::runtime_error(f + ": " + what), field(f) {}
};

enum class RealType { F64, F32 };
RealType real_type_from_string(const std::string& s);  // "float64" | "float32"; TableError("real") otherwise
std::string to_string(RealType r);

struct Entry {
    std::string name;
    int rows = 0, cols = 0;
    std::vector<double> values;  // row-major, rows * cols
    std::string doc;             // optional one-line description (units)
};

struct ParamTable {
    static constexpr const char* kSchema = "frac.ptable";
    static constexpr int kVersion = 1;
    std::string name;
    RealType real = RealType::F64;
    nlohmann::json meta = nlohmann::json::object();  // provenance: source design, seed, equations
    std::vector<Entry> entries;

    void add(const std::string& name, double v, const std::string& doc = "");
    void add(const std::string& name, const Eigen::MatrixXd& M, const std::string& doc = "");
    const Entry& at(const std::string& name) const;  // TableError(name) if absent
    // Throws TableError naming the first field that breaks the rules above.
    void validate() const;
};

nlohmann::json to_json(const ParamTable& t);
// Reads and validates a "frac.ptable" document (TableError naming the field).
ParamTable table_from_json(const nlohmann::json& j);
// A table from a design document: frac.design.fopi / fopd / collocated / lqg are
// mapped to their entries; a frac.ptable document is read as is.
ParamTable table_from_document(const nlohmann::json& j);

// Binary data object "FRPT" v1 in the table's real type (values rounded to float32 for F32).
std::vector<std::uint8_t> to_binary(const ParamTable& t);
// Parses and validates with libfrac's frac_ptable_open; TableError naming the
// failing field and the libfrac status otherwise.
ParamTable table_from_binary(const std::vector<std::uint8_t>& bytes);

// C header: one `static const double|float <table>_<entry>[..]` per entry, dimension
// macros, and the binary object as `<table>_frpt[]` bytes.
std::string to_c_header(const ParamTable& t);
// B&R .var file: VAR ... END_VAR with one LREAL/REAL variable (ARRAY for matrices) per entry.
std::string to_var(const ParamTable& t);

// The emitted formats of `fracdesign table emit` and `fracdesign armctrl`:
// "json" (to_json, 2-space indent), "c" (to_c_header), "var" (to_var) and
// "bin" (to_binary's bytes). emit throws std::invalid_argument for another name.
bool is_emit_format(const std::string& format);
std::string emit(const ParamTable& t, const std::string& format);

}  // namespace fracdesign::tables
