// model_json.cpp - the versioned JSON model format (fracdesign/model_json.hpp, docs/model_format.md).
#include "fracdesign/model_json.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <tuple>

namespace fracdesign {

using nlohmann::json;

ModelFormatError::ModelFormatError(const std::string& f, const std::string& problem)
    : std::runtime_error("model: field '" + f + "': " + problem), field(f)
{
}

namespace {

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

const json& member(const json& j, const std::string& path, const std::string& key)
{
    if (!j.is_object()) throw ModelFormatError(path.empty() ? "(document)" : path, "must be an object");
    auto it = j.find(key);
    if (it == j.end()) throw ModelFormatError(join(path, key), "is missing");
    return *it;
}

enum class Range { Any, Positive, NonNegative };

double number(const json& j, const std::string& path, const std::string& key, Range r, const json* def = nullptr)
{
    const std::string f = join(path, key);
    const json* v = nullptr;
    if (j.is_object() && j.contains(key)) v = &j.at(key);
    else if (def) v = def;
    else member(j, path, key);
    if (!v->is_number()) throw ModelFormatError(f, "must be a number");
    const double x = v->get<double>();
    if (!std::isfinite(x)) throw ModelFormatError(f, "must be finite");
    if (r == Range::Positive && !(x > 0)) throw ModelFormatError(f, "must be > 0");
    if (r == Range::NonNegative && x < 0) throw ModelFormatError(f, "must be >= 0");
    return x;
}

Eigen::MatrixXd matrix(const json& j, const std::string& key, Eigen::Index rows, Eigen::Index cols)
{
    const json& m = member(j, "", key);
    if (!m.is_array()) throw ModelFormatError(key, "must be an array of rows");
    if (rows >= 0 && static_cast<Eigen::Index>(m.size()) != rows)
        throw ModelFormatError(key, "must have " + std::to_string(rows) + " rows, has " + std::to_string(m.size()));
    Eigen::MatrixXd out(static_cast<Eigen::Index>(m.size()), cols < 0 ? (m.empty() ? 0 : static_cast<Eigen::Index>(m[0].size())) : cols);
    for (size_t r = 0; r < m.size(); ++r) {
        const std::string rf = key + "[" + std::to_string(r) + "]";
        if (!m[r].is_array()) throw ModelFormatError(rf, "must be an array of numbers");
        if (static_cast<Eigen::Index>(m[r].size()) != out.cols())
            throw ModelFormatError(rf, "must have " + std::to_string(out.cols()) + " columns, has " + std::to_string(m[r].size()));
        for (size_t c = 0; c < m[r].size(); ++c) {
            const std::string cf = rf + "[" + std::to_string(c) + "]";
            if (!m[r][c].is_number()) throw ModelFormatError(cf, "must be a number");
            const double v = m[r][c].get<double>();
            if (!std::isfinite(v)) throw ModelFormatError(cf, "must be finite");
            out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = v;
        }
    }
    return out;
}

json matrix_json(const Eigen::MatrixXd& m)
{
    json a = json::array();
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
        json row = json::array();
        for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
        a.push_back(row);
    }
    return a;
}

std::vector<std::string> names(const json& j, const std::string& key, Eigen::Index count)
{
    if (!j.contains(key)) return {};
    const json& a = j.at(key);
    if (!a.is_array()) throw ModelFormatError(key, "must be an array of strings");
    if (static_cast<Eigen::Index>(a.size()) != count)
        throw ModelFormatError(key, "must have " + std::to_string(count) + " names, has " + std::to_string(a.size()));
    std::vector<std::string> out;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!a[i].is_string()) throw ModelFormatError(key + "[" + std::to_string(i) + "]", "must be a string");
        out.push_back(a[i].get<std::string>());
    }
    return out;
}

json beam_json(const TimoshenkoParams& b)
{
    return {{"L", b.L}, {"rho", b.rho}, {"I_rho", b.I_rho}, {"K_s", b.K_s}, {"K_b", b.K_b}, {"r_t", b.r_t}, {"r_r", b.r_r}};
}

