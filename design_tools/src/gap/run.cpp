// run.cpp - the `fracdesign gap` pipeline behind one call (see run.hpp).
#include "fracdesign/gap/run.hpp"

#include "fracdesign/io/signal_csv.hpp"
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

Signals signals_from_csv_text(const std::string& text, const std::string& origin)
{
    // The options load_signals() reads files with: at least 3 rows.
    io::SignalCsvOptions opt;
    opt.min_rows = 3;
    const io::SignalTable tab = io::parse_signal_csv(text, origin, opt);
    Signals s;
    s.source = origin;
    s.names = tab.names;
    s.Ts = tab.dt;
    s.t0 = tab.t.front();
    s.values.resize(Eigen::Index(tab.size()), Eigen::Index(tab.names.size()));
    for (size_t j = 0; j < tab.columns.size(); ++j)
        s.values.col(Eigen::Index(j)) = Eigen::Map<const Eigen::VectorXd>(tab.columns[j].data(), Eigen::Index(tab.size()));
    return s;
}

}  // namespace gap
}  // namespace fracdesign
