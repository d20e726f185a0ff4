// family_arm.cpp - gap-bench family "arm": the flexible arm of a user's arm
// document (docs/arm_format.md, issue 16) on the lockstep HIL rig (families.hpp,
// docs/gap.md "Families").
//
// Per case an arm document is drawn in physical ranges around
// docs/examples/arm_b (link, section, material, payload, hub and motor
// inertia, gear, drive, sample time, IMU position and noise, delays) and a
// reversing move of the tip; everything else is derived from the document as
// `fracdesign model/armctrl --arm` derive it, through the same library calls
// (design/arm_design.hpp): the ArmCtrl table of variant D (LQG with the
// document's delays, inverse-model feedforward; design_armctrl_for_arm), the
// rig's plant table (arm_plant_table_for, h = T/8 as --save-plant), the rig
// scenario (arm_hil_scenario) and the diagnosis's nominal (arm_gap_nominal:
// the full arm at ZOH, open loop from torque_actual to motor_velocity and
// imu_rate). The rig runs in process (hil/rig.h) with ArmCtrl in the task
// runtime (hil/plc/plc_law.h), its CSV record is read back with the
// diagnosis's own reader, as `fracdesign gap --data signals.csv` reads it.
//
// The withheld effect is set with the rig's keys on top of the document's
// scenario (friction, drive gain and dead zone, IMU latency, bias and
// quantization) or, for the unmodelled mode, by building the rig's plant
// table from the document with a soft payload mount (a loosely bolted
// payload: its own mode inside the band, which the user's document does not
// have). Not drawn: input delay and saturation (the drive's delay line and
// torque limit act before the torque_actual the open-loop nominal starts
// from, so the record holds no gap of either), backlash and fractional
// damping (the rig's arm plant has neither; plant.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "fracbench/families.hpp"
#include "fracbench/visibility.hpp"
#include "fracdesign/design/arm_design.hpp"
#include "fracdesign/models/arm_document.hpp"
#include "fracdesign/tables/ptable.hpp"

extern "C" {
#include "hil/canopen.h"
#include "hil/rig.h"
#include "plc_law.h"
}

