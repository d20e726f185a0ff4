// effects.cpp - the catalog of candidate effects: one descriptor per effect
// (name, parameters with units, scales, bounds and start rule, sites, the
// terms it sets in the replay). docs/gap.md gives the equations; the replay
// loop that uses the terms is replay.cpp.
#include "fracdesign/gap/effects.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fracdesign {
namespace gap {

namespace {

const double kBig = 1e3;

std::vector<ParamInfo> per_output(const std::string& prefix, const std::vector<std::string>& outputs,
                                  const std::vector<std::string>& units)
{
    std::vector<ParamInfo> v;
    for (size_t i = 0; i < outputs.size(); ++i)
        v.push_back({prefix + outputs[i], i < units.size() ? units[i] : "[" + outputs[i] + "]"});
    return v;
}

// A log grid lo, lo 2^(1/n), ..., up to hi (n per octave).
std::vector<double> octave_grid(double lo, double hi, int n)
{
    std::vector<double> g;
    for (int i = 0; lo * std::pow(2.0, double(i) / n) <= hi * (1 + 1e-9); ++i) g.push_back(lo * std::pow(2.0, double(i) / n));
    return g;
}

// The two signed edges of the dead zone and the saturation (lower < 0 <
// upper), in units of max |u| of the fit part: every pair of `grid` as a
// start (screened by cost, the best three refined) and, with `symmetric`,
// the restriction lower = -upper started from each grid value alone.
// The edges of a record's two directions are separate starts because a
// record may drive one direction much further than the other, and a
// one-way move (a positioning stroke whose braking falls into the
// held-out tail) does not reach the lower edge in the fit part at all:
// there the cost is flat in it, and only the restriction (ranked on
// held-out data like any variant) places it.
EffectSetup edge_setup(Effect e, const FitContext& c, double lo, double hi, const std::vector<double>& grid, bool symmetric)
{
    EffectSetup s{e, Site::force_input, 0, {{c.umax, -hi, -lo, false}, {c.umax, lo, hi, false}}, {}, true};
    // Each edge does nothing at its neutral value: a dead zone's at 0, a
    // limit's at the bound beyond the command (ParamSpec::neutral).
    const double off = e == Effect::saturation ? hi : lo;
    s.spec[0].neutral = -off;
    s.spec[1].neutral = off;
    if (symmetric) {
        s.spec[0].mirror = 1;
        for (double b : grid) s.starts.push_back({-b, b});
    } else {
        for (double a : grid)
            for (double b : grid) s.starts.push_back({-a, b});
    }
    return s;
}

// Dead-zone edges: 1/64 .. 1 x max |u|, two per octave; bounds 0 .. 2 x max
// |u| (in a loop the augmented replay's command exceeds the nominal's).
std::vector<double> deadzone_grid() { return octave_grid(1.0 / 64, 1.0, 2); }
// Limits: 1/8 .. 1.41 x max |u|, two per octave; bounds 2 % .. 200 %.
std::vector<double> saturation_grid() { return octave_grid(1.0 / 8, M_SQRT2, 2); }

// Largest integer delay the grid tries: 50 samples or a 20th of the fit record.
long delay_grid_max(const FitContext& c) { return std::max<long>(1, std::min<long>(50, c.fit_samples / 20)); }

// The gear site's set-up (gear.cpp): [width,] share r, f_hz, zeta. r in
// [0.02, 0.9] (the load's share of the inertia; at 1 the motor would have
// none), f over the band the other modes use, zeta <= 0.5, the width from 0
// (scale: FitContext::Sp). Starts: the largest peaks of the nominal
// residual and a log grid over the band (`per_decade`), r = 0.3 and 0.6,
// zeta 0.1, and with a play its width at 1/4 .. 64 Sp (an octave apart),
// screened by cost.
EffectSetup gear_setup(Effect e, const FitContext& c, bool play, double per_decade)
{
    EffectSetup s{e, Site::gear, 0, {}, {}, true};
    const double flo = std::max(2.0 / c.fit_seconds, 1e-3), fhi = 0.25 / c.Ts;
    if (play) s.spec.push_back({c.Sp, 0, kBig, false});
    s.spec.push_back({1.0, 0.02, 0.9, false});
    s.spec.push_back({1.0, flo, fhi, false});
    s.spec.push_back({1.0, 0.005, 0.5, false});
    std::vector<double> fs = c.residual_peaks_hz;
    for (double f = flo; f <= fhi; f *= std::pow(10.0, 1.0 / per_decade)) fs.push_back(f);
    for (double f : fs) {
        if (f < flo || f > fhi) continue;
        for (double r : {0.3, 0.6}) {
            if (!play) {
                s.starts.push_back({r, f, 0.1});
                continue;
            }
            for (double w = 0.25; w <= 64.0 * (1 + 1e-9); w *= 2.0) s.starts.push_back({w, r, f, 0.1});
        }
    }
    return s;
}

void apply_gear(const std::vector<double>& p, bool play, ReplayTerms& t)
{
    const size_t o = play ? 1 : 0;
    t.gear = true;
    t.gear_w = play ? std::fabs(p[0]) : 0.0;
    t.gear_r = std::min(std::max(p[o], 1e-3), 0.999);
    t.gear_f = std::max(p[o + 1], 1e-6);
    t.gear_zeta = p[o + 2];
}

// Each compared output's model index -> value p[c], into a per-model-output vector.
void per_model_output(const std::vector<double>& p, const std::vector<int>& compared, size_t first,
                      std::vector<double>& out, bool absolute)
{
    for (size_t c = 0; c < compared.size(); ++c)
        out[size_t(compared[c])] = absolute ? std::fabs(p[first + c]) : p[first + c];
}

// What separates an input delay from an output delay (both descriptors' `reveals`).
constexpr const char* kDelayReveals =
    "a closed-loop record (an input delay moves the loop's dynamics, an output delay only the sensors' reading); in open loop an input delay and the same delay on every sensor are one response, and several outputs separate them only when the delay is in one sensor's reading";

const std::vector<EffectDescriptor>& catalog();

}  // namespace

// Accessors for the compared outputs of a replay set-up (replay.cpp defines ReplaySetup).
const std::vector<int>& replay_compared(const ReplaySetup& s);
double replay_Ts(const ReplaySetup& s);

namespace {

const std::vector<EffectDescriptor>& catalog()
{
    static const std::vector<EffectDescriptor> v = {
        {Effect::input_delay, "input_delay", "u(t - d) at every plant input (d real: interpolated between samples)", false,
         {Site::force_input},
         kDelayReveals,
         [](const std::vector<std::string>&, const Units&, Site) { return std::vector<ParamInfo>{{"delay_s", "s"}}; },
         [](const FitContext& c, Site) {
             // The integer grid gives the starts, the solver refines the best three.
             EffectSetup s{Effect::input_delay, Site::force_input, 0, {}, {}, true};
             const long dmax = delay_grid_max(c);
             s.spec = {{c.Ts, 0, double(dmax + 1), false}};
             for (long d = 1; d <= dmax; ++d) s.starts.push_back({double(d)});
             return s;
         },
         [](const std::vector<double>& p, Site, const ReplaySetup& s, ReplayTerms& t) {
             t.din = std::max(0.0, p[0] / replay_Ts(s));
         }},
        {Effect::output_delay, "output_delay", "y_c(t - d_c), one delay per compared output", false, {Site::force_input},
         kDelayReveals,
         [](const std::vector<std::string>& o, const Units&, Site) {
             return per_output("delay_s_", o, std::vector<std::string>(o.size(), "s"));
         },
         [](const FitContext& c, Site) {
             // Every output delayed alike and, with several outputs, each one alone.
             EffectSetup s{Effect::output_delay, Site::force_input, 0, {}, {}, true};
             const size_t ny = c.Sy.size();
             const long dmax = delay_grid_max(c);
             for (size_t i = 0; i < ny; ++i) s.spec.push_back({c.Ts, 0, double(dmax + 1), false});
             for (long d = 1; d <= dmax; ++d) {
                 s.starts.push_back(std::vector<double>(ny, double(d)));
                 for (size_t i = 0; ny > 1 && i < ny; ++i) {
                     std::vector<double> st(ny, 0.0);
                     st[i] = double(d);
                     s.starts.push_back(st);
                 }
             }
             return s;
         },
         [](const std::vector<double>& p, Site, const ReplaySetup& s, ReplayTerms& t) {
             const std::vector<int>& cmp = replay_compared(s);
             for (size_t c = 0; c < cmp.size(); ++c) {
                 const double d = std::max(0.0, p[c] / replay_Ts(s));
                 t.dout[size_t(cmp[c])] = d;
                 t.dout_max = std::max(t.dout_max, int(d));
             }
         }},
        {Effect::coulomb_friction, "coulomb_friction", "F = Fc sgn(v) + offset (discrete stick-slip)", true,
         {Site::force_input}, "moves in both directions, with standstills",
         [](const std::vector<std::string>&, const Units& u, Site) {
             return std::vector<ParamInfo>{{"Fc", u.u}, {"offset", u.u}};
         },
         [](const FitContext& c, Site) {
             return EffectSetup{Effect::coulomb_friction, Site::force_input, 0,
                                {{c.Sf, 0, kBig, false}, {c.Sf, -kBig, kBig, false}}, {{0.05, 0.0}, {0.3, 0.0}}, false};
         },
         [](const std::vector<double>& p, Site, const ReplaySetup&, ReplayTerms& t) {
             t.Fc = p[0];
             t.Foff = p[1];
         },
         // Nested restriction: no offset (Fc alone). Without it a Coulomb
         // machine could be named stribeck_friction with Fs <= Fc (the same
         // replay as Coulomb without offset, effects below) whenever the
         // offset, fitted to the fit rows, replayed the held-out rows worse.
         [](const FitContext& c, Site) {
             EffectSetup s{Effect::coulomb_friction, Site::force_input, 0,
                           {{c.Sf, 0, kBig, false}, {c.Sf, 0, 0, true}}, {{0.05, 0.0}, {0.3, 0.0}}, false};
             s.spec[1].held = true;
             return std::vector<EffectSetup>{s};
         }},
        {Effect::viscous_friction, "viscous_friction", "F = Fv v", true, {Site::force_input},
         "moves at several constant speeds",
         [](const std::vector<std::string>&, const Units& u, Site) {
             return std::vector<ParamInfo>{{"Fv", u.u + "/(" + u.v + ")"}};
         },
         [](const FitContext& c, Site) {
             return EffectSetup{Effect::viscous_friction, Site::force_input, 0, {{c.Sf / c.Sv, -kBig, kBig, false}}, {{0.1}}, false};
         },
         [](const std::vector<double>& p, Site, const ReplaySetup&, ReplayTerms& t) { t.Fv = p[0]; }},
        {Effect::stribeck_friction, "stribeck_friction", "F = (Fc + (Fs - Fc) exp(-(v/vs)^2)) sgn(v)", true,
         {Site::force_input}, "slow moves through zero velocity in both directions (speeds below vs)",
         [](const std::vector<std::string>&, const Units& u, Site) {
             return std::vector<ParamInfo>{{"Fc", u.u}, {"Fs", u.u}, {"vs", u.v}};
         },
         [](const FitContext& c, Site) {
             // The cost is rough in vs (the hump only shows below it): a grid
             // of Fc/Sf x Fs/Fc x vs/Sv (Sf: FitContext), screened by cost, the best 3 refined.
             EffectSetup s{Effect::stribeck_friction, Site::force_input, 0,
                           {{c.Sf, 0, kBig, false}, {c.Sf, 0, kBig, false}, {c.Sv, 1e-3, 1e2, false}}, {}, true};
             for (double fc : {0.05, 0.15, 0.4})
                 for (double ratio : {1.5, 2.5})
                     for (double vs : {0.03, 0.1, 0.3, 1.0}) s.starts.push_back({fc, fc * ratio, vs});
             return s;
         },
         [](const std::vector<double>& p, Site, const ReplaySetup&, ReplayTerms& t) {
             // The curve falls from the static level Fs to Fc: Fs < Fc reads as Fs = Fc.
             t.stribeck = true;
             t.Sc = p[0];
             t.Ss = std::max(p[1], p[0]);
             t.Svs = std::max(std::fabs(p[2]), 1e-12);
         }},
        {Effect::backlash, "backlash",
         "a play of total width w on the force input, or in the deflection of a declared coupling (e.g. a gear between a "
         "motor-side encoder and the load), or in a compliant gear behind the motor-side sensors of a rigid nominal "
         "(a load share r of the inertia on a spring of contact frequency f_hz and damping zeta)", false,
         {Site::force_input, Site::coupling, Site::gear}, "small reversing moves around a standstill, load side measured",
         [](const std::vector<std::string>&, const Units& u, Site site) {
             if (site == Site::gear)
                 return std::vector<ParamInfo>{{"width", u.p}, {"share", "1"}, {"f_hz", "Hz"}, {"zeta", "1"}};
             return std::vector<ParamInfo>{{"width", site == Site::coupling ? u.q : u.u}};
         },
         [](const FitContext& c, Site site) {
             if (site == Site::gear) return gear_setup(Effect::backlash, c, true, 6.0);
             EffectSetup s{Effect::backlash, site, c.coupling, {}, {}, false};
             if (site == Site::coupling) {
                 // Log grid of w / rms(q) from 1/4 to 64, 4 per octave (the contacts
                 // make the cost rough in w), screened, the best 3 refined.
                 s.spec = {{c.Sq, 0, kBig, false}};
                 for (double w = 0.25; w <= 64.0; w *= std::pow(2.0, 0.25)) s.starts.push_back({w});
                 s.screen = true;
             } else {
                 s.spec = {{c.Su, 0, kBig, false}};
                 s.starts = {{0.02}, {0.1}, {0.4}};
             }
             return s;
         },
         [](const std::vector<double>& p, Site site, const ReplaySetup&, ReplayTerms& t) {
             if (site == Site::gear) {
                 apply_gear(p, true, t);
             } else if (site == Site::coupling) {
                 t.bl_coupling = t.coupling;
                 t.cbl = std::fabs(p[0]);
             } else {
                 t.bl = std::fabs(p[0]);
             }
         }},
        {Effect::deadzone, "deadzone", "0 for lower <= u <= upper, else u - upper above, u - lower below (asymmetric)",
         false, {Site::force_input}, "a slow command ramp through zero",
         [](const std::vector<std::string>&, const Units& u, Site) {
             return std::vector<ParamInfo>{{"lower", u.u}, {"upper", u.u}};
         },
         [](const FitContext& c, Site) { return edge_setup(Effect::deadzone, c, 0.0, 2.0, deadzone_grid(), false); },
         [](const std::vector<double>& p, Site, const ReplaySetup&, ReplayTerms& t) {
             t.dz_lo = std::min(p[0], 0.0);
             t.dz_hi = std::max(p[1], 0.0);
         },
         [](const FitContext& c, Site) {
             return std::vector<EffectSetup>{edge_setup(Effect::deadzone, c, 0.0, 2.0, deadzone_grid(), true)};
         }},
        {Effect::saturation, "saturation", "clamp(u, lower, upper) (asymmetric)", false, {Site::force_input},
         "commands up to and beyond the limit, in both directions",
         [](const std::vector<std::string>&, const Units& u, Site) {
             return std::vector<ParamInfo>{{"lower", u.u}, {"upper", u.u}};
         },
         [](const FitContext& c, Site) { return edge_setup(Effect::saturation, c, 0.02, 2.0, saturation_grid(), false); },
         [](const std::vector<double>& p, Site, const ReplaySetup&, ReplayTerms& t) {
             t.sat_lo = std::min(p[0], -1e-12);
             t.sat_hi = std::max(p[1], 1e-12);
         },
         [](const FitContext& c, Site) {
             return std::vector<EffectSetup>{edge_setup(Effect::saturation, c, 0.02, 2.0, saturation_grid(), true)};
         }},
        {Effect::fractional_damping, "fractional_damping",
         "c D^alpha v to ground (Grunwald-Letnikov of order alpha - 1 on v), or c D^alpha q in parallel with a declared "
         "coupling's spring or flexible mode (Kelvin-Voigt)",
         true, {Site::force_input, Site::coupling}, "a frequency sweep through the flexible mode (its damping and phase)",
         [](const std::vector<std::string>&, const Units& u, Site site) {
             return std::vector<ParamInfo>{
                 {"c", site == Site::coupling ? u.u + " s^alpha/(" + u.q + ")" : u.u + " s^(alpha-1)/(" + u.v + ")"},
                 {"alpha", "1"}};
         },
         [](const FitContext& c, Site site) {
             EffectSetup s{Effect::fractional_damping, site, c.coupling, {}, {}, false};
             if (site == Site::coupling) {
                 // Start rule from the block's slowest mode w0: c D^alpha adds,
                 // at w0, the damping ratio zeta = c w0^alpha sin(pi alpha/2) / (2 k)
                 // (and the stiffness c w0^alpha cos(pi alpha/2)); the starts
                 // are zeta = 0.003, 0.02, 0.1 at alpha = 0.25, 0.5, 0.75,
                 // screened. c is scaled by k / w0^0.5, its size at alpha = 0.5.
                 // Without an oscillating block, w0 = 1/Ts.
                 const double w0 = c.wq > 0 ? c.wq : 1.0 / c.Ts;
                 const double sc = c.kq / std::sqrt(w0);
                 s.spec = {{sc, 0, kBig, false}, {1.0, 0.05, 0.95, false}};
                 for (double a : {0.25, 0.5, 0.75})
                     for (double z : {0.003, 0.02, 0.1})
                         s.starts.push_back({2 * c.kq * z / (std::pow(w0, a) * std::sin(M_PI * a / 2)) / sc, a});
                 s.screen = true;
             } else {
                 s.spec = {{c.Sf / c.Sv, -kBig, kBig, false}, {1.0, 0.05, 0.95, false}};
                 s.starts = {{0.1, 0.3}, {0.1, 0.7}};
             }
             return s;
         },
         [](const std::vector<double>& p, Site site, const ReplaySetup&, ReplayTerms& t) {
             if (site == Site::coupling) {
                 t.frac_coupling = t.coupling;
                 t.cfc = p[0];
                 t.calpha = p[1];
             } else {
                 t.fractional = true;
                 t.fc = p[0];
                 t.alpha = p[1];
             }
         }},
        {Effect::unmodelled_mode, "unmodelled_mode",
         "eta'' + 2 zeta w eta' + w^2 eta = w^2 u; in series at the force input (the plant is driven by eta, unit static "
         "gain) or at the outputs (they see g_c eta'/w, a resonance without static gain); or in one sensor's reading, a "
         "second-order sensor: b'' + 2 zeta w b' + w^2 b = m 2 zeta w y' + w^2 y, the sensor reads b (unit static gain; "
         "m = 1 a sensor on a compliant mount, the base-excitation transmissibility; m = 0 the sensor's own low-pass); or a compliant gear without play behind the motor-side sensors of a rigid nominal "
         "(the gear site: a load share r of the inertia on a spring of contact frequency f_hz and damping zeta)", false,
         {Site::output, Site::force_input, Site::sensor, Site::gear},
         "a frequency sweep over the band where the residual peaks, with a sensor at the actuator and one at the load",
         [](const std::vector<std::string>& o, const Units& u, Site site) {
             if (site == Site::gear) return std::vector<ParamInfo>{{"share", "1"}, {"f_hz", "Hz"}, {"zeta", "1"}};
             std::vector<ParamInfo> v = {{"f_hz", "Hz"}, {"zeta", "1"}};
             if (site == Site::sensor) v.push_back({"mount", "1"});
             if (site == Site::force_input || site == Site::sensor) return v;
             std::vector<std::string> gu;
             for (size_t i = 0; i < o.size(); ++i) gu.push_back((i < u.y.size() ? u.y[i] : "[" + o[i] + "]") + "/(" + u.u + ")");
             for (const ParamInfo& g : per_output("gain_", o, gu)) v.push_back(g);
             return v;
         },
         [](const FitContext& c, Site site) {
             // At the gear, 12 per decade: like a series mode it moves the loop's own dynamics.
             if (site == Site::gear) return gear_setup(Effect::unmodelled_mode, c, false, 12.0);
             EffectSetup s{Effect::unmodelled_mode, site, site == Site::sensor ? c.coupling : 0, {}, {}, true};
             const size_t ny = site == Site::output ? c.Sy.size() : 0;
             const double flo = std::max(2.0 / c.fit_seconds, 1e-3), fhi = 0.25 / c.Ts;
             // zeta <= 0.5: a resonant mode, not an extra first-order lag.
             s.spec = {{1.0, flo, fhi, false}, {1.0, 0.005, 0.5, false}};
             // At a sensor, the zero's share m in [0, 1] (the reading is linear in it).
             if (site == Site::sensor) s.spec.push_back({1.0, 0.0, 1.0, false});
             for (size_t i = 0; i < ny; ++i) s.spec.push_back({c.Sy[i] / c.Su, -kBig, kBig, false});
             // Starts: the largest peaks of the nominal residual spectrum and a
             // log grid over the band, screened by cost; gains start at 0.1
             // std(y)/rms(u) (with 0 the screen could not rank them). At the
             // outputs 6 per decade; in series 24 per decade: a series mode
             // moves the loop's own dynamics, so one started 20 % off its
             // frequency costs more than none and the screen drops it.
             // At a sensor, the peaks alone, each at both ends of the zero's
             // share: which.cpp fits this site only where another candidate
             // located the resonance, and puts that one's starts ahead.
             std::vector<double> fs = c.residual_peaks_hz;
             const double per_decade = site == Site::force_input ? 24.0 : 6.0;
             if (site != Site::sensor)
                 for (double f = flo; f <= fhi; f *= std::pow(10.0, 1.0 / per_decade)) fs.push_back(f);
             for (double f : fs) {
                 if (f < flo || f > fhi) continue;
                 if (site == Site::sensor) {
                     s.starts.push_back({f, 0.05, 1.0});
                     s.starts.push_back({f, 0.05, 0.0});
                     continue;
                 }
                 std::vector<double> st = {f, 0.05};
                 st.resize(2 + ny, 0.1);
                 s.starts.push_back(st);
             }
             return s;
         },
         [](const std::vector<double>& p, Site site, const ReplaySetup& s, ReplayTerms& t) {
             if (site == Site::gear) {
                 apply_gear(p, false, t);
                 return;
             }
             t.f_hz = p[0];
             t.zeta = p[1];
             if (site == Site::force_input) {
                 t.series_mode = true;
             } else if (site == Site::sensor) {
                 const std::vector<int>& cmp = replay_compared(s);
                 if (t.coupling < 0 || size_t(t.coupling) >= cmp.size())
                     throw std::logic_error("unmodelled_mode: no compared output " + std::to_string(t.coupling));
                 t.sensor_mode = cmp[size_t(t.coupling)];
                 t.sensor_zero = p.at(2);
             } else {
                 t.mode = true;
                 per_model_output(p, replay_compared(s), 2, t.mode_gain, false);
             }
         }},
        {Effect::gain_error, "gain_error", "g u", false, {Site::force_input}, "a slow ramp of the command at steady speed",
         [](const std::vector<std::string>&, const Units&, Site) { return std::vector<ParamInfo>{{"gain", "1"}}; },
         [](const FitContext&, Site) {
             return EffectSetup{Effect::gain_error, Site::force_input, 0, {{1.0, 0.05, 20.0, false}}, {{1.0}, {0.7}, {1.4}}, false};
         },
         [](const std::vector<double>& p, Site, const ReplaySetup&, ReplayTerms& t) { t.gain = p[0]; }},
        {Effect::sensor_offset, "sensor_offset", "y_c + o_c", false, {Site::force_input},
         "a record that starts at rest (gap.initial_state at_rest)",
         [](const std::vector<std::string>& o, const Units& u, Site) { return per_output("offset_", o, u.y); },
         [](const FitContext& c, Site) {
             EffectSetup s{Effect::sensor_offset, Site::force_input, 0, {}, {}, false};
             for (double sy : c.Sy) s.spec.push_back({sy, -kBig, kBig, false});
             s.starts = {std::vector<double>(c.Sy.size(), 0.0)};
             return s;
         },
         [](const std::vector<double>& p, Site, const ReplaySetup& s, ReplayTerms& t) {
             per_model_output(p, replay_compared(s), 0, t.offset, false);
         },
         // Nested restrictions: with several outputs, the offset on one
         // sensor alone (the others held at 0), each a variant of its own.
         // Where only differences of offsets show (a loop closed through an
         // encoder drives its reading to the reference, so an encoder offset
         // and the opposite offset on a second sensor leave the same record
         // once the start is fitted), the full set spread one encoder offset
         // over both sensors (0.0012 and -0.0090 rad for 0.0102 on the
         // encoder); one offset explains it with one parameter. (Two such
         // variants the record cannot tell apart at all score the same: the
         // first compared output's is named.)
         [](const FitContext& c, Site) {
             std::vector<EffectSetup> v;
             const size_t ny = c.Sy.size();
             for (size_t i = 0; ny > 1 && i < ny; ++i) {
                 EffectSetup s{Effect::sensor_offset, Site::force_input, 0, {}, {std::vector<double>(ny, 0.0)}, false};
                 for (size_t j = 0; j < ny; ++j) {
                     s.spec.push_back({c.Sy[j], j == i ? -kBig : 0.0, j == i ? kBig : 0.0, j != i});
                     s.spec.back().held = j != i;
                 }
                 v.push_back(s);
             }
             return v;
         }},
        {Effect::quantization, "quantization", "q_c round(y_c / q_c), compared by cells", false, {Site::force_input},
         "slow moves with little noise",
         [](const std::vector<std::string>& o, const Units& u, Site) { return per_output("step_", o, u.y); },
         [](const FitContext& c, Site) {
             // The lattice step of each output's data where it is coarser than
             // the noise (0: not quantized); no start when none is.
             EffectSetup s{Effect::quantization, Site::force_input, 0, {}, {}, false};
             bool any = false;
             std::vector<double> one;
             for (size_t i = 0; i < c.Sy.size(); ++i) {
                 s.spec.push_back({1.0, 0, 1e300, true});
                 one.push_back(c.quant_step[i]);
                 any = any || c.quant_step[i] > 0;
             }
             if (any) s.starts = {one};
             return s;
         },
         [](const std::vector<double>& p, Site, const ReplaySetup& s, ReplayTerms& t) {
             per_model_output(p, replay_compared(s), 0, t.step, true);
         }},
        {Effect::mode_shift, "mode_shift",
         "one resonant mode of the nominal plant at f' and zeta' instead of its own (a stiffness and damping change "
         "at fixed modal mass: the force's and the sensors' maps of the mode's displacement and rate kept; or, where a declared "
         "coupling's spring moves the mode, that spring's own stiffness and damping change)", false, {Site::mode},
         "a frequency sweep through the mode (the frequency and the width of its peak); a mode at the nominal's own "
         "frequency that is missing from the record's spectrum, or a new peak beside it, tells an added mode apart",
         [](const std::vector<std::string>&, const Units&, Site) {
             return std::vector<ParamInfo>{{"f_hz", "Hz"}, {"zeta", "1"}};
         },
         [](const FitContext& c, Site) {
             // f' within 1/2 .. 2 x the nominal f0 (and the band the record
             // resolves), zeta' in 0.001 .. 0.7; normalized f'/f0, zeta'/zeta_s.
             EffectSetup s{Effect::mode_shift, Site::mode, c.coupling, {}, {}, true};
             const double f0 = c.mode_f_hz, zs = std::max(c.mode_zeta, 0.01);
             const double rlo = std::max(0.5, 2.0 / c.fit_seconds / f0), rhi = std::min(2.0, 0.45 / c.Ts / f0);
             if (!(f0 > 0) || !(rlo < rhi)) return s;
             s.spec = {{f0, rlo, rhi, false}, {zs, 1e-3 / zs, 0.7 / zs, false}};
             // Starts: the where stage's measured peak of each checked mode
             // within f0/1.5 .. 1.5 f0 (a loop's mode checks stand for the
             // plant's: their ratio measured/checked is applied to f0), the
             // residual's peaks, a grid of ratios 2^(k/8) over the bounds; at
             // each the nominal damping and 3 x it; at f0 also zeta0 / 3 (a
             // mode only mis-damped). Screened.
             std::vector<double> rs;
             for (const std::pair<double, double>& mc : c.mode_checks)
                 if (mc.second > 0 && mc.first > f0 / 1.5 && mc.first < 1.5 * f0) rs.push_back(mc.second / mc.first);
             for (double f : c.residual_peaks_hz) rs.push_back(f / f0);
             for (int k = -8; k <= 8; ++k) rs.push_back(std::pow(2.0, k / 8.0));
             const double z0 = std::max(c.mode_zeta, 1e-3);
             for (double r : rs) {
                 if (r < rlo || r > rhi) continue;
                 for (double z : {z0, std::min(3 * z0, 0.6)}) s.starts.push_back({r, z / zs});
             }
             s.starts.push_back({1.0, z0 / 3 / zs});
             return s;
         },
         [](const std::vector<double>& p, Site, const ReplaySetup& s, ReplayTerms& t) {
             if (t.coupling < 0 || size_t(t.coupling) >= s.plant_modes.size())
                 throw std::logic_error("mode_shift: no resonant plant mode " + std::to_string(t.coupling));
             const PlantMode& pm = s.plant_modes[size_t(t.coupling)];
             if (pm.coupling >= 0)
                 shift_coupling_mode(pm, *s.model, p[0], p[1], t.A, t.B);
             else
                 shift_plant_mode(pm, s.model->Ts, p[0], p[1], s.model->A, s.model->B, s.model->force_input, t.A, t.B);
         }},
    };
    return v;
}

}  // namespace

const EffectDescriptor& descriptor(Effect e)
{
    for (const EffectDescriptor& d : catalog())
        if (d.kind == e) return d;
    throw std::logic_error("effect without a descriptor");
}

const std::vector<Effect>& all_effects()
{
    static const std::vector<Effect> v = [] {
        std::vector<Effect> k;
        for (const EffectDescriptor& d : catalog()) k.push_back(d.kind);
        return k;
    }();
    return v;
}

std::string effect_name(Effect e) { return descriptor(e).name; }

Effect effect_from_name(const std::string& name)
{
    for (const EffectDescriptor& d : catalog())
        if (d.name == name) return d.kind;
    std::string known;
    for (const EffectDescriptor& d : catalog()) known += std::string(known.empty() ? "" : ", ") + d.name;
    throw std::invalid_argument("unknown effect '" + name + "' (known: " + known + ")");
}

bool needs_velocity(Effect e) { return descriptor(e).needs_velocity; }

bool coupling_capable(Effect e)
{
    const std::vector<Site>& s = descriptor(e).sites;
    return std::find(s.begin(), s.end(), Site::coupling) != s.end();
}

std::vector<std::string> param_names(Effect e, const std::vector<std::string>& outputs, Site site)
{
    std::vector<std::string> v;
    for (const ParamInfo& p : descriptor(e).params(outputs, Units(), site)) v.push_back(p.name);
    return v;
}

bool same_term(Effect a, Effect b)
{
    const auto friction = [](Effect e) { return e == Effect::coulomb_friction || e == Effect::stribeck_friction; };
    return a != b && friction(a) && friction(b);
}

bool same_term(Effect a, Site sa, Effect b, Site sb)
{
    const auto viscous_pair = [](Effect x, Site sx, Effect y) {
        return x == Effect::fractional_damping && sx == Site::force_input && y == Effect::viscous_friction;
    };
    // The play in the gear and the gear without play: one gear.
    const bool gears = sa == Site::gear && sb == Site::gear && a != b;
    return same_term(a, b) || viscous_pair(a, sa, b) || viscous_pair(b, sb, a) || gears;
}

std::string site_name(Site s)
{
    switch (s) {
    case Site::force_input: return "force_input";
    case Site::coupling: return "coupling";
    case Site::output: return "output";
    case Site::mode: return "mode";
    case Site::sensor: return "sensor";
    case Site::gear: return "gear";
    }
    return "force_input";
}

std::string site_phrase(const std::string& effect, const std::string& site, const std::string& coupling)
{
    if (site == "coupling") return " (in the coupling '" + coupling + "')";
    if (site == "mode") return " (the nominal's " + coupling + ")";
    if (site == "output") return " (at the outputs)";
    if (site == "sensor") return " (in the reading of sensor '" + coupling + "')";
    if (site == "force_input" && effect == "unmodelled_mode") return " (in series at the force input)";
    if (site == "gear") return " (in a gear behind the motor-side sensors)";
    return "";
}

std::vector<std::pair<Site, int>> effect_sites(Effect e, const NominalModel& m, size_t compared_outputs, size_t plant_modes)
{
    std::vector<std::pair<Site, int>> v;
    for (Site s : descriptor(e).sites) {
        if (s == Site::coupling)
            for (size_t i = 0; i < m.couplings.size(); ++i) v.push_back({s, int(i)});
        else if (s == Site::sensor)
            for (size_t i = 0; i < compared_outputs; ++i) v.push_back({s, int(i)});
        else if (s == Site::mode)
            for (size_t i = 0; i < plant_modes; ++i) v.push_back({s, int(i)});
        else if (s == Site::gear) {
            if (gear_site(m).ok) v.push_back({s, 0});
        } else
            v.push_back({s, 0});
    }
    return v;
}

Units units_at(const Units& u, int coupling)
{
    Units r = u;
    if (coupling >= 0 && size_t(coupling) < u.qs.size()) r.q = u.qs[size_t(coupling)];
    return r;
}

Units model_units(const NominalModel& m, const std::vector<std::string>& outputs)
{
    auto unit_of = [&](const std::string& name) {
        const auto it = m.units.find(name);
        return it != m.units.end() ? it->second : "[" + name + "]";
    };
    Units u;
    u.u = unit_of(m.inputs[size_t(m.force_input)]);
    if (m.velocity >= 0) u.v = unit_of(m.outputs[size_t(m.velocity)]);
    for (const Coupling& c : m.couplings) u.qs.push_back(c.unit.empty() ? "[" + c.name + " deflection]" : c.unit);
    if (!u.qs.empty()) u.q = u.qs[0];
    const GearSite g = gear_site(m);
    if (g.ok && g.position_output >= 0) u.p = unit_of(m.outputs[size_t(g.position_output)]);
    for (const std::string& o : outputs) u.y.push_back(unit_of(o));
    return u;
}

}  // namespace gap
}  // namespace fracdesign
