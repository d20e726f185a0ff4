// family_servo.cpp - gap-bench family "servo": a rigid servo axis
//     J theta'' = Ka (u_drive - F(theta')) - b theta'
// (J, b, Ka drawn per case), position loop: PD with a filtered difference,
//     e_k = r_k - theta_k,  d_k = a d_{k-1} + (1 - a) (e_k - e_{k-1}) / Ts,
//     c_k = Kp e_k + Kd d_k,  clipped to +-10 V, one cycle of computation delay,
// gains placed for a drawn bandwidth (families.hpp, docs/gap.md "Families").
// Forces are in volts at the drive input (the nominal's force input), so the
// diagnosis's friction, dead zone and limit parameters are in V: a friction
// of F Nm at the shaft is F / Ka V.
//
// The simulator is the bench's own (not the diagnosis's replay): 20 exact
// sub-steps per sample of the linear part (axis with its viscous friction,
// and the series mode when injected) with the drive force held, dry
// friction per sub-step as the force that stops the axis within the
// sub-step, limited to its level (Karnopp), so that the effect-free record
// is the zero-order-hold nominal up to the sensor noise. (Before, the mode
// was stepped by semi-implicit Euler and the viscous term explicitly: at
// 20 sub-steps that moved a loop's limit cycle by more than the replay's
// own error; 100 sub-steps differed from 20 by 4.6 % of the position's std
// after 3 s on a 38 Hz mode.)
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>

#include "fracbench/families.hpp"
#include "fracbench/visibility.hpp"
#include "fracdesign/gap/nominal.hpp"

