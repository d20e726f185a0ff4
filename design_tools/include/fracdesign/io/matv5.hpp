// matv5.hpp - reader for MATLAB level-5 MAT-files (the format of `save -v7`).
//
// Enough for the EMPS benchmark files and similar logs: top-level numeric
// matrices (any MATLAB numeric class, stored as any numeric mi* type, real
// only, 2-D), optionally zlib-compressed (miCOMPRESSED). Values are returned
// as doubles in column-major order. Cell arrays, structs, sparse, complex and
// character arrays are skipped (listed in `skipped`); a truncated or corrupt
// file is refused with a MatError naming the file and the variable.
// Layout: MATLAB "MAT-File Format" (The MathWorks, version 5 and later),
// 128-byte header, then tagged data elements (8-byte tag, 8-byte alignment;
// small-data-element format with a 4-byte tag for <= 4 bytes).
#pragma once
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace fracdesign {
namespace io {

struct MatError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct MatMatrix {
    std::size_t rows = 0, cols = 0;
    std::vector<double> data;  // column-major, rows*cols
    std::string mclass;        // "double", "uint8", ...
    double scalar() const;     // MatError unless 1x1
};

struct MatFile {
    std::string header;  // the 116-byte descriptive text, trimmed
    std::map<std::string, MatMatrix> vars;
    std::vector<std::string> skipped;  // variables of unsupported kinds
    // The variable, MatError naming the file's variables if absent.
    const MatMatrix& at(const std::string& name) const;
    // A row or column vector as a flat vector (MatError if not a vector).
    std::vector<double> vector(const std::string& name) const;
    std::string origin;
};

MatFile read_mat_v5(const std::string& path);
MatFile parse_mat_v5(const std::vector<unsigned char>& bytes, const std::string& origin);

}  // namespace io
}  // namespace fracdesign