namespace fracbench {

namespace {

using fracdesign::ArmDocument;
namespace design = fracdesign::design;

const double kPost = 0.4;          // [s] after the move (armctrl --post)
// Redraws of a document the design refuses or on which the drawn effect is invisible. An IMU latency
// (output_delay) has one or two sizes on the rig (reading_cycles up to 8) and is invisible on a slow arm:
// on gap-bench seed 29 case 6, 6 of 10 documents; 30 draws leave 0.6^30 ~ 2e-7 of a run refused.
const int kDocumentDraws = 30;
// Key prefix of the injections that change the document the rig's plant table is built from.
const std::string kPlantDoc = "plant_document.";

// ---- the drawn document ----------------------------------------------------

// The drawn parameters (BenchCase::plant) -> the arm document a user would write.
nlohmann::json document_of(const std::map<std::string, double>& p, const std::string& name)
{
    const bool steel = p.at("material_steel") > 0.5;
    return {{"schema", "frac.arm"},
            {"version", 1},
            {"name", name},
            {"description", std::string("gap-bench arm family: ") + (steel ? "steel" : "aluminium") +
                                " strip link with a tip payload, drawn around docs/examples/arm_b"},
            {"link",
             {{"length", p.at("link.length")},
              {"model", "timoshenko"},
              {"material", {{"E", p.at("link.material.E")}, {"poisson", 0.3}, {"rho", p.at("link.material.rho")}}},
              {"section", {{"shape", "rectangular"}, {"width", p.at("link.section.width")}, {"thickness", p.at("link.section.thickness")}}},
              {"damping", {{"r_t", p.at("link.damping.r_t")}, {"r_r", 0}}}}},
            {"payload", {{"mass", p.at("payload.mass")}, {"inertia", p.at("payload.inertia")}}},
            {"hub", {{"inertia", p.at("hub.inertia")}, {"radius", 0}}},
            {"drive",
             {{"I_M", p.at("drive.I_M")},
              {"gear_stiffness", p.at("drive.gear_stiffness")},
              {"gear_damping", p.at("drive.gear_damping")},
              {"torque_rated", p.at("drive.torque_rated")},
              {"torque_peak", p.at("drive.torque_peak")},
              {"current_loop_tau", p.at("drive.current_loop_tau")}}},
            {"sensors",
             {{"encoder_counts_per_rev", 1048576},
              {"imu_position", p.at("sensors.imu_position")},
              {"imu_noise", p.at("sensors.imu_noise")}}},
            {"sample_time", p.at("sample_time")},
            {"delays", {{"input", int(p.at("delays.input"))}, {"output", int(p.at("delays.output"))}}},
            {"design", {{"N", 9}}}};
}

// Physical ranges around arm_b (0.9 m x 40 mm x 3 mm steel, 0.25 kg payload,
// hub 4e-3, I_M 2.0 kg m^2, gear 8e4 N m/rad, 60/150 N m, T 1 ms, d_i 2,
// d_o 5): docs/gap.md "Families" gives the table. d_o stays <= 4 so that the
// rig's IMU (reading_cycles <= 8) can take an extra latency; T is 1 or
// 1.2 ms (the task runtime needs a multiple of 200 us, the feedforward table
// at most 4096 samples of the 3.5 s move).
std::map<std::string, double> draw_parameters(hil_rng* rng)
{
    std::map<std::string, double> p;
    const bool steel = hil_rng_uniform(rng) < 0.6;
    p["material_steel"] = steel ? 1 : 0;
    p["link.length"] = uniform(rng, 0.7, 1.1);
    p["link.material.E"] = steel ? uniform(rng, 195e9, 215e9) : uniform(rng, 68e9, 72e9);
    p["link.material.rho"] = steel ? uniform(rng, 7750, 7950) : uniform(rng, 2650, 2750);
    p["link.section.width"] = uniform(rng, 0.03, 0.05);
    p["link.section.thickness"] = steel ? uniform(rng, 0.0025, 0.004) : uniform(rng, 0.004, 0.006);
    p["link.damping.r_t"] = uniform(rng, 0.3, 1.0);
    p["payload.mass"] = uniform(rng, 0.1, 0.5);
    p["payload.inertia"] = p["payload.mass"] * std::pow(uniform(rng, 0.0, 0.03), 2);
    p["hub.inertia"] = uniform(rng, 2e-3, 8e-3);
    p["drive.I_M"] = uniform(rng, 1.0, 3.0);
    p["drive.gear_stiffness"] = uniform(rng, 5e4, 1.2e5);
    p["drive.gear_damping"] = uniform(rng, 0.0, 20.0);
    p["drive.torque_rated"] = uniform(rng, 40, 80);
    p["drive.torque_peak"] = p["drive.torque_rated"] * uniform(rng, 2.0, 3.0);
    p["sample_time"] = hil_rng_uniform(rng) < 0.5 ? 1e-3 : 1.2e-3;
    p["drive.current_loop_tau"] = uniform(rng, 1e-4, 4e-4);
    p["sensors.imu_position"] = p["link.length"] * uniform(rng, 0.75, 1.0);
    p["sensors.imu_noise"] = uniform(rng, 5e-4, 2e-3);
    p["delays.input"] = double(1 + hil_rng_u64(rng) % 4);
    p["delays.output"] = double(3 + hil_rng_u64(rng) % 2);
    // The move: out to q1, back to q2, forward to q3 (two reversals, slow ends).
    p["move.q1"] = uniform(rng, 0.6, 1.2);
    p["move.q2"] = p["move.q1"] * uniform(rng, 0.3, 0.6);
    p["move.q3"] = p["move.q2"] + (p["move.q1"] - p["move.q2"]) * uniform(rng, 0.2, 0.6);
    return p;
}

// The move starts at 0.8 s, or at move.t0 where the arm's pre-actuation needs
// a longer lead (a slow non-minimum-phase zero: draw() sets it from the
// design's MoveStartTooEarly, as a user would start the move later).
const double kMoveStart = 0.8;  // [s]

double move_start(const std::map<std::string, double>& p)
{
    const auto it = p.find("move.t0");
    return it == p.end() ? kMoveStart : it->second;
}

std::string move_spec(const std::map<std::string, double>& p)
{
    const double t0 = move_start(p);
    char b[200];
    std::snprintf(b, sizeof b, "0:%.17g@%.17g+1.0,%.17g@%.17g+0.6,%.17g@%.17g+0.5", p.at("move.q1"), t0, p.at("move.q2"),
                  t0 + 1.1, p.at("move.q3"), t0 + 1.8);
    return b;
}

// [s] end of the last segment of move_spec
double move_end(const std::map<std::string, double>& p) { return move_start(p) + 2.3; }

// ---- the rig run -----------------------------------------------------------

// What a case's document gives: the design tables and the nominal.
struct Derived {
    ArmDocument a;
    std::vector<std::uint8_t> ctrl;     // ArmCtrl table (FRPT)
    nlohmann::json nominal;             // arm_gap_nominal
    double duration = 0;                // [s]
};

Derived derive(const BenchCase& c)
{
    Derived d;
    d.a = fracdesign::arm_from_json(document_of(c.plant, "gap_bench_arm_" + std::to_string(c.id)));
    const design::ArmctrlForArm r =
        design::design_armctrl_for_arm(d.a, design::Move::parse(move_spec(c.plant)), design::FfKind::Inverse, kPost);
    d.ctrl = fracdesign::tables::to_binary(r.d.table);
    d.nominal = design::arm_gap_nominal(d.a);
    d.duration = move_end(c.plant) + kPost;
    return d;
}

// The document the rig's plant is built from: the user's, with the plant_document.* injections.
ArmDocument plant_document(const BenchCase& c)
{
    nlohmann::json doc = document_of(c.plant, "gap_bench_arm_" + std::to_string(c.id) + "_plant");
    for (const TruthEffect& t : c.truth)
        for (const auto& kv : t.rig)
            if (kv.first.rfind(kPlantDoc, 0) == 0) {
                std::string path = "/" + kv.first.substr(kPlantDoc.size());
                std::replace(path.begin(), path.end(), '.', '/');
                doc[nlohmann::json::json_pointer(path)] = std::stod(kv.second);
            }
    return fracdesign::arm_from_json(doc);
}

void set_key(hil_rig_config* cfg, const std::string& k, const std::string& v)
{
    if (hil_rig_config_set(cfg, k.c_str(), v.c_str()) != HIL_OK)
        throw std::invalid_argument("gap-bench: family arm: rig key " + k + " = " + v + " refused: " + cfg->err);
}

// The scenario text of the case (what `fracdesign model --arm --save-scenario` writes, the case's seeds and
// injections); the table names are those of the case files (--out): plant.bin, ctrl.bin.
std::string scenario_text(const BenchCase& c, const Derived& d, bool noise)
{
    std::string s = design::arm_hil_scenario(d.a, "plant.bin", "ctrl.bin", d.duration);
    s += "imu.seed = " + std::to_string(c.seed) + "\nbus_seed = " + std::to_string(c.seed ^ 0x9e3779b97f4a7c15ull) + "\n";
    if (!noise) s += "imu.gyro_noise = 0\n";
    for (const TruthEffect& t : c.truth)
        for (const auto& kv : t.rig)
            if (kv.first.rfind(kPlantDoc, 0) != 0) s += kv.first + " = " + kv.second + "\n";
    return s;
}

struct TempFile {
    std::string path;
    explicit TempFile(const std::vector<std::uint8_t>& bytes)
    {
        path = (std::filesystem::temp_directory_path() / "gap_bench_arm_XXXXXX").string();
        std::vector<char> p(path.begin(), path.end());
        p.push_back('\0');
        const int fd = ::mkstemp(p.data());
        if (fd < 0) throw std::runtime_error("gap-bench: family arm: cannot create a temporary plant table");
        path = p.data();
        const ssize_t w = ::write(fd, bytes.data(), bytes.size());
        ::close(fd);
        if (w != ssize_t(bytes.size())) {
            std::remove(path.c_str());
            throw std::runtime_error("gap-bench: family arm: cannot write the temporary plant table " + path);
        }
    }
    ~TempFile() { std::remove(path.c_str()); }
};

// Runs the rig on the case's scenario (noise: the document's gyro noise, else none) and returns its CSV text.
std::string run_rig(const BenchCase& c, const Derived& d, const std::vector<std::uint8_t>& plant_table, bool noise)
{
    hil_rig_config cfg;
    hil_rig_config_default(&cfg);
    std::snprintf(cfg.scenario, sizeof cfg.scenario, "gap-bench arm case %d", c.id);
    std::istringstream in(scenario_text(c, d, noise));
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        const size_t eq = line.find(" = ");
        if (eq == std::string::npos) throw std::logic_error("gap-bench: family arm: scenario line '" + line + "'");
        set_key(&cfg, line.substr(0, eq), line.substr(eq + 3));
    }
    const TempFile table(plant_table);
    set_key(&cfg, "plant.table", table.path);
    auto law = std::make_unique<hil_plc_law>();
    char err[512] = "";
    if (hil_plc_law_init_table(law.get(), cfg.ctrl.T, d.ctrl.data(), (unsigned long)d.ctrl.size(), err, sizeof err) != HIL_OK)
        throw std::runtime_error(std::string("gap-bench: family arm: ArmCtrl refuses the table: ") + err);
    char* buf = nullptr;
    size_t len = 0;
    FILE* csv = open_memstream(&buf, &len);
    if (!csv) throw std::runtime_error("gap-bench: family arm: open_memstream failed");
    auto rig = std::make_unique<hil_rig>();
    int st = hil_rig_init(rig.get(), &cfg, nullptr, csv);
    if (st == HIL_OK) {
        hil_ctrl_set_law(&rig->ctrl, hil_plc_law_step, law.get());
        st = hil_rig_run(rig.get());
    }
    hil_plc_law_stop(law.get());
    std::fclose(csv);
    std::string text(buf ? buf : "", len);
    std::free(buf);
    if (st != HIL_OK) throw std::runtime_error(std::string("gap-bench: family arm: the rig failed: ") + rig->err);
    return text;
}

// A record the case may use: ArmCtrl never faulted and the gyro stayed inside its wire range.
bool usable(const Signals& s)
{
    const auto col = [&](const std::string& n) {
        for (size_t i = 0; i < s.names.size(); ++i)
            if (s.names[i] == n) return s.values.col(Eigen::Index(i));
        throw std::logic_error("gap-bench: family arm: the rig's record lacks " + n);
    };
    return s.values.allFinite() && col("fault").cwiseAbs().maxCoeff() == 0 &&
           col("imu_rate").cwiseAbs().maxCoeff() < 0.9 * 32767 * HIL_GYRO_LSB;
}

Eigen::MatrixXd jmat(const nlohmann::json& j)
{
    Eigen::MatrixXd m(Eigen::Index(j.size()), Eigen::Index(j[0].size()));
    for (Eigen::Index i = 0; i < m.rows(); ++i)
        for (Eigen::Index k = 0; k < m.cols(); ++k) m(i, k) = j[size_t(i)][size_t(k)].get<double>();
    return m;
}

// The record's outputs [motor_velocity, imu_rate] minus the nominal's open-loop replay from its torque_actual
// (the nominal is discrete at T and starts at rest, as the rig does).
Eigen::MatrixXd nominal_residual(const nlohmann::json& nominal, const Signals& s)
{
    const Eigen::MatrixXd A = jmat(nominal["A"]), B = jmat(nominal["B"]), C = jmat(nominal["C"]);
    Eigen::Index iu = -1, iv = -1, ig = -1;
    for (size_t i = 0; i < s.names.size(); ++i) {
        if (s.names[i] == "torque_actual") iu = Eigen::Index(i);
        if (s.names[i] == "motor_velocity") iv = Eigen::Index(i);
        if (s.names[i] == "imu_rate") ig = Eigen::Index(i);
    }
    Eigen::VectorXd x = Eigen::VectorXd::Zero(A.rows());
    Eigen::MatrixXd r(s.samples(), 2);
    for (Eigen::Index k = 0; k < s.samples(); ++k) {
        const Eigen::Vector2d y = C * x;
        r(k, 0) = s.values(k, iv) - y(0);
        r(k, 1) = s.values(k, ig) - y(1);
        x = A * x + B * s.values(k, iu);
    }
    return r;
}

// ---- effects ---------------------------------------------------------------

// Scales of the effect-free record the sizes are drawn from.
struct Scales {
    double tau_pk, v_pk, rate_pk;  // max |torque_actual|, |motor_velocity|, |imu_rate|
};

double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / double(v.size())); }

