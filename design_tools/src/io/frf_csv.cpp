// frf_csv.cpp - frequency-response CSV files (see frf_csv.hpp).
#include "fracdesign/io/frf_csv.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

#include "fracdesign/io/signal_csv.hpp"

namespace fracdesign {
namespace io {

FrfTable parse_frf_csv(const std::string& text, const std::string& origin)
{
    const NumericCsv raw = parse_numeric_csv(text, origin);
    const std::string& f0 = raw.header[0];
    const std::string where = origin + ": row " + std::to_string(raw.header_row) + ", column '" + f0 + "': ";
    double scale;
    if (f0 == "f_hz") scale = 2.0 * M_PI;
    else if (f0 == "w_rad_s") scale = 1.0;
    else throw SignalCsvError(where + "first column must be the frequency 'f_hz' (Hz) or 'w_rad_s' (rad/s)");
    std::size_t jre = 0, jim = 0;
    for (std::size_t j = 1; j < raw.header.size(); ++j) {
        if (raw.header[j] == "re") jre = j;
        if (raw.header[j] == "im") jim = j;
    }
    if (!jre || !jim) throw SignalCsvError(origin + ": missing column 're' or 'im' (the response's real and imaginary parts)");
    const std::size_t n = raw.columns[0].size();
    if (n < 2) throw SignalCsvError(origin + ": too short: " + std::to_string(n) + " frequency rows");
    FrfTable t;
    for (std::size_t k = 0; k < n; ++k) {
        const double w = scale * raw.columns[0][k];
        if (!(w > 0.0) || (k && !(w > t.w.back())))
            throw SignalCsvError(origin + ": row " + std::to_string(raw.file_row[k]) + ", column '" + f0 +
                                 "': frequencies must be positive and strictly increasing");
        t.w.push_back(w);
        t.G.emplace_back(raw.columns[jre][k], raw.columns[jim][k]);
    }
    return t;
}

FrfTable read_frf_csv(const std::string& path) { return parse_frf_csv(read_text_file(path), path); }

void write_frf_csv(const std::string& path, const FrfTable& frf)
{
    if (frf.w.size() != frf.G.size()) throw SignalCsvError("FRF table: w and G sizes differ");
    std::string out = "w_rad_s,re,im\n";
    char buf[96];
    for (std::size_t k = 0; k < frf.w.size(); ++k) {
        if (!std::isfinite(frf.w[k]) || !std::isfinite(frf.G[k].real()) || !std::isfinite(frf.G[k].imag()))
            throw SignalCsvError("FRF table: non-finite value at row " + std::to_string(k));
        std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g\n", frf.w[k], frf.G[k].real(), frf.G[k].imag());
        out += buf;
    }
    std::ofstream f(path, std::ios::binary);
    if (!f) throw SignalCsvError(path + ": cannot open for writing");
    f << out;
    if (!f) throw SignalCsvError(path + ": write failed");
}

}  // namespace io
}  // namespace fracdesign
