// bind_design.cpp - the table-producing verbs of fracdesign (model, tune,
// lqg, armctrl, and the rest of the registry) run in-process (issue 20).
//
// The module links the CLI's own subcommand sources (design_tools/src/cli,
// python/CMakeLists.txt), so a verb called from Python is the registered
// Command the fracdesign executable runs: same option parsing, same checks,
// same files written. Its stdout is captured; its errors come back with the
// CLI's exit status and its stderr line ("fracdesign <verb>: ..."), as
// main.cpp prints them.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "fracdesign/cli.hpp"

namespace py = pybind11;

namespace {

// Restores std::cout's buffer on every exit path.
struct CoutCapture {
    std::ostringstream buf;
    std::streambuf* old;
    CoutCapture() : old(std::cout.rdbuf(buf.rdbuf())) {}
    ~CoutCapture() { std::cout.rdbuf(old); }
};

// (exit status, stdout, stderr message) of `fracdesign <name> <args...>`.
py::tuple run_command(const std::string& name, const std::vector<std::string>& args)
{
    auto& reg = fracdesign::command_registry();
    auto it = reg.find(name);
    if (it == reg.end()) return py::make_tuple(2, std::string(), "fracdesign: unknown command '" + name + "'");
    int status = 0;
    std::string err, out;
    {
        py::gil_scoped_release nogil;
        CoutCapture cap;
        try {
            status = it->second.run(args);
        } catch (const fracdesign::UsageError& e) {
            status = 2;
            err = "fracdesign " + name + ": " + e.what();
        } catch (const std::exception& e) {
            status = 1;
            err = "fracdesign " + name + ": error: " + e.what();
        }
        std::cout.flush();
        out = cap.buf.str();
    }
    return py::make_tuple(status, out, err);
}

}  // namespace

void bind_design(py::module_& m)
{
    m.def("run_command", &run_command, py::arg("name"), py::arg("args"),
          "Runs a fracdesign subcommand in-process: (status, stdout, stderr message).");
    m.def("command_names", [] {
        std::vector<std::string> v;
        for (const auto& kv : fracdesign::command_registry()) v.push_back(kv.first);
        return v;
    });
    m.def("command_help", [](const std::string& name) {
        auto& reg = fracdesign::command_registry();
        auto it = reg.find(name);
        if (it == reg.end()) throw py::value_error("fracdesign: unknown command '" + name + "'");
        return it->second.help;
    });
}
