// gap_report.cpp - HTML report of the gap diagnosis (see gap_report.hpp).
#include "fracdesign/report/gap_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "fracdesign/report/svg.hpp"
#include "fracdesign/welch.hpp"

namespace fracdesign {
namespace report {

namespace {

std::string g4(double v)
{
    if (!std::isfinite(v)) return "n/a";
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return b;
}

std::vector<double> vec(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

// Residual spectral density by the project's Welch estimator (Hamming,
// half-overlapping segments, mean removed), with segments long enough to
// resolve the lowest band that holds at least 1 % of the nominal residual
// energy (r.bands): the resolution fs/nperseg is at most a tenth of that
// band's upper edge, so the plot covers the bands the residual lives in.
void residual_psd(const Eigen::VectorXd& x, double Ts, const std::vector<std::vector<double>>& bands,
                  std::vector<double>& f, std::vector<double>& p)
{
    double f_need = 0.5 / Ts;
    for (const auto& b : bands)
        if (b[2] >= 0.01) {
            f_need = std::min(f_need, 0.1 * b[1]);
            break;
        }
    Eigen::Index seg = 16;
    while (seg < x.size() && 1.0 / (double(seg) * Ts) > f_need) seg *= 2;
    WelchOptions o;
    o.fs = 1.0 / Ts;
    o.nperseg = int(std::min<Eigen::Index>(seg, x.size()));
    o.noverlap = o.nperseg / 2;
    o.detrend_mean = true;
    const WelchPsd w = welch_psd(std::vector<double>(x.data(), x.data() + x.size()), o);
    f.assign(w.f.begin() + 1, w.f.end());
    p.assign(w.P.begin() + 1, w.P.end());
}

// "name [unit]" for an axis.
std::string with_unit(const gap::GapResult& r, size_t c)
{
    return r.outputs[c] + (c < r.units.y.size() ? " " + (r.units.y[c].front() == '[' ? r.units.y[c] : "[" + r.units.y[c] + "]") : "");
}

}  // namespace

std::string gap_report_html(const gap::GapResult& r, const nlohmann::json& j, const std::string& command)
{
    std::ostringstream o;
    o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>gap diagnosis: " << html_escape(r.model_name)
      << "</title>\n<style>body{font-family:sans-serif;max-width:960px;margin:auto;padding:1em}"
         "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}"
         "th{background:#f0f0f0}td.l{text-align:left}code{background:#f6f6f6}</style></head><body>\n";
    o << "<h1>Sim-to-real gap diagnosis</h1>\n";
    o << "<p>Model <b>" << html_escape(r.model_name) << "</b>; fitted on <code>" << html_escape(r.data_source)
      << "</code> (" << r.fit_samples << " samples); held out: <code>" << html_escape(r.eval_source) << "</code> ("
      << r.eval_samples << " samples); Ts = " << g4(r.Ts) << " s. Command: <code>" << html_escape(command) << "</code></p>\n";
    if (!r.loop_feedback.empty()) o << "<p>Loop: " << html_escape(r.loop_feedback_note) << ".</p>\n";
    std::string verdict;
    for (const auto& e : j["verdict"]["effects"]) verdict += (verdict.empty() ? "" : " + ") + e.get<std::string>();
    o << "<h2>Verdict: " << html_escape(verdict) << "</h2>\n<p>Held-out gap (sqrt of the mean nrmse&sup2; over outputs) "
      << g4(r.gap_before_total) << " &rarr; " << g4(r.verdict.gap) << ", shrink " << g4(100 * r.verdict.shrink)
      << " %.</p>\n";
    o << "<table><tr><th>output</th><th>nrmse before</th><th>nrmse after</th></tr>\n";
    for (size_t c = 0; c < r.outputs.size(); ++c)
        o << "<tr><td class=l>" << html_escape(r.outputs[c]) << "</td><td>" << g4(r.gap_before[c]) << "</td><td>"
          << g4(c < r.verdict.gap_after.size() ? r.verdict.gap_after[c] : NAN) << "</td></tr>\n";
    o << "</table>\n<p>Verdict parameters (&plusmn; 1 std from the Gauss-Newton covariance; a parameter the record "
         "does not identify is marked and its std not shown):</p><table><tr><th>parameter</th><th>value</th><th>unit</th><th>std</th><th class=l>identified</th></tr>\n";
    const auto& vj = j["verdict"];
    for (auto it = vj["params"].begin(); it != vj["params"].end(); ++it) {
        const bool unid = vj["unidentified"].contains(it.key());
        const auto& sd = vj["params_std"][it.key()];
        o << "<tr><td class=l>" << html_escape(it.key()) << "</td><td>" << (it.value().is_null() ? "n/a" : g4(it.value().get<double>()))
          << "</td><td class=l>" << html_escape(vj["params_unit"].value(it.key(), std::string())) << "</td><td>"
          << (unid || sd.is_null() ? "" : g4(sd.get<double>())) << "</td><td class=l>"
          << (unid ? "<b>no</b>: " + html_escape(vj["unidentified"][it.key()].get<std::string>()) : std::string("yes")) << "</td></tr>\n";
    }
    o << "</table>\n";
    const auto& cf = vj["confidence"];
    o << "<p>Status <b>" << html_escape(cf["status"].get<std::string>()) << "</b>: " << html_escape(cf["explanation"].get<std::string>())
      << ".</p>\n";
    if (!cf["runner_up"].get<std::string>().empty())
        o << "<p>Confidence: score margin " << g4(cf["margin"].is_null() ? NAN : cf["margin"].get<double>()) << " to the runner-up <b>"
          << html_escape(cf["runner_up"].get<std::string>()) << "</b>.</p>\n";
    for (const auto& l : cf["look_alikes"])
        o << "<p><b>Cannot tell " << html_escape(cf["first"].get<std::string>()) << " from " << html_escape(l["effect"].get<std::string>())
          << "</b> on this record (held-out gap " << g4(l["gap_after_total"].is_null() ? NAN : l["gap_after_total"].get<double>())
          << "): " << html_escape(l["experiment"].get<std::string>()) << ".</p>\n";

    // Measured vs nominal vs augmented, held-out part.
    o << "<h2>Measured vs nominal vs augmented (held-out data)</h2>\n";
    const Eigen::Index a = r.eval_first, n = r.eval_samples;
    for (size_t c = 0; c < r.outputs.size(); ++c) {
        const std::vector<double> t = vec(r.t.segment(a, n));
        std::vector<Series> s = {{"measured", "#222", t, vec(r.measured.col(Eigen::Index(c)).segment(a, n))},
                                 {"nominal", "#1f77b4", t, vec(r.nominal.col(Eigen::Index(c)).segment(a, n))},
                                 {"augmented", "#d62728", t, vec(r.augmented.col(Eigen::Index(c)).segment(a, n))}};
        o << line_chart(r.outputs[c], "t [s]", with_unit(r, c), s);
        std::vector<Series> e = {
            {"nominal error", "#1f77b4", t, vec(r.measured.col(Eigen::Index(c)).segment(a, n) - r.nominal.col(Eigen::Index(c)).segment(a, n))},
            {"augmented error", "#d62728", t, vec(r.measured.col(Eigen::Index(c)).segment(a, n) - r.augmented.col(Eigen::Index(c)).segment(a, n))}};
        o << line_chart(r.outputs[c] + ": output error", "t [s]", "measured - model " + with_unit(r, c).substr(r.outputs[c].size() + 1), e);
    }

    // Residual spectra per band.
    o << "<h2>Residual by frequency band (held-out data)</h2>\n";
    std::vector<std::string> cats;
    for (const auto& b : r.bands) cats.push_back(g4(b[0]) + "-" + g4(b[1]) + " Hz");
    std::vector<std::string> labels;
    std::vector<std::vector<double>> vals;
    for (size_t c = 0; c < r.outputs.size(); ++c) {
        std::vector<double> before, after;
        for (size_t b = 0; b < r.band_nrmse_before.size(); ++b) {
            before.push_back(r.band_nrmse_before[b][c]);
            after.push_back(b < r.verdict.band_nrmse.size() ? r.verdict.band_nrmse[b][c] : NAN);
        }
        labels.push_back(r.outputs[c] + " nominal");
        vals.push_back(before);
        labels.push_back(r.outputs[c] + " augmented");
        vals.push_back(after);
    }
    o << bar_chart("band nrmse, nominal vs augmented", cats, labels, vals, {"#1f77b4", "#d62728", "#6baed6", "#ff9896", "#9ecae1", "#ffbb78"});
    {
        std::vector<double> share;
        for (const auto& b : r.bands) share.push_back(b[2]);
        o << bar_chart("share of the nominal residual energy per band (fit record)", cats, {"share"}, {share}, {"#555"});
    }
    for (size_t c = 0; c < r.outputs.size(); ++c) {
        std::vector<double> f0, p0, f1, p1;
        residual_psd(r.measured.col(Eigen::Index(c)).segment(a, n) - r.nominal.col(Eigen::Index(c)).segment(a, n), r.Ts, r.bands, f0, p0);
        residual_psd(r.measured.col(Eigen::Index(c)).segment(a, n) - r.augmented.col(Eigen::Index(c)).segment(a, n), r.Ts, r.bands, f1, p1);
        const std::string u = c < r.units.y.size() ? r.units.y[c] : "[" + r.outputs[c] + "]";
        o << line_chart(r.outputs[c] + ": residual spectrum", "f [Hz]", "PSD [(" + u + ")^2/Hz]",
                        {{"nominal", "#1f77b4", f0, p0}, {"augmented", "#d62728", f1, p1}}, {}, true, true);
    }
    if (!r.modes.empty()) {
        o << "<h3>Nominal modes against the measured spectrum</h3><table><tr><th>f [Hz]</th><th>&zeta;</th><th>residual share</th>"
             "<th>measured peak [Hz]</th><th>model peak [Hz]</th><th>peak ratio</th><th>flag</th></tr>\n";
        for (const auto& m : r.modes)
            o << "<tr><td>" << g4(m.f_hz) << "</td><td>" << g4(m.zeta) << "</td><td>" << g4(m.residual_share) << "</td><td>"
              << g4(m.measured_peak_hz) << "</td><td>" << g4(m.model_peak_hz) << "</td><td>" << g4(m.peak_ratio)
              << "</td><td class=l>" << m.flag << "</td></tr>\n";
        o << "</table>\n";
    }

    // Residual vs time with the flagged windows.
    o << "<h2>Nominal residual vs time (fit record) and flagged windows</h2>\n";
    std::vector<Shade> sh;
    for (const auto& w : r.windows) sh.push_back({w.t0, w.t1, w.condition});
    std::vector<Series> rs;
    const char* colors[] = {"#1f77b4", "#2ca02c", "#9467bd", "#8c564b"};
    for (size_t c = 0; c < r.outputs.size(); ++c)
        rs.push_back({r.outputs[c] + " / std", colors[c % 4], vec(r.where_t), vec(r.where_residual.col(Eigen::Index(c)))});
    o << line_chart("normalized nominal residual", "t [s]", "residual / std(output)", rs, sh);
    o << "<table><tr><th>t0 [s]</th><th>t1 [s]</th><th>rms</th><th>condition</th></tr>\n";
    for (const auto& w : r.windows)
        o << "<tr><td>" << g4(w.t0) << "</td><td>" << g4(w.t1) << "</td><td>" << g4(w.rms) << "</td><td class=l>"
          << html_escape(w.condition) << "</td></tr>\n";
    o << "</table>\n";

    // Candidates.
    o << "<h2>Candidates (best first)</h2>\n<p>score = shrink &minus; 0.005 &times; fitted parameters; shrink = 1 &minus; gap_after/gap_before on held-out data.</p>\n"
         "<table><tr><th>effect</th><th>shrink</th><th>score</th><th>gap after</th><th class=l>parameters</th></tr>\n";
    for (const auto& c : j["candidates"]) {
        std::string ps;
        for (auto it = c["params"].begin(); it != c["params"].end(); ++it) {
            const auto& sd = c["params_std"][it.key()];
            const bool unid = c.contains("unidentified") && c["unidentified"].contains(it.key());
            const std::string unit = c.contains("params_unit") ? c["params_unit"].value(it.key(), std::string()) : "";
            ps += it.key() + " = " + (it.value().is_null() ? "n/a" : g4(it.value().get<double>())) +
                  (unit.empty() || unit == "1" ? "" : " " + html_escape(unit)) +
                  (unid ? " (not identified)" : sd.is_null() ? "" : " &plusmn; " + g4(sd.get<double>())) + "; ";
        }
        o << "<tr><td class=l>" << html_escape(c["effect"].get<std::string>())
          << html_escape(gap::site_phrase(c["effect"].get<std::string>(), c.value("site", std::string()), c.value("coupling", std::string())))
          << "</td><td>"
          << g4(c["shrink"].is_null() ? NAN : c["shrink"].get<double>()) << "</td><td>"
          << g4(c["score"].is_null() ? NAN : c["score"].get<double>()) << "</td><td>"
          << g4(c["gap_after_total"].is_null() ? NAN : c["gap_after_total"].get<double>()) << "</td><td class=l>" << ps
          << "</td></tr>\n";
    }
    o << "</table>\n";
    if (!r.skipped.empty()) {
        o << "<p>Not tried:</p><ul>";
        for (const auto& s : r.skipped) o << "<li>" << html_escape(s) << "</li>";
        o << "</ul>\n";
    }
    o << "<p style=\"color:#777\">fracdesign gap, " << g4(r.seconds) << " s.</p></body></html>\n";
    return o.str();
}

}  // namespace report
}  // namespace fracdesign
