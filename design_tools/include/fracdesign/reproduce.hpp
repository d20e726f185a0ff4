// reproduce.hpp - registry of seed reproduction checks for `fracdesign reproduce`.
//
// A check recomputes a number the seeds print (or the corrected value the
// notes give) on the spot and compares it with the expected value. `got` is
// always computed when the check runs, never stored. Checks live in
// design_tools/src/reproduce/<topic>.cpp and register with a static
// CheckRegistrar; ids are the ones fixed by the issues (e.g. "wang.tableC1").
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace fracdesign {

struct CheckOutcome {
    std::vector<double> expected;  // one or more numbers
    std::vector<double> got;       // same length as expected
    double tol = 0.0;              // per-number tolerance
    bool relative = false;         // tol relative to |expected| (else absolute)
    std::string note;              // optional: units, the erratum applied, caveats
    // Pass when every |got-expected| <= tol (or tol*|expected|) and all finite.
    bool pass() const;
};

struct Check {
    std::string id;      // fixed id, e.g. "wang.table3.1.gl.n9"
    std::string source;  // seed file and table/equation, e.g. "seed 004 Table 3.1"
    std::function<CheckOutcome()> run;
};

std::vector<Check>& check_registry();

struct CheckRegistrar {
    explicit CheckRegistrar(Check c);
};

}  // namespace fracdesign
