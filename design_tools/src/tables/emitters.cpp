// emitters.cpp - parameter table emitters (binary FRPT, C header, B&R .var) and
// the binary reader, which is libfrac's frac_ptable (the code the PLC runs).
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "frac/ptable.h"
#include "fracdesign/tables/ptable.hpp"

namespace fracdesign::tables {
namespace {

void put_u16(std::vector<std::uint8_t>& b, size_t at, unsigned v)
{
    b[at] = static_cast<std::uint8_t>(v & 0xFF);
    b[at + 1] = static_cast<std::uint8_t>((v >> 8) & 0xFF);
}

void put_u32(std::vector<std::uint8_t>& b, size_t at, std::uint32_t v)
{
    for (int k = 0; k < 4; ++k) b[at + k] = static_cast<std::uint8_t>((v >> (8 * k)) & 0xFF);
}

// IEEE-754 bits written little-endian regardless of the host (std::memcpy to an integer of the same size).
void put_f64(std::vector<std::uint8_t>& b, size_t at, double v)
{
    std::uint64_t u;
    std::memcpy(&u, &v, 8);
    for (int k = 0; k < 8; ++k) b[at + k] = static_cast<std::uint8_t>((u >> (8 * k)) & 0xFF);
}

void put_f32(std::vector<std::uint8_t>& b, size_t at, float v)
{
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    put_u32(b, at, u);
}

// Shortest literal that reads back to the same value in the table's type.
std::string literal(double v, RealType r)
{
    char buf[40];
    if (r == RealType::F32) {
        const float f = static_cast<float>(v);
        for (int p = 6; p <= 9; ++p) {
            std::snprintf(buf, sizeof buf, "%.*g", p, static_cast<double>(f));
            if (std::strtof(buf, nullptr) == f) break;
        }
    } else {
        for (int p = 15; p <= 17; ++p) {
            std::snprintf(buf, sizeof buf, "%.*g", p, v);
            if (std::strtod(buf, nullptr) == v) break;
        }
    }
    std::string s = buf;
    // C and IEC 61131-3 real literals need a '.' or an exponent.
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
}

// Text safe inside a C or IEC comment: no '*' (closes "*/" and "*)"), no newline.
std::string comment_safe(std::string s)
{
    for (char& c : s)
        if (c == '*' || c == '\n' || c == '\r') c = ' ';
    return s;
}

std::string meta_line(const ParamTable& t)
{
    return t.meta.is_object() && t.meta.contains("source") && t.meta["source"].is_string()
               ? comment_safe(t.meta["source"].get<std::string>())
               : "";
}

}  // namespace

std::vector<std::uint8_t> to_binary(const ParamTable& t)
{
    t.validate();
    const size_t esz = t.real == RealType::F64 ? 8 : 4, n = t.entries.size();
    size_t off = FRAC_PTABLE_HEADER_SIZE + n * FRAC_PTABLE_ENTRY_SIZE;
    std::vector<size_t> offsets;
    for (const auto& e : t.entries) {
        off = (off + 7) / 8 * 8;  // every entry on an 8-byte boundary
        offsets.push_back(off);
        off += e.values.size() * esz;
    }
    const size_t total = off + 4;
    if (total > 0xFFFFFFFFu) throw TableError("total_size", "table exceeds 4 GiB");
    std::vector<std::uint8_t> b(total, 0);
    std::memcpy(b.data(), "FRPT", 4);
    put_u16(b, 4, FRAC_PTABLE_VERSION);
    put_u16(b, 6, t.real == RealType::F64 ? FRAC_PTABLE_F64 : FRAC_PTABLE_F32);
    put_u32(b, 8, static_cast<std::uint32_t>(total));
    put_u32(b, 12, static_cast<std::uint32_t>(n));
    std::memcpy(b.data() + 16, t.name.data(), t.name.size());
    for (size_t i = 0; i < n; ++i) {
        const Entry& e = t.entries[i];
        const size_t d = FRAC_PTABLE_HEADER_SIZE + i * FRAC_PTABLE_ENTRY_SIZE;
        std::memcpy(b.data() + d, e.name.data(), e.name.size());
        put_u16(b, d + 24, static_cast<unsigned>(e.rows));
        put_u16(b, d + 26, static_cast<unsigned>(e.cols));
        put_u32(b, d + 28, static_cast<std::uint32_t>(offsets[i]));
        for (size_t k = 0; k < e.values.size(); ++k) {
            if (t.real == RealType::F64)
                put_f64(b, offsets[i] + 8 * k, e.values[k]);
            else
                put_f32(b, offsets[i] + 4 * k, static_cast<float>(e.values[k]));
        }
    }
    put_u32(b, total - 4, static_cast<std::uint32_t>(frac_crc32(b.data(), total - 4)));
    return b;
}

ParamTable table_from_binary(const std::vector<std::uint8_t>& bytes)
{
    frac_ptable pt;
    const int st = frac_ptable_open(&pt, bytes.data(), static_cast<unsigned long>(bytes.size()));
    if (st != FRAC_OK) {
        std::string field = pt.fail_field;
        if (pt.fail_entry >= 0) field = "entries[" + std::to_string(pt.fail_entry) + "]" + field.substr(5);
        throw TableError(field, std::string("refused by frac_ptable_open: ") + frac_status_str(st));
    }
    ParamTable t;
    char name[FRAC_PTABLE_TABLE_NAME_LEN];
    frac_ptable_name(&pt, name);
    t.name = name;
    t.real = pt.elem_type == FRAC_PTABLE_F64 ? RealType::F64 : RealType::F32;
    for (unsigned long i = 0; i < pt.n_entries; ++i) {
        frac_ptable_entry e;
        frac_ptable_entry_at(&pt, i, &e);
        Entry out{e.name, static_cast<int>(e.rows), static_cast<int>(e.cols), {}, ""};
        std::vector<frac_real> v(static_cast<size_t>(e.rows) * e.cols);
        if (frac_ptable_get(&pt, e.name, e.rows, e.cols, v.data()) != FRAC_OK)
            throw TableError(out.name, "entry unreadable after validation");
        out.values.assign(v.begin(), v.end());
        t.entries.push_back(std::move(out));
    }
    return t;
}

std::string to_c_header(const ParamTable& t)
{
    t.validate();
    const std::string type = t.real == RealType::F64 ? "double" : "float";
    const std::string suffix = t.real == RealType::F64 ? "" : "f";
    std::string up = t.name;
    for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    std::ostringstream os;
    os << "/* " << t.name << ".h - parameter table '" << t.name << "' (schema " << ParamTable::kSchema << " v"
       << ParamTable::kVersion << ", " << to_string(t.real) << "), generated by fracdesign table.\n";
    const std::string src = meta_line(t);
    if (!src.empty()) os << " * Source: " << src << "\n";
    os << " * Do not edit: regenerate from the design. C89; row-major arrays. */\n"
       << "#ifndef FRAC_PTABLE_" << up << "_H\n#define FRAC_PTABLE_" << up << "_H\n\n";
    for (const auto& e : t.entries) {
        std::string eu = e.name;
        for (char& c : eu) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (!e.doc.empty()) os << "/* " << e.name << ": " << comment_safe(e.doc) << " */\n";
        os << "#define " << up << "_" << eu << "_ROWS " << e.rows << "\n#define " << up << "_" << eu << "_COLS "
           << e.cols << "\n";
        os << "static const " << type << " " << t.name << "_" << e.name << "[" << e.values.size() << "] = {";
        for (size_t k = 0; k < e.values.size(); ++k)
            os << (k ? (k % 4 ? ", " : ",\n    ") : "") << literal(e.values[k], t.real) << suffix;
        os << "};\n\n";
    }
    const auto bin = to_binary(t);
    os << "/* The same table as the binary data object (docs/param_table_format.md), " << bin.size()
       << " bytes. */\nstatic const unsigned char " << t.name << "_frpt[" << bin.size() << "] = {";
    char buf[8];
    for (size_t k = 0; k < bin.size(); ++k) {
        std::snprintf(buf, sizeof buf, "0x%02X", bin[k]);
        os << (k ? (k % 12 ? ", " : ",\n    ") : "") << buf;
    }
    os << "};\n\n#endif\n";
    return os.str();
}

std::string to_var(const ParamTable& t)
{
    t.validate();
    const std::string type = t.real == RealType::F64 ? "LREAL" : "REAL";
    std::ostringstream os;
    os << "(* " << t.name << ".var - parameter table '" << t.name << "' (schema " << ParamTable::kSchema << " v"
       << ParamTable::kVersion << ", " << to_string(t.real) << "), generated by fracdesign table. *)\n";
    const std::string src = meta_line(t);
    if (!src.empty()) os << "(* Source: " << src << " *)\n";
    os << "VAR\n";
    for (const auto& e : t.entries) {
        os << "\t" << t.name << "_" << e.name << " : ";
        if (e.values.size() == 1) {
            os << type << " := " << literal(e.values[0], t.real) << ";";
        } else {
            os << "ARRAY[0.." << e.rows - 1 << ",0.." << e.cols - 1 << "] OF " << type << " := [";
            for (size_t k = 0; k < e.values.size(); ++k) os << (k ? "," : "") << literal(e.values[k], t.real);
            os << "];";
        }
        if (!e.doc.empty()) os << " (*" << comment_safe(e.doc) << "*)";
        os << "\n";
    }
    os << "END_VAR\n";
    return os.str();
}

bool is_emit_format(const std::string& format)
{
    return format == "json" || format == "c" || format == "var" || format == "bin";
}

std::string emit(const ParamTable& t, const std::string& format)
{
    if (format == "bin") {
        const std::vector<std::uint8_t> b = to_binary(t);
        return std::string(b.begin(), b.end());
    }
    if (format == "json") return to_json(t).dump(2) + "\n";
    if (format == "c") return to_c_header(t);
    if (format == "var") return to_var(t);
    throw std::invalid_argument("unknown table format '" + format + "' (json, c, var or bin)");
}

}  // namespace fracdesign::tables
