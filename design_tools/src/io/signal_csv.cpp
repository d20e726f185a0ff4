// signal_csv.cpp - strict signal CSV reader/writer (see signal_csv.hpp).
#include "fracdesign/io/signal_csv.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

namespace fracdesign {
namespace io {
namespace {

std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t\r");
    return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line)
{
    std::vector<std::string> out;
    std::string cell;
    std::istringstream ss(line);
    while (std::getline(ss, cell, ',')) out.push_back(trim(cell));
    if (!line.empty() && line.back() == ',') out.push_back("");
    return out;
}

[[noreturn]] void fail(const std::string& origin, std::size_t row, const std::string& col, const std::string& msg)
{
    std::string where = origin + ": row " + std::to_string(row);
    if (!col.empty()) where += ", column '" + col + "'";
    throw SignalCsvError(where + ": " + msg);
}

}  // namespace

std::size_t SignalTable::index(const std::string& name) const
{
    for (std::size_t j = 0; j < names.size(); ++j)
        if (names[j] == name) return j;
    std::string have;
    for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
    throw SignalCsvError("missing column '" + name + "' (columns: " + have + ")");
}

NumericCsv parse_numeric_csv(const std::string& text, const std::string& origin)
{
    std::istringstream in(text);
    std::string line;
    std::size_t row = 0;
    NumericCsv out;
    while (std::getline(in, line)) {
        ++row;
        if (!trim(line).empty()) {
            out.header = split(line);
            out.header_row = row;
            break;
        }
    }
    if (out.header.empty()) throw SignalCsvError(origin + ": empty file (expected a header row)");
    std::set<std::string> seen;
    for (const auto& h : out.header) {
        if (h.empty()) fail(origin, row, "", "empty column name in header");
        if (!seen.insert(h).second) fail(origin, row, h, "duplicate column name");
    }
    out.columns.assign(out.header.size(), {});
    while (std::getline(in, line)) {
        ++row;
        if (trim(line).empty()) continue;
        const auto cells = split(line);
        if (cells.size() != out.header.size())
            fail(origin, row, "", "ragged row: " + std::to_string(cells.size()) + " cells, header has " +
                                      std::to_string(out.header.size()));
        for (std::size_t j = 0; j < cells.size(); ++j) {
            const std::string& c = cells[j];
            if (c.empty()) fail(origin, row, out.header[j], "missing value");
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(c.c_str(), &end);
            if (end == c.c_str() || *end != '\0') fail(origin, row, out.header[j], "not a number: '" + c + "'");
            // ERANGE is also set on underflow (a subnormal such as a
            // rig's -1.3e-311, returned as the nearest representable value,
            // finite): only an overflow (|v| = HUGE_VAL) is refused.
            if (!std::isfinite(v) || (errno == ERANGE && std::fabs(v) > 1.0))
                fail(origin, row, out.header[j], "non-finite value '" + c + "'");
            out.columns[j].push_back(v);
        }
        out.file_row.push_back(row);
    }
    return out;
}

std::string read_text_file(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    if (!f) throw SignalCsvError(path + ": cannot open");
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

SignalTable parse_signal_csv(const std::string& text, const std::string& origin, const SignalCsvOptions& opt)
{
    NumericCsv raw = parse_numeric_csv(text, origin);
    const std::vector<std::string>& header = raw.header;
    const std::size_t hrow = raw.header_row;
    const std::string& t0 = header[0];
    if (t0 != "t" && t0 != "t_s") {
        if (t0.size() > 2 && t0.compare(0, 2, "t_") == 0)
            fail(origin, hrow, t0, "time column must be in seconds ('t' or 't_s'); convert '" + t0 + "' to s");
        fail(origin, hrow, t0, "first column must be the time 't' in seconds");
    }
    if (header.size() < 2) fail(origin, hrow, "", "no signal column after 't'");
    SignalTable tab;
    tab.names.assign(header.begin() + 1, header.end());
    tab.t = std::move(raw.columns[0]);
    tab.columns.assign(raw.columns.begin() + 1, raw.columns.end());
    const std::vector<std::size_t>& file_row = raw.file_row;
    const std::size_t n = tab.t.size();
    if (n < opt.min_rows)
        throw SignalCsvError(origin + ": too short: " + std::to_string(n) + " data rows, need at least " +
                             std::to_string(opt.min_rows));
    tab.dt = (tab.t.back() - tab.t.front()) / double(n - 1);
    std::vector<double> steps(n - 1);
    for (std::size_t k = 1; k < n; ++k) {
        steps[k - 1] = tab.t[k] - tab.t[k - 1];
        if (!(steps[k - 1] > 0.0)) {
            char buf[128];
            std::snprintf(buf, sizeof buf, "time not increasing (t = %.9g s after %.9g s)", tab.t[k], tab.t[k - 1]);
            fail(origin, file_row[k], header[0], buf);
        }
    }
    // Uniformity is judged against the median step, so the message points at
    // the offending sample rather than at whatever a gap did to the mean.
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double ref = sorted[sorted.size() / 2];
    for (std::size_t k = 1; k < n; ++k) {
        if (std::fabs(steps[k - 1] - ref) > opt.max_jitter * ref) {
            char buf[160];
            std::snprintf(buf, sizeof buf, "non-uniform time step %.9g s at t = %.9g s (median step %.9g s, tolerance %g)",
                          steps[k - 1], tab.t[k], ref, opt.max_jitter);
            fail(origin, file_row[k], header[0], buf);
        }
    }
    return tab;
}

SignalTable read_signal_csv(const std::string& path, const SignalCsvOptions& opt)
{
    return parse_signal_csv(read_text_file(path), path, opt);
}

std::string format_signal_csv(const SignalTable& table)
{
    if (table.columns.size() != table.names.size())
        throw SignalCsvError("signal table: " + std::to_string(table.names.size()) + " names for " +
                             std::to_string(table.columns.size()) + " columns");
    std::string out = "t";
    for (const auto& n : table.names) out += "," + n;
    out += "\n";
    for (std::size_t j = 0; j < table.columns.size(); ++j)
        if (table.columns[j].size() != table.t.size())
            throw SignalCsvError("signal table: column '" + table.names[j] + "' has " +
                                 std::to_string(table.columns[j].size()) + " rows, t has " +
                                 std::to_string(table.t.size()));
    char buf[32];
    for (std::size_t k = 0; k < table.t.size(); ++k) {
        for (std::size_t j = 0; j <= table.columns.size(); ++j) {
            const double v = j == 0 ? table.t[k] : table.columns[j - 1][k];
            if (!std::isfinite(v))
                throw SignalCsvError("signal table: non-finite value at row " + std::to_string(k) + ", column '" +
                                     (j == 0 ? std::string("t") : table.names[j - 1]) + "'");
            std::snprintf(buf, sizeof buf, "%s%.17g", j ? "," : "", v);
            out += buf;
        }
        out += "\n";
    }
    return out;
}

void write_signal_csv(const std::string& path, const SignalTable& table)
{
    const std::string text = format_signal_csv(table);
    std::ofstream f(path, std::ios::binary);
    if (!f) throw SignalCsvError(path + ": cannot open for writing");
    f << text;
    if (!f) throw SignalCsvError(path + ": write failed");
}

}  // namespace io
}  // namespace fracdesign