TimoshenkoParams beam_from(const json& j)
{
    const json& b = member(j, "", "beam");
    TimoshenkoParams p;
    const json zero = 0.0;
    p.L = number(b, "beam", "L", Range::Positive);
    p.rho = number(b, "beam", "rho", Range::Positive);
    p.I_rho = number(b, "beam", "I_rho", Range::Positive);
    p.K_s = number(b, "beam", "K_s", Range::Positive);
    p.K_b = number(b, "beam", "K_b", Range::Positive);
    p.r_t = number(b, "beam", "r_t", Range::NonNegative, &zero);
    p.r_r = number(b, "beam", "r_r", Range::NonNegative, &zero);
    return p;
}

json disc_json(int N, Collocation c)
{
    return {{"N", N}, {"collocation", c == Collocation::GaussLegendre ? "gauss-legendre" : "equidistant"}};
}

void disc_from(const json& j, int& N, Collocation& c)
{
    const json& d = member(j, "", "discretization");
    const json& n = member(d, "discretization", "N");
    if (!n.is_number_integer()) throw ModelFormatError("discretization.N", "must be an integer");
    // Read wide and bound before narrowing: N = 3000000000 must be refused, not wrap around in an int.
    if (n.is_number_unsigned() ? n.get<unsigned long long>() > static_cast<unsigned long long>(kModelNMax)
                               : (n.get<long long>() < 2 || n.get<long long>() > kModelNMax))
        throw ModelFormatError("discretization.N", "must lie in [2, " + std::to_string(kModelNMax) + "] (got " + n.dump() + ")");
    N = static_cast<int>(n.get<long long>());
    if (N < 2) throw ModelFormatError("discretization.N", "must lie in [2, " + std::to_string(kModelNMax) + "] (got " + std::to_string(N) + ")");
    c = Collocation::GaussLegendre;
    if (d.contains("collocation")) {
        const json& s = d.at("collocation");
        if (!s.is_string()) throw ModelFormatError("discretization.collocation", "must be a string");
        const std::string v = s.get<std::string>();
        if (v == "equidistant") c = Collocation::Equidistant;
        else if (v != "gauss-legendre")
            throw ModelFormatError("discretization.collocation", "must be \"gauss-legendre\" or \"equidistant\"");
    }
}

// Fixed values of the structures of seed 000 Table 2 (NaN = free parameter).
void antenna_check_structure(AntennaStructure s, const AntennaDamping<double>& d)
{
    const double F = NAN;
    double fixed[4];  // zeta, alpha, gamma, lambda
    switch (s) {
    case AntennaStructure::I: fixed[0] = F, fixed[1] = 1, fixed[2] = 0, fixed[3] = 0; break;
    case AntennaStructure::II: fixed[0] = 0, fixed[1] = 0, fixed[2] = F, fixed[3] = 1; break;
    case AntennaStructure::III: fixed[0] = F, fixed[1] = 1, fixed[2] = F, fixed[3] = 1; break;
    case AntennaStructure::IV: fixed[0] = F, fixed[1] = F, fixed[2] = 0, fixed[3] = 0; break;
    case AntennaStructure::V: fixed[0] = 0, fixed[1] = 0, fixed[2] = F, fixed[3] = F; break;
    case AntennaStructure::VI: fixed[0] = F, fixed[1] = F, fixed[2] = F, fixed[3] = F; break;
    }
    const double v[4] = {d.zeta, d.alpha, d.gamma, d.lambda};
    const char* nm[4] = {"zeta", "alpha", "gamma", "lambda"};
    for (int i = 0; i < 4; ++i)
        if (!std::isnan(fixed[i]) && v[i] != fixed[i])
            throw ModelFormatError(std::string("damping.") + nm[i], "structure " + antenna_structure_name(s) +
                                                                        " fixes it to " + std::to_string(int(fixed[i])));
    if (d.alpha >= 2) throw ModelFormatError("damping.alpha", "must be < 2 (seed 000 Remark 1)");
    if (d.lambda >= 2) throw ModelFormatError("damping.lambda", "must be < 2 (seed 000 Remark 1)");
}

// [lo, hi] pair of numbers at key (optional: def when absent).
std::pair<double, double> range_pair(const json& j, const std::string& path, const std::string& key,
                                     std::pair<double, double> def)
{
    if (!j.contains(key)) return def;
    const json& r = j.at(key);
    const std::string f = join(path, key);
    if (!r.is_array() || r.size() != 2) throw ModelFormatError(f, "must be an array [lo, hi] of two numbers");
    return {number(r, f, "0", Range::Any, &r[0]), number(r, f, "1", Range::Any, &r[1])};
}