namespace fracbench {

namespace {

const double kTs = 1e-3;        // [s]
const double kDuration = 3.0;   // [s]
const int kSub = 20;            // sub-steps per sample
const double kClip = 10.0;      // [V]
const int kCompDelay = 1;       // controller -> drive, samples
const double kInf = std::numeric_limits<double>::infinity();

struct Plant {
    double J, b, Ka;            // [kg m^2], [Nm s/rad], [Nm/V]
    double Kp, Kd, a;           // [V/rad], [V s/rad], difference filter pole
    double A1, f1, A2, f2;      // reference tones [rad], [Hz]
    double sigma_pos, sigma_vel;  // sensor noise std [rad], [rad/s]
};

struct Injection {
    int extra_delay = 0;        // samples, drive command path
    int vel_delay = 0;          // samples, velocity sensor
    int pos_delay = 0;          // samples, position sensor (never drawn: a drive delay's equivalent, add_equivalents)
    double gain = 1;                                // drive gain
    double lim_lo = -kInf, lim_hi = kInf;           // drive limits [V] (asymmetric)
    double dz_lo = 0, dz_hi = 0;                    // drive dead-zone edges [V] (asymmetric, lower <= 0 <= upper)
    double Fc = 0, Fv = 0, Fs = 0, vs = 1;         // friction [V], [V s/rad], Stribeck static level [V], [rad/s]
    bool stribeck = false;
    double vel_offset = 0;      // [rad/s]
    double pos_quant = 0;       // encoder step [rad]
    double mode_hz = 0, mode_zeta = 0.05;  // resonance in series at the actuator (0: none)
};

Plant draw_plant(hil_rng* rng)
{
    Plant p;
    p.J = uniform(rng, 4e-4, 4e-3);
    p.b = p.J * uniform(rng, 0.5, 2.0);
    p.Ka = uniform(rng, 0.05, 0.3);
    const double wc = 2 * M_PI * uniform(rng, 6, 15);
    p.Kp = p.J * wc * wc / p.Ka;
    p.Kd = 2 * 0.7 * p.J * wc / p.Ka;
    p.a = std::exp(-kTs * 8 * wc);  // difference filter at 8 x the bandwidth
    p.f1 = uniform(rng, 0.8, 1.5);
    p.f2 = 2.7 * p.f1;
    // Tones sized for a peak acceleration torque of 30-60 % of Ka x 10 V.
    const double w1 = 2 * M_PI * p.f1, w2 = 2 * M_PI * p.f2, Tpk = uniform(rng, 0.3, 0.6) * p.Ka * kClip;
    p.A1 = Tpk / (p.J * (w1 * w1 + 0.4 * w2 * w2));
    p.A2 = 0.4 * p.A1;
    p.sigma_pos = 2e-4 * p.A1;
    p.sigma_vel = 3e-3 * p.A1 * w1;
    return p;
}

double reference(const Plant& p, double t)
{
    const double ts = 0.05, Tr = 0.3, ph = 1.0;
    const double e = t >= ts + Tr ? 1.0 : t > ts ? 0.5 * (1 - std::cos(M_PI * (t - ts) / Tr)) : 0.0;
    return e * (p.A1 * std::sin(2 * M_PI * p.f1 * t) + p.A2 * (std::sin(2 * M_PI * p.f2 * t + ph) - std::sin(ph)));
}

struct Run {
    Eigen::MatrixXd y;   // samples x [position, velocity] as the sensors read them
    Eigen::VectorXd ref, cmd;
};

// The axis's linear part, z = [theta, v, eta, eta'] with inputs [u, F] (F the
// dry friction force, V at the drive input, opposing):
//   J v' = Ka (d - Fv v - F) - b v,  d = eta with the mode, else u;
//   eta'' = wm^2 (u - eta) - 2 zeta wm eta'.
// Without the mode, eta and eta' stay at zero and do not act.
void axis_generator(const Plant& p, const Injection& in, Eigen::MatrixXd& Ac, Eigen::MatrixXd& Bc)
{
    const double wm = 2 * M_PI * in.mode_hz;
    Ac = Eigen::MatrixXd::Zero(4, 4);
    Bc = Eigen::MatrixXd::Zero(4, 2);
    Ac(0, 1) = 1;
    Ac(1, 1) = -(p.b + p.Ka * in.Fv) / p.J;
    Bc(1, 1) = -p.Ka / p.J;
    if (in.mode_hz > 0) {
        Ac(1, 2) = p.Ka / p.J;
        Ac(2, 3) = 1;
        Ac(3, 2) = -wm * wm;
        Ac(3, 3) = -2 * in.mode_zeta * wm;
        Bc(3, 0) = wm * wm;
    } else {
        Bc(1, 0) = p.Ka / p.J;
    }
}

// noise == nullptr: noise-free.
Run simulate(const Plant& p, const Injection& in, hil_rng* noise)
{
    const long N = long(std::lround(kDuration / kTs));
    Run out;
    out.y.resize(N, 2);
    out.ref.resize(N);
    out.cmd.resize(N);
    double e_prev = 0, d_prev = 0;
    const int dl = kCompDelay + in.extra_delay;
    std::vector<double> cbuf(size_t(dl) + 1, 0.0), vbuf(size_t(in.vel_delay) + 1, 0.0), pbuf(size_t(in.pos_delay) + 1, 0.0);
    // The linear part (axis_generator), exact zero-order hold over a
    // sub-step: z+ = Phi z + Gam [u; F].
    const double h = kTs / kSub;
    Eigen::MatrixXd Ac, Bc, Phi, Gam;
    axis_generator(p, in, Ac, Bc);
    fracdesign::gap::zoh(Ac, Bc, h, Phi, Gam);
    Eigen::Vector4d z = Eigen::Vector4d::Zero();
    auto gauss = [&](double s) {
        if (!noise || s == 0) return 0.0;
        const double u1 = std::max(hil_rng_uniform(noise), 1e-300), u2 = hil_rng_uniform(noise);
        return s * std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
    };
    for (long k = 0; k < N; ++k) {
        const double t = double(k) * kTs, r = reference(p, t);
        for (size_t i = pbuf.size() - 1; i > 0; --i) pbuf[i] = pbuf[i - 1];
        pbuf[0] = z(0);
        double ypos = pbuf.back() + gauss(p.sigma_pos);
        if (in.pos_quant > 0) ypos = in.pos_quant * std::round(ypos / in.pos_quant);
        for (size_t i = vbuf.size() - 1; i > 0; --i) vbuf[i] = vbuf[i - 1];
        vbuf[0] = z(1);
        const double yvel = vbuf.back() + in.vel_offset + gauss(p.sigma_vel);
        const double e = r - ypos, d = p.a * d_prev + (1 - p.a) * (e - e_prev) / kTs;
        const double c = std::clamp(p.Kp * e + p.Kd * d, -kClip, kClip);
        e_prev = e;
        d_prev = d;
        for (size_t i = cbuf.size() - 1; i > 0; --i) cbuf[i] = cbuf[i - 1];
        cbuf[0] = c;
        out.y(k, 0) = ypos;
        out.y(k, 1) = yvel;
        out.ref(k) = r;
        out.cmd(k) = c;
        // The drive (the diagnosis's order: gain, limit, dead zone).
        double u = std::clamp(in.gain * cbuf.back(), in.lim_lo, in.lim_hi);
        u = u > in.dz_hi ? u - in.dz_hi : (u < in.dz_lo ? u - in.dz_lo : 0.0);
        for (int s = 0; s < kSub; ++s) {
            const double v = z(1);
            Eigen::Vector4d zn = Phi * z + Gam.col(0) * u;
            double level = in.Fc;
            if (in.stribeck) level = in.Fc + (in.Fs - in.Fc) * std::exp(-(v / in.vs) * (v / in.vs));
            // The force that stops the axis within the sub-step (v+ = 0), limited to the level.
            if (level > 0) zn += Gam.col(1) * std::clamp(-zn(1) / Gam(1, 1), -level, level);
            z = zn;
        }
    }
    return out;
}

// The small-signal loop of the drawn plant with the injection's linear part
// (gain, drive and sensor delays, series mode; limits, dead zone, friction
// and quantization left out): the zero-order hold of the axis (and mode) at
// Ts, the PD with filtered difference, the command delay line. Returns the
// smallest damping ratio over its poles (s = log(z)/Ts of the oscillatory
// poles with |z| > 0.3), -1 when a pole lies on or outside the unit circle.
double loop_damping(const Plant& p, const Injection& in)
{
    const bool mode = in.mode_hz > 0;
    const int np = mode ? 4 : 2, dl = kCompDelay + in.extra_delay, dp = in.pos_delay;
    Eigen::MatrixXd Ac4, Bc4, Ad, Bd;
    axis_generator(p, in, Ac4, Bc4);
    // Without the mode, eta and eta' are decoupled from the axis: its 2 states, driven by u.
    const Eigen::MatrixXd Ac = Ac4.topLeftCorner(np, np), Bc = Bc4.topLeftCorner(np, 1);
    fracdesign::gap::zoh(Ac, Bc, kTs, Ad, Bd);
    // State: plant (np), position readings theta(k-1..k-dp) (dp), e_{k-1}, d_{k-1}, commands c(k-1..k-dl).
    const int ip = np, ie = ip + dp, id = ie + 1, ic = id + 1, n = ic + dl;
    const double g = (1 - p.a) / kTs;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    Eigen::RowVectorXd ym = Eigen::RowVectorXd::Zero(n);  // the position the controller reads
    if (dp > 0) ym(ip + dp - 1) = 1;
    else ym(0) = 1;
    // e_k = -ym (r = 0), d_k = a d + g (e_k - e_{k-1}), c_k = Kp e_k + Kd d_k.
    const Eigen::RowVectorXd e = -ym;
    Eigen::RowVectorXd d = g * e;
    d(ie) -= g;
    d(id) += p.a;
    A.block(0, 0, np, np) = Ad;
    A.block(0, ic + dl - 1, np, 1) = in.gain * Bd;
    if (dp > 0) A(ip, 0) = 1;
    for (int i = 1; i < dp; ++i) A(ip + i, ip + i - 1) = 1;
    A.row(ie) = e;
    A.row(id) = d;
    A.row(ic) = p.Kp * e + p.Kd * d;
    for (int i = 1; i < dl; ++i) A(ic + i, ic + i - 1) = 1;
    const Eigen::VectorXcd z = Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
    double zmin = 1;
    for (Eigen::Index i = 0; i < z.size(); ++i) {
        if (std::abs(z(i)) >= 1) return -1;
        if (std::abs(z(i)) <= 0.3 || std::fabs(z(i).imag()) < 1e-12) continue;
        const std::complex<double> sk = std::log(z(i)) / kTs;
        zmin = std::min(zmin, -sk.real() / std::abs(sk));
    }
    return zmin;
}

double peak_cmd(const Plant& p)
{
    return simulate(p, Injection(), nullptr).cmd.cwiseAbs().maxCoeff();
}

TruthEffect draw_effect(const std::string& e, const Plant& p, double peak, hil_rng* rng, Injection& in)
{
    const double vmax = p.A1 * 2 * M_PI * p.f1 + p.A2 * 2 * M_PI * p.f2;
    TruthEffect t;
    t.effect = e;
    auto key = [&](const std::string& k, double v) { t.rig.push_back({k, format_value(v)}); };
    if (e == "input_delay") {
        in.extra_delay = 3 + int(hil_rng_u64(rng) % 8);
        key("drive.extra_delay_samples", in.extra_delay);
        t.params = {{"delay_s", in.extra_delay * kTs}};
    } else if (e == "output_delay") {
        in.vel_delay = 1 + int(hil_rng_u64(rng) % 4);
        key("velocity.delay_samples", in.vel_delay);
        t.params = {{"delay_s_velocity", in.vel_delay * kTs}};
    } else if (e == "coulomb_friction") {
        in.Fc = uniform(rng, 0.05, 0.15) * peak;
        key("axis.coulomb_V", in.Fc);
        t.params = {{"Fc", in.Fc}};
    } else if (e == "viscous_friction") {
        in.Fv = uniform(rng, 0.05, 0.2) * peak / vmax;
        key("axis.viscous_V_s_per_rad", in.Fv);
        t.params = {{"Fv", in.Fv}};
    } else if (e == "stribeck_friction") {
        in.stribeck = true;
        in.Fc = uniform(rng, 0.05, 0.12) * peak;
        in.Fs = in.Fc * uniform(rng, 1.6, 2.4);
        in.vs = uniform(rng, 0.05, 0.2) * vmax;
        key("axis.stribeck_Fc_V", in.Fc);
        key("axis.stribeck_Fs_V", in.Fs);
        key("axis.stribeck_vs", in.vs);
        t.params = {{"Fc", in.Fc}, {"Fs", in.Fs}};
    } else if (e == "deadzone") {
        // Asymmetric: each edge drawn on its own.
        in.dz_lo = -uniform(rng, 0.03, 0.1) * peak;
        in.dz_hi = uniform(rng, 0.03, 0.1) * peak;
        key("drive.deadzone_low_V", in.dz_lo);
        key("drive.deadzone_high_V", in.dz_hi);
        t.params = {{"lower", in.dz_lo}, {"upper", in.dz_hi}};
    } else if (e == "saturation") {
        in.lim_lo = -uniform(rng, 0.55, 0.8) * peak;
        in.lim_hi = uniform(rng, 0.55, 0.8) * peak;
        key("drive.limit_low_V", in.lim_lo);
        key("drive.limit_high_V", in.lim_hi);
        t.params = {{"lower", in.lim_lo}, {"upper", in.lim_hi}};
    } else if (e == "gain_error") {
        in.gain = hil_rng_uniform(rng) < 0.5 ? uniform(rng, 0.7, 0.88) : uniform(rng, 1.12, 1.4);
        key("drive.gain", in.gain);
        t.params = {{"gain", in.gain}};
    } else if (e == "sensor_offset") {
        in.vel_offset = (hil_rng_uniform(rng) < 0.5 ? -1 : 1) * uniform(rng, 0.02, 0.1) * vmax;
        key("velocity.offset", in.vel_offset);
        t.params = {{"offset_velocity", in.vel_offset}};
    } else if (e == "quantization") {
        in.pos_quant = uniform(rng, 0.005, 0.02) * p.A1;
        key("encoder.step_rad", in.pos_quant);
        t.params = {{"step_position", in.pos_quant}};
    } else if (e == "unmodelled_mode") {
        in.mode_hz = uniform(rng, 15, 40);
        in.mode_zeta = uniform(rng, 0.03, 0.1);
        key("drive.series_mode_hz", in.mode_hz);
        key("drive.series_mode_zeta", in.mode_zeta);
        t.params = {{"f_hz", in.mode_hz}};
    } else {
        throw std::invalid_argument("gap-bench: family servo has no injection for '" + e + "'");
    }
    return t;
}

// The injection a case's truth keys describe (the inverse of draw_effect's keys).
Injection injection_of(const BenchCase& c)
{
    Injection in;
    for (const TruthEffect& t : c.truth)
        for (const auto& kv : t.rig) {
            const std::string& k = kv.first;
            const double v = std::stod(kv.second);
            if (k == "drive.extra_delay_samples") in.extra_delay = int(v);
            else if (k == "velocity.delay_samples") in.vel_delay = int(v);
            else if (k == "axis.coulomb_V") in.Fc = v;
            else if (k == "axis.viscous_V_s_per_rad") in.Fv = v;
            else if (k == "axis.stribeck_Fc_V") { in.stribeck = true; in.Fc = v; }
            else if (k == "axis.stribeck_Fs_V") in.Fs = v;
            else if (k == "axis.stribeck_vs") in.vs = v;
            else if (k == "drive.deadzone_low_V") in.dz_lo = v;
            else if (k == "drive.deadzone_high_V") in.dz_hi = v;
            else if (k == "drive.limit_low_V") in.lim_lo = v;
            else if (k == "drive.limit_high_V") in.lim_hi = v;
            else if (k == "drive.gain") in.gain = v;
            else if (k == "velocity.offset") in.vel_offset = v;
            else if (k == "encoder.step_rad") in.pos_quant = v;
            else if (k == "drive.series_mode_hz") in.mode_hz = v;
            else if (k == "drive.series_mode_zeta") in.mode_zeta = v;
            else throw std::invalid_argument("gap-bench: family servo: unknown injection key '" + k + "'");
        }
    return in;
}

// A servo axis in service runs a commissioned loop: every small-signal pole
// damped at least this much. A drawn delay or resonance that takes the loop
// below it makes a record no real axis gives (the loop rings for tens of
// periods, or sings at the +-10 V clip in a limit cycle whose phase the
// sensor noise sets, and the drive trips on its following error); before
// this rule, 3-10 extra cycles of delay and a 15-40 Hz resonance under a
// 6-15 Hz loop made most such records limit cycles (docs/gap.md "servo").
// Not applied to the series resonance: under this PD a resonance near the
// bandwidth is visible but undamps the loop, and one far above it (4-10 x)
// is damped but below the visibility rule on most axes, so no size is both
// on many drawn plants; its records stay limit cycles (docs/gap.md).
constexpr double kLoopDampingMin = 0.01;

// Draws `e` until it is visible (visibility.hpp) on top of the injection so
// far and leaves the small-signal loop damped (kLoopDampingMin).
TruthEffect draw_visible(const std::string& e, const Plant& p, double peak, hil_rng* rng, Injection& in)
{
    const Eigen::MatrixXd without = simulate(p, in, nullptr).y;
    // (On top of a series resonance that undamped the loop already, the rule has nothing left to keep.)
    const bool keep_damped = e != "unmodelled_mode" && loop_damping(p, in) >= kLoopDampingMin;
    for (int i = 0; i < kVisibleDraws; ++i) {
        Injection trial = in;
        TruthEffect t = draw_effect(e, p, peak, rng, trial);
        if (keep_damped && loop_damping(p, trial) < kLoopDampingMin) continue;
        if (visibility(simulate(p, trial, nullptr).y, without, {p.sigma_pos, p.sigma_vel}) >= kVisibleNoiseMultiple) {
            in = trial;
            return t;
        }
    }
    throw InvisibleEffect("gap-bench: family servo: no visible size of '" + e + "' that leaves the loop damped in " +
                          std::to_string(kVisibleDraws) + " draws");
}

// The look-alikes this family proves (gap_bench.hpp, TruthEffect::
// equivalents): a drive delay of n samples against n samples more on both
// sensors. The loop is closed through the position sensor and the record
// starts at rest, so the two give the same record sample for sample (the
// command, the readings); kept when the simulator confirms it on this case.
void add_equivalents(const Plant& p, const Injection& in, TruthEffect& t)
{
    if (t.effect != "input_delay") return;
    Injection alt = in;
    alt.extra_delay = 0;
    alt.pos_delay += in.extra_delay;
    alt.vel_delay += in.extra_delay;
    if (visibility(simulate(p, alt, nullptr).y, simulate(p, in, nullptr).y, {p.sigma_pos, p.sigma_vel}) >=
        kEquivalentNoiseMultiple)
        return;
    TruthEffect q;
    q.effect = "output_delay";
    q.params = {{"delay_s_position", alt.pos_delay * kTs}, {"delay_s_velocity", alt.vel_delay * kTs}};
    t.equivalents.push_back(q);
}

const std::vector<std::string>& servo_labels()
{
    static const std::vector<std::string> v = {"input_delay", "output_delay", "coulomb_friction", "viscous_friction",
                                               "stribeck_friction", "deadzone", "saturation", "gain_error",
                                               "sensor_offset", "quantization", "unmodelled_mode", "none"};
    return v;
}

Plant plant_of(const BenchCase& c)
{
    Plant p;
    p.J = c.plant.at("J");
    p.b = c.plant.at("b");
    p.Ka = c.plant.at("Ka");
    p.Kp = c.plant.at("Kp");
    p.Kd = c.plant.at("Kd");
    p.a = c.plant.at("a");
    p.A1 = c.plant.at("A1");
    p.f1 = c.plant.at("f1");
    p.A2 = c.plant.at("A2");
    p.f2 = c.plant.at("f2");
    p.sigma_pos = c.plant.at("sigma_pos");
    p.sigma_vel = c.plant.at("sigma_vel");
    return p;
}

struct Drawn {
    BenchCase c;
    Injection in;
};

Drawn draw(const BenchOptions& opt, int id)
{
    Drawn d;
    d.c.id = id;
    d.c.family = "servo";
    d.c.seed = case_seed(opt.seed, id);
    hil_rng rng;
    hil_rng_seed(&rng, d.c.seed);
    const std::vector<std::string>& labels = servo_labels();
    const std::string first = drawn_label(labels, opt.seed, id);
    // An axis on which no size of the drawn effect is visible and keeps the
    // loop damped is redrawn (visibility.hpp, kPlantDraws).
    Plant p;
    with_plant_redraws("servo", id, "axes", [&] {
        p = draw_plant(&rng);
        d.c.truth.clear();
        d.in = Injection();
        const double peak = peak_cmd(p);
        if (first != "none") {
            d.c.truth.push_back(draw_visible(first, p, peak, &rng, d.in));
            if (hil_rng_uniform(&rng) < opt.two_effect_prob)
                d.c.truth.push_back(draw_visible(second_label(labels, first, &rng), p, peak, &rng, d.in));
        }
    });
    d.c.plant = {{"J", p.J},   {"b", p.b},   {"Ka", p.Ka}, {"Kp", p.Kp}, {"Kd", p.Kd},
                 {"a", p.a},   {"A1", p.A1}, {"f1", p.f1}, {"A2", p.A2}, {"f2", p.f2},
                 {"sigma_pos", p.sigma_pos}, {"sigma_vel", p.sigma_vel}};
    for (TruthEffect& t : d.c.truth) add_equivalents(p, d.in, t);
    d.c.scenario = "family = servo\n";
    for (const auto& kv : d.c.plant) d.c.scenario += scenario_line("plant." + kv.first, kv.second);
    d.c.scenario += scenario_line("Ts", kTs) + scenario_line("duration", kDuration) + scenario_line("clip_V", kClip) +
                    scenario_line("delay_samples", kCompDelay);
    for (const TruthEffect& t : d.c.truth)
        for (const auto& kv : t.rig) d.c.scenario += kv.first + " = " + kv.second + "\n";
    return d;
}

nlohmann::json rows(const Eigen::MatrixXd& X)
{
    nlohmann::json j = nlohmann::json::array();
    for (Eigen::Index i = 0; i < X.rows(); ++i) {
        nlohmann::json r = nlohmann::json::array();
        for (Eigen::Index k = 0; k < X.cols(); ++k) r.push_back(X(i, k));
        j.push_back(r);
    }
    return j;
}

}  // namespace

// The nominal: the continuous axis (zero-order hold at Ts by the diagnosis),
// the PD with filtered difference as a discrete controller with states
// [e_{k-1}, d_{k-1}] and inputs [r, theta]: with g = (1 - a)/Ts,
//   xc+ = [[0, 0], [-g, a]] xc + [[1, -1], [g, -g]] w,
//   c   = [-Kd g, Kd a] xc + [Kp + Kd g, -(Kp + Kd g)] w.
nlohmann::json servo_nominal_doc(const BenchCase& c)
{
    const Plant p = plant_of(c);
    Eigen::MatrixXd A(2, 2), B(2, 1), C = Eigen::MatrixXd::Identity(2, 2), D = Eigen::MatrixXd::Zero(2, 1);
    A << 0, 1, 0, -p.b / p.J;
    B << 0, p.Ka / p.J;
    const double g = (1 - p.a) / kTs;
    Eigen::MatrixXd Ac(2, 2), Bc(2, 2), Cc(1, 2), Dc(1, 2);
    Ac << 0, 0, -g, p.a;
    Bc << 1, -1, g, -g;
    Cc << -p.Kd * g, p.Kd * p.a;
    Dc << p.Kp + p.Kd * g, -(p.Kp + p.Kd * g);
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "gap_bench_servo"},
            {"description", "gap-bench servo family: rigid axis J theta'' = Ka u - b theta', PD with filtered difference, "
                            "+-10 V clip, one cycle of computation delay"},
            {"time", "continuous"},
            {"states", {"theta", "omega"}},
            {"A", rows(A)},
            {"B", rows(B)},
            {"C", rows(C)},
            {"D", rows(D)},
            {"inputs", {"voltage"}},
            {"outputs", {"position", "velocity"}},
            // The records start at rest (axis, controller and reference at
            // zero): stated, so that the start is not fitted to the first
            // noisy samples (docs/gap.md "What the document states").
            {"gap",
             {{"velocity", "velocity"},
              {"force_input", "voltage"},
              {"initial_state", "at_rest"},
              {"closed_loop",
               {{"references", {"ref"}},
                {"measured", {"position"}},
                {"controller", {{"time", "discrete"}, {"Ts", kTs}, {"A", rows(Ac)}, {"B", rows(Bc)}, {"C", rows(Cc)}, {"D", rows(Dc)}}},
                {"delay_samples", kCompDelay},
                {"saturation", kClip}}}}}};
}

Family servo_family()
{
    Family f;
    f.name = "servo";
    f.summary = "rigid servo axis (J, b, Ka drawn), PD with filtered difference, +-10 V clip, 1 ms";
    f.labels = servo_labels();
    f.draw = [](const BenchOptions& opt, int id) { return draw(opt, id).c; };
    f.run = [](const BenchOptions& opt, const BenchCase& c) {
        hil_rng noise;
        hil_rng_seed(&noise, c.seed ^ 0x5851f42d4c957f2dull);
        const Run r = simulate(plant_of(c), injection_of(c), &noise);
        CaseRun out;
        out.draw = c;
        Signals& s = out.data;
        s.source = "gap-bench servo";
        s.names = {"ref", "voltage_cmd", "position", "velocity"};
        s.Ts = kTs;
        s.values.resize(r.y.rows(), 4);
        s.values.col(0) = r.ref;
        s.values.col(1) = r.cmd;
        s.values.col(2) = r.y.col(0);
        s.values.col(3) = r.y.col(1);
        out.nominal = servo_nominal_doc(c);
        diagnose_case(opt, {"position", "velocity"}, out);
        return out;
    };
    return f;
}

}  // namespace fracbench
