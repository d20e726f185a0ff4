// coupling.cpp - gap.coupling: the springs and flexible modes inside the plant
// where backlash and Kelvin-Voigt fractional damping may act (nominal.hpp,
// Coupling; docs/gap.md "coupling").
#include <cmath>
#include <complex>
#include <stdexcept>

#include "fracdesign/gap/nominal.hpp"

namespace fracdesign {
namespace gap {

using nlohmann::json;

namespace {

// The sub-step matrices of a coupling (nominal.hpp, Coupling).
void setup_coupling_substeps(Coupling& c, const Eigen::MatrixXd& A, double Ts, const json& cp, const std::string& w)
{
    const Eigen::Index n = A.rows();
    if (cp.contains("states")) {
        if (!cp.at("states").is_array() || cp.at("states").empty())
            throw std::runtime_error(w + ": 'states' must list plant state indices");
        for (const json& e : cp.at("states")) {
            if (!e.is_number_integer() || e.get<long>() < 0 || e.get<long>() >= long(n))
                throw std::runtime_error(w + ": 'states' entries must be integers in [0, " + std::to_string(n - 1) + "]");
            c.states.push_back(e.get<int>());
        }
    } else {
        for (Eigen::Index i = 0; i < n; ++i) c.states.push_back(int(i));
    }
    c.substeps = cp.value("substeps", 8);
    if (c.substeps < 1 || c.substeps > 256) throw std::runtime_error(w + ": 'substeps' must be in [1, 256]");
    const Eigen::Index ns = Eigen::Index(c.states.size());
    std::vector<bool> in(size_t(n), false);
    for (int i : c.states) {
        if (in[size_t(i)]) throw std::runtime_error(w + ": 'states' lists state " + std::to_string(i) + " twice");
        in[size_t(i)] = true;
    }
    for (Eigen::Index i = 0; i < n; ++i)
        if (!in[size_t(i)] && (c.twist(i) != 0.0 || c.torque(i) != 0.0))
            throw std::runtime_error(w + ": 'twist' and 'torque' must vanish outside 'states' (state " + std::to_string(i) + ")");
    c.Phi.resize(ns, ns);
    c.twist_s.resize(ns);
    Eigen::VectorXd ts(ns);
    for (Eigen::Index i = 0; i < ns; ++i) {
        c.twist_s(i) = c.twist(c.states[size_t(i)]);
        ts(i) = c.torque(c.states[size_t(i)]);
        for (Eigen::Index j = 0; j < ns; ++j) c.Phi(i, j) = A(c.states[size_t(i)], c.states[size_t(j)]);
    }
    // The block's generator Ac = log(Phi)/Ts and its inverted hold integral
    // (discrete_generator); zoh(Ac, I, Ts/m) gives the sub-step.
    Eigen::MatrixXd Ac;
    bool singular = false;
    if (!discrete_generator(c.Phi, Ts, Ac, c.Gamma_inv, &singular))
        throw std::runtime_error(singular ? w + ": the block of 'states' gives a singular hold integral"
                                          : w + ": the block of 'states' has no real matrix logarithm (a pure delay or a "
                                                "mode at or above Nyquist in it); list the plant's physical states in 'states'");
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(ns, ns);
    zoh(Ac, I, Ts / c.substeps, c.Phi_m, c.Gamma_m);
    c.torque_m = c.Gamma_m * (c.Gamma_inv * ts);
    // The block's slowest oscillation (its eigenvalues s = log(z)/Ts with a
    // nonzero imaginary part): the time scale the fractional memory must cover.
    Eigen::EigenSolver<Eigen::MatrixXd> es(c.Phi, false);
    for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
        const std::complex<double> z = es.eigenvalues()[i];
        if (std::abs(z) < 1e-12) continue;
        const double wi = std::fabs((std::log(z) / Ts).imag());
        if (wi > 1e-9 && (c.w_slow == 0.0 || wi < c.w_slow)) c.w_slow = wi;
    }
}

Coupling read_one(const json& cp, const Eigen::MatrixXd& A, const Eigen::MatrixXd& Ac, double Ts, const std::string& w)
{
    if (!cp.is_object()) throw std::runtime_error(w + ": must be an object");
    const Eigen::Index n = A.rows();
    Coupling c;
    c.name = cp.value("name", std::string("coupling"));
    if (cp.contains("unit")) {
        if (!cp.at("unit").is_string()) throw std::runtime_error(w + ": 'unit' must be a string");
        c.unit = cp.at("unit").get<std::string>();
    }
    Eigen::VectorXd t;
    if (cp.contains("modal")) {
        // A flexible mode of a continuous modal model: eta'' = -w^2 eta - ...,
        // position state i, rate state j; an extra modal force f (unit modal
        // mass) adds -f to eta'' as a spring force of the mode would.
        const json& md = cp.at("modal");
        for (const char* k : {"twist", "torque", "stiffness"})
            if (cp.contains(k)) throw std::runtime_error(w + ": give either 'modal' or '" + k + "', not both");
        if (Ac.size() == 0)
            throw std::runtime_error(w + ": 'modal' needs a continuous plant (a discrete one states 'twist', 'torque' and 'stiffness')");
        auto index = [&](const char* k) {
            if (!md.is_object() || !md.contains(k) || !md.at(k).is_number_integer() || md.at(k).get<long>() < 0 ||
                md.at(k).get<long>() >= long(n))
                throw std::runtime_error(w + ": 'modal' needs '" + k + "', a plant state index in [0, " + std::to_string(n - 1) + "]");
            return Eigen::Index(md.at(k).get<long>());
        };
        const Eigen::Index i = index("position"), j = index("rate");
        if (i == j) throw std::runtime_error(w + ": 'modal' position and rate must be different states");
        if (Ac(i, j) != 1.0)
            throw std::runtime_error(w + ": 'modal' position state " + std::to_string(i) + " must be the integral of rate state " +
                                     std::to_string(j) + " (A[" + std::to_string(i) + "][" + std::to_string(j) + "] = 1)");
        c.stiffness = -Ac(j, i);
        if (!(c.stiffness > 0))
            throw std::runtime_error(w + ": 'modal' state " + std::to_string(i) + " is not an oscillating mode (A[" +
                                     std::to_string(j) + "][" + std::to_string(i) + "] = " + std::to_string(Ac(j, i)) +
                                     ", must be -w^2 < 0)");
        c.twist = Eigen::RowVectorXd::Zero(n);
        c.twist(i) = 1.0;
        t = Eigen::VectorXd::Zero(n);
        t(j) = -1.0;
    } else {
        auto vec = [&](const char* key) {
            if (!cp.contains(key) || !cp.at(key).is_array() || Eigen::Index(cp.at(key).size()) != n)
                throw std::runtime_error(w + ": '" + key + "' must list " + std::to_string(n) + " numbers (one per plant state)");
            Eigen::VectorXd v(n);
            for (Eigen::Index i = 0; i < n; ++i) {
                const json& e = cp.at(key)[size_t(i)];
                if (!e.is_number()) throw std::runtime_error(w + ": '" + key + "' has a non-numeric entry");
                v(i) = e.get<double>();
            }
            if (!v.allFinite()) throw std::runtime_error(w + ": '" + key + "' has a non-finite entry");
            if (v.cwiseAbs().maxCoeff() == 0.0) throw std::runtime_error(w + ": '" + key + "' is all zero");
            return v;
        };
        c.twist = vec("twist").transpose();
        t = vec("torque");
        if (!cp.contains("stiffness") || !cp.at("stiffness").is_number())
            throw std::runtime_error(w + ": missing number 'stiffness'");
        c.stiffness = cp.at("stiffness").get<double>();
        if (!(c.stiffness > 0) || !std::isfinite(c.stiffness))
            throw std::runtime_error(w + ": 'stiffness' must be a finite number > 0");
    }
    if (Ac.size() != 0) {
        // A continuous plant's torque column is discretised with it (zero-order hold).
        c.torque_c = t;
        Eigen::MatrixXd Ad, Bd;
        zoh(Ac, t, Ts, Ad, Bd);
        t = Bd.col(0);
    }
    c.torque = t;
    setup_coupling_substeps(c, A, Ts, cp, w);
    return c;
}

}  // namespace

std::vector<Coupling> read_couplings(const json& spec, const Eigen::MatrixXd& A, const Eigen::MatrixXd& Ac, double Ts)
{
    std::vector<Coupling> out;
    if (spec.is_array()) {
        if (spec.empty()) throw std::runtime_error("model gap.coupling: an empty list (leave the key out for no coupling)");
        for (size_t i = 0; i < spec.size(); ++i)
            out.push_back(read_one(spec[i], A, Ac, Ts, "model gap.coupling[" + std::to_string(i) + "]"));
    } else {
        out.push_back(read_one(spec, A, Ac, Ts, "model gap.coupling"));
    }
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < i; ++j)
            if (out[i].name == out[j].name)
                throw std::runtime_error("model gap.coupling: two couplings are named '" + out[i].name + "' (names must differ)");
    return out;
}

int coupling_gl_memory(const Coupling& c, double Ts, int base, long cap)
{
    long L = base;
    if (c.w_slow > 0) L = std::max(L, long(std::ceil(20.0 / (c.w_slow * Ts))));
    return int(std::max(1L, std::min(L, cap)));
}

}  // namespace gap
}  // namespace fracdesign
