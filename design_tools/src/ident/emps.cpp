// emps.cpp - loading the EMPS benchmark records (see emps.hpp).
#include "fracdesign/ident/emps.hpp"

#include <cmath>
#include <stdexcept>

#include "fracdesign/io/matv5.hpp"

namespace fracdesign {
namespace ident {

std::vector<double> EmpsRecord::force() const
{
    std::vector<double> f(vir.size());
    for (std::size_t k = 0; k < vir.size(); ++k) f[k] = controller.gtau * vir[k];
    return f;
}

EmpsRecord load_emps_mat(const std::string& path)
{
    const io::MatFile m = io::read_mat_v5(path);
    EmpsRecord r;
    r.t = m.vector("t");
    r.qm = m.vector("qm");
    r.qg = m.vector("qg");
    r.vir = m.vector("vir");
    if (m.vars.count("pulses_N")) r.pulses = m.vector("pulses_N");
    r.controller.gtau = m.at("gtau").scalar();
    r.controller.kp = m.at("kp").scalar();
    r.controller.kv = m.at("kv").scalar();
    const std::size_t n = r.t.size();
    if (n < 3) throw std::invalid_argument(path + ": too short (" + std::to_string(n) + " samples)");
    for (const auto* v : {&r.qm, &r.qg, &r.vir})
        if (v->size() != n)
            throw std::invalid_argument(path + ": vectors of different lengths (t has " + std::to_string(n) + ")");
    if (!r.pulses.empty() && r.pulses.size() != n) throw std::invalid_argument(path + ": pulses_N length differs from t");
    r.dt = (r.t.back() - r.t.front()) / double(n - 1);
    for (std::size_t k = 0; k < n; ++k) {
        if (!std::isfinite(r.t[k]) || !std::isfinite(r.qm[k]) || !std::isfinite(r.qg[k]) || !std::isfinite(r.vir[k]))
            throw std::invalid_argument(path + ": non-finite sample at index " + std::to_string(k));
        if (k && std::fabs(r.t[k] - r.t[k - 1] - r.dt) > 1e-3 * r.dt)
            throw std::invalid_argument(path + ": non-uniform time step at index " + std::to_string(k));
    }
    return r;
}

std::string emps_data_path(const std::string& file)
{
    return std::string(FRAC_SHARED_DIR) + "/data/real/emps/" + file;
}

}  // namespace ident
}  // namespace fracdesign
