// wang_design.cpp - seed 004 (M. Wang, PhD thesis, TUM) trajectory and control design checks.
#include <cmath>

#include "fracdesign/design/trajectory.hpp"
#include "fracdesign/reproduce.hpp"

namespace fracdesign {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Table 8.5: q_s = 0, q_e = pi/2, qd_m = pi/2, qdd_m = 2 pi, t_s = 0.5 s, t_e = 2 s.
design::SinSquaredPtp table85() { return design::SinSquaredPtp({0.0, kPi / 2, kPi / 2, 2 * kPi, 0.5, 2.0}); }

CheckRegistrar traj({"wang.traj", "seed 004 Table 8.5, eqs. (4.1)-(4.7) (corrected (4.5), (4.7))", [] {
    const auto p = table85();
    CheckOutcome r;
    // t_a, absolute t_e, q(t_a), q(t_b), q(t_e), qd at mid-cruise, qdd(0.25 local), qdd(1.25 local)
    r.expected = {0.5, 2.0, kPi / 8, 3 * kPi / 8, kPi / 2, kPi / 2, 2 * kPi, -2 * kPi};
    r.got = {p.t_a(), p.t_end(), p.eval(1.0)[0], p.eval(1.5)[0], p.eval(2.0)[0], p.eval(1.25)[1], p.eval(0.75)[2],
             p.eval(1.75)[2]};
    r.tol = 1e-12;
    r.note = "t_a [s], t_e [s], waypoints q(t_a), q(t_b), q(t_e) [rad], cruise velocity, peak accelerations (notes 004b C1-C3)";
    return r;
}});

}  // namespace
}  // namespace fracdesign
