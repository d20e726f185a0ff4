// nominal.cpp - reading and discretising the nominal model (see nominal.hpp).
#include "fracdesign/gap/nominal.hpp"

#include "controllers/document.hpp"

#include "fracdesign/design/riccati.hpp"
#include "fracdesign/model_json.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>
#include <complex>
#include <fstream>
#include <stdexcept>

namespace fracdesign {
namespace gap {

using nlohmann::json;

int NominalModel::output_index(const std::string& n) const
{
    for (size_t i = 0; i < outputs.size(); ++i)
        if (outputs[i] == n) return int(i);
    return -1;
}

// The project's one zero-order hold (design::c2d_zoh, seed 004 (7.3)-(7.7)).
void zoh(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double Ts, Eigen::MatrixXd& Ad, Eigen::MatrixXd& Bd)
{
    StateSpace s;
    s.A = A;
    s.B = B;
    s.C = Eigen::MatrixXd::Zero(0, A.rows());
    s.D = Eigen::MatrixXd::Zero(0, B.cols());
    const StateSpace d = design::c2d_zoh(s, Ts);
    Ad = d.A;
    Bd = d.B;
}

bool discrete_generator(const Eigen::MatrixXd& A, double Ts, Eigen::MatrixXd& Ac, Eigen::MatrixXd& G_inv, bool* singular)
{
    if (singular) *singular = false;
    const Eigen::Index n = A.rows();
    if (n == 0 || !A.allFinite()) return false;
    const Eigen::MatrixXd L = Eigen::MatrixXd(A.log()) / Ts;
    if (!L.allFinite()) return false;
    Eigen::MatrixXd Phi, G;
    zoh(L, Eigen::MatrixXd::Identity(n, n), Ts, Phi, G);
    if (!((Phi - A).cwiseAbs().maxCoeff() <= 1e-8 * std::max(1.0, A.cwiseAbs().maxCoeff()))) return false;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
    if (!lu.isInvertible()) {
        if (singular) *singular = true;
        return false;
    }
    Ac = L;
    G_inv = lu.inverse();
    return true;
}

namespace {

Eigen::MatrixXd matrix(const json& j, const std::string& key, Eigen::Index rows, Eigen::Index cols, bool required,
                       const std::string& where)
{
    if (!j.contains(key)) {
        if (required && rows > 0 && cols > 0) throw std::runtime_error(where + ": missing matrix '" + key + "'");
        return Eigen::MatrixXd::Zero(rows, cols);
    }
    const json& a = j.at(key);
    if (!a.is_array() || Eigen::Index(a.size()) != rows)
        throw std::runtime_error(where + ": matrix '" + key + "' must have " + std::to_string(rows) + " rows");
    Eigen::MatrixXd M(rows, cols);
    for (Eigen::Index r = 0; r < rows; ++r) {
        const json& row = a[size_t(r)];
        if (!row.is_array() || Eigen::Index(row.size()) != cols)
            throw std::runtime_error(where + ": matrix '" + key + "' row " + std::to_string(r) + " must have " +
                                     std::to_string(cols) + " entries");
        for (Eigen::Index c = 0; c < cols; ++c) {
            if (!row[size_t(c)].is_number())
                throw std::runtime_error(where + ": matrix '" + key + "' has a non-numeric entry");
            M(r, c) = row[size_t(c)].get<double>();
        }
    }
    if (!M.allFinite()) throw std::runtime_error(where + ": matrix '" + key + "' has a non-finite entry");
    return M;
}

Eigen::Index rows_of(const json& j, const std::string& key)
{
    return j.contains(key) && j.at(key).is_array() ? Eigen::Index(j.at(key).size()) : 0;
}

std::vector<std::string> names(const json& j, const std::string& key, const std::string& where)
{
    if (!j.contains(key) || !j.at(key).is_array()) throw std::runtime_error(where + ": missing name list '" + key + "'");
    std::vector<std::string> v;
    for (const json& e : j.at(key)) {
        if (!e.is_string()) throw std::runtime_error(where + ": '" + key + "' must list strings");
        v.push_back(e.get<std::string>());
    }
    return v;
}

}  // namespace

void read_statespace(const json& j, Eigen::Index m, Eigen::Index p, double Ts, const std::string& where,
                     Eigen::MatrixXd& A, Eigen::MatrixXd& B, Eigen::MatrixXd& C, Eigen::MatrixXd& D)
{
    const Eigen::Index n = rows_of(j, "A");
    A = matrix(j, "A", n, n, true, where);
    B = matrix(j, "B", n, m, true, where);
    C = matrix(j, "C", p, n, true, where);
    D = matrix(j, "D", p, m, false, where);
    const std::string domain = j.value("time", "continuous");
    if (domain == "continuous") {
        Eigen::MatrixXd Ad, Bd;
        zoh(A, B, Ts, Ad, Bd);
        A = Ad;
        B = Bd;
    } else if (domain == "discrete") {
        if (!j.contains("Ts") || !j.at("Ts").is_number())
            throw std::runtime_error(where + ": a discrete model needs its sample time 'Ts'");
        const double mTs = j.at("Ts").get<double>();
        if (std::fabs(mTs - Ts) > 1e-3 * Ts)
            throw std::runtime_error(where + ": model sample time " + std::to_string(mTs) +
                                     " s does not match the data's " + std::to_string(Ts) + " s");
    } else {
        throw std::runtime_error(where + ": 'time' must be \"continuous\" or \"discrete\"");
    }
}

NominalModel nominal_from_json(const json& doc, double Ts, const std::string& base_dir, double record_seconds)
{
    // The plant: any model of the project's model format (model_json.hpp);
    // a fractional one realized (plant_state_space, nominal_known.cpp).
    if (!doc.is_object()) throw std::runtime_error("model: not a JSON object");
    double plant_delay_s = 0.0;
    NominalModel m;
    const StateSpace ss = plant_state_space(doc, Ts, record_seconds, &plant_delay_s, &m.realization);
    m.name = doc.value("name", model_kind(model_from_json(doc)));
    m.Ts = Ts;
    m.inputs = ss.inputs;
    m.outputs = ss.outputs;
    if (m.inputs.size() != size_t(ss.nu()) || m.outputs.size() != size_t(ss.ny()))
        throw std::runtime_error("model: the gap diagnosis needs input and output names (they name the data columns)");
    // A discrete plant's inverted hold integral (discrete_generator), empty
    // without a generator: its couplings' continuous torque columns below.
    Eigen::MatrixXd G_inv;
    if (ss.continuous()) {
        zoh(ss.A, ss.B, Ts, m.A, m.B);
        m.Ac = ss.A;
        m.Bc = ss.B;
    } else {
        if (std::fabs(ss.Ts - Ts) > 1e-3 * Ts)
            throw std::runtime_error("model: sample time " + std::to_string(ss.Ts) + " s does not match the data's " +
                                     std::to_string(Ts) + " s");
        m.A = ss.A;
        m.B = ss.B;
        if (discrete_generator(m.A, Ts, m.Ac, G_inv)) m.Bc = G_inv * m.B;
    }
    m.C = ss.C;
    m.D = ss.D;
    if (m.A.rows() == 0) throw std::runtime_error("model: the plant has no states");
    const json g = doc.value("gap", json::object());
    if (g.contains("velocity")) {
        m.velocity = m.output_index(g.at("velocity").get<std::string>());
        if (m.velocity < 0) throw std::runtime_error("model: gap.velocity names no model output");
    }
    if (g.contains("force_input")) {
        const std::string f = g.at("force_input").get<std::string>();
        m.force_input = -1;
        for (size_t i = 0; i < m.inputs.size(); ++i)
            if (m.inputs[i] == f) m.force_input = int(i);
        if (m.force_input < 0) throw std::runtime_error("model: gap.force_input names no model input");
    }
    m.friction_input = m.force_input;
    if (g.contains("friction_input")) {
        const json& f = g.at("friction_input");
        m.friction_input = -1;
        for (size_t i = 0; f.is_string() && i < m.inputs.size(); ++i)
            if (m.inputs[i] == f.get<std::string>()) m.friction_input = int(i);
        if (m.friction_input < 0)
            throw std::runtime_error("model gap.friction_input: is " + f.dump() + ", must be the name of a model input (the torque "
                                     "on the moving part, zero in the record and from the controller)");
    }
    if (g.contains("units")) {
        // gap.units: {"signal": "unit"} for the report and the parameters' units.
        const json& u = g.at("units");
        if (!u.is_object()) throw std::runtime_error("model gap.units: must be an object {\"signal\": \"unit\"}");
        for (auto it = u.begin(); it != u.end(); ++it) {
            if (!it.value().is_string())
                throw std::runtime_error("model gap.units: the unit of '" + it.key() + "' must be a string");
            m.units[it.key()] = it.value().get<std::string>();
        }
    }
    // gap.coupling: springs and flexible modes inside the plant (coupling.cpp).
    if (g.contains("coupling")) {
        m.couplings = read_couplings(g.at("coupling"), m.A, ss.continuous() ? ss.A : Eigen::MatrixXd(), Ts);
        // A discrete plant's coupling states its torque's discrete column:
        // with the plant's generator, its continuous column is G^-1 torque
        // (mode_shift's variant in the coupling's spring, mode_shift.cpp).
        if (G_inv.size() != 0)
            for (Coupling& c : m.couplings) c.torque_c = G_inv * c.torque;
    }
    if (g.contains("closed_loop")) {
        const json& cl = g.at("closed_loop");
        const std::string w = "model gap.closed_loop";
        m.closed_loop = true;
        m.loop.references = names(cl, "references", w);
        const std::vector<std::string> measured = names(cl, "measured", w);
        for (const std::string& s : measured) {
            const int i = m.output_index(s);
            if (i < 0) throw std::runtime_error(w + ": measured output '" + s + "' is not a model output");
            m.loop.measured.push_back(i);
        }
        if (!cl.contains("controller")) throw std::runtime_error(w + ": missing 'controller'");
        ControllerContext ctx;
        ctx.Ts = Ts;
        ctx.references = m.loop.references;
        ctx.measured = measured;
        ctx.outputs = int(m.inputs.size());
        ctx.inputs = m.inputs;
        ctx.where = w + ".controller";
        ctx.base_dir = base_dir;
        m.loop.controller = make_controller(cl.at("controller"), ctx);
        m.loop.delay_samples = cl.value("delay_samples", 0);
        if (m.loop.delay_samples < 0) throw std::runtime_error(w + ": delay_samples must be >= 0");
        if (cl.contains("saturation")) {
            const Limits l = read_limits(cl.at("saturation"), w + ".saturation");
            m.loop.saturation_min = l.lo;
            m.loop.saturation_max = l.hi;
            m.loop.saturation = l.scale();
        }
        if (cl.contains("additive")) m.loop.additive = names(cl, "additive", w);
        if (m.D.cwiseAbs().maxCoeff() != 0.0)
            throw std::runtime_error(w + ": the plant must be strictly proper (D = 0) in a closed loop");
    }
    read_known_section(g, plant_delay_s, m);
    return m;
}

NominalModel load_nominal_model(const std::string& path, double Ts, double record_seconds)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open model file");
    json doc;
    try {
        in >> doc;
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": not valid JSON (" + e.what() + ")");
    }
    const size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash == 0 ? 1 : slash);
    try {
        return nominal_from_json(doc, Ts, dir, record_seconds);
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(path + ": malformed model (" + e.what() + ")");
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
}