// The IMU delay the diagnosis should find against the nominal [cycles]: a reading every r/2 cycles, sent
// r/2 cycles after its sample, is r/2 .. r - 1 cycles old through its hold, mean (3 r/2 - 1)/2; the
// nominal (arm_gap_nominal) holds that mean for the document's r, so the extra delay is the difference.
double imu_delay_vs_nominal(int reading_cycles, int nominal_reading_cycles)
{
    return 0.75 * (reading_cycles - nominal_reading_cycles);
}

// Oscillatory modes (f [Hz], zeta) of a continuous A, one per conjugate pair, slowest first.
std::vector<std::pair<double, double>> continuous_modes(const Eigen::MatrixXd& A)
{
    const Eigen::VectorXcd ev = A.eigenvalues();
    std::vector<std::pair<double, double>> m;
    for (Eigen::Index i = 0; i < ev.size(); ++i)
        if (ev(i).imag() > 0) m.push_back({std::abs(ev(i)) / (2 * M_PI), -ev(i).real() / std::abs(ev(i))});
    std::sort(m.begin(), m.end());
    return m;
}

// The loose payload's second truth (docs/gap.md "Family arm"): the mount
// mode also moves the arm's own modes (interlacing), so the plant's first
// flexible mode sits at f', zeta' instead of the document's; the record's
// slow move excites that mode most. mode_shift's truth is the plant's mode
// nearest the document's first resonant mode (zeta < 1/sqrt 2), the mount
// mode `mount_hz` left out.
TruthEffect first_mode_shift(const BenchCase& c, double mount_hz)
{
    const fracdesign::ArmDocument da = fracdesign::arm_from_json(document_of(c.plant, "nominal"));
    const fracdesign::ArmBuild db = fracdesign::build_arm_from_document(da, da.design.N, false, {});
    std::vector<std::pair<double, double>> nominal = continuous_modes(fracdesign::arm_document_measured(da, db).A);
    nominal.erase(std::remove_if(nominal.begin(), nominal.end(), [](const std::pair<double, double>& m) { return m.second >= M_SQRT1_2; }),
                  nominal.end());
    const ArmDocument pa = plant_document(c);
    const fracdesign::ArmBuild pb = fracdesign::build_arm_from_document(pa, pa.design.N, false, {});
    const std::vector<std::pair<double, double>> plant = continuous_modes(fracdesign::arm_document_measured(pa, pb).A);
    const double f0 = nominal.at(0).first;
    std::pair<double, double> best{0, 0};
    for (const std::pair<double, double>& m : plant)
        if (m.first != mount_hz && std::fabs(m.first - f0) < std::fabs(best.first - f0)) best = m;
    TruthEffect t;
    t.effect = "mode_shift";
    t.params = {{"f_hz", best.first}, {"zeta", best.second}};
    return t;
}

