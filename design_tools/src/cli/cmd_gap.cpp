// cmd_gap.cpp - `fracdesign gap`: the sim-to-real gap diagnosis (issue 10).
// Reads the nominal model and the record, runs the diagnosis, and writes
// DIR/result.json and DIR/report.html through a temporary directory that is
// renamed into place, so a failed run leaves nothing half-written.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "fracdesign/cli.hpp"
#include "fracdesign/gap/diagnosis.hpp"
#include "fracdesign/gap/run.hpp"

namespace fracdesign {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& s)
{
    std::vector<std::string> v;
    std::stringstream ss(s);
    std::string x;
    while (std::getline(ss, x, ','))
        if (!x.empty()) v.push_back(x);
    return v;
}

void write_atomically(const fs::path& dir, const std::vector<std::pair<std::string, std::string>>& files)
{
    const fs::path parent = fs::absolute(dir).parent_path();
    fs::create_directories(parent);
    std::string tmpl = (parent / ".gap-tmp-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a temporary directory in " + parent.string());
    const fs::path tmp(tmpl);
    try {
        for (const auto& f : files) {
            std::ofstream o(tmp / f.first, std::ios::binary);
            o << f.second;
            o.close();
            if (!o) throw std::runtime_error("cannot write " + (tmp / f.first).string());
        }
        fs::create_directories(dir);
        for (const auto& f : files) fs::rename(tmp / f.first, dir / f.first);
        fs::remove_all(tmp);
    } catch (...) {
        std::error_code ec;
        fs::remove_all(tmp, ec);
        throw;
    }
}