// The seed 002 collocated arm: the printed robot (m2_lb) or the physical form (link + masses). Types are
// checked here, ranges by CollocatedArm::validate (one message naming field, value and allowed range).
CollocatedModelSpec collocated_from(const json& j)
{
    CollocatedModelSpec c;
    CollocatedArm& a = c.arm;
    const bool printed = j.contains("m2_lb"), physical = j.contains("link") || j.contains("masses");
    if (printed && physical)
        throw ModelFormatError("m2_lb", "is the printed robot's tip mass; a physical arm (link, masses) gives masses.m2");
    if (!printed && !physical)
        throw ModelFormatError("masses", "is missing (give link and masses, or m2_lb for the paper's robot)");
    if (printed) {
        a = feliu_robot_arm();
        a.m2_nominal = number(j, "", "m2_lb", Range::Any);
        std::tie(a.m2_min, a.m2_max) = range_pair(j, "", "m2_range_lb", {a.m2_min, a.m2_max});
    } else {
        a.form = CollocatedArm::Form::Physical;
        const json& l = member(j, "", "link");
        a.L = number(l, "link", "L", Range::Any);
        a.EI = number(l, "link", "EI", Range::Any);
        const json& m = member(j, "", "masses");
        a.m1 = number(m, "masses", "m1", Range::Any);
        a.x1 = number(m, "masses", "x1", Range::Any);
        a.m2_nominal = number(m, "masses", "m2", Range::Any);
        // the admissible tip masses of the robust design; without a range the arm has one tip mass
        std::tie(a.m2_min, a.m2_max) = range_pair(m, "masses", "m2_range", {a.m2_nominal, a.m2_nominal});
        const json one = 1.0;
        a.moment_gain = number(j, "", "moment_gain", Range::Any, &one);
    }
    if (j.contains("inner_loop")) a.eps = number(j.at("inner_loop"), "inner_loop", "eps", Range::Any);
    if (j.contains("damping")) {
        const json& d = j.at("damping");
        a.rayleigh_a = number(d, "damping", "rayleigh_a", Range::Any);
        a.rayleigh_b = number(d, "damping", "rayleigh_b", Range::Any);
    }
    if (j.contains("damped")) {
        if (!j.at("damped").is_boolean()) throw ModelFormatError("damped", "must be true or false");
        c.damped = j.at("damped").get<bool>();
    }
    try {
        a.validate();
    } catch (const CollocatedArmError& e) {
        throw ModelFormatError(e.field, e.problem);
    }
    return c;
}

}  // namespace

std::string antenna_structure_name(AntennaStructure s)
{
    static const char* n[] = {"I", "II", "III", "IV", "V", "VI"};
    return n[static_cast<int>(s) - 1];
}

AntennaStructure antenna_structure_from_name(const std::string& s)
{
    for (int i = 1; i <= 6; ++i)
        if (antenna_structure_name(static_cast<AntennaStructure>(i)) == s) return static_cast<AntennaStructure>(i);
    throw std::invalid_argument("antenna structure must be one of I, II, III, IV, V, VI (got '" + s + "')");
}

std::string model_kind(const ModelSpec& m)
{
    static const char* k[] = {"beam", "arm", "antenna", "collocated", "foprocess", "statespace"};
    return k[m.index()];
}