TruthEffect draw_effect(const std::string& e, const BenchCase& c, const Scales& s, hil_rng* rng)
{
    TruthEffect t;
    t.effect = e;
    auto key = [&](const std::string& k, double v) { t.rig.push_back({k, format_value(v)}); };
    const double T = c.plant.at("sample_time");
    if (e == "output_delay") {
        const int d_o = int(c.plant.at("delays.output")), r = 2 * std::max(1, d_o - 1);  // arm_imu_reading_cycles
        const int r_new = r + 2 * (1 + int(hil_rng_u64(rng) % std::uint64_t((8 - r) / 2)));
        t.rig = {{"imu.reading_cycles", std::to_string(r_new)}};
        t.params = {{"delay_s_imu_rate", T * imu_delay_vs_nominal(r_new, r)}};
    } else if (e == "coulomb_friction") {
        const double b0 = uniform(rng, 0.03, 0.12) * s.tau_pk;
        key("plant.fric_b0", b0);
        t.params = {{"Fc", b0}};
    } else if (e == "viscous_friction") {
        const double b1 = uniform(rng, 0.03, 0.12) * s.tau_pk / s.v_pk;
        key("plant.fric_b1", b1);
        t.params = {{"Fv", b1}};
    } else if (e == "stribeck_friction") {
        const double b1s = uniform(rng, 0.03, 0.1) * s.tau_pk, b2s = b1s * uniform(rng, 1.6, 2.4),
                     vs = uniform(rng, 0.05, 0.2) * s.v_pk;
        t.rig = {{"plant.friction", "2"}, {"plant.fric_b3s", "0"}, {"plant.fric_delta", "2"}};
        key("plant.fric_b1s", b1s);
        key("plant.fric_b2s", b2s);
        key("plant.fric_v_s", vs);
        t.params = {{"Fc", b1s}, {"Fs", b2s}};
    } else if (e == "deadzone") {
        const double a = uniform(rng, 0.03, 0.1) * s.tau_pk;
        key("drive.deadzone", a);
        t.params = {{"lower", -a}, {"upper", a}};
    } else if (e == "gain_error") {
        const double g = hil_rng_uniform(rng) < 0.5 ? uniform(rng, 0.7, 0.88) : uniform(rng, 1.12, 1.4);
        key("drive.gain", g);
        t.params = {{"gain", g}};
    } else if (e == "sensor_offset") {
        const double o = (hil_rng_uniform(rng) < 0.5 ? -1 : 1) * uniform(rng, 0.01, 0.05) * s.rate_pk;
        key("imu.gyro_bias", o);
        t.params = {{"offset_imu_rate", o}};
    } else if (e == "quantization") {
        const double q = std::max(uniform(rng, 0.03, 0.08) * s.rate_pk, 4 * c.plant.at("sensors.imu_noise"));
        key("imu.gyro_quant", q);
        t.params = {{"step_imu_rate", q}};
    } else if (e == "unmodelled_mode") {
        // A loosely bolted payload: its mount mode at f_m (k_w = m (2 pi f_m)^2) instead of the default far
        // above the controller; the truth is the plant arm's eigenfrequency nearest f_m.
        const double fm = uniform(rng, 8, 35), m = c.plant.at("payload.mass");
        key(kPlantDoc + "payload.mount_stiffness", m * std::pow(2 * M_PI * fm, 2));
        BenchCase probe = c;
        probe.truth = {t};
        const ArmDocument pa = plant_document(probe);
        const fracdesign::ArmBuild b = fracdesign::build_arm_from_document(pa, pa.design.N, false, {});
        const std::vector<std::pair<double, double>> modes = continuous_modes(fracdesign::arm_document_measured(pa, b).A);
        size_t mount = 0;
        for (size_t i = 1; i < modes.size(); ++i)
            if (std::fabs(modes[i].first - fm) < std::fabs(modes[mount].first - fm)) mount = i;
        t.params = {{"f_hz", modes.at(mount).first}};
    } else {
        throw std::invalid_argument("gap-bench: family arm has no injection for '" + e + "'");
    }
    return t;
}