int run_gap(const std::vector<std::string>& argv)
{
    Args args(argv, {"json"});
    args.check_known({"model", "data", "validate", "inputs", "outputs", "out", "json", "effects", "holdout", "threads", "loop-feedback"});
    const std::string model_path = args.str("model"), data_path = args.str("data");
    const fs::path out = args.str("out", "gap_out");
    gap::GapOptions opt;
    opt.inputs = split(args.str("inputs", ""));
    opt.outputs = split(args.str("outputs", ""));
    opt.holdout = args.num("holdout", 0.3);
    opt.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    if (!(opt.holdout > 0 && opt.holdout < 1)) throw UsageError("--holdout must be in (0, 1)");
    // --threads: workers for the independent candidate fits (GapOptions::threads;
    // the result does not depend on it). 0, the default, is one per core.
    const double threads = args.num("threads", 0);
    if (!(threads >= 0 && threads <= 256 && threads == std::floor(threads)))
        throw UsageError("--threads must be a whole number in 0..256 (0: one per core), got " + args.str("threads"));
    opt.threads = int(threads);
    // --loop-feedback: what the replayed controller of a closed-loop nominal
    // reads (GapOptions::loop_feedback, docs/gap.md "Loop feedback").
    try {
        opt.loop_feedback = gap::loop_feedback_from_name(args.str("loop-feedback", "auto"));
    } catch (const std::invalid_argument& ex) {
        throw UsageError(ex.what());
    }
    if (args.has("effects")) {
        opt.effects.clear();
        for (const std::string& e : split(args.str("effects"))) {
            try {
                opt.effects.push_back(gap::effect_from_name(e));
            } catch (const std::invalid_argument& ex) {
                throw UsageError(ex.what());
            }
        }
    }
    const gap::Signals data = gap::load_signals(data_path);
    gap::Signals val;
    const bool has_val = args.has("validate");
    if (has_val) val = gap::load_signals(args.str("validate"));
    const gap::NominalModel model = gap::load_nominal_model(model_path, data.Ts, data.Ts * double(data.samples()));
    std::string cmd = command_program().empty() ? "fracdesign gap" : command_program();
    for (const std::string& a : argv) cmd += " " + a;
    const gap::GapRun run = gap::run_diagnosis(model, data, has_val ? &val : nullptr, opt, cmd);
    const gap::GapResult& r = run.result;
    nlohmann::json j = run.json;  // the summary reads it with operator[] (keys it lacks read as null)
    write_atomically(out, {{"result.json", j.dump(2) + "\n"}, {"report.html", run.report_html}});

    if (args.has("json")) {
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    char b[256];
    std::cout << "gap diagnosis of " << r.model_name << " on " << data_path << "\n  held out: " << r.eval_source << "\n";
    if (!r.loop_feedback.empty()) std::cout << "  loop: " << r.loop_feedback_note << "\n";
    for (size_t c = 0; c < r.outputs.size(); ++c) {
        std::snprintf(b, sizeof b, "  %-20s nrmse before %.4g  after %.4g\n", r.outputs[c].c_str(), r.gap_before[c],
                      c < r.verdict.gap_after.size() ? r.verdict.gap_after[c] : r.gap_before[c]);
        std::cout << b;
    }
    if (!r.bands.empty()) {
        size_t bmax = 0;
        for (size_t i = 0; i < r.bands.size(); ++i)
            if (r.bands[i][2] > r.bands[bmax][2]) bmax = i;
        std::snprintf(b, sizeof b, "  where: %.0f %% of the residual energy in %g-%g Hz; %zu flagged time windows\n",
                      100 * r.bands[bmax][2], r.bands[bmax][0], r.bands[bmax][1], r.windows.size());
        std::cout << b;
    }
    std::cout << "  candidates (best first):\n";
    for (size_t i = 0; i < j["candidates"].size() && i < 6; ++i) {
        const auto& c = j["candidates"][i];
        const std::string name = c["effect"].get<std::string>() + gap::site_phrase(c["effect"], c["site"], c.value("coupling", ""));
        std::snprintf(b, sizeof b, "    %-36s shrink %6.1f %%  score %7.3f\n", name.c_str(), 100 * c["shrink"].get<double>(),
                      c["score"].get<double>());
        std::cout << b;
    }
    std::string v;
    for (size_t i = 0; i < j["verdict"]["effects"].size(); ++i)
        v += (v.empty() ? "" : " + ") + j["verdict"]["effects"][i].get<std::string>() +
             gap::site_phrase(j["verdict"]["effects"][i], j["verdict"]["sites"][i], j["verdict"]["couplings"][i].get<std::string>());
    std::snprintf(b, sizeof b, "  verdict: %s (held-out gap %.4g -> %.4g, shrink %.1f %%)\n", v.c_str(),
                  r.gap_before_total, r.verdict.gap, 100 * r.verdict.shrink);
    std::cout << b;
    const auto& vj = j["verdict"];
    for (auto it = vj["params"].begin(); it != vj["params"].end(); ++it) {
        const auto& sd = vj["params_std"][it.key()];
        const std::string unit = vj["params_unit"].value(it.key(), std::string());
        std::cout << "    " << it.key() << " = " << it.value() << (unit.empty() || unit == "1" ? "" : " " + unit);
        if (vj["unidentified"].contains(it.key()))
            std::cout << "  (not identified by this record: " << vj["unidentified"][it.key()].get<std::string>() << ")";
        else if (!sd.is_null())
            std::cout << " +- " << sd.dump();
        std::cout << "\n";
    }
    const auto& cf = vj["confidence"];
    std::cout << "  status: " << cf["status"].get<std::string>() << ": " << cf["explanation"].get<std::string>() << "\n";
    if (!cf["runner_up"].get<std::string>().empty()) {
        std::snprintf(b, sizeof b, "  confidence: score margin %.3f to the runner-up %s\n",
                      cf["margin"].is_null() ? NAN : cf["margin"].get<double>(), cf["runner_up"].get<std::string>().c_str());
        std::cout << b;
    }
    for (const auto& l : cf["look_alikes"])
        std::cout << "  cannot tell " << cf["first"].get<std::string>() << " from " << l["effect"].get<std::string>()
                  << " on this record: " << l["experiment"].get<std::string>() << "\n";
    std::cout << "  wrote " << (out / "result.json").string() << " and " << (out / "report.html").string() << "\n";
    return 0;
}

CommandRegistrar reg({"gap", "diagnose the sim-to-real gap: where, which unmodelled effect, how far it shrinks",
                      "usage: fracdesign gap --model nominal.json --data run.csv [--validate other.csv]\n"
                      "                      [--inputs u1,..] [--outputs y1,..] [--out DIR] [--json]\n"
                      "                      [--effects e1,e2,..] [--holdout 0.3] [--threads N]\n"
                      "                      [--loop-feedback auto|model|measured]\n\n"
                      "Replays the nominal model (a \"frac.model\" state space; closed loop when its\n"
                      "gap.closed_loop section gives the controller) on the recorded data, locates the\n"
                      "residual (output, frequency band, nominal modes, time windows with the\n"
                      "operating condition), fits every candidate effect with Ceres on the fit part\n"
                      "and ranks them by the held-out gap they remove (score = shrink - 0.005 per\n"
                      "fitted parameter), then adds effects by forward selection while the held-out\n"
                      "gap falls by >= 5 %. Without --validate the last --holdout fraction (30 %) of\n"
                      "the record is held out and never fitted. --threads N fits the independent\n"
                      "candidates on N workers (default 0: one per core; the result does not\n"
                      "depend on it). The verdict's status says whether the gap is at the stated\n"
                      "noise floor, explained, partly explained or unexplained.\n"
                      "Closed loop, the replayed controller reads the model's outputs (model); when\n"
                      "that does not explain the gap and the misfit is structured, auto (the default)\n"
                      "diagnoses again with the controller reading the record's measured outputs\n"
                      "(measured: the plant replayed on the command the machine got, so a limit cycle\n"
                      "keeps its phase), refits the closed loop also from that pass's effects (kept\n"
                      "when it scores higher), and, when the closed loop still names no effect or\n"
                      "one removing less than half the gap, keeps the measured pass when it explains\n"
                      "the gap with every parameter identified (and, after a weak effect without\n"
                      "look-alikes, names the same effects).\n\n"
                      "Effects: input_delay output_delay coulomb_friction viscous_friction\n"
                      "  stribeck_friction backlash deadzone saturation fractional_damping\n"
                      "  unmodelled_mode gain_error sensor_offset quantization mode_shift (and none).\n"
                      "  With a gap.coupling section (a spring inside the plant, e.g. a gear), backlash\n"
                      "  and fractional_damping are also fitted in that spring; mode_shift is fitted at\n"
                      "  each resonant mode of the plant; unmodelled_mode in series at the force\n"
                      "  input, at the outputs and in each compared sensor's reading (a sensor on a\n"
                      "  compliant mount); the best site is kept.\n\n"
                      "Writes DIR/result.json (schema frac.gap v1) and DIR/report.html (default DIR:\n"
                      "gap_out); --json prints result.json. See docs/gap.md.\n",
                      run_gap});

}  // namespace
}  // namespace fracdesign