json model_to_json(const ModelSpec& m)
{
    json j = {{"schema", kModelSchema}, {"version", kModelVersion}, {"kind", model_kind(m)}, {"units", "SI"}};
    if (auto* b = std::get_if<BeamModelSpec>(&m)) {
        j["beam"] = beam_json(b->beam);
        j["discretization"] = disc_json(b->N, b->collocation);
    } else if (auto* a = std::get_if<ArmModelSpec>(&m)) {
        j["beam"] = beam_json(a->beam);
        j["drive"] = {{"I_M", a->drive.I_M}, {"I_h", a->drive.I_h}, {"c_s", a->drive.c_s}, {"r_h", a->drive.r_h}};
        j["discretization"] = disc_json(a->options.N, a->options.collocation);
        j["reduction"] = a->options.reduce ? json{{"method", "krylov"}, {"shifts", a->options.shifts}} : json(nullptr);
    } else if (auto* n = std::get_if<AntennaModelSpec>(&m)) {
        j["link"] = {{"L", n->link.L}, {"rho", n->link.rho}, {"E", n->link.E}, {"I", n->link.I}};
        j["structure"] = antenna_structure_name(n->structure);
        j["damping"] = {{"zeta", n->damping.zeta}, {"alpha", n->damping.alpha}, {"gamma", n->damping.gamma},
                        {"lambda", n->damping.lambda}};
    } else if (auto* c = std::get_if<CollocatedModelSpec>(&m)) {
        const CollocatedArm& a = c->arm;
        if (a.form == CollocatedArm::Form::Printed) {
            j["m2_lb"] = a.m2_nominal;
            j["m2_range_lb"] = {a.m2_min, a.m2_max};
        } else {
            j["link"] = {{"L", a.L}, {"EI", a.EI}};
            j["masses"] = {{"m1", a.m1}, {"x1", a.x1}, {"m2", a.m2_nominal}, {"m2_range", {a.m2_min, a.m2_max}}};
            j["moment_gain"] = a.moment_gain;
        }
        j["inner_loop"] = {{"eps", a.eps}};
        j["damping"] = {{"rayleigh_a", a.rayleigh_a}, {"rayleigh_b", a.rayleigh_b}};
        j["damped"] = c->damped;
    } else if (auto* f = std::get_if<FoProcessModelSpec>(&m)) {
        j["K"] = f->process.K;
        j["T"] = f->process.T;
        j["lambda"] = f->process.lambda;
        j["tau"] = f->process.tau;
    } else {
        const StateSpace& s = std::get<StateSpace>(m);
        j["time"] = s.continuous() ? "continuous" : "discrete";
        if (!s.continuous()) j["Ts"] = s.Ts;
        j["A"] = matrix_json(s.A);
        j["B"] = matrix_json(s.B);
        j["C"] = matrix_json(s.C);
        j["D"] = matrix_json(s.D);
        // the names are optional on reading (names()): an unnamed model is
        // written without them, since [] would not read back (fuzz_model_json)
        if (!s.inputs.empty()) j["inputs"] = s.inputs;
        if (!s.outputs.empty()) j["outputs"] = s.outputs;
        if (!s.states.empty()) j["states"] = s.states;
    }
    return j;
}

