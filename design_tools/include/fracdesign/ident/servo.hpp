// servo.hpp - rigid servo axis with friction, its closed-loop simulation with
// the EMPS position controller, and inverse-model least squares (IDIM-LS).
//
// Model (EMPS description, Janot, Gautier & Brunot 2019, eqs. 1-4, extended
// with a Stribeck term):
//   M q'' = F - Fv q' - (Fc + Fs exp(-(q'/vs)^2)) sign(q') - offset
// with F the actuator force in N (F = gtau u for a drive of gain gtau N/V).
// Parameter vector order (everywhere in this header and in the CLI):
//   theta = [M, Fv, Fc, offset, Fs, vs]   (kg, N s/m, N, N, N, m/s)
// Fs = 0 gives the EMPS reference model; vs must be > 0 when Fs != 0.
//
// Controller (EMPS description eq. 6 and the reference Simulink model, as
// documented in data/real/emps/README.md):
//   qf(k) = (q(k) + q(k-1))/2,  v(k) = (qf(k) - qf(k-1))/dt
//   u_pd(k) = kv (kp (qr(k) - q(k)) - v(k))         [V]
//   u(k) = sat(u_pd(k - delay), +-u_max) + u_add(k)  [V], held over [t_k, t_k+dt)
// The plant is integrated with classical RK4 on `substeps` equal steps per
// sample (the reference model uses ode45 with MaxStep = dt/10). The sign()
// makes the right-hand side discontinuous at q' = 0; with substeps = 10 the
// position error that causes is far below the encoder resolution.
// Templates run with double and ceres::Jet (automatic derivatives through the
// whole simulation for output-error identification).
#pragma once
#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

