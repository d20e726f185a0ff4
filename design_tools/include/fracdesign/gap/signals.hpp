// signals.hpp - a uniformly sampled multichannel record for the gap diagnosis.
//
// The gap diagnosis reads recorded data through load_signals() only, so the
// file reader behind it can be swapped in one place.
#pragma once
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace fracdesign {
namespace gap {

struct Signals {
    std::string source;               // file the record came from
    std::vector<std::string> names;   // signal names, without the time column
    double Ts = 0.0;                  // sample time, s
    double t0 = 0.0;                  // first time stamp, s
    Eigen::MatrixXd values;           // samples x names.size()

    Eigen::Index samples() const { return values.rows(); }
    bool has(const std::string& name) const;
    // Column `name`; std::runtime_error naming the file and the signal if absent.
    Eigen::VectorXd col(const std::string& name) const;
    // First `n` samples starting at `first` (a held-out split).
    Signals slice(Eigen::Index first, Eigen::Index n) const;
};

// Reads a signal CSV (first column `t` in seconds, then named signals) with the
// project's strict reader; its errors (ragged rows, NaN/Inf, non-uniform or
// non-increasing time, ...) name the file, row and column.
Signals load_signals(const std::string& path);
// The same from signal-CSV text, with the same checks and messages (they name
// `origin` where load_signals names the file); the Python package's DataFrames.
Signals signals_from_csv_text(const std::string& text, const std::string& origin);

}  // namespace gap
}  // namespace fracdesign
