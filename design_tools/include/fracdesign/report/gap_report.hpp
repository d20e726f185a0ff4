// gap_report.hpp - the self-contained HTML report of a gap diagnosis
// (inline SVG plots, no external resources).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "fracdesign/gap/diagnosis.hpp"

namespace fracdesign {
namespace report {

// `result` is gap::result_json(r); `command` the command line that made it.
std::string gap_report_html(const gap::GapResult& r, const nlohmann::json& result, const std::string& command);

}  // namespace report
}  // namespace fracdesign
