// foprocess.cpp - the fractional-order delayed process of seed 001, eqs. (1), (4), (51).
#include "fracdesign/models/foprocess.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace fracdesign {

void FoProcess::validate() const
{
    auto bad = [](const char* f, const char* what) { throw std::invalid_argument(std::string("fo process: ") + f + " " + what); };
    if (!std::isfinite(K)) bad("K", "must be finite");
    if (!std::isfinite(T) || T <= 0) bad("T", "must be finite and > 0");
    if (!std::isfinite(lambda) || lambda <= 0 || lambda > 2) bad("lambda", "must be in (0, 2]");
    if (!std::isfinite(tau) || tau < 0) bad("tau", "must be finite and >= 0");
}

double FoProcess::time_scale() const { return std::pow(T, 1.0 / lambda); }

double FoProcess::normalised_delay() const { return tau / time_scale(); }  // erratum E1: T^(1/lambda), not T^lambda

double FoProcess::normalised_frequency(double w) const { return w * time_scale(); }

static std::complex<double> jw_pow(double w, double a)
{
    return std::polar(std::pow(w, a), a * M_PI / 2.0);  // principal branch of (j w)^a, w > 0
}

std::complex<double> FoProcess::frf(double w) const
{
    return K * std::exp(std::complex<double>(0.0, -w * tau)) / (T * jw_pow(w, lambda) + 1.0);
}

std::complex<double> FoProcess::normalised_frf(double wn) const
{
    return std::exp(std::complex<double>(0.0, -wn * normalised_delay())) / (jw_pow(wn, lambda) + 1.0);
}

FoProcess feliu_benftima_robot()
{
    FoProcess p;
    const double w0 = 5.8434;  // rad/s, seed 001 Sec. 5.1
    p.K = 1.0;
    p.T = 1.0 / (w0 * w0);     // (51): 1/w0^2
    p.lambda = 1.92;           // (46)
    p.tau = 0.1613;            // 15 % of the 1.0753 s period
    return p;
}

}  // namespace fracdesign
