// signal_csv.hpp - strict reader/writer for the project's signal CSV files.
//
// Format (ARCHITECTURE.md "Data formats"): one header row; the first column
// is the time `t` in seconds (the header may spell it `t` or `t_s`); every
// other column is one signal in SI units; uniform sampling. The reader never
// guesses: a ragged row, a missing or non-numeric cell, a NaN/Inf, a time
// column that is not strictly increasing or not uniform, or a time column in
// other units (`t_ms`, `t_us`, ...) is refused with a SignalCsvError whose
// message names the file, the row (1-based, header = row 1) and the column.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

namespace fracdesign {
namespace io {

struct SignalCsvError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A uniformly sampled multichannel record.
struct SignalTable {
    std::vector<std::string> names;            // signal column names, without `t`
    std::vector<double> t;                     // time stamps, s
    std::vector<std::vector<double>> columns;  // columns[j][k]: signal j at t[k]
    double dt = 0.0;                           // mean sample time, s

    std::size_t size() const { return t.size(); }
    // Index of the column called `name`; SignalCsvError listing the
    // available names if absent.
    std::size_t index(const std::string& name) const;
    const std::vector<double>& column(const std::string& name) const { return columns[index(name)]; }
};

struct SignalCsvOptions {
    // Largest accepted deviation of any time step from the median step, relative
    // to the mean step. The EMPS records carry ~3e-8 s jitter on 1 ms (3e-5);
    // 1e-3 accepts logging jitter and refuses a dropped or doubled sample.
    double max_jitter = 1e-3;
    std::size_t min_rows = 2;  // fewer data rows: "too short"
};

// The strict numeric table beneath the signal and FRF readers: a header of
// unique non-empty names, then rows of exactly as many finite numbers (blank
// lines skipped). file_row[k] is the 1-based file row of data row k.
struct NumericCsv {
    std::vector<std::string> header;
    std::vector<std::vector<double>> columns;
    std::vector<std::size_t> file_row;
    std::size_t header_row = 1;
};
NumericCsv parse_numeric_csv(const std::string& text, const std::string& origin);
std::string read_text_file(const std::string& path);  // SignalCsvError if it cannot be read

// Parses CSV text. `origin` names the source in error messages.
SignalTable parse_signal_csv(const std::string& text, const std::string& origin,
                             const SignalCsvOptions& opt = SignalCsvOptions());
SignalTable read_signal_csv(const std::string& path, const SignalCsvOptions& opt = SignalCsvOptions());

// Writes `table` with a `t` column first, %.17g (round-trips exactly).
// Throws SignalCsvError if the columns do not all have size() rows or a
// value is not finite.
void write_signal_csv(const std::string& path, const SignalTable& table);
std::string format_signal_csv(const SignalTable& table);

}  // namespace io
}  // namespace fracdesign
