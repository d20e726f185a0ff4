// gap_bench.cpp - gap-bench: the diagnosis against hidden truth on the HIL rig
// (gap_bench.hpp; docs/gap.md "gap-bench" gives the set-up and the mapping of each
// injected effect to the parameter the diagnosis reports).
#include "fracbench/gap_bench.hpp"

#include <algorithm>
#include <functional>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "fracbench/families.hpp"
#include "fracdesign/design/riccati.hpp"
#include "fracdesign/io/signal_csv.hpp"

extern "C" {
#include "hil/rig.h"
#include "hil/rng.h"
}

namespace fracbench {

using namespace fracdesign::gap;
namespace io = fracdesign::io;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- the bench set-up ------------------------------------------------------
// Rig: the two-mass plant of seed 004 (4.8)-(4.12) with the thesis cycle
// T = 1.2 ms and torque path delay of 4 cycles, friction off, an ideal current
// loop (tau_current = 0), one torque limit (rated = peak = 251 Nm, so the i^2t
// switch-over never acts), one IMU reading per cycle (reading_cycles = 2) and
// white gyro noise. Controller: this file's PD law on the motor angle and
// velocity with a two-tone reference (known to the nominal model).
const double kT = 1.2e-3;
const unsigned kDelay = 4;
const double kTorqueLimit = 251.0;
const double kKp = 1500.0, kKd = 150.0;     // [Nm/rad], [Nm s/rad]
const double kIM = 160.0 * 160.0 * 2.29e-4; // hil_plant_params_default (seed 004 Table 8.2)
const double kIL = 1.69e-4 + 0.7221;
const double kCs = 5.0e4;
const double kDitherNm = 2.0;

// Reference: a smooth start (0.05 s .. 0.35 s, 1 - cos ramp) times two tones,
// so that the record has velocity reversals, standstill-free motion and
// accelerations that use a good part of the torque range.
void reference(double t, double* r, double* rd)
{
    const double ts = 0.05, Tr = 0.3, A1 = 0.3, f1 = 0.7, A2 = 0.12, f2 = 1.9, ph = 1.0;
    double e = 0, ed = 0;
    if (t >= ts + Tr) {
        e = 1;
    } else if (t > ts) {
        e = 0.5 * (1 - std::cos(M_PI * (t - ts) / Tr));
        ed = 0.5 * M_PI / Tr * std::sin(M_PI * (t - ts) / Tr);
    }
    const double w1 = 2 * M_PI * f1, w2 = 2 * M_PI * f2;
    double s = A1 * std::sin(w1 * t) + A2 * (std::sin(w2 * t + ph) - std::sin(ph));
    double sd = A1 * w1 * std::cos(w1 * t) + A2 * w2 * std::cos(w2 * t + ph);
    // Dither: four tones around the gear mode (44 Hz open loop), each asking
    // about kDitherNm of the PD's derivative path, so that the gear's own
    // effects (its damping above all, which nothing else excites) show, as
    // in an identification experiment; the tones are part of the reference
    // the nominal model replays. Measured on --seed 1 (docs/gap.md): without
    // the dither the gear's Kelvin-Voigt damping stays within the gyro
    // noise; 4 Nm tones over 23-71 Hz make an extra link mode look like gear
    // damping; 2 Nm at 37-55 Hz separates both.
    static const double fd[] = {37.0, 43.0, 49.0, 55.0};
    for (size_t i = 0; i < sizeof fd / sizeof fd[0]; ++i) {
        const double w = 2 * M_PI * fd[i], a = kDitherNm / (kKd * w), p = 1.7 * double(i * i);
        s += a * std::sin(w * t + p);
        sd += a * w * std::cos(w * t + p);
    }
    *r = e * s;
    *rd = ed * s + e * sd;
}

int bench_law(void*, const struct hil_ctrl_law_in* in, double* torque, double* ref)
{
    double r, rd;
    reference(in->t, &r, &rd);
    *ref = r;
    *torque = kKp * (r - in->theta) + kKd * (rd - in->omega);
    return 0;
}

void set_key(hil_rig_config* c, const std::string& k, const std::string& v)
{
    if (hil_rig_config_set(c, k.c_str(), v.c_str()) != HIL_OK)
        throw std::runtime_error("gap-bench: rig key " + k + " = " + v + " refused");
}

std::string fmt(double x)
{
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", x);
    return b;
}

hil_rig_config base_config(const BenchOptions& opt, std::uint64_t seed)
{
    hil_rig_config c;
    hil_rig_config_default(&c);
    std::snprintf(c.scenario, sizeof c.scenario, "gap-bench");
    set_key(&c, "T", fmt(kT));
    set_key(&c, "plant", "twomass");
    set_key(&c, "duration", fmt(opt.duration));
    set_key(&c, "plant.substeps", "8");
    set_key(&c, "plant.friction", "0");
    set_key(&c, "plant.fric_b0", "0");
    set_key(&c, "plant.fric_b1", "0");
    set_key(&c, "drive.delay", std::to_string(kDelay));
    set_key(&c, "drive.tau_current", "0");
    set_key(&c, "drive.torque_rated", fmt(kTorqueLimit));
    set_key(&c, "drive.torque_peak", fmt(kTorqueLimit));
    set_key(&c, "ctrl.torque_max", fmt(kTorqueLimit));
    set_key(&c, "imu.reading_cycles", "2");
    set_key(&c, "imu.gyro_noise", fmt(opt.gyro_noise));
    set_key(&c, "imu.seed", std::to_string(seed));
    set_key(&c, "bus_seed", std::to_string(seed ^ 0x9e3779b97f4a7c15ull));
    return c;
}

std::uint64_t splitmix(std::uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Frequency of the plant mode the extra inertia adds: the undamped
// motor - gear spring - link - k_e - I_e chain, the eigenfrequency nearest f_e.
double chain_mode_hz(double Ie, double fe)
{
    const double ke = Ie * std::pow(2 * M_PI * fe, 2);
    Eigen::Matrix3d M = Eigen::Vector3d(kIM, kIL, Ie).asDiagonal(), K;
    K << kCs, -kCs, 0, -kCs, kCs + ke, -ke, 0, -ke, ke;
    const Eigen::Matrix3d Ms = M.inverse().cwiseSqrt();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Ms * K * Ms);
    double best = 0;
    for (int i = 0; i < 3; ++i) {
        const double f = std::sqrt(std::max(es.eigenvalues()(i), 0.0)) / (2 * M_PI);
        if (std::fabs(f - fe) < std::fabs(best - fe)) best = f;
    }
    return best;
}

// The effect of one name with a size drawn from rng.
TruthEffect draw_effect(const std::string& e, hil_rng* rng, double cmd_peak)
{
    auto U = [&](double lo, double hi) { return lo + (hi - lo) * hil_rng_uniform(rng); };
    TruthEffect t;
    t.effect = e;
    if (e == "input_delay") {
        const int d = 1 + int(hil_rng_u64(rng) % 4);
        t.rig = {{"drive.delay", std::to_string(kDelay + unsigned(d))}};
        t.params = {{"delay_s", d * kT}};
    } else if (e == "output_delay") {
        // reading_cycles r: a reading every r/2 cycles, sent r/2 cycles after
        // its sample (the bench's r = 2: every cycle, one cycle late). Its
        // delay as an LTI map: the extra latency r/2 - 1 plus half the extra
        // hold period (r/2 - 1)/2 cycles.
        const int r = 4 + 2 * int(hil_rng_u64(rng) % 3);
        t.rig = {{"imu.reading_cycles", std::to_string(r)}};
        t.params = {{"delay_s_imu_rate", 1.5 * (r / 2 - 1) * kT}};
    } else if (e == "coulomb_friction") {
        const double b0 = U(3, 10);
        t.rig = {{"plant.fric_b0", fmt(b0)}};
        t.params = {{"Fc", b0}};
    } else if (e == "viscous_friction") {
        const double b1 = U(1.5, 6);
        t.rig = {{"plant.fric_b1", fmt(b1)}};
        t.params = {{"Fv", b1}};
    } else if (e == "stribeck_friction") {
        const double b1s = U(3, 7), b2s = b1s * U(1.6, 2.4), vs = U(0.05, 0.2);
        t.rig = {{"plant.friction", "2"}, {"plant.fric_b1s", fmt(b1s)}, {"plant.fric_b2s", fmt(b2s)},
                 {"plant.fric_b3s", "0"}, {"plant.fric_v_s", fmt(vs)}, {"plant.fric_delta", "2"}};
        t.params = {{"Fc", b1s}, {"Fs", b2s}};
    } else if (e == "backlash") {
        const double b = U(0.002, 0.008);
        t.rig = {{"plant.backlash", fmt(b)}};
        t.params = {{"width", b}};
    } else if (e == "deadzone") {
        const double a = U(3, 10);
        t.rig = {{"drive.deadzone", fmt(a)}};
        t.params = {{"lower", -a}, {"upper", a}};
    } else if (e == "saturation") {
        const double L = U(0.55, 0.8) * cmd_peak;
        t.rig = {{"drive.torque_rated", fmt(L)}, {"drive.torque_peak", fmt(L)}};
        t.params = {{"lower", -L}, {"upper", L}};
    } else if (e == "fractional_damping") {
        const double c = U(200, 800), a = U(0.3, 0.7);
        t.rig = {{"plant.kv_damping", fmt(c)}, {"plant.kv_order", fmt(a)}};
        t.params = {{"c", c}, {"alpha", a}};
    } else if (e == "unmodelled_mode") {
        const double Ie = U(0.05, 0.2), fe = U(6, 20), z = U(0.02, 0.08);
        t.rig = {{"plant.extra_inertia", fmt(Ie)}, {"plant.extra_hz", fmt(fe)}, {"plant.extra_zeta", fmt(z)}};
        t.params = {{"f_hz", chain_mode_hz(Ie, fe)}};
    } else if (e == "gain_error") {
        const double g = hil_rng_uniform(rng) < 0.5 ? U(0.7, 0.88) : U(1.12, 1.4);
        t.rig = {{"drive.gain", fmt(g)}};
        t.params = {{"gain", g}};
    } else if (e == "sensor_offset") {
        const double o = (hil_rng_uniform(rng) < 0.5 ? -1 : 1) * U(0.02, 0.1);
        t.rig = {{"imu.gyro_bias", fmt(o)}};
        t.params = {{"offset_imu_rate", o}};
    } else if (e == "quantization") {
        const double q = U(0.02, 0.08);
        t.rig = {{"imu.gyro_quant", fmt(q)}};
        t.params = {{"step_imu_rate", q}};
    } else {
        throw std::invalid_argument("gap-bench: no rig injection for '" + e + "'");
    }
    return t;
}

bool friction_family(const std::string& e)
{
    return e == "coulomb_friction" || e == "viscous_friction" || e == "stribeck_friction";
}

struct RigRecord {
    Signals data;
    double cmd_peak = 0;
};

RigRecord run_rig(const hil_rig_config& cfg)
{
    auto rig = std::make_unique<hil_rig>();
    if (hil_rig_init(rig.get(), &cfg, nullptr, nullptr) != HIL_OK)
        throw std::runtime_error("gap-bench: the rig refused the case's configuration");
    hil_ctrl_set_law(&rig->ctrl, bench_law, nullptr);
    const long n = long(std::floor(cfg.duration / cfg.ctrl.T + 0.5));
    RigRecord out;
    Signals& s = out.data;
    s.source = "gap-bench rig";
    s.names = {"ref", "ref_rate", "torque_cmd", "motor_angle", "motor_velocity", "imu_rate", "torque_actual"};
    s.Ts = cfg.ctrl.T;
    s.values.resize(n, Eigen::Index(s.names.size()));
    for (long k = 0; k < n; ++k) {
        if (hil_rig_cycle(rig.get()) != HIL_OK) throw std::runtime_error("gap-bench: rig cycle failed");
        const hil_ctrl_signals& g = rig->ctrl.sig;
        double r, rd;
        reference(g.t, &r, &rd);
        s.values.row(k) << g.ref, rd, g.torque_cmd, g.theta, g.omega, g.imu_rate, rig->drive.tau_act;
        out.cmd_peak = std::max(out.cmd_peak, std::fabs(g.torque_cmd));
    }
    return out;
}

std::string config_text(const hil_rig_config& c)
{
    char* buf = nullptr;
    size_t len = 0;
    FILE* f = open_memstream(&buf, &len);
    if (!f) throw std::runtime_error("gap-bench: open_memstream failed");
    hil_rig_config_write(&c, f);
    std::fclose(f);
    std::string s(buf, len);
    std::free(buf);
    return s;
}

nlohmann::json truth_json(const std::vector<TruthEffect>& truth)
{
    nlohmann::json a = nlohmann::json::array();
    for (const TruthEffect& t : truth) {
        nlohmann::json rig = nlohmann::json::object(), p = nlohmann::json::object();
        for (const auto& kv : t.rig) rig[kv.first] = kv.second;
        for (const TruthParam& q : t.params) p[q.name] = q.value;
        a.push_back({{"effect", t.effect}, {"rig", rig}, {"params", p}});
        if (!t.equivalents.empty()) a.back()["equivalents"] = truth_json(t.equivalents);
    }
    return a;
}

double median(std::vector<double> v)
{
    if (v.empty()) return kNaN;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

nlohmann::json num(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

std::vector<std::string> bench_labels()
{
    std::vector<std::string> v;
    for (Effect e : all_effects()) v.push_back(effect_name(e));
    v.push_back("none");
    return v;
}

namespace {

// The twomass family's labels: bench_labels() but mode_shift (the rig's
// two-mass plant is the seed's; no nominal mode of it is drawn off).
std::vector<std::string> twomass_labels()
{
    std::vector<std::string> v;
    for (const std::string& l : bench_labels())
        if (l != "mode_shift") v.push_back(l);
    return v;
}

}  // namespace

BenchScore score_bench(const std::vector<CaseOutcome>& cases)
{
    BenchScore S;
    S.labels = bench_labels();
    const size_t L = S.labels.size();
    S.confusion.assign(L, std::vector<int>(L, 0));
    auto index = [&](const std::string& n) {
        for (size_t i = 0; i < L; ++i)
            if (S.labels[i] == n) return int(i);
        throw std::invalid_argument("gap-bench: unknown effect '" + n + "'");
    };
    std::vector<double> perr, shrinks;
    std::map<std::string, std::vector<double>> label_perr;
    for (const CaseOutcome& c : cases) {
        CaseScore cs;
        cs.param_error = kNaN;
        cs.shrink = c.shrink;
        cs.top1 = c.verdict.empty() ? "none" : c.verdict.front();
        for (const TruthEffect& t : c.truth) cs.truth_label += (cs.truth_label.empty() ? "" : "+") + t.effect;
        if (c.truth.empty()) cs.truth_label = "none";
        const TruthEffect* found = nullptr;
        for (const TruthEffect& t : c.truth)
            if (t.effect == cs.top1) found = &t;
        // A proved equivalent of a true effect counts when the verdict
        // states that effect as its look-alike (the record cannot tell them
        // apart, and the verdict says so: issue 17 item 5).
        for (const TruthEffect& t : c.truth) {
            if (found) break;
            if (std::find(c.look_alikes.begin(), c.look_alikes.end(), t.effect) == c.look_alikes.end()) continue;
            for (const TruthEffect& q : t.equivalents)
                if (q.effect == cs.top1) {
                    found = &q;
                    cs.by_look_alike = true;
                    break;
                }
        }
        cs.correct = c.truth.empty() ? cs.top1 == "none" : found != nullptr;
        S.look_alike_correct += cs.by_look_alike;
        if (c.truth.size() <= 1) S.confusion[size_t(index(cs.truth_label))][size_t(index(cs.top1))] += 1;
        else {
            index(cs.top1);
            S.two_effect_cases += 1;
            S.two_effect_correct += cs.correct;
        }
        S.cases += 1;
        S.correct += cs.correct;
        if (found) {
            shrinks.push_back(c.shrink);
            if (!found->params.empty() && !c.verdict_params.empty()) {
                const std::map<std::string, double>& rec = c.verdict_params.front();
                double sum = 0;
                int n = 0;
                for (const TruthParam& p : found->params) {
                    auto it = rec.find(p.name);
                    if (it == rec.end() || !std::isfinite(it->second)) {
                        sum = kNaN;
                        break;
                    }
                    sum += std::fabs(it->second - p.value) / std::fabs(p.value);
                    ++n;
                }
                cs.param_error = n > 0 ? sum / n : kNaN;
                // A parameter the diagnosis could not report counts as a miss (100 %).
                perr.push_back(std::isfinite(cs.param_error) ? cs.param_error : 1.0);
                if (c.truth.size() == 1) label_perr[cs.truth_label].push_back(perr.back());
            }
        }
        if (c.truth.size() <= 1) {
            LabelScore& ls = S.per_label[cs.truth_label];
            ls.cases += 1;
            ls.correct += cs.correct;
        }
        S.per_case.push_back(cs);
    }
    for (auto& kv : S.per_label) kv.second.median_param_error = median(label_perr[kv.first]);
    S.accuracy = S.cases ? double(S.correct) / S.cases : kNaN;
    S.median_param_error = median(perr);
    S.param_cases = int(perr.size());
    S.median_shrink_found = median(shrinks);
    S.found_cases = int(shrinks.size());
    return S;
}

std::string drawn_label(const std::vector<std::string>& labels, std::uint64_t seed, int id)
{
    // Shuffled rounds of all labels (every label equally often over
    // labels.size() consecutive cases).
    const int L = int(labels.size()), round = id / L;
    hil_rng perm;
    hil_rng_seed(&perm, splitmix(seed * 1000003ull + std::uint64_t(round)));
    std::vector<int> order(static_cast<size_t>(L));
    for (int i = 0; i < L; ++i) order[size_t(i)] = i;
    for (int i = L - 1; i > 0; --i) std::swap(order[size_t(i)], order[size_t(hil_rng_u64(&perm) % std::uint64_t(i + 1))]);
    return labels[size_t(order[size_t(id % L)])];
}

std::uint64_t case_seed(std::uint64_t seed, int id) { return splitmix(seed ^ splitmix(std::uint64_t(id) + 1)); }

std::string second_label(const std::vector<std::string>& labels, const std::string& first, hil_rng* rng)
{
    // labels ends with "none", which is never a second effect; no two friction models.
    std::string second;
    do {
        second = labels[size_t(hil_rng_u64(rng) % std::uint64_t(labels.size() - 1))];
    } while (second == first || (friction_family(first) && friction_family(second)));
    return second;
}

BenchCase draw_case(const BenchOptions& opt, int id, double cmd_peak)
{
    // Effects are drawn in shuffled rounds of all 14 labels, sizes from the
    // case's own generator.
    const std::vector<std::string> labels = twomass_labels();
    BenchCase c;
    c.id = id;
    c.family = "twomass";
    c.seed = case_seed(opt.seed, id);
    hil_rng rng;
    hil_rng_seed(&rng, c.seed);
    const std::string first = drawn_label(labels, opt.seed, id);
    if (first != "none") {
        c.truth.push_back(draw_effect(first, &rng, cmd_peak));
        if (hil_rng_uniform(&rng) < opt.two_effect_prob)
            c.truth.push_back(draw_effect(second_label(labels, first, &rng), &rng, cmd_peak));
    }
    hil_rig_config cfg = base_config(opt, c.seed);
    for (const TruthEffect& t : c.truth)
        for (const auto& kv : t.rig) set_key(&cfg, kv.first, kv.second);
    c.scenario = config_text(cfg);
    return c;
}

nlohmann::json bench_nominal_doc()
{
    // Plant states x = [theta_M, omega_M, psi, psi'] (seed 004 (4.8)-(4.12),
    // no friction). Over a cycle the drive's torque ramps from its previous
    // value to the new one (hil/drive.h with tau_current = 0), so the exact
    // discretisation is first-order hold (design::c2d_foh):
    // x+ = Phi x + B_prev u- + B_now u. Two more states: the previous torque
    // u- and the link rate one cycle ago (the IMU reading the controller sees
    // at cycle k was sampled at t_{k-1}).
    fracdesign::StateSpace plant;
    plant.A.resize(4, 4);
    plant.A << 0, 1, 0, 0, -kCs / kIM, 0, kCs / kIM, 0, 0, 0, 0, 1, kCs / kIL, 0, -kCs / kIL, 0;
    plant.B = Eigen::Vector4d(0, 1 / kIM, 0, 0);
    plant.C = Eigen::MatrixXd::Identity(4, 4);
    plant.D = Eigen::MatrixXd::Zero(4, 1);
    const fracdesign::design::FohDiscretisation foh = fracdesign::design::c2d_foh(plant, kT);
    Eigen::MatrixXd Ad = Eigen::MatrixXd::Zero(6, 6), Bd = Eigen::MatrixXd::Zero(6, 1);
    Ad.topLeftCorner(4, 4) = foh.Ad;
    Ad.block(0, 4, 4, 1) = foh.B_prev;
    Ad(5, 3) = 1;
    Bd.block(0, 0, 4, 1) = foh.B_now;
    Bd(4, 0) = 1;
    auto rows = [](const Eigen::MatrixXd& X) {
        nlohmann::json j = nlohmann::json::array();
        for (Eigen::Index i = 0; i < X.rows(); ++i) {
            nlohmann::json r = nlohmann::json::array();
            for (Eigen::Index k = 0; k < X.cols(); ++k) r.push_back(X(i, k));
            j.push_back(r);
        }
        return j;
    };
    // The gear (gap.coupling): twist theta_M - psi, spring torque c_s twist
    // decelerating the motor and driving the link; an extra spring torque
    // held over one cycle moves the state by its zero-order-hold input
    // column int_0^T e^{As} ds [0, -1/I_M, 0, 1/I_L]' (design::c2d_zoh).
    fracdesign::StateSpace gear = plant;
    gear.B = Eigen::Vector4d(0, -1 / kIM, 0, 1 / kIL);
    const fracdesign::StateSpace gear_d = fracdesign::design::c2d_zoh(gear, kT);
    nlohmann::json gear_torque = nlohmann::json::array(), gear_twist = {1, 0, -1, 0, 0, 0};
    for (int i = 0; i < 6; ++i) gear_torque.push_back(i < 4 ? gear_d.B(i, 0) : 0.0);
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, 6), D = Eigen::MatrixXd::Zero(3, 1);
    C(0, 0) = 1;
    C(1, 1) = 1;
    C(2, 5) = 1;
    return {{"schema", "frac.model"},
            {"version", 1},
            {"kind", "statespace"},
            {"name", "gap_bench_twomass"},
            {"description",
             "gap-bench nominal: seed 004 two-mass drive (I_M = 160^2 * 2.29e-4, I_L = 0.722269 kg m^2, c_s = 5e4 "
             "Nm/rad), no friction, first-order hold of the drive torque, IMU one cycle late; the bench PD loop "
             "with the drive's 4-cycle delay and 251 Nm limit"},
            {"time", "discrete"},
            {"Ts", kT},
            {"states", {"theta_M", "omega_M", "psi", "psi_rate", "torque_prev", "psi_rate_prev"}},
            {"A", rows(Ad)},
            {"B", rows(Bd)},
            {"C", rows(C)},
            {"D", rows(D)},
            {"inputs", {"torque_shaft"}},
            {"outputs", {"motor_angle", "motor_velocity", "imu_rate"}},
            {"gap",
             {{"velocity", "motor_velocity"},
              {"force_input", "torque_shaft"},
              {"coupling",
               {{"name", "gear"}, {"twist", gear_twist}, {"torque", gear_torque}, {"stiffness", kCs},
                {"states", {0, 1, 2, 3}}}},
              {"closed_loop",
               {{"references", {"ref", "ref_rate"}},
                {"measured", {"motor_angle", "motor_velocity"}},
                {"controller", {{"time", "discrete"}, {"Ts", kT}, {"D", {{kKp, kKd, -kKp, -kKd}}}}},
                {"delay_samples", int(kDelay)},
                {"saturation", kTorqueLimit}}}}}};
}

double bench_cmd_peak(const BenchOptions& opt) { return run_rig(base_config(opt, splitmix(opt.seed))).cmd_peak; }

Family twomass_family()
{
    Family f;
    f.name = "twomass";
    f.summary = "seed 004 two-mass drive on the lockstep HIL rig, the bench's PD loop, 4-cycle drive delay";
    f.labels = twomass_labels();
    f.draw = [](const BenchOptions& opt, int id) { return draw_case(opt, id, bench_cmd_peak(opt)); };
    f.run = run_case;
    return f;
}

CaseRun run_case(const BenchOptions& opt, const BenchCase& c)
{
    CaseRun out;
    out.draw = c;
    hil_rig_config cfg = base_config(opt, c.seed);
    for (const TruthEffect& t : c.truth)
        for (const auto& kv : t.rig) set_key(&cfg, kv.first, kv.second);
    out.data = run_rig(cfg).data;
    out.nominal = bench_nominal_doc();
    diagnose_case(opt, {"motor_velocity", "imu_rate"}, out);
    return out;
}

void diagnose_case(const BenchOptions& opt, const std::vector<std::string>& outputs, CaseRun& out)
{
    const NominalModel m = nominal_from_json(out.nominal, out.data.Ts, ".", out.data.Ts * double(out.data.samples()));
    GapOptions g;
    g.outputs = outputs;
    g.max_iterations = opt.max_iterations;
    out.result = diagnose(m, out.data, nullptr, g);
    out.outcome.truth = out.draw.truth;
    out.outcome.shrink = out.result.verdict.shrink;
    for (const auto& l : out.result.confidence.look_alikes) out.outcome.look_alikes.push_back(l.effect);
    for (const EffectInstance& e : out.result.verdict.effects) {
        out.outcome.verdict.push_back(effect_name(e.kind));
        const std::vector<std::string> pn = param_names(e.kind, out.result.outputs, e.site);
        std::map<std::string, double> p;
        for (size_t i = 0; i < pn.size() && i < e.params.size(); ++i) p[pn[i]] = e.params[i];
        out.outcome.verdict_params.push_back(p);
    }
}

std::string format_value(double x) { return fmt(x); }

std::string scenario_line(const std::string& key, double value) { return key + " = " + fmt(value) + "\n"; }

namespace {

void write_case_files(const std::filesystem::path& dir, const CaseRun& r)
{
    namespace fs = std::filesystem;
    fs::create_directories(dir);
    auto put = [&](const std::string& name, const std::string& text) {
        std::ofstream o(dir / name, std::ios::binary);
        o << text;
        o.close();
        if (!o) throw std::runtime_error("gap-bench: cannot write " + (dir / name).string());
    };
    put("scenario.txt", "# gap-bench family " + r.draw.family + " case " + std::to_string(r.draw.id) +
                            (r.draw.family == "twomass" ? ": rig configuration (the controller is gap-bench's PD law, not a scenario key)\n"
                             : r.draw.family == "arm"   ? ": hil_bench scenario (fracdesign model --arm --save-scenario) with the case's injection\n"
                                                        : ": plant, controller and injection of the bench's simulator\n") +
                            r.draw.scenario);
    put("nominal.json", r.nominal.dump(1) + "\n");
    for (const auto& f : r.files) put(f.first, f.second);
    put("truth.json", truth_json(r.draw.truth).dump(2) + "\n");
    nlohmann::json res = result_json(r.result);
    put("result.json", res.dump(2) + "\n");
    io::SignalTable tab;
    tab.names = r.data.names;
    for (Eigen::Index k = 0; k < r.data.samples(); ++k) tab.t.push_back(double(k) * r.data.Ts);
    for (Eigen::Index j = 0; j < r.data.values.cols(); ++j)
        tab.columns.emplace_back(r.data.values.col(j).data(), r.data.values.col(j).data() + r.data.samples());
    tab.dt = r.data.Ts;
    io::write_signal_csv((dir / "signals.csv").string(), tab);
}

}  // namespace

nlohmann::json score_json(const BenchScore& S)
{
    nlohmann::json conf = nlohmann::json::array();
    for (const auto& row : S.confusion) conf.push_back(row);
    nlohmann::json per_effect = nlohmann::json::object();
    for (const auto& kv : S.per_label)
        per_effect[kv.first] = {{"cases", kv.second.cases},
                                {"correct", kv.second.correct},
                                {"accuracy", num(double(kv.second.correct) / kv.second.cases)},
                                {"median_param_error", num(kv.second.median_param_error)}};
    return {{"score",
             {{"cases", S.cases},
              {"correct", S.correct},
              {"accuracy", num(S.accuracy)},
              {"two_effect_cases", S.two_effect_cases},
              {"two_effect_correct", S.two_effect_correct},
              {"look_alike_correct", S.look_alike_correct},
              {"median_param_error", num(S.median_param_error)},
              {"param_cases", S.param_cases},
              {"median_shrink_found", num(S.median_shrink_found)},
              {"found_cases", S.found_cases}}},
            {"confusion", {{"labels", S.labels}, {"rows_truth_cols_top1", conf}}},
            {"per_effect", per_effect},
            {"goals",
             {{"accuracy_min", 0.9},
              {"median_param_error_max", 0.1},
              {"median_shrink_found_min", 0.8},
              {"accuracy_met", S.accuracy >= 0.9},
              {"param_error_met", S.median_param_error <= 0.1},
              {"shrink_met", S.median_shrink_found >= 0.8}}}};
}

CaseOutcome outcome_from_json(const nlohmann::json& c)
{
    // null stands for a non-finite number in the document (num above)
    const auto val = [](const nlohmann::json& x) { return x.is_null() ? kNaN : x.get<double>(); };
    CaseOutcome o;
    std::function<TruthEffect(const nlohmann::json&)> truth_of = [&](const nlohmann::json& t) {
        TruthEffect te;
        te.effect = t.at("effect").get<std::string>();
        for (auto it = t.at("params").begin(); it != t.at("params").end(); ++it)
            te.params.push_back({it.key(), val(it.value())});
        if (t.contains("equivalents"))
            for (const auto& q : t.at("equivalents")) te.equivalents.push_back(truth_of(q));
        return te;
    };
    for (const auto& t : c.at("truth")) o.truth.push_back(truth_of(t));
    if (c.contains("look_alikes"))
        for (const auto& l : c.at("look_alikes")) o.look_alikes.push_back(l.get<std::string>());
    for (const auto& e : c.at("verdict")) {
        o.verdict.push_back(e.at("effect").get<std::string>());
        std::map<std::string, double> p;
        for (auto it = e.at("params").begin(); it != e.at("params").end(); ++it) p[it.key()] = val(it.value());
        o.verdict_params.push_back(p);
    }
    o.shrink = val(c.at("shrink"));
    return o;
}

nlohmann::json run_bench(const BenchOptions& opt, std::ostream* progress)
{
    if (opt.cases < 1) throw std::invalid_argument("gap-bench: --cases must be >= 1");
    if (!(opt.duration >= 0.5 && opt.duration <= 60)) throw std::invalid_argument("gap-bench: --duration must be in [0.5, 60] s");
    if (!(opt.gyro_noise >= 0 && std::isfinite(opt.gyro_noise))) throw std::invalid_argument("gap-bench: --noise must be >= 0");
    if (opt.only_case >= opt.cases) throw std::invalid_argument("gap-bench: --replay names a case beyond --cases");
    const Family& fam = family(opt.family);
    std::vector<CaseOutcome> outcomes;
    nlohmann::json cases = nlohmann::json::array();
    for (int id = 0; id < opt.cases; ++id) {
        if (opt.only_case >= 0 && id != opt.only_case) continue;
        const BenchCase c = fam.draw(opt, id);
        const CaseRun r = fam.run(opt, c);
        outcomes.push_back(r.outcome);
        if (!opt.out_dir.empty()) {
            char name[32];
            std::snprintf(name, sizeof name, "case_%03d", id);
            write_case_files(std::filesystem::path(opt.out_dir) / name, r);
        }
        nlohmann::json vp = nlohmann::json::array();
        for (size_t i = 0; i < r.outcome.verdict.size(); ++i) {
            nlohmann::json p = nlohmann::json::object();
            for (const auto& kv : r.outcome.verdict_params[i]) p[kv.first] = num(kv.second);
            vp.push_back({{"effect", r.outcome.verdict[i]}, {"params", p}});
        }
        nlohmann::json plant = nlohmann::json::object();
        for (const auto& kv : c.plant) plant[kv.first] = kv.second;
        nlohmann::json cj = {{"id", id},
                             {"family", c.family},
                             {"seed", c.seed},
                             {"plant", plant},
                             {"truth", truth_json(c.truth)},
                             {"verdict", vp},
                             {"shrink", num(r.outcome.shrink)},
                             {"look_alikes", r.outcome.look_alikes},
                             {"gap_before", num(r.result.gap_before_total)},
                             {"gap_after", num(r.result.verdict.gap)},
                             {"scenario", c.scenario}};
        const BenchScore one = score_bench({r.outcome});
        cj["truth_label"] = one.per_case[0].truth_label;
        cj["top1"] = one.per_case[0].top1;
        cj["correct"] = one.per_case[0].correct;
        cj["by_look_alike"] = one.per_case[0].by_look_alike;
        cj["param_error"] = num(one.per_case[0].param_error);
        cases.push_back(cj);
        if (progress) {
            char b[256];
            std::snprintf(b, sizeof b, "  case %3d  %-38s -> %-20s %s  shrink %6.1f %%  param err %s\n", id,
                          cj["truth_label"].get<std::string>().c_str(), cj["top1"].get<std::string>().c_str(),
                          one.per_case[0].by_look_alike ? "ok= " : one.per_case[0].correct ? "ok  " : "MISS", 100 * r.outcome.shrink,
                          std::isfinite(one.per_case[0].param_error)
                              ? (std::to_string(int(std::lround(100 * one.per_case[0].param_error))) + " %").c_str()
                              : "-");
            *progress << b;
            // True and recovered values of the mapped parameters.
            std::string line;
            for (const TruthEffect& t : c.truth) {
                const std::map<std::string, double>* rec = nullptr;
                for (size_t i = 0; i < r.outcome.verdict.size(); ++i)
                    if (r.outcome.verdict[i] == t.effect) rec = &r.outcome.verdict_params[i];
                for (const TruthParam& p : t.params) {
                    char v[160];
                    const auto it = rec ? rec->find(p.name) : std::map<std::string, double>::const_iterator();
                    if (rec && it != rec->end())
                        std::snprintf(v, sizeof v, "  %s %.4g / %.4g", p.name.c_str(), p.value, it->second);
                    else
                        std::snprintf(v, sizeof v, "  %s %.4g / -", p.name.c_str(), p.value);
                    line += v;
                }
            }
            if (!line.empty()) *progress << "            params true / recovered:" << line << "\n";
            *progress << std::flush;
        }
    }
    nlohmann::json out = {{"schema", "frac.gap_bench"},
            {"version", 2},
            {"family", fam.name},
            {"family_summary", fam.summary},
            {"seed", opt.seed},
            {"cases_requested", opt.cases},
            {"replay", opt.only_case},
            {"duration_s", opt.duration},
            {"gyro_noise", opt.gyro_noise},
            {"two_effect_prob", opt.two_effect_prob},
            {"cases", cases}};
    out.update(score_json(score_bench(outcomes)));
    if (fam.name == "twomass") out["cmd_peak_nominal"] = bench_cmd_peak(opt);
    return out;
}

}  // namespace fracbench
