// fo_realization.cpp - Oustaloup state spaces and the rational realization of
// the seed 001 process (see fo_realization.hpp for the equations).
#include "fracdesign/models/fo_realization.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace fracdesign {

void OustaloupBand::validate() const
{
    auto bad = [](const std::string& f, double v, const std::string& allowed) {
        char b[64];
        std::snprintf(b, sizeof b, "%.6g", v);
        throw std::invalid_argument("realization." + f + ": is " + b + ", must be " + allowed);
    };
    if (!std::isfinite(wb) || !(wb > 0)) bad("wb", wb, "a finite band edge > 0 rad/s");
    if (!std::isfinite(wh) || !(wh > wb)) bad("wh", wh, "a finite band edge above wb, in rad/s");
    if (N < 1 || N > kOustaloupNMax) bad("N", N, "an integer in [1, " + std::to_string(kOustaloupNMax) + "]");
}

OustaloupBand default_oustaloup_band(double Ts, double record_seconds)
{
    OustaloupBand b;
    b.wb = 2 * M_PI / (1e4 * record_seconds);
    b.wh = 1000 * M_PI / Ts;
    b.N = int(std::ceil(1.5 * std::log10(b.wh / b.wb)));
    if (b.N > kOustaloupNMax) b.N = kOustaloupNMax;
    return b;
}

StateSpace oustaloup_state_space(double r, const OustaloupBand& band)
{
    band.validate();
    if (!(r >= 0 && r < 1)) throw std::invalid_argument("oustaloup: order " + std::to_string(r) + " must be in [0, 1)");
    StateSpace s;
    s.inputs = {"u"};
    s.outputs = {"y"};
    if (r == 0) {
        s.A.resize(0, 0);
        s.B.resize(0, 1);
        s.C.resize(1, 0);
        s.D = Eigen::MatrixXd::Ones(1, 1);
        return s;
    }
    const int N = band.N, ns = 2 * N + 1;
    const double ratio = band.wh / band.wb;
    // Cascade of sections (s + z)/(s + p) = 1 + (z - p)/(s + p): section i's
    // state is driven by the cascade's output so far and adds (z - p) x_i.
    s.A = Eigen::MatrixXd::Zero(ns, ns);
    s.B = Eigen::MatrixXd::Zero(ns, 1);
    s.C = Eigen::MatrixXd::Zero(1, ns);
    s.D = Eigen::MatrixXd::Ones(1, 1);
    for (int k = -N; k <= N; ++k) {
        const int i = k + N;
        const double z = band.wb * std::pow(ratio, (k + N + 0.5 * (1 - r)) / ns);
        const double p = band.wb * std::pow(ratio, (k + N + 0.5 * (1 + r)) / ns);
        s.A.block(i, 0, 1, i) = s.C.leftCols(i);
        s.A(i, i) = -p;
        s.B(i, 0) = s.D(0, 0);
        s.C(0, i) = z - p;
        s.states.push_back("oustaloup_" + std::to_string(i));
    }
    // Gain: |O(j wg)| = wg^r at the geometric centre wg = sqrt(wb wh).
    const double wg = std::sqrt(band.wb * band.wh);
    const double g = std::pow(wg, r) / std::abs(s.frequency_response(wg)(0, 0));
    s.C *= g;
    s.D *= g;
    return s;
}

StateSpace foprocess_realization(const FoProcess& p, const OustaloupBand& band)
{
    p.validate();
    const int n = p.lambda > 1 ? 2 : 1;
    const StateSpace o = oustaloup_state_space(double(n) - p.lambda, band);
    // Unity loop around F = O(s)/(T s^n): e = K v - y, w = O e,
    // z_1' = w/T, z_2' = z_1 (n = 2), y = z_n.
    const Eigen::Index no = o.nx(), nx = no + n, yi = nx - 1;
    StateSpace s;
    s.A = Eigen::MatrixXd::Zero(nx, nx);
    s.B = Eigen::MatrixXd::Zero(nx, 1);
    s.C = Eigen::MatrixXd::Zero(1, nx);
    s.D = Eigen::MatrixXd::Zero(1, 1);
    s.A.topLeftCorner(no, no) = o.A;
    s.A.block(0, yi, no, 1) = -o.B;
    s.B.topRows(no) = p.K * o.B;
    s.A.block(no, 0, 1, no) = o.C / p.T;
    s.A(no, yi) -= o.D(0, 0) / p.T;
    s.B(no, 0) = p.K * o.D(0, 0) / p.T;
    if (n == 2) s.A(no + 1, no) = 1.0;
    s.C(0, yi) = 1.0;
    s.inputs = {"u"};
    s.outputs = {"y"};
    s.states = o.states;
    for (int j = 0; j < n; ++j) s.states.push_back("integrator_" + std::to_string(j));
    // The cascade's entries span the band (up to wh^(1 + r)/T, 1e12 at 1 ms
    // over eleven decades, beside wb ~ 1e-5): its zero-order hold lost the
    // step response (a 12 s record at 1 ms, lambda 1.09: the step's end at
    // 0.33 for K = 1.86). Balanced, the entries are of the poles' size.
    return s.balanced();
}

double foprocess_realization_error(const FoProcess& p, const OustaloupBand& band, double w_lo, double w_hi)
{
    const StateSpace s = foprocess_realization(p, band);
    FoProcess exact = p;
    exact.tau = 0;
    double worst = 0;
    const int n = std::max(2, int(std::ceil(200 * std::log10(w_hi / w_lo))) + 1);
    for (int i = 0; i < n; ++i) {
        const double w = w_lo * std::pow(w_hi / w_lo, double(i) / double(n - 1));
        const std::complex<double> g = exact.frf(w), h = s.frequency_response(w)(0, 0);
        worst = std::max(worst, std::abs(h - g) / std::abs(g));
    }
    return worst;
}

}  // namespace fracdesign
