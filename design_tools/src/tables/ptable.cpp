// ptable.cpp - parameter table schema: validation, JSON, designs -> tables.
#include "fracdesign/tables/ptable.hpp"

#include <cctype>
#include <cmath>
#include <set>

namespace fracdesign::tables {
namespace {

bool is_identifier(const std::string& s)
{
    if (s.empty() || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
    // IEC 61131-3 identifiers: no two consecutive underscores, none at the end.
    return s.find("__") == std::string::npos && s.back() != '_';
}

}  // namespace

RealType real_type_from_string(const std::string& s)
{
    if (s == "float64") return RealType::F64;
    if (s == "float32") return RealType::F32;
    throw TableError("real", "'" + s + "' is not float64 or float32");
}

std::string to_string(RealType r) { return r == RealType::F64 ? "float64" : "float32"; }

void ParamTable::add(const std::string& n, double v, const std::string& doc)
{
    entries.push_back(Entry{n, 1, 1, {v}, doc});
}

void ParamTable::add(const std::string& n, const Eigen::MatrixXd& M, const std::string& doc)
{
    Entry e{n, static_cast<int>(M.rows()), static_cast<int>(M.cols()), {}, doc};
    for (Eigen::Index i = 0; i < M.rows(); ++i)
        for (Eigen::Index j = 0; j < M.cols(); ++j) e.values.push_back(M(i, j));
    entries.push_back(std::move(e));
}

const Entry& ParamTable::at(const std::string& n) const
{
    for (const auto& e : entries)
        if (e.name == n) return e;
    throw TableError(n, "no entry of that name in table '" + name + "'");
}

void ParamTable::validate() const
{
    if (!is_identifier(name) || name.size() > 31)
        throw TableError("name", "table name '" + name + "' is not an identifier of at most 31 characters");
    if (entries.empty()) throw TableError("entries", "a table needs at least one entry");
    std::set<std::string> seen;
    for (size_t i = 0; i < entries.size(); ++i) {
        const Entry& e = entries[i];
        const std::string f = "entries[" + std::to_string(i) + "]";
        if (!is_identifier(e.name) || e.name.size() > 23)
            throw TableError(f + ".name", "'" + e.name + "' is not an identifier of at most 23 characters");
        if (!seen.insert(e.name).second) throw TableError(f + ".name", "duplicate entry name '" + e.name + "'");
        if (e.rows < 1 || e.rows > 65535) throw TableError(f + ".rows", "must lie in 1..65535");
        if (e.cols < 1 || e.cols > 65535) throw TableError(f + ".cols", "must lie in 1..65535");
        if (e.values.size() != static_cast<size_t>(e.rows) * static_cast<size_t>(e.cols))
            throw TableError(f + ".values", "has " + std::to_string(e.values.size()) + " values, rows*cols = " +
                                                std::to_string(static_cast<long>(e.rows) * e.cols));
        for (size_t k = 0; k < e.values.size(); ++k) {
            const double v = e.values[k];
            const bool ok = std::isfinite(v) && (real == RealType::F64 || std::fabs(v) <= 3.4028234663852886e38);
            if (!ok)
                throw TableError(f + ".values[" + std::to_string(k) + "]",
                                 "value of '" + e.name + "' is not finite in " + to_string(real));
        }
    }
}

nlohmann::json to_json(const ParamTable& t)
{
    t.validate();
    nlohmann::json entries = nlohmann::json::array();
    for (const auto& e : t.entries) {
        nlohmann::json je = {{"name", e.name}, {"rows", e.rows}, {"cols", e.cols}, {"values", e.values}};
        if (!e.doc.empty()) je["doc"] = e.doc;
        entries.push_back(je);
    }
    return {{"schema", ParamTable::kSchema}, {"version", ParamTable::kVersion}, {"name", t.name},
            {"real", to_string(t.real)}, {"meta", t.meta}, {"entries", entries}};
}

ParamTable table_from_json(const nlohmann::json& j)
{
    auto need = [&](const nlohmann::json& o, const std::string& key, const std::string& field) -> const nlohmann::json& {
        if (!o.is_object() || !o.contains(key)) throw TableError(field, "missing");
        return o.at(key);
    };
    if (!j.is_object()) throw TableError("document", "not a JSON object");
    const auto& schema = need(j, "schema", "schema");
    if (!schema.is_string() || schema.get<std::string>() != ParamTable::kSchema)
        throw TableError("schema", "expected \"frac.ptable\"");
    const auto& version = need(j, "version", "version");
    if (!version.is_number_integer() || version.get<int>() != ParamTable::kVersion)
        throw TableError("version", "unsupported version (this tool reads version 1)");
    ParamTable t;
    const auto& name = need(j, "name", "name");
    if (!name.is_string()) throw TableError("name", "not a string");
    t.name = name.get<std::string>();
    if (j.contains("real")) {
        if (!j["real"].is_string()) throw TableError("real", "not a string");
        t.real = real_type_from_string(j["real"].get<std::string>());
    }
    if (j.contains("meta")) t.meta = j["meta"];
    const auto& entries = need(j, "entries", "entries");
    if (!entries.is_array()) throw TableError("entries", "not an array");
    for (size_t i = 0; i < entries.size(); ++i) {
        const std::string f = "entries[" + std::to_string(i) + "]";
        const auto& je = entries[i];
        Entry e;
        const auto& n = need(je, "name", f + ".name");
        if (!n.is_string()) throw TableError(f + ".name", "not a string");
        e.name = n.get<std::string>();
        const auto& r = need(je, "rows", f + ".rows");
        const auto& c = need(je, "cols", f + ".cols");
        if (!r.is_number_integer()) throw TableError(f + ".rows", "not an integer");
        if (!c.is_number_integer()) throw TableError(f + ".cols", "not an integer");
        e.rows = r.get<int>();
        e.cols = c.get<int>();
        const auto& v = need(je, "values", f + ".values");
        if (!v.is_array()) throw TableError(f + ".values", "not an array");
        for (size_t k = 0; k < v.size(); ++k) {
            if (!v[k].is_number()) throw TableError(f + ".values[" + std::to_string(k) + "]", "not a number");
            e.values.push_back(v[k].get<double>());
        }
        if (je.contains("doc") && je["doc"].is_string()) e.doc = je["doc"].get<std::string>();
        t.entries.push_back(std::move(e));
    }
    t.validate();
    return t;
}

ParamTable table_from_document(const nlohmann::json& j)
{
    if (!j.is_object() || !j.contains("schema") || !j["schema"].is_string())
        throw TableError("schema", "document has no schema string");
    const std::string schema = j["schema"].get<std::string>();
    if (schema == ParamTable::kSchema) return table_from_json(j);
    ParamTable t;
    t.meta = {{"from_schema", schema}, {"source", j.value("source", "")}};
    auto num = [&](const char* obj, const char* key) {
        if (!j.contains(obj) || !j[obj].contains(key) || !j[obj][key].is_number())
            throw TableError(std::string(obj) + "." + key, "missing or not a number in the " + schema + " document");
        return j[obj][key].get<double>();
    };
    if (schema == "frac.design.fopi") {
        // C(s) = Kp + Ki s^-alpha (seed 001 eq. (5), (14))
        t.name = "fopi";
        t.add("Kp", num("controller", "Kp"), "proportional gain");
        t.add("Ki", num("controller", "Ki"), "integral gain of s^-alpha");
        t.add("alpha", num("controller", "alpha"), "integral order");
    } else if (schema == "frac.design.fopd") {
        // C(s) = (Kp + delta) + Kd s^mu, u = C e + delta y (seed 001 eq. (41), Fig. 12)
        t.name = "fopd";
        t.add("Kp", num("controller", "Kp"), "proportional gain of C^ (delta not included)");
        t.add("Kd", num("controller", "Kd"), "derivative gain of s^mu");
        t.add("mu", num("controller", "mu"), "derivative order");
        t.add("delta", num("controller", "delta"), "positive output feedback 1/K");
    } else if (schema == "frac.design.collocated") {
        // C(s) = Kc (1 + 2 eps s) s^(alpha - 2) (seed 002 eq. (48))
        t.name = "collocated";
        t.add("Kc", num("controller", "Kc"), "gain (24)");
        t.add("alpha", num("controller", "alpha"), "fractional order");
        t.add("eps", num("controller", "eps"), "inner-loop time constant [s]");
    } else if (schema == "frac.design.lqg") {
        // u = u* + K e_x_hat - e_z_hat, observer (7.27) (seed 004)
        auto matrix = [&](const char* key) {
            if (!j.contains(key) || !j[key].is_array() || j[key].empty() || !j[key][0].is_array())
                throw TableError(key, "missing or not a matrix in the " + schema + " document");
            Eigen::MatrixXd M(j[key].size(), j[key][0].size());
            for (size_t r = 0; r < j[key].size(); ++r) {
                if (j[key][r].size() != static_cast<size_t>(M.cols()))
                    throw TableError(std::string(key) + "[" + std::to_string(r) + "]", "ragged matrix row");
                for (size_t c = 0; c < j[key][r].size(); ++c) M(r, c) = j[key][r][c].get<double>();
            }
            return M;
        };
        auto scalar = [&](const char* key) {
            if (!j.contains(key) || !j[key].is_number()) throw TableError(key, "missing or not a number");
            return j[key].get<double>();
        };
        t.name = "lqg";
        t.add("K", matrix("K"), "state feedback gain (7.24)");
        t.add("Le", matrix("Le"), "predictor Kalman gain (7.27)");
        t.add("Ae", matrix("Ae"), "observer model A_e (7.26)");
        t.add("Be", matrix("Be"), "observer model B_e");
        t.add("Ce", matrix("Ce"), "observer model C_e");
        t.add("Ts", scalar("T"), "sample time [s]");
        t.add("di", scalar("di"), "input delay [samples]");
        t.add("d_o", scalar("do"), "IMU output delay [samples]");
    } else {
        throw TableError("schema", "no table mapping for documents of schema '" + schema + "'");
    }
    t.validate();
    return t;
}

}  // namespace fracdesign::tables
