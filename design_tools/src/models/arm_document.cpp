// arm_document.cpp - the frac.arm document: reading, validation, and the arm's PH model with payload
// (fracdesign/models/arm_document.hpp, docs/arm_format.md).
#include "fracdesign/models/arm_document.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "fracdesign/models/krylov.hpp"
#include "fracdesign/models/lagrange.hpp"

namespace fracdesign {

using nlohmann::json;

namespace {

std::string num_str(double v)
{
    char b[40];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

// One section of the document: typed, range-checked reads with the field's path in every message, and
// a refusal of fields the format does not have (a misspelt key would otherwise be silently ignored).
class Section {
public:
    Section(const json& j, std::string path, std::set<std::string> known) : j_(j), path_(std::move(path)), known_(std::move(known))
    {
        if (!j_.is_object()) throw ArmDocumentError(path_.empty() ? "(document)" : path_, "must be an object");
        for (auto it = j_.begin(); it != j_.end(); ++it)
            if (!known_.count(it.key())) throw ArmDocumentError(join(path_, it.key()), "is not a field of this section");
    }
    bool has(const std::string& k) const { return j_.contains(k) && !j_.at(k).is_null(); }
    const json& raw(const std::string& k) const { return j_.at(k); }
    std::string field(const std::string& k) const { return join(path_, k); }

    // A number in [lo, hi] (lo_open / hi_open exclude the end); absent -> def, or an error when required.
    double num(const std::string& k, double lo, double hi, bool lo_open, bool hi_open, const std::string& unit,
               const double* def = nullptr) const
    {
        const std::string range = std::string(lo_open ? "(" : "[") + num_str(lo) + ", " + num_str(hi) + (hi_open ? ")" : "]") +
                                  (unit.empty() ? "" : " " + unit);
        if (!has(k)) {
            if (def) return *def;
            throw ArmDocumentError(field(k), "is missing: allowed " + range);
        }
        const json& v = j_.at(k);
        if (!v.is_number()) throw ArmDocumentError(field(k), "value " + v.dump() + " is not a number: allowed " + range);
        const double x = v.get<double>();
        if (!std::isfinite(x) || (lo_open ? !(x > lo) : !(x >= lo)) || (hi_open ? !(x < hi) : !(x <= hi)))
            throw ArmDocumentError(field(k), "value " + num_str(x) + " out of range: allowed " + range);
        return x;
    }
    double num_def(const std::string& k, double lo, double hi, bool lo_open, bool hi_open, const std::string& unit,
                   double def) const
    {
        return num(k, lo, hi, lo_open, hi_open, unit, &def);
    }
    long integer(const std::string& k, long lo, long hi, long def, bool required = false) const
    {
        const std::string range = "integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
        if (!has(k)) {
            if (required) throw ArmDocumentError(field(k), "is missing: allowed " + range);
            return def;
        }
        const json& v = j_.at(k);
        if (!v.is_number_integer()) throw ArmDocumentError(field(k), "value " + v.dump() + " is not an integer: allowed " + range);
        // wide before narrow: a huge value must be refused, not wrapped
        if (v.is_number_unsigned() ? v.get<unsigned long long>() > static_cast<unsigned long long>(hi)
                                   : (v.get<long long>() < lo || v.get<long long>() > hi))
            throw ArmDocumentError(field(k), "value " + v.dump() + " out of range: allowed " + range);
        return static_cast<long>(v.get<long long>());
    }
    std::string choice(const std::string& k, const std::vector<std::string>& allowed, const std::string& def) const
    {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
        if (!has(k)) return def;
        const json& v = j_.at(k);
        if (v.is_string())
            for (const auto& a : allowed)
                if (v.get<std::string>() == a) return a;
        throw ArmDocumentError(field(k), "value " + v.dump() + ": allowed " + list);
    }
    Section sub(const std::string& k, const std::set<std::string>& known) const
    {
        if (!has(k)) throw ArmDocumentError(field(k), "is missing (a section)");
        return Section(j_.at(k), field(k), known);
    }

private:
    const json& j_;
    std::string path_;
    std::set<std::string> known_;
};


}  // namespace

ArmDocumentError::ArmDocumentError(const std::string& f, const std::string& problem)
    : std::runtime_error("arm: field '" + f + "': " + problem), field(f)
{
}

double ArmDocument::rigid_link_inertia() const
{
    const double L = beam.L, r = drive.r_h;
    return drive.I_h + beam.rho * (std::pow(L + r, 3) - std::pow(r, 3)) / 3.0 + beam.I_rho * L +
           payload_mass * (L + r) * (L + r) + payload_inertia;
}

ArmDocument arm_from_json(const json& j)
{
    ArmDocument a;
    const Section doc(j, "", {"schema", "version", "name", "description", "units", "link", "payload", "hub", "drive",
                              "sensors", "sample_time", "delays", "friction", "design"});
    if (!doc.has("schema") || !doc.raw("schema").is_string() || doc.raw("schema").get<std::string>() != kArmSchema)
        throw ArmDocumentError("schema", "value " + (doc.has("schema") ? doc.raw("schema").dump() : std::string("(missing)")) +
                                             ": allowed \"frac.arm\"");
    doc.integer("version", kArmVersion, kArmVersion, 0, true);
    if (doc.has("units") && doc.raw("units") != "SI") throw ArmDocumentError("units", "value " + doc.raw("units").dump() + ": allowed \"SI\"");
    if (doc.has("name")) {
        if (!doc.raw("name").is_string()) throw ArmDocumentError("name", "value " + doc.raw("name").dump() + " is not a string");
        a.name = doc.raw("name").get<std::string>();
    }
    // sample time and delays first: the design section's bandwidth is bounded by the Nyquist frequency
    a.T = doc.num("sample_time", kArmTMin, kArmTMax, false, false, "s");
    {
        const Section d = doc.sub("delays", {"input", "output"});
        a.di = static_cast<int>(d.integer("input", 0, kArmDelayMax, 0, true));
        a.dout = static_cast<int>(d.integer("output", 0, kArmDelayMax, 0, true));
    }
    // link
    {
        const Section l = doc.sub("link", {"length", "model", "material", "section", "kappa", "per_length", "damping"});
        const double L = l.num("length", 0.0, 100.0, true, false, "m");
        a.beam.L = L;
        a.timoshenko = l.choice("model", {"timoshenko", "euler-bernoulli"}, "timoshenko") == "timoshenko";
        const bool per = l.has("per_length");
        if (per == (l.has("material") || l.has("section")))
            throw ArmDocumentError(l.field(per ? "per_length" : "material"),
                                   "give either per_length (EI, GA, rhoA, rhoI) or material and section, not both");
        double EI, GA = 0.0, rhoA, rhoI = 0.0;
        if (per) {
            const Section p = l.sub("per_length", {"EI", "GA", "rhoA", "rhoI"});
            EI = p.num("EI", 0.0, 1e12, true, false, "N m^2");
            rhoA = p.num("rhoA", 0.0, 1e6, true, false, "kg/m");
            if (a.timoshenko) {
                GA = p.num("GA", 0.0, 1e14, true, false, "N (kappa G A)");
                rhoI = p.num("rhoI", 0.0, 1e6, true, false, "kg m");
            }
        } else {
            const Section m = l.sub("material", {"E", "G", "poisson", "rho"});
            const Section s = l.sub("section", {"shape", "width", "thickness", "area", "second_moment"});
            const double E = m.num("E", 0.0, 1e13, true, false, "Pa");
            const double rho = m.num("rho", 0.0, 1e5, true, false, "kg/m^3");
            if (m.has("G") && m.has("poisson")) throw ArmDocumentError(m.field("G"), "give G or poisson, not both");
            const double nu = m.num_def("poisson", -1.0, 0.5, true, true, "", 0.3);
            const double G = m.num_def("G", 0.0, 1e13, true, false, "Pa", E / (2.0 * (1.0 + nu)));
            double A, I;
            if (s.choice("shape", {"rectangular", "general"}, "rectangular") == "rectangular") {
                const double w = s.num("width", 0.0, 10.0, true, false, "m");
                const double t = s.num("thickness", 0.0, 10.0, true, false, "m");
                A = w * t;
                I = w * t * t * t / 12.0;  // bending about the thin direction (seed 004 Table 8.3)
            } else {
                A = s.num("area", 0.0, 100.0, true, false, "m^2");
                I = s.num("second_moment", 0.0, 1e3, true, false, "m^4");
            }
            const double kappa = l.num_def("kappa", 0.0, 1.0, true, false, "", 5.0 / 6.0);
            EI = E * I;
            GA = kappa * G * A;
            rhoA = rho * A;
            rhoI = rho * I;
        }
        if (!a.timoshenko) {
            // the shear-rigid limit (file comment): bending modes within O(1/kEbShear + kEbRotary) of EB
            GA = kEbShear * EI / (L * L);
            rhoI = kEbRotary * rhoA * L * L;
        }
        a.beam.K_b = EI;
        a.beam.K_s = GA;
        a.beam.rho = rhoA;
        a.beam.I_rho = rhoI;
        if (l.has("damping")) {
            const Section d = l.sub("damping", {"r_t", "r_r"});
            a.beam.r_t = d.num_def("r_t", 0.0, 1e6, false, false, "N s/m^2", 0.0);
            a.beam.r_r = d.num_def("r_r", 0.0, 1e6, false, false, "N s", 0.0);
        }
        a.beam.validate();
    }
    const double nyq = 3.14159265358979323846 / a.T;
    const double wm = kMountPerNyquist * nyq;
    if (doc.has("payload")) {
        const Section p = doc.sub("payload", {"mass", "inertia", "mount_stiffness", "mount_rotational_stiffness"});
        a.payload_mass = p.num_def("mass", 0.0, 1e5, false, false, "kg", 0.0);
        a.payload_inertia = p.num_def("inertia", 0.0, 1e5, false, false, "kg m^2", 0.0);
        a.mount_k_w = a.payload_mass > 0 ? p.num_def("mount_stiffness", 0.0, 1e16, true, false, "N/m", a.payload_mass * wm * wm) : 0.0;
        a.mount_k_psi = a.payload_inertia > 0
                            ? p.num_def("mount_rotational_stiffness", 0.0, 1e16, true, false, "N m/rad", a.payload_inertia * wm * wm)
                            : 0.0;
    }
    {
        const Section h = doc.sub("hub", {"inertia", "radius"});
        a.drive.I_h = h.num("inertia", 0.0, 1e5, true, false, "kg m^2");
        a.drive.r_h = h.num_def("radius", 0.0, 10.0, false, false, "m", 0.0);
    }
    {
        const Section d = doc.sub("drive", {"I_M", "gear_stiffness", "gear_damping", "torque_rated", "torque_peak",
                                            "current_loop_tau"});
        a.drive.I_M = d.num("I_M", 0.0, 1e6, true, false, "kg m^2 (n^2 I_m, driven side)");
        a.drive.c_s = d.num("gear_stiffness", 0.0, 1e12, true, false, "N m/rad");
        a.drive.d_s = d.num_def("gear_damping", 0.0, 1e9, false, false, "N m s/rad", 0.0);
        a.torque_rated = d.num("torque_rated", 0.0, 1e6, true, false, "N m");
        a.torque_peak = d.num("torque_peak", a.torque_rated, 1e6, false, false, "N m (>= torque_rated)");
        a.current_tau = d.num_def("current_loop_tau", 0.0, a.T, false, false, "s (at most the sample time)", 0.0);
    }
    if (doc.has("sensors")) {
        const Section s = doc.sub("sensors", {"encoder_counts_per_rev", "imu_position", "imu_noise", "encoder_noise"});
        a.encoder_counts = s.integer("encoder_counts_per_rev", 2, 1L << 31, 1L << 20);
        a.imu_position = s.num_def("imu_position", 0.0, a.beam.L, true, false, "m (along the link, hub end 0)", a.beam.L);
        a.imu_noise = s.num_def("imu_noise", 0.0, 100.0, false, false, "rad/s", 0.0);
        a.encoder_noise = s.num_def("encoder_noise", 0.0, 1.0, false, false, "rad", 0.0);
    } else {
        a.imu_position = a.beam.L;
    }
    if (doc.has("friction")) {
        const Section f = doc.sub("friction", {"model", "viscous", "coulomb", "tanh_k"});
        f.choice("model", {"linear"}, "linear");
        a.friction.known = true;
        a.friction.b1 = f.num_def("viscous", 0.0, 1e6, false, false, "N m s/rad", 0.0);
        a.friction.b0 = f.num_def("coulomb", 0.0, 1e6, false, false, "N m", 0.0);
        a.friction.k = f.num_def("tanh_k", 0.0, 1e6, true, false, "s/rad", 60.0);
    }
    if (doc.has("design")) {
        const Section d = doc.sub("design", {"N", "bandwidth_hz", "reduce", "reduce_multiple", "mode_error_max", "lqg"});
        ArmDesignSection& s = a.design;
        s.N = static_cast<int>(d.integer("N", kArmNMin, kArmNMax, s.N));
        s.bandwidth_hz = d.num_def("bandwidth_hz", 0.0, 0.5 / a.T, true, true, "Hz (below Nyquist 1/(2T))", 0.0);
        if (d.has("reduce")) {
            if (!d.raw("reduce").is_boolean()) throw ArmDocumentError(d.field("reduce"), "value " + d.raw("reduce").dump() + ": allowed true, false");
            s.reduce = d.raw("reduce").get<bool>();
        }
        s.reduce_multiple = d.num_def("reduce_multiple", 1.0, 100.0, false, false, "", s.reduce_multiple);
        s.mode_error_max = d.num_def("mode_error_max", 0.0, 0.5, true, false, "(relative)", s.mode_error_max);
        if (d.has("lqg")) {
            const Section q = d.sub("lqg", {"n_low", "q_low", "q_high", "q_delay", "S_c", "Qo_drive", "Qo_beam",
                                            "Qo_delay", "Qo_dist", "S_o"});
            s.n_low = static_cast<int>(q.integer("n_low", 0, 64, s.n_low));
            s.q_low = q.num_def("q_low", 0.0, 1e15, true, false, "", 0.0);
            s.q_high = q.num_def("q_high", 0.0, 1e15, true, false, "", 0.0);
            s.q_delay = q.num_def("q_delay", 0.0, 1e15, false, false, "", 0.0);
            s.s_c = q.num_def("S_c", 0.0, 1e15, true, false, "", 0.0);
            s.qo_drive = q.num_def("Qo_drive", 0.0, 1e15, false, false, "", s.qo_drive);
            s.qo_beam = q.num_def("Qo_beam", 0.0, 1e15, false, false, "", s.qo_beam);
            s.qo_delay = q.num_def("Qo_delay", 0.0, 1e15, false, false, "", s.qo_delay);
            s.qo_dist = q.num_def("Qo_dist", 0.0, 1e15, true, false, "", s.qo_dist);
            s.s_o = q.num_def("S_o", 0.0, 1e15, true, false, "", 0.0);
        }
    }
    a.drive.validate();
    return a;
}

ArmDocument read_arm_file(const std::string& path)
{
    std::ifstream f(path);
    if (!f) throw ArmDocumentError(path, "cannot read the file");
    std::stringstream ss;
    ss << f.rdbuf();
    json j;
    try {
        j = json::parse(ss.str());
    } catch (const json::parse_error& e) {
        throw ArmDocumentError(path, std::string("is not valid JSON (") + e.what() + ")");
    }
    return arm_from_json(j);
}

json arm_to_json(const ArmDocument& a)
{
    json j = {{"schema", kArmSchema}, {"version", kArmVersion}, {"units", "SI"}, {"name", a.name}};
    j["link"] = {{"length", a.beam.L},
                 {"model", a.timoshenko ? "timoshenko" : "euler-bernoulli"},
                 {"per_length", {{"EI", a.beam.K_b}, {"GA", a.beam.K_s}, {"rhoA", a.beam.rho}, {"rhoI", a.beam.I_rho}}},
                 {"damping", {{"r_t", a.beam.r_t}, {"r_r", a.beam.r_r}}}};
    json p = {{"mass", a.payload_mass}, {"inertia", a.payload_inertia}};
    if (a.payload_mass > 0) p["mount_stiffness"] = a.mount_k_w;
    if (a.payload_inertia > 0) p["mount_rotational_stiffness"] = a.mount_k_psi;
    j["payload"] = p;
    j["hub"] = {{"inertia", a.drive.I_h}, {"radius", a.drive.r_h}};
    j["drive"] = {{"I_M", a.drive.I_M}, {"gear_stiffness", a.drive.c_s}, {"gear_damping", a.drive.d_s},
                  {"torque_rated", a.torque_rated}, {"torque_peak", a.torque_peak}, {"current_loop_tau", a.current_tau}};
    j["sensors"] = {{"encoder_counts_per_rev", a.encoder_counts}, {"imu_position", a.imu_position},
                    {"imu_noise", a.imu_noise}, {"encoder_noise", a.encoder_noise}};
    j["sample_time"] = a.T;
    j["delays"] = {{"input", a.di}, {"output", a.dout}};
    if (a.friction.known)
        j["friction"] = {{"model", "linear"}, {"viscous", a.friction.b1}, {"coulomb", a.friction.b0}, {"tanh_k", a.friction.k}};
    const ArmDesignSection& s = a.design;
    json d = {{"N", s.N}, {"reduce", s.reduce}, {"reduce_multiple", s.reduce_multiple}, {"mode_error_max", s.mode_error_max}};
    if (s.bandwidth_hz > 0) d["bandwidth_hz"] = s.bandwidth_hz;
    json q = {{"n_low", s.n_low}, {"q_delay", s.q_delay}, {"Qo_drive", s.qo_drive}, {"Qo_beam", s.qo_beam},
              {"Qo_delay", s.qo_delay}, {"Qo_dist", s.qo_dist}};
    if (s.s_o > 0) q["S_o"] = s.s_o;
    if (s.q_low > 0) q["q_low"] = s.q_low;
    if (s.q_high > 0) q["q_high"] = s.q_high;
    if (s.s_c > 0) q["S_c"] = s.s_c;
    d["lqg"] = q;
    j["design"] = d;
    return j;
}

PhSystem payload_model(const ArmDocument& a)
{
    std::vector<int> axes;  // 0: translation (mass), 1: rotation (inertia)
    if (a.payload_mass > 0) axes.push_back(0);
    if (a.payload_inertia > 0) axes.push_back(1);
    const Eigen::Index h = static_cast<Eigen::Index>(axes.size()), n = 2 * h;
    PhSystem p;
    p.Q = Eigen::MatrixXd::Zero(n, n);
    p.J = Eigen::MatrixXd::Zero(n, n);
    p.R = Eigen::MatrixXd::Zero(n, n);
    p.B = Eigen::MatrixXd::Zero(n, 2);
    p.D = Eigen::MatrixXd::Zero(2, 2);
    for (Eigen::Index i = 0; i < h; ++i) {
        const bool tr = axes[i] == 0;
        p.Q(i, i) = tr ? a.mount_k_w : a.mount_k_psi;
        p.Q(h + i, h + i) = 1.0 / (tr ? a.payload_mass : a.payload_inertia);
        p.J(i, h + i) = 1.0;
        p.J(h + i, i) = -1.0;
        p.B(i, axes[i]) = -1.0;
        p.states.push_back(tr ? "d_w [m]" : "d_psi [rad]");
    }
    for (Eigen::Index i = 0; i < h; ++i) p.states.push_back(axes[i] == 0 ? "p_m [kg m/s]" : "p_J [kg m^2/s]");
    p.inputs = {"w_dot(L) [m/s]", "psi_dot(L) [rad/s]"};
    p.outputs = {"-Q_s(L) [N]", "-M_b(L) [N m]"};
    return p;
}

PhSystem couple_payload(const PhSystem& beam, double sigma, const PhSystem& payload)
{
    if (beam.B.cols() != 4) throw std::invalid_argument("couple_payload: the beam must have 4 boundary inputs");
    const Eigen::Index nb = beam.J.rows(), np = payload.J.rows(), n = nb + np;
    const Eigen::MatrixXd Bb0 = beam.B.leftCols(2), BbL = beam.B.rightCols(2);
    PhSystem l;
    l.J = Eigen::MatrixXd::Zero(n, n);
    l.J.topLeftCorner(nb, nb) = beam.J;
    l.J.bottomRightCorner(np, np) = payload.J;
    l.J.topRightCorner(nb, np) = -BbL * payload.B.transpose();
    l.J.bottomLeftCorner(np, nb) = payload.B * BbL.transpose();
    l.R = Eigen::MatrixXd::Zero(n, n);
    l.R.topLeftCorner(nb, nb) = beam.R;
    l.R.bottomRightCorner(np, np) = payload.R;
    l.Q = Eigen::MatrixXd::Zero(n, n);
    l.Q.topLeftCorner(nb, nb) = beam.Q;
    l.Q.bottomRightCorner(np, np) = payload.Q;
    // hub inputs: x_b' += B_b0 u0, and x_p' += B_p y_b^L with y_b^L = B_bL^T Q_b x_b - sigma u0 (3.95);
    // the tip inputs are closed by the payload (zero columns keep couple_arm's 4-input layout).
    l.B = Eigen::MatrixXd::Zero(n, 4);
    l.B.block(0, 0, nb, 2) = Bb0;
    l.B.block(nb, 0, np, 2) = -sigma * payload.B;
    l.D = Eigen::MatrixXd::Zero(4, 4);
    l.inputs = beam.inputs;
    l.outputs = beam.outputs;
    l.states = beam.states;
    l.states.insert(l.states.end(), payload.states.begin(), payload.states.end());
    return l;
}

ArmBuild build_arm_from_document(const ArmDocument& a, int N, bool reduce, const std::vector<double>& shifts)
{
    if (N < kArmNMin || N > kArmNMax)
        throw std::invalid_argument("arm: N = " + std::to_string(N) + " out of range: allowed [" + std::to_string(kArmNMin) +
                                    ", " + std::to_string(kArmNMax) + "]");
    ArmBuild b;
    b.beam = build_ps_beam(a.beam, N, Collocation::GaussLegendre);
    const PhSystem pay = payload_model(a);
    b.payload = pay.J.rows() > 0;
    if (reduce) {
        b.shifts = shifts;
        b.beam_used = krylov_reduce(b.beam.ph, shifts, &b.V);
    } else {
        b.beam_used = b.beam.ph;
        b.V = Eigen::MatrixXd::Identity(4 * N, 4 * N);
    }
    b.link_used = b.payload ? couple_payload(b.beam_used, b.beam.sigma, pay) : b.beam_used;
    // with a payload the link has no feedthrough left; couple_arm's sigma term then multiplies zero columns
    b.arm = couple_arm(drive_model(a.drive), b.link_used, b.beam.sigma);
    if (b.payload) {
        // Mount damping (ratio kMountZeta of the mount mode) in parallel with each mount spring: the
        // relative velocity v_rel = g^T e (e = Q x) with v_payload = e_p and the beam tip velocity
        // y_b^L = B_bL^T e_b - sigma u0, u0 = [r_h theta_h'; theta_h'] (3.95), (3.100); R += d g g^T keeps
        // R >= 0 (PH). Without it a payload axis is an undamped mode the loop cannot reach.
        const Eigen::Index nb = b.beam_used.J.rows(), np = b.link_used.J.rows() - nb;
        const Eigen::Index h = np / 2;
        int k = 0;
        for (int axis = 0; axis < 2; ++axis) {
            const double m = axis == 0 ? a.payload_mass : a.payload_inertia, kk = axis == 0 ? a.mount_k_w : a.mount_k_psi;
            if (!(m > 0)) continue;
            Eigen::VectorXd g = Eigen::VectorXd::Zero(b.arm.J.rows());
            g(4 + nb + h + k) = 1.0;
            g.segment(4, nb) -= b.beam_used.B.col(2 + axis);
            g(3) += b.beam.sigma * (axis == 0 ? a.drive.r_h : 1.0);
            b.arm.R += 2.0 * kMountZeta * std::sqrt(kk * m) * g * g.transpose();
            ++k;
        }
    }
    return b;
}

Eigen::RowVectorXd arm_rate_row(const ArmBuild& b, double z)
{
    const Eigen::Index n = b.arm.J.rows(), N = b.beam.N;
    const int Ni = b.beam.N;
    Eigen::MatrixXd A0(Ni + 1, Ni + 1);
    A0 << b.beam.M.transpose(), b.beam.Phi.row(0);
    const Eigen::MatrixXd A0i = A0.fullPivLu().inverse();
    const BarycentricBasis we(b.beam.effort_nodes);
    const Eigen::RowVectorXd wz = we.values(z).transpose();
    Eigen::RowVectorXd cb = Eigen::RowVectorXd::Zero(4 * N);
    cb.segment(N, N) = wz * A0i.leftCols(Ni) * b.beam.ph.Q.block(N, N, N, N);
    Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(n);
    c.segment(4, b.V.cols()) = cb * b.V;
    c(3) = (wz * A0i.col(Ni))(0) * b.arm.Q(3, 3);  // p0 theta_h', theta_h' = p_h / I_h
    return c;
}

Eigen::RowVectorXd arm_angle_row(const ArmBuild& b, double z)
{
    const Eigen::Index n = b.arm.J.rows(), N = b.beam.N;
    Eigen::VectorXd qx, qw;
    gauss_legendre(b.beam.N, 0.0, z, qx, qw);  // degree N-1 integrands: N Gauss points are exact
    const BarycentricBasis wf(b.beam.flow_nodes);
    Eigen::RowVectorXd I = Eigen::RowVectorXd::Zero(N);
    for (Eigen::Index q = 0; q < N; ++q) I += qw[q] * wf.values(qx[q]).transpose();
    Eigen::RowVectorXd cb = Eigen::RowVectorXd::Zero(4 * N);
    cb.segment(3 * N, N) = I;
    Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(n);
    c(1) = 1.0;
    c.segment(4, b.V.cols()) = cb * b.V;
    return c;
}

StateSpace arm_document_measured(const ArmDocument& a, const ArmBuild& b)
{
    const StateSpace s = b.arm.state_space();
    const Eigen::Index n = s.nx(), nb = b.beam_used.J.rows();
    StateSpace m;
    m.A = s.A;
    m.B = s.B.col(0);
    m.C = Eigen::MatrixXd::Zero(3, n);
    m.C(0, 0) = 1.0;
    m.C.row(1) = s.C.row(0);
    if (std::fabs(a.imu_position - a.beam.L) <= 1e-12 * a.beam.L) {
        m.C.block(2, 4, 1, nb) = b.beam_used.B.col(3).transpose() * b.beam_used.Q;
        m.C(2, 3) = b.beam_used.D(3, 1) * b.arm.Q(3, 3);  // D(3,1) = -sigma (3.95)
    } else {
        m.C.row(2) = arm_rate_row(b, a.imu_position);
    }
    m.D = Eigen::MatrixXd::Zero(3, 1);
    m.inputs = {"tau_M [N m]"};
    m.outputs = {"theta_M [rad]", "theta_M_dot [rad/s]", "psi_dot(z_imu) [rad/s]"};
    m.states = s.states;
    return m;
}

}  // namespace fracdesign
