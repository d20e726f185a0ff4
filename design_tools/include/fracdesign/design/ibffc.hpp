// ibffc.hpp - inversion-based feedforward by stable inversion (seed 004 Sec. 4.3, App. E, F).
//
// The project inverts the sampled arm channel tau_M -> psi'(L) as a whole (ZOH at the PLC
// period h, the torque being held between samples on the drive): the exact discrete inverse of
//   x[k+1] = A x[k] + b u[k],  y[k] = c x[k]   (c b != 0, discrete relative degree 1)
// is u[k] = (y*[k+1] - c A x[k]) / (c b) with the internal dynamics (App. E, (E.10)-(E.11))
//   x[k+1] = A_bar x[k] + b_bar y*[k+1],  A_bar = A - b c A/(c b),  b_bar = b/(c b).
// Stable inversion (4.32)-(4.34), App. F: modal form of A_bar, the part with |lambda| <= 1 is
// run forward in time from rest before the motion, the part with |lambda| > 1 backward in time
// from rest after it, so x* and u* are bounded and non-causal: pre- and post-actuation. The
// states give the drive references directly: theta_M* = x*_1, theta_M*' = c_1 x* (the thesis'
// separate drive inversion (4.35)-(4.40) is not needed, which also avoids its r_h inconsistency,
// notes 004b 4.4). The beam damping r_t, r_r (not given by the thesis) enters through the model.
#pragma once
#include <functional>
#include <vector>

#include "fracdesign/models/lti.hpp"

namespace fracdesign::design {

// Eigenvalues of the zero dynamics within this distance of 1 are the angle mode (run forward).
constexpr double kIbffcAngleModeTol = 1e-6;

struct IbffcResult {
    double h = 0.0;
    std::vector<double> t, u, y_des;  // time [s], tau_M* [N m], desired psi'(L) [rad/s]
    std::vector<double> theta_M, theta_M_dot;  // drive references from x*
    std::vector<double> y_sim;        // psi'(L) of the model driven by u* from rest
    double rel_rms = 0.0;             // rms(y_sim - y_des) / rms(y_des)
    int n_forward = 0, n_backward = 0;  // modes integrated forward / backward in time
};

// plant: continuous measured arm model (arm_measured_model: outputs theta_M, theta_M', psi'(L)).
// y_des(t): desired tip angular velocity; the horizon [t0, t1] must contain the motion plus
// enough time for the pre-/post-actuation to decay. Throws std::invalid_argument on bad
// arguments and std::runtime_error when c b = 0 (relative degree > 1 at this h).
IbffcResult stable_inversion(const StateSpace& plant, double h, const std::function<double(double)>& y_des, double t0,
                             double t1);

}  // namespace fracdesign::design
