// document.cpp - reading a controller kind's document object (document.hpp).
#include "document.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fracdesign {
namespace gap {

std::string field(const std::string& where, const std::string& key) { return where + "." + key; }

std::string shown(const json& v) { return v.dump(); }

void refuse(const std::string& where, const std::string& key, const json& v, const std::string& allowed)
{
    throw std::runtime_error(field(where, key) + ": " + shown(v) + " is not allowed (" + allowed + ")");
}

void check_fields(const json& doc, const std::string& where, const std::string& kind, std::initializer_list<const char*> own)
{
    const std::vector<std::string>& common = controller_common_fields();
    for (auto it = doc.begin(); it != doc.end(); ++it) {
        const std::string& k = it.key();
        if (k == "kind" || std::find(common.begin(), common.end(), k) != common.end()) continue;
        bool known = false;
        for (const char* o : own) known = known || k == o;
        if (known) continue;
        std::string list;
        for (const char* o : own) list += std::string(list.empty() ? "" : ", ") + o;
        for (const std::string& c : common) list += ", " + c;
        throw std::runtime_error(field(where, k) + ": unknown field of controller kind '" + kind + "' (fields: kind, " +
                                 list + ")");
    }
}

double number(const json& doc, const char* key, const std::string& where, double def)
{
    if (!doc.contains(key)) {
        if (std::isnan(def)) throw std::runtime_error(field(where, key) + ": missing (a finite number is required)");
        return def;
    }
    const json& v = doc.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>())) refuse(where, key, v, "a finite number");
    return v.get<double>();
}

long integer(const json& doc, const char* key, const std::string& where, long def, long lo)
{
    if (!doc.contains(key)) return def;
    const json& v = doc.at(key);
    const std::string allowed = "an integer >= " + std::to_string(lo);
    if (!v.is_number()) refuse(where, key, v, allowed);
    const double d = v.get<double>();
    if (!std::isfinite(d) || d != std::floor(d) || d < double(lo) || d > 1e9) refuse(where, key, v, allowed);
    return long(d);
}

int choice(const json& doc, const char* key, const std::string& where, int def, std::initializer_list<const char*> allowed)
{
    if (!doc.contains(key)) return def;
    const json& v = doc.at(key);
    std::string list;
    int i = 0, found = -1;
    for (const char* a : allowed) {
        if (v.is_string() && v.get<std::string>() == a) found = i;
        list += std::string(list.empty() ? "one of " : ", ") + "\"" + a + "\"";
        ++i;
    }
    if (found < 0) refuse(where, key, v, list);
    return found;
}

double Limits::scale() const { return std::max(std::fabs(lo), std::fabs(hi)); }

Limits read_limits(const json& v, const std::string& where)
{
    Limits l;
    if (v.is_number()) {
        const double L = v.get<double>();
        if (!(L > 0) || !std::isfinite(L))
            throw std::runtime_error(where + ": " + shown(v) + " is not allowed (a finite number > 0, the symmetric limit, "
                                     "or {\"min\": a, \"max\": b})");
        l.lo = -L;
        l.hi = L;
        return l;
    }
    if (!v.is_object())
        throw std::runtime_error(where + ": " + shown(v) + " is not allowed (a finite number > 0 or {\"min\": a, \"max\": b})");
    for (auto it = v.begin(); it != v.end(); ++it)
        if (it.key() != "min" && it.key() != "max")
            throw std::runtime_error(where + "." + it.key() + ": unknown field of a limit (fields: min, max)");
    const double inf = std::numeric_limits<double>::infinity();
    l.lo = number(v, "min", where, -inf);
    l.hi = number(v, "max", where, inf);
    if (!(l.lo < l.hi))
        throw std::runtime_error(where + ".min: " + shown(v.at("min")) + " is not allowed (min must be < max = " +
                                 shown(v.at("max")) + ")");
    return l;
}

frac_fo_params read_realization(const json& doc, const std::string& where, double Ts)
{
    frac_fo_params p;
    p.method = FRAC_FO_GL;
    p.order = 0;
    p.ts = frac_real(Ts);
    p.memory = 500;
    p.wb = 0;
    p.wh = 0;
    p.n = 0;
    if (!doc.contains("op")) return p;
    const json& op = doc.at("op");
    const std::string w = field(where, "op");
    if (!op.is_object()) throw std::runtime_error(w + ": " + shown(op) + " is not allowed (an object)");
    for (auto it = op.begin(); it != op.end(); ++it) {
        const std::string& k = it.key();
        if (k != "method" && k != "memory" && k != "wb" && k != "wh" && k != "n")
            throw std::runtime_error(field(w, k) + ": unknown field of a realization (fields: method, memory, wb, wh, n)");
    }
    p.method = 1 + choice(op, "method", w, 0, {"gl", "oustaloup", "oustaloup_refined", "cfe_tustin", "cfe_alalaoui"});
    p.memory = size_t(integer(op, "memory", w, 500, 1));
    if (p.method != FRAC_FO_GL) {
        p.n = unsigned(integer(op, "n", w, 4, 1));
        if (p.method == FRAC_FO_OUSTALOUP || p.method == FRAC_FO_OUSTALOUP_REFINED) {
            p.wb = frac_real(number(op, "wb", w));
            p.wh = frac_real(number(op, "wh", w));
            if (!(p.wb > 0)) refuse(w, "wb", op.at("wb"), "> 0 rad/s");
            if (!(p.wh > p.wb) || !(p.wh <= M_PI / Ts))
                refuse(w, "wh", op.at("wh"), "wb < wh <= pi/Ts = " + std::to_string(M_PI / Ts) + " rad/s");
        }
    }
    return p;
}

namespace {

int lookup(const json& doc, const char* key, const ControllerContext& ctx, const std::vector<std::string>& names,
           const std::string& what)
{
    if (!doc.contains(key)) return 0;
    const json& v = doc.at(key);
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    if (v.is_string()) {
        const auto it = std::find(names.begin(), names.end(), v.get<std::string>());
        if (it != names.end()) return int(it - names.begin());
    }
    refuse(ctx.where, key, v, "the name of one of the loop's " + what + ": " + list);
}

}  // namespace

int signal_index(const json& doc, const char* key, const ControllerContext& ctx, int def)
{
    if (!doc.contains(key)) {
        if (def < 0) throw std::runtime_error(field(ctx.where, key) + ": missing (the name of a reference or measured output)");
        return def;
    }
    std::vector<std::string> all = ctx.references;
    all.insert(all.end(), ctx.measured.begin(), ctx.measured.end());
    return lookup(doc, key, ctx, all, "references or measured outputs");
}

int reference_index(const json& doc, const char* key, const ControllerContext& ctx)
{
    return lookup(doc, key, ctx, ctx.references, "references");
}

int measured_index(const json& doc, const char* key, const ControllerContext& ctx)
{
    return lookup(doc, key, ctx, ctx.measured, "measured outputs");
}

int output_index(const json& doc, const char* key, const ControllerContext& ctx)
{
    std::vector<std::string> names = ctx.inputs;
    if (names.empty())
        for (int i = 0; i < ctx.outputs; ++i) names.push_back(std::to_string(i));
    return lookup(doc, key, ctx, names, "plant inputs");
}

void check_status(int status, const std::string& where, const std::string& what)
{
    if (status != FRAC_OK)
        throw std::runtime_error(where + ": " + what + " refused by libfrac (" + frac_status_str(status) + ")");
}

}  // namespace gap
}  // namespace fracdesign
