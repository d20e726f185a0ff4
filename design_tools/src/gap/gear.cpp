// gear.cpp - the gear site (effects.hpp GearSite, docs/gap.md "The gear
// site"): where a rigid nominal has a motor-side body that a compliant gear
// with a play may split from its load, and the play's sub-steps, which a
// declared coupling's play (replay.cpp) shares.
//
// The two-body split of a rigid body (Nordin & Gutman, "Controlling
// mechanical systems with backlash - a survey", Automatica 38 (2002),
// the dead-zone model of the shaft): the motor (inertia (1 - r) J) drives
// the load (r J) through a spring k with a damper c and a play of total
// width w, T = k dz(q) + c q', q = theta_m - theta_l, dz(q) = q -
// clamp(q, -w/2, w/2). With the viscous friction proportional to each
// body's inertia (b J on the whole), the centre of mass moves exactly as the
// rigid nominal, theta_m = theta_cm + r q, and
//     q'' = a / (1 - r) - b q' - 2 zeta w_g q' - w_g^2 dz(q),
// a = the nominal's force per inertia (its acceleration less the viscous
// term), w_g^2 = k / mu and 2 zeta w_g = c / mu with mu = r (1 - r) J the
// reduced inertia: w_g is the contact resonance, the gear's mode.
#include <algorithm>
#include <cmath>

#include "fracdesign/gap/effects.hpp"

namespace fracdesign {
namespace gap {

GearSite gear_site(const NominalModel& m)
{
    GearSite g;
    const Eigen::Index n = m.A.rows();
    if (!m.couplings.empty()) {
        g.why = "the model declares a coupling (gap.coupling), which holds its own play";
        return g;
    }
    if (m.velocity < 0) {
        g.why = "the model names no velocity output (gap.velocity)";
        return g;
    }
    if (m.Ac.rows() != n || m.Bc.rows() != n) {
        g.why = "the plant has no continuous generator";
        return g;
    }
    // The velocity output reads one state.
    int j = -1;
    for (Eigen::Index i = 0; i < n; ++i) {
        if (m.C(m.velocity, i) == 0.0) continue;
        if (j >= 0) {
            g.why = "the velocity output reads more than one state";
            return g;
        }
        j = int(i);
    }
    if (j < 0) {
        g.why = "the velocity output reads no state";
        return g;
    }
    // Its integral: a state whose derivative is kappa x_j alone.
    for (Eigen::Index i = 0; i < n && g.p < 0; ++i) {
        if (i == j || m.Ac(i, j) == 0.0 || m.Bc.row(i).cwiseAbs().maxCoeff() != 0.0) continue;
        bool only = true;
        for (Eigen::Index l = 0; l < n; ++l) only = only && (l == j || m.Ac(i, l) == 0.0);
        if (only) g.p = int(i), g.kappa = m.Ac(i, j);
    }
    if (g.p < 0) {
        g.why = "no plant state is the integral of the velocity state (a position)";
        return g;
    }
    // The body's position must not feed back (a rigid body: no spring to ground).
    for (Eigen::Index i = 0; i < n; ++i)
        if (m.Ac(i, g.p) != 0.0) {
            g.why = "the position state feeds back into the plant (a spring to ground, not a free body)";
            g.p = -1;
            return g;
        }
    g.j = j;
    for (Eigen::Index o = 0; o < m.C.rows() && g.position_output < 0; ++o) {
        bool only = m.C(o, g.p) != 0.0;
        for (Eigen::Index i = 0; i < n; ++i) only = only && (i == g.p || m.C(o, i) == 0.0);
        if (only) g.position_output = int(o);
    }
    g.ok = true;
    return g;
}

namespace {

// The sub-step loop on any Eigen vector/matrix types: fixed-size 2 for the
// gear and a two-state coupling (no allocation per sample), dynamic else.
template <class Vec, class Mat, class Row>
void play_loop(Vec& z, const Vec& drive, const Mat& Phi, const Vec& torque, const Row& twist, double k, double w,
               int substeps)
{
    const double tt = twist.dot(torque);
    Vec zp(z.size());
    for (int s = 0; s < substeps; ++s) {
        zp.noalias() = Phi * z;
        zp += drive;
        const double a0 = twist.dot(z), a1 = twist.dot(zp);
        double D = 0;
        for (int it = 0; it < 3; ++it) {
            const double q = 0.5 * (a0 + a1 + tt * D);
            D = -k * std::min(std::max(q, -0.5 * w), 0.5 * w);
        }
        z = zp;
        z += torque * D;
    }
}

}  // namespace

void play_substeps(Eigen::VectorXd& z, const Eigen::VectorXd& drive, const Eigen::MatrixXd& Phi,
                   const Eigen::VectorXd& torque, const Eigen::RowVectorXd& twist, double k, double w, int substeps)
{
    if (z.size() == 2) {
        Eigen::Vector2d z2 = z;
        const Eigen::Vector2d d2 = drive, t2 = torque;
        const Eigen::Matrix2d P2 = Phi;
        const Eigen::RowVector2d w2 = twist;
        play_loop(z2, d2, P2, t2, w2, k, w, substeps);
        z = z2;
        return;
    }
    play_loop(z, drive, Phi, torque, twist, k, w, substeps);
}

}  // namespace gap
}  // namespace fracdesign
