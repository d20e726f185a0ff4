// bind_bench.cpp - gap-bench's scoring for shards run apart (issue 20).
//
// fracarm.fleet runs each gap-bench case as its own task (`gap-bench
// --replay ID`, the bench's one-case entry) and scores the gathered
// cases here with the bench's own score_bench, into the "score" and
// "confusion" sections run_bench writes, so a sharded bench and the
// single-machine bench report the same figures for the same seed.
#include <pybind11/pybind11.h>

#include <string>

#include "fracbench/gap_bench.hpp"

namespace py = pybind11;
using namespace fracdesign;

namespace {

// cases: the JSON array of per-case entries of gap-bench --json; returns the
// bench document's score sections (fracbench::score_json) as text.
std::string score(const std::string& cases_text)
{
    std::vector<fracbench::CaseOutcome> v;
    for (const auto& c : nlohmann::json::parse(cases_text)) v.push_back(fracbench::outcome_from_json(c));
    return fracbench::score_json(fracbench::score_bench(v)).dump();
}

}  // namespace

void bind_bench(py::module_& m) { m.def("bench_score", &score, "The bench document's score sections (fracbench::score_json) of gap-bench case entries."); }
