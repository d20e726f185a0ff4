// nominal_known.cpp - what the nominal model document states beyond the
// plant's equations (nominal.hpp, docs/gap.md "What the document states"):
// a fractional plant's realization, the open-loop input delay, the initial
// state, the sensors' noise, the actuator's limits and the sensors read
// less often than every sample (output_hold), the known friction.
#include "fracdesign/gap/nominal.hpp"

#include "fracdesign/model_json.hpp"
#include "fracdesign/models/fo_realization.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace fracdesign {
namespace gap {

using nlohmann::json;

namespace {

// "model gap.<field>: is <value>, must be <allowed>".
[[noreturn]] void refuse(const std::string& field, const json& value, const std::string& allowed)
{
    throw std::runtime_error("model gap." + field + ": is " + value.dump() + ", must be " + allowed);
}

double finite_number(const json& v, const std::string& field, const std::string& allowed)
{
    if (!v.is_number() || !std::isfinite(v.get<double>())) refuse(field, v, allowed);
    return v.get<double>();
}

std::string one_name(const json& doc, const char* key, const char* dflt)
{
    if (!doc.contains(key)) return dflt;
    const json& v = doc.at(key);
    if (!v.is_array() || v.size() != 1 || !v[0].is_string() || v[0].get<std::string>().empty())
        throw std::runtime_error(std::string("model: field '") + key + "': is " + v.dump() +
                                 ", must list one name (a foprocess has one " + (key[0] == 'i' ? "input" : "output") + ")");
    return v[0].get<std::string>();
}

}  // namespace

StateSpace plant_state_space(const json& doc, double Ts, double record_seconds, double* delay_s, std::string* realization)
{
    *delay_s = 0.0;
    realization->clear();
    ModelSpec spec;
    try {
        spec = model_from_json(doc);
    } catch (const ModelFormatError& e) {
        throw std::runtime_error(e.what());
    }
    if (auto* f = std::get_if<FoProcessModelSpec>(&spec)) {
        // Seed 001 eq. (1): the rational part realized (fo_realization.hpp),
        // the dead time as the nominal's input delay.
        const double Trec = record_seconds > 0 ? record_seconds : 1e5 * Ts;
        OustaloupBand band = default_oustaloup_band(Ts, Trec);
        const json g = doc.value("gap", json::object());
        if (g.is_object() && g.contains("realization")) {
            const json& r = g.at("realization");
            if (!r.is_object()) refuse("realization", r, "an object {\"wb\": rad/s, \"wh\": rad/s, \"N\": integer}");
            for (auto it = r.begin(); it != r.end(); ++it)
                if (it.key() != "wb" && it.key() != "wh" && it.key() != "N")
                    refuse("realization." + it.key(), it.value(), "left out: the realization takes wb, wh and N only");
            if (r.contains("wb")) band.wb = finite_number(r.at("wb"), "realization.wb", "a finite band edge > 0 rad/s");
            if (r.contains("wh")) band.wh = finite_number(r.at("wh"), "realization.wh", "a finite band edge above wb, in rad/s");
            if (r.contains("N")) {
                const json& n = r.at("N");
                if (!n.is_number_integer() || n.get<long>() < 1 || n.get<long>() > kOustaloupNMax)
                    refuse("realization.N", n, "an integer in [1, " + std::to_string(kOustaloupNMax) + "]");
                band.N = n.get<int>();
            }
        }
        StateSpace s;
        try {
            s = foprocess_realization(f->process, band);
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(std::string("model gap.") + e.what());
        }
        s.inputs = {one_name(doc, "inputs", "u")};
        s.outputs = {one_name(doc, "outputs", "y")};
        *delay_s = f->process.tau;
        const double err = foprocess_realization_error(f->process, band, 2 * M_PI / Trec, M_PI / Ts);
        const int n = f->process.lambda > 1 ? 2 : 1;
        char b[600];
        std::snprintf(b, sizeof b,
                      "foprocess K %.6g, T %.6g s^lambda, lambda %.6g, tau %.6g s: unity loop around s^%.6g/(T s^%d), "
                      "s^%.6g by Oustaloup over [%.4g, %.4g] rad/s with 2N + 1 = %d pole/zero pairs, %d exact "
                      "integrator(s); max relative error %.3g %% against the exact frequency response over "
                      "[%.4g, %.4g] rad/s; zero-order hold at %g s; the dead time as an input delay of %.6g samples",
                      f->process.K, f->process.T, f->process.lambda, f->process.tau, n - f->process.lambda, n,
                      n - f->process.lambda, band.wb, band.wh, 2 * band.N + 1, n, 100 * err, 2 * M_PI / Trec, M_PI / Ts,
                      Ts, f->process.tau / Ts);
        *realization = b;
        return s;
    }
    if (std::holds_alternative<AntennaModelSpec>(spec))
        throw std::runtime_error("model: kind 'antenna' (seed 000 eq. (25)) cannot be a gap nominal: its coupling torque "
                                 "per hub angle grows without bound with frequency (improper), so no state space has the "
                                 "hub angle as its input; give the plant as kind 'statespace'");
    return model_state_space(spec);
}

void read_known_section(const json& g, double plant_delay_s, NominalModel& m)
{
    const double inf = std::numeric_limits<double>::infinity();
    const Eigen::Index nx = m.A.rows(), nu = m.B.cols();
    m.input_delay = plant_delay_s / m.Ts;
    m.input_lo.assign(size_t(nu), -inf);
    m.input_hi.assign(size_t(nu), inf);
    if (!g.is_object()) return;
    if (g.contains("input_delay")) {
        const json& v = g.at("input_delay");
        if (m.closed_loop)
            refuse("input_delay", v, "left out in a closed loop (the loop's delay is gap.closed_loop.delay_samples)");
        const double d = finite_number(v, "input_delay", "a finite delay >= 0 in seconds");
        if (d < 0 || d / m.Ts > 1e6) refuse("input_delay", v, "a finite delay >= 0 in seconds, at most 1e6 samples");
        m.input_delay += d / m.Ts;
    }
    if (g.contains("initial_state")) {
        const json& v = g.at("initial_state");
        const std::string allowed = "\"fitted\", \"at_rest\" or {\"given\": [one number per plant state (" +
                                    std::to_string(nx) + ")]}";
        if (v == "fitted") {
            m.initial_state = NominalModel::Start::fitted;
        } else if (v == "at_rest") {
            m.initial_state = NominalModel::Start::at_rest;
        } else if (v.is_object() && v.size() == 1 && v.contains("given")) {
            const json& x = v.at("given");
            if (!x.is_array() || Eigen::Index(x.size()) != nx) refuse("initial_state.given", x, allowed);
            m.x0_given.resize(nx);
            for (Eigen::Index i = 0; i < nx; ++i)
                m.x0_given(i) = finite_number(x[size_t(i)], "initial_state.given", "finite numbers, " + allowed);
            m.initial_state = NominalModel::Start::given;
        } else {
            refuse("initial_state", v, allowed);
        }
    }
    if (g.contains("noise")) {
        const json& v = g.at("noise");
        if (!v.is_object() || v.empty()) refuse("noise", v, "an object {\"output\": noise std > 0}");
        for (auto it = v.begin(); it != v.end(); ++it) {
            if (m.output_index(it.key()) < 0) refuse("noise." + it.key(), it.value(), "left out: '" + it.key() + "' is no model output");
            const double sd = finite_number(it.value(), "noise." + it.key(), "a finite noise std > 0 in the output's units");
            if (!(sd > 0)) refuse("noise." + it.key(), it.value(), "a finite noise std > 0 in the output's units");
            m.noise[it.key()] = sd;
        }
    }
    if (g.contains("output_hold")) {
        const json& v = g.at("output_hold");
        if (!v.is_object() || v.empty())
            refuse("output_hold", v, "an object {\"output\": {\"every\": n >= 2, \"sample\": model output, \"phase\": 0 .. n - 1}}");
        for (auto it = v.begin(); it != v.end(); ++it) {
            const std::string f = "output_hold." + it.key();
            NominalModel::OutputHold h;
            h.output = m.output_index(it.key());
            if (h.output < 0) refuse(f, it.value(), "left out: '" + it.key() + "' is no model output");
            const json& o = it.value();
            if (!o.is_object()) refuse(f, o, "an object {\"every\": n >= 2, \"sample\": model output, \"phase\": 0 .. n - 1}");
            for (auto k = o.begin(); k != o.end(); ++k)
                if (k.key() != "every" && k.key() != "sample" && k.key() != "phase")
                    refuse(f + "." + k.key(), k.value(), "left out (allowed: every, sample, phase)");
            if (!o.contains("every")) refuse(f, o, "an object with \"every\": the samples per reading, an integer >= 2");
            const json& e = o.at("every");
            if (!e.is_number_integer() || e.get<long>() < 2 || e.get<long>() > 1000000)
                refuse(f + ".every", e, "the samples per reading, an integer in [2, 1e6]");
            h.every = int(e.get<long>());
            h.sample = h.output;
            if (o.contains("sample")) {
                const json& s = o.at("sample");
                if (!s.is_string() || m.output_index(s.get<std::string>()) < 0)
                    refuse(f + ".sample", s, "the name of the model output the reading takes");
                h.sample = m.output_index(s.get<std::string>());
            }
            if (o.contains("phase")) {
                const json& ph = o.at("phase");
                if (!ph.is_number_integer() || ph.get<long>() < 0 || ph.get<long>() >= h.every)
                    refuse(f + ".phase", ph, "the first sample of a reading modulo every, an integer in [0, " +
                                                 std::to_string(h.every - 1) + "] (left out: from the record)");
                h.phase = int(ph.get<long>());
            }
            m.holds.push_back(h);
        }
    }
    if (g.contains("friction")) {
        // The friction the user knows (NominalModel::KnownFriction), e.g. an arm document's.
        const json& v = g.at("friction");
        const std::string allowed = "an object {\"viscous\": b1 >= 0, \"coulomb\": b0 >= 0, \"tanh_k\": k > 0 (optional)}";
        if (!v.is_object() || v.empty()) refuse("friction", v, allowed);
        if (m.velocity < 0) refuse("friction", v, "left out, or gap.velocity stated (the friction's velocity)");
        for (auto it = v.begin(); it != v.end(); ++it) {
            const std::string f = "friction." + it.key();
            if (it.key() != "viscous" && it.key() != "coulomb" && it.key() != "tanh_k")
                refuse(f, it.value(), "left out (allowed: viscous, coulomb, tanh_k)");
            const double x = finite_number(it.value(), f, it.key() == "tanh_k" ? "a finite gain > 0 in s per velocity unit"
                                                                                : "a finite coefficient >= 0");
            if (it.key() == "tanh_k") {
                if (!(x > 0)) refuse(f, it.value(), "a finite gain > 0 in s per velocity unit (left out: dry friction)");
                m.friction.tanh_k = x;
            } else {
                if (x < 0) refuse(f, it.value(), "a finite coefficient >= 0");
                (it.key() == "viscous" ? m.friction.viscous : m.friction.coulomb) = x;
            }
        }
    }
    if (g.contains("input_limits")) {
        const json& v = g.at("input_limits");
        if (m.closed_loop)
            refuse("input_limits", v, "left out in a closed loop (the loop states its limits in gap.closed_loop)");
        if (!v.is_object() || v.empty()) refuse("input_limits", v, "an object {\"input\": [lo, hi]} (null: no limit on that side)");
        for (auto it = v.begin(); it != v.end(); ++it) {
            const std::string f = "input_limits." + it.key();
            const std::string allowed = "[lo, hi] with lo < hi (null: no limit on that side)";
            size_t i = 0;
            while (i < m.inputs.size() && m.inputs[i] != it.key()) ++i;
            if (i == m.inputs.size()) refuse(f, it.value(), "left out: '" + it.key() + "' is no model input");
            const json& l = it.value();
            if (!l.is_array() || l.size() != 2) refuse(f, l, allowed);
            const double lo = l[0].is_null() ? -inf : finite_number(l[0], f, allowed);
            const double hi = l[1].is_null() ? inf : finite_number(l[1], f, allowed);
            if (!(lo < hi)) refuse(f, l, allowed);
            m.input_lo[i] = lo;
            m.input_hi[i] = hi;
        }
    }
}

}  // namespace gap
}  // namespace fracdesign
