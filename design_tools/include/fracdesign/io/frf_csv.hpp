// frf_csv.hpp - reader/writer for frequency-response CSV files.
//
// Format: one header row; the first column is the frequency, `f_hz` (Hz) or
// `w_rad_s` (rad/s); then the real and imaginary parts of the response in
// columns named `re` and `im` (other columns, e.g. a coherence, are kept
// but not used). Frequencies must be positive and strictly increasing; the
// cells follow the strict rules of signal_csv.hpp (NaN, ragged rows, missing
// values refused with row and column). A frequency column in other units
// (`f_khz`, `f`, `w_hz`, ...) is refused.
#pragma once
#include <complex>
#include <string>
#include <vector>

namespace fracdesign {
namespace io {

struct FrfTable {
    std::vector<double> w;                    // rad/s
    std::vector<std::complex<double>> G;      // response
};

FrfTable parse_frf_csv(const std::string& text, const std::string& origin);
FrfTable read_frf_csv(const std::string& path);
// Writes w_rad_s,re,im with %.17g; SignalCsvError on size mismatch or non-finite values.
void write_frf_csv(const std::string& path, const FrfTable& frf);

}  // namespace io
}  // namespace fracdesign
