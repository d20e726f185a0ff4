// haro_synthetic.cpp - synthetic antenna FRFs (see haro_synthetic.hpp).
#include "fracdesign/ident/haro_synthetic.hpp"

#include <cmath>
#include <random>

namespace fracdesign {
namespace ident {

Frf haro_synthetic_frf(const AntennaDamping<double>& d, const std::vector<double>& w, double rel_noise,
                       unsigned seed, const AntennaLink& link)
{
    std::mt19937_64 rng(seed);
    auto uniform = [&rng]() { return (double(rng() >> 11) + 0.5) * (1.0 / 9007199254740992.0); };
    Frf f;
    f.w = w;
    for (double x : w) {
        const std::complex<double> g = antenna_frf(link, d, x);
        const double r = std::sqrt(-2.0 * std::log(uniform())), a = 2.0 * M_PI * uniform();
        f.G.push_back(g * std::complex<double>(1.0 + rel_noise * r * std::cos(a), rel_noise * r * std::sin(a)));
    }
    return f;
}

}  // namespace ident
}  // namespace fracdesign
