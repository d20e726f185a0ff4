// bind_gap.cpp - model documents and the gap diagnosis for fracarm (issue 20).
//
// Documents cross the boundary as JSON text, so Python sees exactly the
// document the CLI reads and writes. The gap diagnosis goes through
// gap::run_diagnosis (fracdesign/gap/run.hpp), the pipeline of
// `fracdesign gap`; records are read by the CLI's strict reader (a path) or
// its parser (CSV text of a DataFrame), so every error message is the CLI's.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "fracdesign/gap/nominal.hpp"
#include "fracdesign/gap/run.hpp"
#include "fracdesign/gap/signals.hpp"
#include "fracdesign/model_json.hpp"

namespace py = pybind11;
using namespace fracdesign;

namespace {

// A record given as {"path": p} or {"text": csv, "origin": name}.
gap::Signals record(const py::dict& d)
{
    if (d.contains("path")) return gap::load_signals(d["path"].cast<std::string>());
    return gap::signals_from_csv_text(d["text"].cast<std::string>(), d["origin"].cast<std::string>());
}

py::tuple diagnose(const py::dict& model, const py::dict& data, const py::object& validate, const py::dict& options,
                   const std::string& command)
{
    gap::GapOptions opt;
    if (options.contains("inputs")) opt.inputs = options["inputs"].cast<std::vector<std::string>>();
    if (options.contains("outputs")) opt.outputs = options["outputs"].cast<std::vector<std::string>>();
    if (options.contains("holdout")) opt.holdout = options["holdout"].cast<double>();
    if (!(opt.holdout > 0 && opt.holdout < 1)) throw py::value_error("--holdout must be in (0, 1)");
    if (options.contains("threads")) opt.threads = options["threads"].cast<int>();
    if (opt.threads < 0) throw py::value_error("threads must be >= 0 (0: one per core)");
    if (options.contains("loop_feedback")) {
        try {
            opt.loop_feedback = gap::loop_feedback_from_name(options["loop_feedback"].cast<std::string>());
        } catch (const std::invalid_argument& ex) {
            throw py::value_error(ex.what());
        }
    }
    if (options.contains("effects")) {
        opt.effects.clear();
        for (const std::string& e : options["effects"].cast<std::vector<std::string>>()) opt.effects.push_back(gap::effect_from_name(e));
    }
    const gap::Signals d = record(data);
    gap::Signals v;
    const bool has_val = !validate.is_none();
    if (has_val) v = record(validate.cast<py::dict>());
    gap::GapRun run;
    {
        const gap::NominalModel nom = model.contains("path")
                                          ? gap::load_nominal_model(model["path"].cast<std::string>(), d.Ts, d.Ts * double(d.samples()))
                                          : gap::nominal_from_json(nlohmann::json::parse(model["text"].cast<std::string>()), d.Ts,
                                                                   ".", d.Ts * double(d.samples()));
        py::gil_scoped_release nogil;
        run = gap::run_diagnosis(nom, d, has_val ? &v : nullptr, opt, command);
    }
    return py::make_tuple(run.json.dump(2) + "\n", run.report_html);
}

// Validates a model document; returns its kind.
std::string model_check(const std::string& text) { return model_kind(model_from_json(nlohmann::json::parse(text))); }

// The document of a model file as fracdesign reads it (errors name the file).
std::string model_read(const std::string& path) { return model_to_json(read_model_file(path)).dump(); }

// The LTI model of a rational document: (A, B, C, D, Ts, inputs, outputs, states).
py::tuple model_lti(const std::string& text)
{
    const StateSpace ss = model_state_space(model_from_json(nlohmann::json::parse(text)));
    auto mat = [](const Eigen::MatrixXd& M) {
        py::array_t<double> a({py::ssize_t(M.rows()), py::ssize_t(M.cols())});
        for (Eigen::Index i = 0; i < M.rows(); ++i)
            for (Eigen::Index j = 0; j < M.cols(); ++j) a.mutable_at(i, j) = M(i, j);
        return a;
    };
    return py::make_tuple(mat(ss.A), mat(ss.B), mat(ss.C), mat(ss.D), ss.Ts, ss.inputs, ss.outputs, ss.states);
}

}  // namespace

void bind_gap(py::module_& m)
{
    m.def("gap_diagnose", &diagnose, py::arg("model"), py::arg("data"), py::arg("validate"), py::arg("options"),
          py::arg("command"), "gap::run_diagnosis: returns (result.json text, report.html text).");
    m.def("gap_effect_names", [] {
        std::vector<std::string> v;
        for (gap::Effect e : gap::all_effects()) v.push_back(gap::effect_name(e));
        return v;
    });
    m.def("model_check", &model_check);
    m.def("model_read", &model_read);
    m.def("model_lti", &model_lti);
}