std::vector<std::uint8_t> plant_table(const BenchCase& c, const Derived& d)
{
    return fracdesign::tables::to_binary(design::arm_plant_table_for(plant_document(c), d.a.T / 8.0));
}

Signals record(const BenchCase& c, const Derived& d, bool noise)
{
    return fracdesign::gap::signals_from_csv_text(run_rig(c, d, plant_table(c, d), noise), "gap-bench arm case " + std::to_string(c.id));
}

// Visibility of an open-loop diagnosis (docs/gap.md "Families", arm): the residual of the nominal's replay
// from the record's own torque_actual must change, on some compared output, by kVisibleNoiseMultiple times
// that output's floor: the noise std (gyro: the document's imu_noise; motor velocity: the wire step / sqrt 12)
// and the nominal's own error on the effect-free record, rms-combined. A document on which no size is
// visible throws InvisibleEffect (visibility.hpp) and is redrawn.
struct Baseline {
    Eigen::MatrixXd residual;   // of the effect-free (or the effects so far) noise-free record
    std::vector<double> floor;  // per output
};

Baseline baseline(const BenchCase& c, const Derived& d, const Eigen::MatrixXd& effect_free)
{
    Baseline b;
    b.residual = nominal_residual(d.nominal, record(c, d, false));
    const double nv = HIL_VEL_LSB / std::sqrt(12.0), ng = c.plant.at("sensors.imu_noise");
    b.floor = {std::hypot(nv, rms(effect_free.col(0))), std::hypot(ng, rms(effect_free.col(1)))};
    return b;
}

