// cmd_reproduce.cpp - `fracdesign reproduce`: runs every registered seed
// reproduction check, prints id, source, expected, got, tol, pass per check,
// then totals. Exit status 1 if any check fails.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fracdesign/cli.hpp"
#include "fracdesign/reproduce.hpp"

namespace fracdesign {
namespace {

std::string fmt_list(const std::vector<double>& v)
{
    std::string s;
    char buf[64];
    for (size_t i = 0; i < v.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%s%.10g", i ? ", " : "", v[i]);
        s += buf;
    }
    return v.size() > 1 ? "[" + s + "]" : s;
}

int run_reproduce(const std::vector<std::string>& argv)
{
    Args args(argv, {"json"});
    args.check_known({"json", "only"});
    const std::string only = args.str("only", "");
    const bool json = args.has("json");
    nlohmann::json out = {{"schema", "frac.reproduce"}, {"version", 1}, {"checks", nlohmann::json::array()}};
    int n = 0, failed = 0;
    for (const Check& c : check_registry()) {
        if (!only.empty() && c.id.compare(0, only.size(), only) != 0) continue;
        CheckOutcome r;
        std::string error;
        try {
            r = c.run();
        } catch (const std::exception& e) {
            error = e.what();
        }
        const bool pass = error.empty() && r.pass();
        ++n;
        failed += pass ? 0 : 1;
        if (json) {
            nlohmann::json j = {{"id", c.id}, {"source", c.source}, {"expected", r.expected}, {"got", r.got},
                                {"tol", r.tol}, {"tol_kind", r.relative ? "relative" : "absolute"}, {"pass", pass}};
            if (!r.note.empty()) j["note"] = r.note;
            if (!error.empty()) j["error"] = error;
            out["checks"].push_back(j);
        } else {
            std::cout << (pass ? "PASS " : "FAIL ") << c.id << "  (" << c.source << ")\n"
                      << "     expected " << fmt_list(r.expected) << "  got " << fmt_list(r.got) << "  tol "
                      << r.tol << (r.relative ? " rel" : " abs") << "\n";
            if (!r.note.empty()) std::cout << "     note: " << r.note << "\n";
            if (!error.empty()) std::cout << "     error: " << error << "\n";
        }
    }
    if (n == 0 && !only.empty()) throw UsageError("no check id starts with '" + only + "'");
    if (json) {
        out["total"] = n;
        out["passed"] = n - failed;
        out["failed"] = failed;
        std::cout << out.dump(2) << "\n";
    } else {
        std::cout << "\n" << n - failed << " passed, " << failed << " failed\n";
    }
    return failed ? 1 : 0;
}

CommandRegistrar reg({"reproduce", "recompute every number the project reproduces from the seeds",
                      "usage: fracdesign reproduce [--only PREFIX] [--json]\n\n"
                      "Runs every seed reproduction check (or those whose id starts with PREFIX) and\n"
                      "prints per check: id, source, expected, got, tol, pass; then totals.\n"
                      "`got` is computed on the spot. Exit status 1 if any check fails.\n",
                      run_reproduce});

}  // namespace
}  // namespace fracdesign