ModelSpec model_from_json(const json& j)
{
    if (!j.is_object()) throw ModelFormatError("(document)", "must be a JSON object");
    const json& schema = member(j, "", "schema");
    if (!schema.is_string() || schema.get<std::string>() != kModelSchema)
        throw ModelFormatError("schema", std::string("must be \"") + kModelSchema + "\"");
    const json& version = member(j, "", "version");
    if (!version.is_number_integer() || version.get<int>() != kModelVersion)
        throw ModelFormatError("version", "must be " + std::to_string(kModelVersion) + " (this fracdesign reads version 1)");
    if (j.contains("units") && j.at("units") != "SI") throw ModelFormatError("units", "must be \"SI\"");
    const json& kind = member(j, "", "kind");
    if (!kind.is_string()) throw ModelFormatError("kind", "must be a string");
    const std::string k = kind.get<std::string>();
    if (k == "beam") {
        BeamModelSpec b;
        b.beam = beam_from(j);
        disc_from(j, b.N, b.collocation);
        return b;
    }
    if (k == "arm") {
        ArmModelSpec a;
        a.beam = beam_from(j);
        const json& d = member(j, "", "drive");
        a.drive.I_M = number(d, "drive", "I_M", Range::Positive);
        a.drive.I_h = number(d, "drive", "I_h", Range::Positive);
        a.drive.c_s = number(d, "drive", "c_s", Range::Positive);
        a.drive.r_h = number(d, "drive", "r_h", Range::NonNegative);
        disc_from(j, a.options.N, a.options.collocation);
        a.options.reduce = j.contains("reduction") && !j.at("reduction").is_null();
        if (a.options.reduce) {
            const json& r = j.at("reduction");
            const json& method = member(r, "reduction", "method");
            if (method != "krylov") throw ModelFormatError("reduction.method", "must be \"krylov\"");
            const json& s = member(r, "reduction", "shifts");
            if (!s.is_array() || s.empty()) throw ModelFormatError("reduction.shifts", "must be a non-empty array");
            a.options.shifts.clear();
            for (size_t i = 0; i < s.size(); ++i)
                a.options.shifts.push_back(number(s, "reduction.shifts", std::to_string(i), Range::Positive, &s[i]));
            if (4 * a.options.shifts.size() > 4 * static_cast<size_t>(a.options.N))
                throw ModelFormatError("reduction.shifts", "4 x shifts must not exceed the 4N beam states");
        }
        return a;
    }
    if (k == "antenna") {
        AntennaModelSpec a;
        const json& l = member(j, "", "link");
        a.link.L = number(l, "link", "L", Range::Positive);
        a.link.rho = number(l, "link", "rho", Range::Positive);
        a.link.E = number(l, "link", "E", Range::Positive);
        a.link.I = number(l, "link", "I", Range::Positive);
        const json& s = member(j, "", "structure");
        if (!s.is_string()) throw ModelFormatError("structure", "must be a string I..VI");
        try {
            a.structure = antenna_structure_from_name(s.get<std::string>());
        } catch (const std::invalid_argument&) {
            throw ModelFormatError("structure", "must be one of I, II, III, IV, V, VI");
        }
        const json& d = member(j, "", "damping");
        a.damping.zeta = number(d, "damping", "zeta", Range::NonNegative);
        a.damping.alpha = number(d, "damping", "alpha", Range::NonNegative);
        a.damping.gamma = number(d, "damping", "gamma", Range::NonNegative);
        a.damping.lambda = number(d, "damping", "lambda", Range::NonNegative);
        antenna_check_structure(a.structure, a.damping);
        return a;
    }
    if (k == "collocated") return collocated_from(j);
    if (k == "foprocess") {
        FoProcessModelSpec f;
        f.process.K = number(j, "", "K", Range::Any);
        f.process.T = number(j, "", "T", Range::Positive);
        f.process.lambda = number(j, "", "lambda", Range::Positive);
        if (f.process.lambda > 2) throw ModelFormatError("lambda", "must be <= 2");
        f.process.tau = number(j, "", "tau", Range::NonNegative);
        return f;
    }
    if (k == "statespace") {
        StateSpace s;
        const json& t = member(j, "", "time");
        if (t == "discrete") {
            s.Ts = number(j, "", "Ts", Range::Positive);
        } else if (t != "continuous") {
            throw ModelFormatError("time", "must be \"continuous\" or \"discrete\"");
        }
        s.A = matrix(j, "A", -1, -1);
        if (s.A.rows() != s.A.cols()) throw ModelFormatError("A", "must be square");
        const Eigen::Index n = s.A.rows();
        s.B = matrix(j, "B", n, -1);
        const Eigen::Index m = s.B.cols();
        s.C = matrix(j, "C", -1, n);
        s.D = matrix(j, "D", s.C.rows(), m);
        s.inputs = names(j, "inputs", m);
        s.outputs = names(j, "outputs", s.C.rows());
        s.states = names(j, "states", n);
        s.validate();
        return s;
    }
    throw ModelFormatError("kind", "must be one of beam, arm, antenna, collocated, foprocess, statespace (got '" + k + "')");
}

ModelSpec read_model_file(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw ModelFormatError(path, "cannot be read");
    json j;
    try {
        j = json::parse(in);
    } catch (const json::parse_error& e) {
        throw ModelFormatError(path, std::string("is not valid JSON (") + e.what() + ")");
    }
    return model_from_json(j);
}

void write_model_file(const std::string& path, const ModelSpec& m)
{
    std::ofstream out(path);
    if (!out) throw std::runtime_error("model: cannot write '" + path + "'");
    out << model_to_json(m).dump(2) << "\n";
}

StateSpace model_state_space(const ModelSpec& m)
{
    if (auto* b = std::get_if<BeamModelSpec>(&m)) return build_ps_beam(b->beam, b->N, b->collocation).ph.state_space();
    if (auto* a = std::get_if<ArmModelSpec>(&m)) return build_arm(a->beam, a->drive, a->options).arm.state_space();
    if (auto* c = std::get_if<CollocatedModelSpec>(&m))
        return collocated_state_space(c->arm.plant(c->arm.m2_nominal), c->damped);
    if (auto* s = std::get_if<StateSpace>(&m)) return *s;
    throw std::invalid_argument("model: kind '" + model_kind(m) + "' is irrational and has no state space");
}

}  // namespace fracdesign
