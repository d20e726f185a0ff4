// result_json.cpp - result.json of a diagnosis (schema frac.gap, version 1;
// see diagnosis.hpp, docs/gap.md).
#include <cmath>
#include <string>
#include <vector>

#include "stages.hpp"

namespace fracdesign {
namespace gap {

namespace {

nlohmann::json num(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json per_output(const std::vector<std::string>& outs, const std::vector<double>& v)
{
    nlohmann::json j = nlohmann::json::object();
    for (size_t i = 0; i < outs.size() && i < v.size(); ++i) j[outs[i]] = num(v[i]);
    return j;
}

nlohmann::json fit_json(const GapResult& R, const FitReport& f, const std::vector<std::pair<double, double>>& bands)
{
    nlohmann::json params = nlohmann::json::object(), sd = nlohmann::json::object(), units = nlohmann::json::object(),
                   unid = nlohmann::json::object(), unid_kind = nlohmann::json::object();
    std::vector<std::string> names, sites, couplings;
    for (size_t i = 0; i < f.effects.size(); ++i) {
        const EffectInstance& e = f.effects[i];
        sites.push_back(site_name(e.site));
        couplings.push_back(site_subject(R, e.site, e.coupling));
        const std::vector<ParamInfo> pn =
            descriptor(e.kind).params(R.outputs, units_at(R.units, e.site == Site::coupling ? e.coupling : -1), e.site);
        const std::string prefix = f.effects.size() > 1 ? effect_name(e.kind) + "." : "";
        for (size_t j = 0; j < pn.size(); ++j) {
            params[prefix + pn[j].name] = num(e.params[j]);
            sd[prefix + pn[j].name] = num(f.stddev[i][j]);
            units[prefix + pn[j].name] = pn[j].unit;
            if (i < f.identification.size() && j < f.identification[i].size() && !f.identification[i][j].identified()) {
                unid[prefix + pn[j].name] = f.identification[i][j].text;
                unid_kind[prefix + pn[j].name] = unidentified_name(f.identification[i][j].why);
            }
        }
        names.push_back(effect_name(e.kind));
    }
nlohmann::json bj = nlohmann::json::array();
    for (size_t b = 0; b < f.band_nrmse.size() && b < bands.size(); ++b)
        bj.push_back({{"band_hz", {bands[b].first, bands[b].second}}, {"nrmse", per_output(R.outputs, f.band_nrmse[b])}});
    nlohmann::json j = {{"params", params},         {"params_std", sd},     {"gap_after", per_output(R.outputs, f.gap_after)},
                        {"gap_after_total", num(f.gap)}, {"shrink", num(f.shrink)}, {"score", num(f.score)},
                        {"fitted_params", f.fitted_params}, {"bands", bj}, {"solver", f.solver},
                        {"params_unit", units}, {"unidentified", unid},
                        {"unidentified_kind", unid_kind}};
    if (names.empty()) {
        names.push_back("none");
        sites.push_back("");
        couplings.push_back("");
    }
    j["effects"] = names;
    j["sites"] = sites;
    j["couplings"] = couplings;  // the coupling's name for effects in a coupling, the nominal mode's for mode_shift, else ""

    return j;
}

}  // namespace

std::string site_subject(const GapResult& R, Site site, int index)
{
    const std::vector<std::string>* names =
        site == Site::coupling ? &R.coupling_names : site == Site::mode ? &R.mode_names : site == Site::sensor ? &R.outputs : nullptr;
    return names && index >= 0 && size_t(index) < names->size() ? (*names)[size_t(index)] : "";
}

nlohmann::json result_json(const GapResult& R)
{
    const auto bands = band_edges(R.Ts);
    nlohmann::json j;
    j["schema"] = "frac.gap";
    j["version"] = 1;
    j["metric"] = "nrmse";
    j["gap_before"] = per_output(R.outputs, R.gap_before);
    nlohmann::json bj = nlohmann::json::array(), wj = nlohmann::json::array(), mj = nlohmann::json::array();
    for (const auto& b : R.bands) bj.push_back({b[0], b[1], b[2]});
    for (const Window& w : R.windows) wj.push_back({w.t0, w.t1, w.condition});
    for (const ModeCheck& m : R.modes)
        mj.push_back({{"f_hz", m.f_hz}, {"zeta", m.zeta}, {"residual_share", num(m.residual_share)},
                      {"measured_peak_hz", num(m.measured_peak_hz)}, {"model_peak_hz", num(m.model_peak_hz)},
                      {"peak_ratio", num(m.peak_ratio)}, {"flag", m.flag}});
    j["where"] = {{"outputs", R.outputs}, {"bands_hz", bj}, {"windows_s", wj}, {"modes", mj}};
    nlohmann::json cj = nlohmann::json::array();
    for (const FitReport& f : R.candidates) {
        nlohmann::json c = fit_json(R, f, bands);
        c["effect"] = c["effects"][0];
        c["site"] = c["sites"][0];
        c["coupling"] = c["couplings"][0];
        c.erase("effects");
        c.erase("sites");
        c.erase("couplings");
        cj.push_back(c);
    }
    j["candidates"] = cj;
    j["verdict"] = fit_json(R, R.verdict, bands);
    nlohmann::json la = nlohmann::json::array();
    for (const GapResult::LookAlike& l : R.confidence.look_alikes)
        la.push_back({{"effect", l.effect}, {"gap_after_total", num(l.gap)}, {"experiment", l.experiment}});
    j["verdict"]["confidence"] = {{"first", R.confidence.first}, {"runner_up", R.confidence.runner_up},
                                  {"margin", num(R.confidence.margin)}, {"look_alikes", la},
                                  {"status", R.confidence.status}, {"explanation", R.confidence.explanation},
                                  {"noise_reach", num(R.confidence.noise_reach)}};
    nlohmann::json bb = nlohmann::json::array();
    for (size_t b = 0; b < R.band_nrmse_before.size() && b < bands.size(); ++b)
        bb.push_back({{"band_hz", {bands[b].first, bands[b].second}}, {"nrmse", per_output(R.outputs, R.band_nrmse_before[b])}});
    j["gap_before_total"] = num(R.gap_before_total);
    j["gap_before_bands"] = bb;
    j["criterion"] = {{"nrmse", "rms(measured - model) on held-out data / std(measured output over its whole record)"},
                      {"gap", "sqrt(mean over outputs of nrmse^2) on held-out data"},
                      {"shrink", "1 - gap_after/gap_before"},
                      {"score", "shrink - 0.005 * fitted parameters"},
                      {"nesting", "stribeck_friction ranks above coulomb_friction, mode_shift above fractional_damping and unmodelled_mode (not at a sensor), output_delay above input_delay, only if its gap is >= 5 % (relative) lower, alone and within a selected set (the contained effect fitted in the container's place); a verdict with unmodelled_mode and mode_shift names unmodelled_mode first"},
                      {"forward_selection", "add the best-scoring effect, refit jointly, keep it while the gap falls by >= 5 % (relative) and the score rises; after each addition drop an effect without which the set, refitted, has a gap the set does not undercut by 5 % or a score at least the set's; then try each effect's look-alikes (single shrink within 5 %) in its place, keeping a swap that scores better; never add an effect holding the same term as one in the set (coulomb_friction and stribeck_friction)"},
                      {"continuation", "a candidate that lowers the nominal's fit cost by < 10 % is fitted again by continuation in record length when the nominal's misfit is > 2 x the residual's white-noise cost and no single fit explained half of the part above it"}};
    j["data"] = {{"model", R.model_name}, {"fit", R.data_source}, {"held_out", R.eval_source},
                 {"fit_samples", R.fit_samples}, {"held_out_samples", R.eval_samples}, {"Ts", R.Ts},
                 {"continued_candidates", R.continued}};
    if (R.noise_floor > 0) {
        j["noise_floor"] = num(R.noise_floor);
        j["noise_floor_limit"] = num(R.noise_floor_limit);
        j["noise_floor_outputs"] = per_output(R.outputs, R.noise_floor_outputs);
        j["criterion"]["noise_floor"] = "gap.noise: a gap_before_total within noise_floor_limit (1.1 x the noise floor) is none; "
                                        "channels weighted by (std/noise)^2; in a closed loop the noise is the noise-only residual, "
                                        "the replay run with the stated sensor noise read by the controller (8 draws) against the "
                                        "noise-free replay, and the limit at least the one-sided 99 % prediction bound of a draw's noise-only gap";
    }
    if (!R.realization.empty()) j["data"]["realization"] = R.realization;
    if (!R.loop_feedback.empty()) {
        j["data"]["loop_feedback"] = R.loop_feedback;
        j["data"]["loop_feedback_note"] = R.loop_feedback_note;
        j["criterion"]["loop_feedback"] =
            "closed loop: the replayed controller reads the model's outputs; when that does not explain the gap "
            "(partly_explained, no_candidate, unexplained) and the nominal's misfit is > 2 x its white-noise cost, "
            "the diagnosis is run again with the controller reading the measured outputs; the closed-loop fits "
            "run again also started from that pass's effects, and replace the first pass when they score higher; "
            "when the closed loop then names nothing or a weak verdict (partly_explained, shrink < 50 %), the "
            "measured pass is the result when it explains the gap with every parameter identified and, after a "
            "weak verdict without a look-alike, names the same effects at the same sites";
    }
    j["skipped"] = R.skipped;
    j["seconds"] = R.seconds;
    return j;
}

}  // namespace gap
}  // namespace fracdesign
