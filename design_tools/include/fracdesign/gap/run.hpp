// run.hpp - the whole `fracdesign gap` pipeline behind one call, for callers
// other than the CLI (the Python package fracarm, issue 20): nominal model +
// record(s) + options -> result.json document and report.html, exactly as
// cmd_gap.cpp assembles them (gap::diagnose, gap::result_json with the
// "command" key, report::gap_report_html).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "fracdesign/gap/diagnosis.hpp"

namespace fracdesign {
namespace gap {

struct GapRun {
    GapResult result;
    nlohmann::json json;      // result.json: result_json(result) plus "command"
    std::string report_html;  // report.html
};

// Diagnoses `data` (and `validate`, may be null) against `model`; `command`
// is recorded in result.json and the report as the command that made them.
GapRun run_diagnosis(const NominalModel& model, const Signals& data, const Signals* validate, const GapOptions& opt,
                     const std::string& command);

}  // namespace gap
}  // namespace fracdesign