std::vector<Mode> NominalModel::modes() const
{
    Eigen::MatrixXd Acl = A;
    Eigen::MatrixXd Ac, Bc, Cc, Dc;
    if (closed_loop && loop.controller->small_signal(Ac, Bc, Cc, Dc)) {
        // x+ = A x + B (Cc xc + Dc [r; Cm x]),  xc+ = Ac xc + Bc [r; Cm x]  (r = 0)
        const Eigen::Index n = A.rows(), nc = Ac.rows();
        Eigen::MatrixXd Cm(loop.measured.size(), n);
        for (size_t i = 0; i < loop.measured.size(); ++i) Cm.row(Eigen::Index(i)) = C.row(loop.measured[i]);
        const Eigen::MatrixXd Dm = Dc.rightCols(Cm.rows()), Bm = Bc.rightCols(Cm.rows());
        Acl.resize(n + nc, n + nc);
        Acl.topLeftCorner(n, n) = A + B * Dm * Cm;
        Acl.topRightCorner(n, nc) = B * Cc;
        Acl.bottomLeftCorner(nc, n) = Bm * Cm;
        Acl.bottomRightCorner(nc, nc) = Ac;
    }
    Eigen::EigenSolver<Eigen::MatrixXd> es(Acl, false);
    std::vector<Mode> out;
    for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
        const std::complex<double> z = es.eigenvalues()[i];
        if (z.imag() < 0 || std::abs(z) < 1e-12) continue;  // one of each conjugate pair; skip pure delays
        const std::complex<double> s = std::log(z) / Ts;
        const double wn = std::abs(s);
        if (wn < 1e-9) continue;  // integrators
        out.push_back({wn / (2 * M_PI), -s.real() / wn});
    }
    return out;
}

}  // namespace gap
}  // namespace fracdesign
