// bind_bench.cpp - gap-bench's scoring for shards run apart (issue 20).
//
// fracarm.fleet runs each gap-bench case as its own task (`gap-bench
// --replay ID`, the bench's one-case entry) and scores the gathered
// cases here with the bench's own score_bench, into the "score" and
// "confusion" sections run_bench writes, so a sharded bench and the
// single-machine bench report the same figures for the same seed.
#include <pybind11/pybind11.h>

#include <cmath>
#include <limits>
#include <string>

#include "fracbench/gap_bench.hpp"

namespace py = pybind11;
using namespace fracdesign;

namespace {

double num(const nlohmann::json& x) { return x.is_null() ? std::numeric_limits<double>::quiet_NaN() : x.get<double>(); }
nlohmann::json out(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

// cases: the JSON array of per-case entries of gap-bench --json ("truth",
// "verdict", "shrink"); returns {"score": ..., "confusion": ...} as text.
std::string score(const std::string& cases_text)
{
    const nlohmann::json cases = nlohmann::json::parse(cases_text);
    std::vector<fracbench::CaseOutcome> v;
    for (const auto& c : cases) {
        fracbench::CaseOutcome o;
        for (const auto& t : c.at("truth")) {
            gap::TruthEffect te;
            te.effect = t.at("effect").get<std::string>();
            for (auto it = t.at("params").begin(); it != t.at("params").end(); ++it)
                te.params.push_back({it.key(), num(it.value())});
            o.truth.push_back(te);
        }
        for (const auto& e : c.at("verdict")) {
            o.verdict.push_back(e.at("effect").get<std::string>());
            std::map<std::string, double> p;
            for (auto it = e.at("params").begin(); it != e.at("params").end(); ++it) p[it.key()] = num(it.value());
            o.verdict_params.push_back(p);
        }
        o.shrink = num(c.at("shrink"));
        v.push_back(o);
    }
    const fracbench::BenchScore S = fracbench::score_bench(v);
    nlohmann::json conf = nlohmann::json::array();
    for (const auto& row : S.confusion) conf.push_back(row);
    const nlohmann::json j = {{"score",
                               {{"cases", S.cases},
                                {"correct", S.correct},
                                {"accuracy", out(S.accuracy)},
                                {"two_effect_cases", S.two_effect_cases},
                                {"two_effect_correct", S.two_effect_correct},
                                {"median_param_error", out(S.median_param_error)},
                                {"param_cases", S.param_cases},
                                {"median_shrink_found", out(S.median_shrink_found)},
                                {"found_cases", S.found_cases}}},
                              {"confusion", {{"labels", S.labels}, {"rows_truth_cols_top1", conf}}}};
    return j.dump();
}

}  // namespace

void bind_bench(py::module_& m) { m.def("bench_score", &score, "fracbench::score_bench over gap-bench case entries."); }