TruthEffect draw_visible(const std::string& e, BenchCase& c, const Derived& d, const Scales& s,
                         const Eigen::MatrixXd& effect_free, hil_rng* rng)
{
    const Baseline b = baseline(c, d, effect_free);
    for (int i = 0; i < kVisibleDraws; ++i) {
        BenchCase trial = c;
        trial.truth.push_back(draw_effect(e, c, s, rng));
        const Signals r = record(trial, d, false);
        if (usable(r) && visibility(nominal_residual(d.nominal, r), b.residual, b.floor) >= kVisibleNoiseMultiple) {
            c.truth = trial.truth;
            return c.truth.back();
        }
    }
    throw InvisibleEffect("gap-bench: family arm: no visible size of '" + e + "' in " + std::to_string(kVisibleDraws) +
                             " draws (case " + std::to_string(c.id) + ")");
}

const std::vector<std::string>& arm_labels()
{
    static const std::vector<std::string> v = {"output_delay", "coulomb_friction", "viscous_friction", "stribeck_friction",
                                               "deadzone",     "gain_error",       "sensor_offset",    "quantization",
                                               "unmodelled_mode", "none"};
    return v;
}

BenchCase draw(const BenchOptions& opt, int id)
{
    BenchCase c;
    c.id = id;
    c.family = "arm";
    c.seed = case_seed(opt.seed, id);
    hil_rng rng;
    hil_rng_seed(&rng, c.seed);
    // A document the design refuses (reduction, unstable loop, feedforward beyond the peak torque or not at
    // rest where the table starts) is redrawn, as a user would change it; so is a document on which no size
    // of the drawn effect is visible (e.g. one IMU latency step on a slow arm).
    const std::vector<std::string>& labels = arm_labels();
    const std::string first = drawn_label(labels, opt.seed, id);
    Derived d;
    std::string why;
    for (int i = 0;; ++i) {
        if (i == kDocumentDraws)
            throw std::runtime_error("gap-bench: family arm: case " + std::to_string(id) + ": " +
                                     std::to_string(kDocumentDraws) + " documents refused, the last: " + why);
        c.plant = draw_parameters(&rng);
        c.truth.clear();
        Signals free;
        try {
            try {
                d = derive(c);
            } catch (const design::MoveStartTooEarly& e) {
                // The lead the design asks for, rounded up to 0.1 s with 0.1 s to spare; a design that still
                // refuses (a table beyond ARMCTRL_FF_MAX samples, a lead beyond the inversion's horizon) is redrawn.
                c.plant["move.t0"] = std::ceil(e.lead / 0.1 + 1.0 - 1e-9) * 0.1;
                d = derive(c);
            }
            free = record(c, d, false);
        } catch (const std::exception& e) {
            why = e.what();
            continue;
        }
        if (!usable(free)) {
            why = "the effect-free rig run faulted";
            continue;
        }
        const Eigen::MatrixXd effect_free = nominal_residual(d.nominal, free);
        const auto col = [&](const char* n) {
            for (size_t k = 0; k < free.names.size(); ++k)
                if (free.names[k] == n) return free.values.col(Eigen::Index(k)).cwiseAbs().maxCoeff();
            throw std::logic_error("gap-bench: family arm: no column " + std::string(n));
        };
        const Scales s{col("torque_actual"), col("motor_velocity"), col("imu_rate")};
        try {
            if (first != "none") {
                draw_visible(first, c, d, s, effect_free, &rng);
                if (hil_rng_uniform(&rng) < opt.two_effect_prob)
                    draw_visible(second_label(labels, first, &rng), c, d, s, effect_free, &rng);
            }
            // A loose payload is two true differences: the mount mode and the arm's shifted first mode.
            for (size_t i = 0, n = c.truth.size(); i < n; ++i)
                if (c.truth[i].effect == "unmodelled_mode") c.truth.push_back(first_mode_shift(c, c.truth[i].params.at(0).value));
        } catch (const InvisibleEffect& e) {
            why = e.what();
            continue;
        }
        break;
    }
    c.scenario = scenario_text(c, d, true);
    for (const TruthEffect& t : c.truth)
        for (const auto& kv : t.rig)
            if (kv.first.rfind(kPlantDoc, 0) == 0) c.scenario += "# plant.bin from the document with " + kv.first.substr(kPlantDoc.size()) + " = " + kv.second + "\n";
    return c;
}

}  // namespace

