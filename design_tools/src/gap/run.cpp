// run.cpp - the `fracdesign gap` pipeline behind one call (see run.hpp).
#include "fracdesign/gap/run.hpp"

#include "fracdesign/report/gap_report.hpp"

namespace fracdesign {
namespace gap {

GapRun run_diagnosis(const NominalModel& model, const Signals& data, const Signals* validate, const GapOptions& opt,
                     const std::string& command)
{
    GapRun run;
    run.result = diagnose(model, data, validate, opt);
    run.json = result_json(run.result);
    run.json["command"] = command;
    run.report_html = report::gap_report_html(run.result, run.json, command);
    return run;
}

}  // namespace gap
}  // namespace fracdesign
