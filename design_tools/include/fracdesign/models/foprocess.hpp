// foprocess.hpp - the fractional-order delayed process of seed 001 (eq. (1), (4)):
//
//   G(s) = K e^{-tau s} / (T s^lambda + 1),   1 < lambda <= 2
//
// and its normalisation (Sec. 3): t_n = t / T^(1/lambda), w_cn = w_c T^(1/lambda),
// tau_n = tau / T^(1/lambda). The paper prints tau_n = tau / T^lambda; notes 001 erratum E1: only the
// 1/lambda form is consistent with t_n and reproduces the published controller (52).
// The robot of Sec. 5 (eq. (51)): K = 1, T = 1/w0^2, w0 = 5.8434 rad/s, lambda = 1.92, tau = 0.1613 s.
#pragma once
#include <complex>

namespace fracdesign {

struct FoProcess {
    double K = 1.0;        // static gain
    double T = 1.0;        // "time constant" [s^lambda]
    double lambda = 1.0;   // order
    double tau = 0.0;      // dead time [s]
    void validate() const; // std::invalid_argument naming the field (non-finite, T <= 0, lambda <= 0, tau < 0)

    double time_scale() const;                       // T^(1/lambda) [s]
    double normalised_delay() const;                 // tau_n = tau / T^(1/lambda) (erratum E1)
    double normalised_frequency(double w) const;     // w T^(1/lambda)
    std::complex<double> frf(double w) const;        // G(j w), w > 0 rad/s, principal branch
    std::complex<double> normalised_frf(double wn) const;  // G_n(j wn) = e^{-tau_n j wn}/((j wn)^lambda + 1)
};

// The teleoperated robot of seed 001 Sec. 5, eq. (51).
FoProcess feliu_benftima_robot();

}  // namespace fracdesign