nlohmann::json arm_document_of(const BenchCase& c) { return document_of(c.plant, "gap_bench_arm_" + std::to_string(c.id)); }

Family arm_family()
{
    Family f;
    f.name = "arm";
    f.summary = "flexible arm of a drawn arm document (around docs/examples/arm_b) on the lockstep HIL rig, ArmCtrl "
                "variant D from the document, open-loop nominal from torque_actual (--gap-nominal)";
    f.labels = arm_labels();
    f.draw = draw;
    f.run = [](const BenchOptions& opt, const BenchCase& c) {
        const Derived d = derive(c);
        const std::vector<std::uint8_t> table = plant_table(c, d);
        CaseRun out;
        out.draw = c;
        out.data = fracdesign::gap::signals_from_csv_text(run_rig(c, d, table, true), "gap-bench arm case " + std::to_string(c.id));
        out.data.source = "gap-bench arm";
        out.nominal = d.nominal;
        out.files["arm.json"] = arm_document_of(c).dump(2) + "\n";
        out.files["plant.bin"] = std::string(table.begin(), table.end());
        out.files["ctrl.bin"] = std::string(d.ctrl.begin(), d.ctrl.end());
        diagnose_case(opt, {"motor_velocity", "imu_rate"}, out);
        return out;
    };
    return f;
}

}  // namespace fracbench
