// tables.cpp - the table stages (kinds.hpp): the LUT1D and TrajLUT blocks
// (plc_blocks/FracCtrl/LUT1D.c, TrajLUT.c) as the PLC runs them:
// frac_lut1_init (breakpoints) or frac_lut1_init_uniform (x0, dx), then
// frac_lut1_eval of the input each cycle; frac_trajlut_init, then
// frac_trajlut_step each cycle (the block with Run TRUE, playing cycle k
// and advancing; seed 004 Sec. 6.4, 8.6: lead +d_i on a torque channel,
// -d_o on an IMU reference).
//
// A table is given inline or by "file", a CSV relative to the model
// document (ControllerContext::base_dir): LUT1D the breakpoint and value
// columns ("columns": [x, y], default the first two), TrajLUT a time column
// first (uniform: its step is dt, its first value t0) and the channel
// columns ("columns", default all the others). Breakpoints must be strictly
// increasing, sizes consistent: refused naming the field before libfrac sees them.
#include <cmath>
#include <stdexcept>

#include "fracdesign/io/signal_csv.hpp"
#include "kinds.hpp"

namespace fracdesign {
namespace gap {

struct LutData {
    std::vector<frac_real> x, y, d;
};
struct TrajData {
    std::vector<std::vector<frac_real>> ch;
    std::vector<const frac_real*> ptr;
    std::vector<long> lead;
    std::vector<frac_real> slopes;
};

namespace {

void check_keys(const json& doc, const std::string& where, const char* what, std::initializer_list<const char*> keys)
{
    if (!doc.is_object()) throw std::runtime_error(where + ": " + shown(doc) + " is not allowed (an object)");
    for (auto it = doc.begin(); it != doc.end(); ++it) {
        bool known = false;
        std::string list;
        for (const char* k : keys) {
            known = known || it.key() == k;
            list += std::string(list.empty() ? "" : ", ") + k;
        }
        if (!known) throw std::runtime_error(field(where, it.key()) + ": unknown field of " + what + " (fields: " + list + ")");
    }
}

std::vector<frac_real> reals(const json& doc, const char* key, const std::string& where)
{
    const json& v = doc.at(key);
    if (!v.is_array()) refuse(where, key, v, "an array of finite numbers");
    std::vector<frac_real> out;
    for (size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
            refuse(where, std::string(key) + "[" + std::to_string(i) + "]", v[i], "a finite number");
        out.push_back(frac_real(v[i].get<double>()));
    }
    return out;
}

// The CSV named by doc.file, relative to the document's directory.
io::NumericCsv table_file(const json& doc, const ControllerContext& ctx, const std::string& where)
{
    const json& f = doc.at("file");
    if (!f.is_string() || f.get<std::string>().empty()) refuse(where, "file", f, "a CSV path relative to the model document");
    std::string path = f.get<std::string>();
    if (path[0] != '/') path = (ctx.base_dir.empty() ? "." : ctx.base_dir) + "/" + path;
    try {
        return io::parse_numeric_csv(io::read_text_file(path), path);
    } catch (const std::exception& e) {
        throw std::runtime_error(field(where, "file") + ": " + e.what());
    }
}

std::vector<std::string> column_names(const json& doc, const std::string& where, const std::vector<std::string>& header,
                                      std::vector<std::string> def)
{
    if (!doc.contains("columns")) return def;
    const json& c = doc.at("columns");
    if (!c.is_array()) refuse(where, "columns", c, "an array of column names of the file");
    std::vector<std::string> out;
    for (const json& n : c) {
        bool found = false;
        for (const std::string& h : header) found = found || (n.is_string() && n.get<std::string>() == h);
        if (!found) refuse(where, "columns", c, "names of columns of the file");
        out.push_back(n.get<std::string>());
    }
    return out;
}

const std::vector<double>& column(const io::NumericCsv& t, const std::string& name)
{
    for (size_t i = 0; i < t.header.size(); ++i)
        if (t.header[i] == name) return t.columns[i];
    throw std::logic_error("column checked above");
}

void strictly_increasing(const std::vector<frac_real>& x, const std::string& where, const std::string& key)
{
    for (size_t i = 1; i < x.size(); ++i)
        if (!(x[i] > x[i - 1]))
            throw std::runtime_error(field(where, key + "[" + std::to_string(i) + "]") + ": " + shown(json(double(x[i]))) +
                                     " is not allowed (breakpoints strictly increasing: " + key + "[" +
                                     std::to_string(i - 1) + "] = " + shown(json(double(x[i - 1]))) + ")");
}

}  // namespace

Lut1Term::Lut1Term(const json& term, const ControllerContext& ctx, const std::string& where)
{
    check_keys(term, where, "a feedforward term", {"lut1d", "trajlut", "channel", "input", "output"});
    const std::string w = field(where, "lut1d");
    const json& doc = term.at("lut1d");
    check_keys(doc, w, "a LUT1D table", {"x", "x0", "dx", "y", "file", "columns", "interpolation", "range"});
    auto data = std::make_shared<LutData>();
    bool uniform = false;
    double x0 = 0, dx = 0;
    if (doc.contains("file")) {
        for (const char* k : {"x", "y", "x0", "dx"})
            if (doc.contains(k)) throw std::runtime_error(field(w, k) + ": given together with 'file' (give one of them)");
        const io::NumericCsv t = table_file(doc, ctx, w);
        if (t.header.size() < 2) refuse(w, "file", doc.at("file"), "a CSV with a breakpoint and a value column");
        const std::vector<std::string> c = column_names(doc, w, t.header, {t.header[0], t.header[1]});
        if (c.size() != 2) refuse(w, "columns", doc.at("columns"), "two names: the breakpoint and the value column");
        for (double v : column(t, c[0])) data->x.push_back(frac_real(v));
        for (double v : column(t, c[1])) data->y.push_back(frac_real(v));
    } else {
        if (!doc.contains("y")) throw std::runtime_error(field(w, "y") + ": missing (the table's values)");
        data->y = reals(doc, "y", w);
        if (doc.contains("x")) {
            if (doc.contains("x0") || doc.contains("dx"))
                throw std::runtime_error(field(w, "x0") + ": given together with 'x' (breakpoints or a uniform grid)");
            data->x = reals(doc, "x", w);
        } else {
            uniform = true;
            x0 = number(doc, "x0", w);
            dx = number(doc, "dx", w);
            if (!(dx > 0)) refuse(w, "dx", doc.at("dx"), "a grid step > 0");
        }
    }
    if (data->y.size() < 2) refuse(w, "y", doc.contains("y") ? doc.at("y") : doc.at("file"), "at least 2 values");
    if (!uniform) {
        if (data->x.size() != data->y.size())
            throw std::runtime_error(field(w, "x") + ": " + std::to_string(data->x.size()) + " breakpoints for " +
                                     std::to_string(data->y.size()) + " values (sizes must agree)");
        strictly_increasing(data->x, w, "x");
    }
    const int interp = choice(doc, "interpolation", w, 0, {"linear", "cubic"});
    const int range = choice(doc, "range", w, 0, {"clamp", "extrapolate"});
    data->d.assign(data->y.size(), frac_real(0));
    const int st = uniform ? frac_lut1_init_uniform(&lut_, frac_real(x0), frac_real(dx), data->y.data(), data->y.size(),
                                                    interp, range, data->d.data())
                           : frac_lut1_init(&lut_, data->x.data(), data->y.data(), data->y.size(), interp, range, data->d.data());
    check_status(st, w, "the LUT1D table");
    data_ = data;
    ControllerContext c = ctx;
    c.where = where;
    input_ = signal_index(term, "input", c, -1);
    output_ = output_index(term, "output", c);
}

void Lut1Term::add(const double* w, double* u)
{
    frac_real y = 0;
    frac_lut1_eval(&lut_, frac_real(w[input_]), &y);
    u[output_] += double(y);
}

TrajTable::TrajTable(const json& doc, const ControllerContext& ctx, const std::string& w)
{
    check_keys(doc, w, "a TrajLUT table",
               {"data", "file", "columns", "t0", "dt", "lead", "t_motion_start", "t_motion_end", "interpolation", "references"});
    auto data = std::make_shared<TrajData>();
    double t0 = 0, dt = 0;
    if (doc.contains("file")) {
        for (const char* k : {"data", "t0", "dt"})
            if (doc.contains(k)) throw std::runtime_error(field(w, k) + ": given together with 'file' (give one of them)");
        const io::NumericCsv t = table_file(doc, ctx, w);
        if (t.header.size() < 2 || t.columns[0].size() < 2)
            refuse(w, "file", doc.at("file"), "a CSV with a time column and at least one channel, 2 rows or more");
        const std::vector<double>& time = t.columns[0];
        t0 = time[0];
        dt = (time.back() - time.front()) / double(time.size() - 1);
        for (size_t i = 1; i < time.size(); ++i)
            if (!(std::fabs(time[i] - time[i - 1] - dt) <= 1e-6 * dt) || !(dt > 0))
                throw std::runtime_error(field(w, "file") + ": time column '" + t.header[0] + "' not uniform at row " +
                                         std::to_string(t.file_row[i]) + " (TrajLUT plays a uniform grid)");
        std::vector<std::string> def(t.header.begin() + 1, t.header.end());
        for (const std::string& c : column_names(doc, w, t.header, def)) {
            std::vector<frac_real> v;
            for (double x : column(t, c)) v.push_back(frac_real(x));
            data->ch.push_back(v);
        }
    } else {
        if (!doc.contains("data")) throw std::runtime_error(field(w, "data") + ": missing (the channels' samples)");
        const json& d = doc.at("data");
        if (!d.is_array() || d.empty()) refuse(w, "data", d, "an array of channels, each an array of samples");
        for (size_t c = 0; c < d.size(); ++c) {
            json one = {{"c", d[c]}};
            data->ch.push_back(reals(one, "c", field(w, "data[" + std::to_string(c) + "]")));
        }
        t0 = number(doc, "t0", w, 0.0);
        dt = number(doc, "dt", w);
        if (!(dt > 0)) refuse(w, "dt", doc.at("dt"), "a table sample time > 0 s");
    }
    const size_t nc = data->ch.size(), n = data->ch[0].size();
    if (nc > FRAC_TRAJLUT_MAX_CH)
        throw std::runtime_error(field(w, "data") + ": " + std::to_string(nc) + " channels (at most " +
                                 std::to_string(FRAC_TRAJLUT_MAX_CH) + ")");
    for (size_t c = 0; c < nc; ++c)
        if (data->ch[c].size() != n || n < 2)
            throw std::runtime_error(field(w, "data[" + std::to_string(c) + "]") + ": " + std::to_string(data->ch[c].size()) +
                                     " samples (every channel needs the same number, at least 2; channel 0 has " +
                                     std::to_string(n) + ")");
    for (const auto& c : data->ch) data->ptr.push_back(c.data());
    data->lead.assign(nc, 0);
    if (doc.contains("lead")) {
        const json& l = doc.at("lead");
        if (!l.is_array() || l.size() != nc)
            refuse(w, "lead", l, "one integer lead in controller samples per channel (" + std::to_string(nc) + ")");
        for (size_t c = 0; c < nc; ++c) {
            json one = {{"lead", l[c]}};
            data->lead[c] = integer(one, "lead", field(w, "lead[" + std::to_string(c) + "]"), 0, -1000000000L);
        }
    }
    const double t_end = t0 + dt * double(n - 1);
    frac_trajlut_params p;
    p.channels = nc;
    p.n = n;
    p.data = data->ptr.data();
    p.t0 = frac_real(t0);
    p.dt = frac_real(dt);
    p.Ts = frac_real(ctx.Ts);
    p.lead = data->lead.data();
    p.t_motion_start = frac_real(number(doc, "t_motion_start", w, t0));
    p.t_motion_end = frac_real(number(doc, "t_motion_end", w, t_end));
    if (!(p.t_motion_start >= p.t0 && p.t_motion_start <= p.t_motion_end))
        refuse(w, "t_motion_start", doc.value("t_motion_start", json(t0)), "t0 <= t_motion_start <= t_motion_end");
    p.interp = choice(doc, "interpolation", w, 0, {"linear", "cubic"});
    data->slopes.assign(nc * n, frac_real(0));
    check_status(frac_trajlut_init(&tl_, &p, data->slopes.data()), w, "the TrajLUT table");
    data_ = data;
}

void TrajTable::eval(double* out)
{
    frac_real y[FRAC_TRAJLUT_MAX_CH];
    frac_trajlut_eval(&tl_, tl_.k, y, nullptr);
    for (size_t c = 0; c < tl_.channels; ++c) out[c] = double(y[c]);
}

void TrajTable::step(double* out)
{
    frac_real y[FRAC_TRAJLUT_MAX_CH];
    frac_trajlut_step(&tl_, y, nullptr);
    for (size_t c = 0; c < tl_.channels; ++c) out[c] = double(y[c]);
}

}  // namespace gap
}  // namespace fracdesign