namespace fracdesign {
namespace ident {

constexpr int kServoParams = 6;
extern const char* const kServoParamNames[kServoParams];  // "M", "Fv", "Fc", "offset", "Fs", "vs"

// The EMPS-type cascaded P/PD position controller.
struct ServoController {
    double kp = 0.0;      // outer position gain, 1/s
    double kv = 0.0;      // velocity gain, V/(m/s)
    double gtau = 1.0;    // drive gain, N/V
    double u_max = 10.0;  // saturation, V
    int delay = 1;        // computation delay, samples (>= 0)
};

template <class T>
T servo_sign(const T& v)
{
    return v > T(0.0) ? T(1.0) : (v < T(0.0) ? T(-1.0) : T(0.0));
}

// Friction force at velocity v (N): viscous + Coulomb/Stribeck + offset.
template <class T>
T servo_friction(const T* th, const T& v)
{
    using std::exp;
    T stribeck = T(0.0);
    if (th[4] != T(0.0)) {
        const T r = v / th[5];
        stribeck = th[4] * exp(-r * r);
    }
    return th[1] * v + (th[2] + stribeck) * servo_sign(v) + th[3];
}

// Advances (q, v) over one sample of length dt with the force F held, by RK4
// on `substeps` sub-steps.
template <class T>
void servo_step(const T* th, const T& F, double dt, int substeps, T& q, T& v)
{
    const double h = dt / substeps;
    for (int i = 0; i < substeps; ++i) {
        const T a1 = (F - servo_friction(th, v)) / th[0];
        const T v2 = v + 0.5 * h * a1;
        const T a2 = (F - servo_friction(th, v2)) / th[0];
        const T v3 = v + 0.5 * h * a2;
        const T a3 = (F - servo_friction(th, v3)) / th[0];
        const T v4 = v + h * a3;
        const T a4 = (F - servo_friction(th, v4)) / th[0];
        q += h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
        v += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    }
}

// Open loop: the force sequence F[k] (N) held over each sample; returns q[k]
// at t_k (q[0] = q0).
template <class T>
std::vector<T> simulate_servo_open_loop(const T* th, const std::vector<double>& F, double dt, int substeps,
                                        double q0 = 0.0, double v0 = 0.0)
{
    std::vector<T> q(F.size());
    T qs = T(q0), vs = T(v0);
    for (std::size_t k = 0; k < F.size(); ++k) {
        q[k] = qs;
        servo_step(th, T(F[k]), dt, substeps, qs, vs);
    }
    return q;
}

// Closed loop with `ctl` from the reference qr (m) and the signal u_add (V,
// empty = none) added after the saturation. Starts at rest at q0 with zero
// controller history. Fills q[k] (m) and, if u is not null, the command as
// the EMPS rig records it: u_pd[k] + u_add[k] (V, before the delay; the
// README's check: recorded vir = PD law + pulses at zero lag).
template <class T>
void simulate_servo_closed_loop(const T* th, const ServoController& ctl, const std::vector<double>& qr,
                                const std::vector<double>& u_add, double dt, int substeps, std::vector<T>& q,
                                std::vector<T>* u = nullptr, double q0 = 0.0)
{
    const std::size_t n = qr.size();
    q.assign(n, T(0.0));
    if (u) u->assign(n, T(0.0));
    std::vector<T> hist(std::size_t(ctl.delay) + 1, T(0.0));  // ring of controller outputs
    T qs = T(q0), vs = T(0.0), q_prev = T(q0), qf_prev = T(q0);
    for (std::size_t k = 0; k < n; ++k) {
        q[k] = qs;
        const T qf = 0.5 * (qs + q_prev);
        const T vel = (qf - qf_prev) / dt;
        const T upd = ctl.kv * (ctl.kp * (qr[k] - qs) - vel);
        if (u) (*u)[k] = u_add.empty() ? upd : upd + u_add[k];
        hist[k % hist.size()] = upd;
        T ua = hist[(k + 1) % hist.size()];  // output from `delay` samples ago (zero before start)
        if (ua > T(ctl.u_max)) ua = T(ctl.u_max);
        if (ua < T(-ctl.u_max)) ua = T(-ctl.u_max);
        if (!u_add.empty()) ua += u_add[k];
        q_prev = qs;
        qf_prev = qf;
        servo_step(th, ctl.gtau * ua, dt, substeps, qs, vs);
    }
}

// Relative norm error 100 ||y - yhat|| / ||y|| in percent over samples
// [skip, n) (EMPS description sec. 3.5: first 50 samples dropped).
double relative_error_percent(const std::vector<double>& y, const std::vector<double>& yhat, std::size_t skip);

struct IdimOptions {
    int filter_order = 4;        // Butterworth order for the position filter
    double filter_fc_hz = 100.0;  // its cut-off (the EMPS authors' 100 Hz)
    int decimation = 10;         // parallel decimation factor
    int decimation_order = 8;    // Butterworth order of the decimation filter, cut-off 0.8 fs/(2 decimation)
    std::size_t border = 100;    // samples dropped at each end (filter edge effects)
};

struct IdimResult {
    Eigen::Vector4d theta;       // [M, Fv, Fc, offset]
    Eigen::Vector4d std_dev;     // sigma_hat sqrt(diag((W'W)^-1)), with sigma_hat^2 = ||r||^2/(rows - 4)
    double cond = 0.0;           // condition number of the observation matrix W
    double rel_error = 0.0;      // 100 ||Y - W theta|| / ||Y|| on the decimated system, percent
    std::size_t rows = 0;        // rows of W after decimation
};

// IDIM-LS for a servo axis: Y = W theta with Y the filtered and decimated
// force and W = [q'', q', sign(q'), 1] from the filtered position
// (EMPS description sec. 3.4; Gautier, Janot & Vandanjon 2013).
// q in m, F in N, sampled every dt s. Throws std::invalid_argument for
// non-finite samples, mismatched lengths, or a record too short for the
// filters and the decimation (the message gives the minimum length).
IdimResult idim_ls_servo(const std::vector<double>& q, const std::vector<double>& F, double dt,
                         const IdimOptions& opt = IdimOptions());

}  // namespace ident
}  // namespace fracdesign
