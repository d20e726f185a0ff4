// replay.cpp - the replay of the nominal model augmented with effects: the
// set-up from a record and the sample loop (effects.hpp; each effect's terms
// come from its descriptor in effects.cpp; docs/gap.md gives the equations).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <unsupported/Eigen/MatrixFunctions>

#include "fracdesign/gap/effects.hpp"
#include "fracdesign/gap/matvec.hpp"

#include "frac/fo_gl.h"

namespace fracdesign {
namespace gap {

const std::vector<int>& replay_compared(const ReplaySetup& s) { return s.compared; }
double replay_Ts(const ReplaySetup& s) { return s.model->Ts; }

// The initial plant state the document states (gap.initial_state,
// nominal.hpp): fitted (default): least squares through the first measured
// sample of the compared outputs; at_rest: the steady state of the first
// plant input, (I - A) x0 = B u(0) (open loop, the input after the
// document's limits), x0 = 0 in a closed loop; given: the document's.
static Eigen::VectorXd initial_state(const NominalModel& m, ReplaySetup& s, const Signals& data,
                              const std::vector<std::string>& outputs)
{
    const Eigen::Index nx = m.A.rows();
    if (m.initial_state == NominalModel::Start::given) return m.x0_given;
    if (m.initial_state == NominalModel::Start::at_rest) {
        if (m.closed_loop) return Eigen::VectorXd::Zero(nx);
        Eigen::VectorXd u0(m.B.cols());
        for (Eigen::Index j = 0; j < u0.size(); ++j)
            u0(j) = m.limit_input(size_t(j), s.exo(0, j));
        const Eigen::MatrixXd IA = Eigen::MatrixXd::Identity(nx, nx) - m.A;
        const Eigen::VectorXd b = m.B * u0;
        const Eigen::VectorXd x0 = IA.completeOrthogonalDecomposition().solve(b);
        if (!((IA * x0 - b).norm() <= 1e-9 * std::max(1.0, b.norm())))
            throw std::runtime_error("model gap.initial_state: is \"at_rest\", but the plant has no steady state for the first "
                                     "input of " + data.source + " (it integrates it); give {\"given\": [..]} or \"fitted\"");
        return x0;
    }
    Eigen::MatrixXd Cc(s.compared.size(), nx);
    Eigen::VectorXd y0(s.compared.size());
    for (size_t i = 0; i < s.compared.size(); ++i) {
        Cc.row(Eigen::Index(i)) = m.C.row(s.compared[i]);
        y0(Eigen::Index(i)) = data.col(outputs[i])(0);
    }
    s.x0_fit = Cc.completeOrthogonalDecomposition().pseudoInverse();
    return s.x0_fit * y0;
}

ReplaySetup make_replay_setup(const NominalModel& m, const Signals& data, const std::vector<std::string>& inputs,
                              const std::vector<std::string>& outputs, bool feed_measured)
{
    ReplaySetup s;
    s.model = &m;
    const Eigen::Index N = data.samples();
    std::vector<std::string> drive = m.closed_loop ? m.loop.references : m.inputs;
    const std::string what = m.closed_loop ? "references" : "inputs";
    if (!inputs.empty()) {
        if (inputs.size() != drive.size())
            throw std::runtime_error("model/data mismatch: --inputs names " + std::to_string(inputs.size()) +
                                     " columns but the model has " + std::to_string(drive.size()) + " " + what);
        drive = inputs;
    }
    // A separate friction input (gap.friction_input) is zero in the record: no column needed.
    for (size_t j = 0; j < drive.size(); ++j)
        if (!data.has(drive[j]) && !(!m.closed_loop && int(j) == m.friction_input && m.friction_input != m.force_input))
            throw std::runtime_error("model/data mismatch: the model's " + what.substr(0, what.size() - 1) + " '" + drive[j] +
                                     "' is not a column of " + data.source);
    std::vector<std::string> exo_names = drive;
    if (m.closed_loop)
        for (const std::string& a : m.loop.additive) exo_names.push_back(a);
    s.exo = Eigen::MatrixXd::Zero(N, Eigen::Index(exo_names.size()));
    for (size_t j = 0; j < exo_names.size(); ++j)
        if (data.has(exo_names[j])) s.exo.col(Eigen::Index(j)) = data.col(exo_names[j]);
    for (const std::string& o : outputs) {
        const int i = m.output_index(o);
        if (i < 0) throw std::runtime_error("model/data mismatch: '" + o + "' is not an output of the model");
        if (!data.has(o)) throw std::runtime_error("model/data mismatch: output '" + o + "' is not a column of " + data.source);
        s.compared.push_back(i);
    }
    s.measured.resize(N, Eigen::Index(outputs.size()));
    for (size_t c = 0; c < outputs.size(); ++c) s.measured.col(Eigen::Index(c)) = data.col(outputs[c]);
    if (s.compared.empty()) throw std::runtime_error("model/data mismatch: no model output is a column of " + data.source);
    for (const NominalModel::OutputHold& h : m.holds) {
        int phase = h.phase;
        if (phase < 0) {
            phase = 0;
            const std::string& name = m.outputs[size_t(h.output)];
            if (data.has(name)) {
                const Eigen::VectorXd y = data.col(name);
                std::vector<long> changes(size_t(h.every), 0);
                for (Eigen::Index k = 1; k < y.size(); ++k)
                    if (y(k) != y(k - 1)) ++changes[size_t(k % h.every)];
                for (int p = 1; p < h.every; ++p)
                    if (changes[size_t(p)] > changes[size_t(phase)]) phase = p;
            }
        }
        s.hold_phase.push_back(phase);
    }
    s.x0 = initial_state(m, s, data, outputs);
    s.plant_modes = resonant_plant_modes(m);
    if (m.closed_loop && feed_measured) {
        s.loop_measured.resize(N, Eigen::Index(m.loop.measured.size()));
        for (size_t j = 0; j < m.loop.measured.size(); ++j) {
            const std::string& o = m.outputs[size_t(m.loop.measured[j])];
            if (!data.has(o))
                throw std::runtime_error("model/data mismatch: the controller reads the output '" + o +
                                         "', which is not a column of " + data.source +
                                         "; a replay that feeds the controller the measured outputs needs it "
                                         "(--loop-feedback model replays without it)");
            s.loop_measured.col(Eigen::Index(j)) = data.col(o);
        }
    }
    if (m.closed_loop) {
        // The controller at the first sample: first references, measured outputs of x0.
        std::vector<double> r0(m.loop.references.size()), y0(m.loop.measured.size());
        for (size_t j = 0; j < r0.size(); ++j) r0[j] = s.exo(0, Eigen::Index(j));
        for (size_t j = 0; j < y0.size(); ++j)
            y0[j] = feed_measured ? s.loop_measured(0, Eigen::Index(j)) : m.C.row(m.loop.measured[j]).dot(s.x0);
        std::unique_ptr<Controller> c = m.loop.controller->clone();
        c->start(r0.data(), y0.data());
        s.controller0 = std::move(c);
    }
    return s;
}

namespace {

// s0 + sum_j a[j] b[j] (a and b of one length), each term added in the
// order j = 0, 1, .. to the running sum from s0, the order the replay's sums
// keep (a reordered sum moves fits on fragile closed loops: docs/gap.md,
// "Threads and progress"); chained, dot(c, d, dot(a, b)) is one running sum
// over both. Not inlined, so that the sum stays in a register: inlined into
// the replay's loop, GCC 12 summed into the stack slot of the velocity the
// step's lambdas share, a store and a reload per term, which took a quarter
// of an arm diagnosis (48 states; perf).
__attribute__((noinline)) double dot(const std::vector<double>& a, const std::vector<double>& b, double s0 = 0.0)
{
    double s = s0;
    for (size_t j = 0; j < a.size(); ++j) s += a[j] * b[j];
    return s;
}

// Sub-steps per sample of the gear site's play: each spans at most
// pi/24 = 0.13 rad of the contact mode (w_g Ts / n <= pi/24), which is 12 at
// a quarter of the sampling rate (the candidate's upper frequency bound) and
// 1 below 1/48 of it (the 1e-9 keeps the band's top at 12, where
// w_g Ts / (pi/24) is 12 up to rounding). Without a play (w = 0) the
// contact is linear and stepped exactly (zero-order hold), so one step per
// sample.
int gear_substeps(double wg, double Ts, double w)
{
    if (w <= 0) return 1;
    return int(std::min(64.0, std::max(1.0, std::ceil(wg * Ts / (M_PI / 24) - 1e-9))));
}

// Ring buffer holding the last `len` vectors of dimension `dim`.
struct History {
    std::vector<double> buf;
    int dim = 0, len = 0, head = 0;
    void init(int d, int l, const double* fill)
    {
        dim = d;
        len = std::max(l, 1);
        buf.assign(size_t(dim) * size_t(len), 0.0);
        for (int i = 0; i < len; ++i) std::copy(fill, fill + dim, buf.begin() + long(i) * dim);
        head = 0;
    }
    // Called several times per sample and output: a loop, not memmove, for
    // the few entries, and no integer division for the common lags (the two
    // modulos took a fifth of the replay's own time on a servo; perf).
    void push(const double* x)
    {
        double* d = &buf[size_t(head) * size_t(dim)];
        for (int i = 0; i < dim; ++i) d[i] = x[i];
        if (++head == len) head = 0;
    }
    // Value pushed `lag` pushes ago (lag 1 = the latest).
    const double* lagged(int lag) const
    {
        int i = head - lag;
        if (i < 0) i += len;
        if (i < 0 || i >= len) i = ((head - lag) % len + len) % len;  // a lag beyond the ring's length
        return &buf[size_t(i) * size_t(dim)];
    }
};

double tanh_sign(double v, double eps) { return std::tanh(v / eps); }

// A Grunwald-Letnikov operator of order r with L terms in caller storage
// (frac_gl_init); a non-finite order (a diverged fit) makes it throw.
void gl_init_or_throw(frac_gl& gl, double r, double Ts, int L, std::vector<frac_real>& store)
{
    const size_t n = size_t(std::max(L, 1));
    store.assign(FRAC_GL_STORAGE(n), frac_real(0));
    if (frac_gl_init(&gl, frac_real(r), frac_real(Ts), n, store.data(), store.size()) != FRAC_OK)
        throw std::runtime_error("fractional operator of order " + std::to_string(r) + " rejected by frac_gl_init");
}

// The mode in series at the force input over one sample, a held:
//   eta'' + 2 zeta w eta' + w^2 eta = w^2 a,  x' = Ac x + Bc (eta e_f + u_rest).
// xm = [eta, eta'] steps by (As, Bs); the mean of eta over the sample is
// Cs xm + Ds a (zero-order hold of [xm; int eta]). With the plant's
// generator known, the plant sees eta's exact path: the zero-order hold of
// the joint generator [[Ac, Bc e_f 0], [0, Am]] gives
//   x(k+1) = A x + B u_rest + Pxm xm + Gxa a,
// and the replay adds corr = Pxm xm + Gxa a - B e_f (Cs xm + Ds a) to the
// step that feeds the plant eta's mean. The mean alone is second order in
// w Ts: at w Ts = 0.24 (38 Hz at 1 ms) under a PD loop its phase error
// moves a limit cycle's period, and the replay drifts off the record (the
// servo family, docs/gap.md). The generator is NominalModel::Ac (the
// document's, else discrete_generator's: log(A)/Ts with Bc = (int_0^Ts
// e^{Ac s} ds)^-1 B); a plant without one (a pure delay chain) keeps the
// mean (exact = false).
struct SeriesHold {
    Eigen::Matrix2d As = Eigen::Matrix2d::Identity();
    Eigen::Vector2d Bs = Eigen::Vector2d::Zero(), Cs = Eigen::Vector2d::Zero();
    double Ds = 1.0;
    bool exact = false;
    Eigen::MatrixXd Pxm;  // nx x 2
    Eigen::VectorXd Gxa;  // nx
};

SeriesHold series_mode_hold(const NominalModel& m, double w, double zeta)
{
    const double Ts = m.Ts;
    SeriesHold h;
    {
        Eigen::MatrixXd Ac = Eigen::MatrixXd::Zero(3, 3), Bc = Eigen::MatrixXd::Zero(3, 1), Ad, Bd;
        Ac(0, 1) = 1;
        Ac(1, 0) = -w * w;
        Ac(1, 1) = -2 * zeta * w;
        Ac(2, 0) = 1;
        Bc(1, 0) = w * w;
        zoh(Ac, Bc, Ts, Ad, Bd);
        h.As = Ad.topLeftCorner(2, 2);
        h.Bs = Bd.col(0).head(2);
        h.Cs = Ad.row(2).head(2).transpose() / Ts;
        h.Ds = Bd(2, 0) / Ts;
    }
    const Eigen::Index nx = m.A.rows();
    Eigen::MatrixXd Ag = m.Ac;
    Eigen::VectorXd bf;
    if (Ag.rows() == nx && m.Bc.rows() == nx && m.Bc.cols() == m.B.cols()) {
        bf = m.Bc.col(m.force_input);
    } else {
        Eigen::MatrixXd G_inv;
        if (!discrete_generator(m.A, Ts, Ag, G_inv)) return h;
        bf = G_inv * m.B.col(m.force_input);
    }
    Eigen::MatrixXd Aj = Eigen::MatrixXd::Zero(nx + 2, nx + 2), Bj = Eigen::MatrixXd::Zero(nx + 2, 1), Ad, Bd;
    Aj.topLeftCorner(nx, nx) = Ag;
    Aj.block(0, nx, nx, 1) = bf;
    Aj(nx, nx + 1) = 1;
    Aj(nx + 1, nx) = -w * w;
    Aj(nx + 1, nx + 1) = -2 * zeta * w;
    Bj(nx + 1, 0) = w * w;
    zoh(Aj, Bj, Ts, Ad, Bd);
    if (!Ad.allFinite() || !Bd.allFinite()) return h;
    h.Pxm = Ad.block(0, nx, nx, 2);
    h.Gxa = Bd.col(0).head(nx);
    h.exact = true;
    return h;
}

}  // namespace

ReplayTrace replay(const ReplaySetup& s, const std::vector<EffectInstance>& effects, Eigen::Index n,
                   const Eigen::MatrixXd* sensor_noise)
{
    const NominalModel& m = *s.model;
    const Eigen::Index N = n < 0 ? s.samples() : std::min(n, s.samples());
    const int nx = int(m.A.rows()), nu = int(m.B.cols()), ny = int(m.C.rows());
    const int ncmp = int(s.compared.size()), fi = m.force_input;
    const double Ts = m.Ts, inf = std::numeric_limits<double>::infinity();

    // Effect terms (absent effects leave the nominal unchanged), each set by
    // its descriptor. Delays in samples, real: d = n + f reads
    // (1 - f) x(k - n) + f x(k - n - 1) (linear interpolation between
    // samples, so that a delay between two samples, e.g. of a
    // sample-and-hold, is not rounded to one of them).
    ReplayTerms T;
    T.dout.assign(size_t(ny), 0.0);
    T.mode_gain.assign(size_t(ny), 0.0);
    T.offset.assign(size_t(ny), 0.0);
    T.step.assign(size_t(ny), 0.0);
    for (const EffectInstance& e : effects) {
        T.coupling = e.coupling;
        descriptor(e.kind).apply(e.params, e.site, s, T);
    }
    const double din = m.input_delay + T.din;  // the nominal's delay (gap.input_delay, a foprocess's tau) + the effect's
    // A fractional input delay d = (n + f) Ts of a continuous plant under a
    // zero-order hold: over each sample the plant sees the older input for
    // f Ts, then the newer one, so exactly
    //   x(k+1) = Phi x(k) + B1 u(k - n - 1) + (Gamma(Ts) - B1) u(k - n),
    //   B1 = e^{Ac (1 - f) Ts} Gamma(f Ts),  Gamma(t) = int_0^t e^{Ac s} ds Bc
    // (Astrom & Wittenmark, Computer-Controlled Systems, 3rd ed., sec. 2.3).
    // The replay feeds the interpolation (1 - f) u(k - n) + f u(k - n - 1)
    // through B = Gamma(Ts) and adds (B1 - f B) (u(k - n - 1) - u(k - n)):
    // zero while the input is steady, and what the interpolation misses at
    // each of its steps (on a fractional process of order 0.44 with a dead
    // time of 7.38 samples, twice the noise's gap, named an unmodelled mode
    // at 50 Hz). Exact for the linear path; the force input's gain, limits
    // and dead zone enter it, a play or a series mode does not (the
    // interpolation stays for them), and a plant without a generator
    // (NominalModel::Ac), or one whose mode is moved (mode_shift), keeps the
    // interpolation alone.
    const int din_n = int(din);
    const double din_f = din - din_n;
    Eigen::MatrixXd Bfrac;
    if (din_f > 1e-9 && T.A.size() == 0 && m.Ac.rows() == nx && m.Bc.rows() == nx && m.Bc.cols() == nu) {
        Eigen::MatrixXd Pf, Gf, Pg, Gg;
        zoh(m.Ac, m.Bc, din_f * Ts, Pf, Gf);
        zoh(m.Ac, m.Bc, (1 - din_f) * Ts, Pg, Gg);
        Bfrac = Pg * Gf - din_f * m.B;
    }
    std::vector<double> dfrac(Bfrac.size() ? size_t(nu) : 0, 0.0);
    const int dout_max = T.dout_max;
    const std::vector<double>& dout = T.dout;
    const double Fc = T.Fc, Foff = T.Foff, Fv = T.Fv, Sc = T.Sc, Ss = T.Ss, Svs = T.Svs, bl = T.bl, fc = T.fc,
                 alpha = T.alpha, gain = T.gain;
    // Limits and dead-zone edges, asymmetric (lower < 0 < upper).
    const bool limited = T.sat_lo < 0 || T.sat_hi > 0, deadzone = T.dz_lo < 0 || T.dz_hi > 0;
    const double sat_lo = limited ? T.sat_lo : -inf, sat_hi = limited ? T.sat_hi : inf, dz_lo = T.dz_lo, dz_hi = T.dz_hi;
    const bool stribeck = T.stribeck, fractional = T.fractional, mode = T.mode, series = T.series_mode;
    const double cfc = T.cfc, calpha = T.calpha;
    const double f_hz = T.f_hz, zeta = T.zeta;
    const std::vector<double>&mode_gain = T.mode_gain, &offset = T.offset, &step = T.step;
    // The plant's matrices: the nominal's, or with a mode moved (mode_shift).
    // A coupling's sub-steps keep the nominal block's Phi: the change
    // (A' - A) x + (B' - B) u then acts as forcing held over the sample.
    const Eigen::MatrixXd& A = T.A.size() ? T.A : m.A;
    const Eigen::MatrixXd& B = T.B.size() ? T.B : m.B;

    // Velocity row, and the velocity one step ahead: v(k+1) = cvA x(k) + cvB u(k).
    std::vector<double> cv(size_t(nx), 0.0), cvA(size_t(nx), 0.0), cvB(size_t(nu), 0.0);
    if (m.velocity >= 0) {
        for (int j = 0; j < nx; ++j) {
            cv[size_t(j)] = m.C(m.velocity, j);
            for (int i = 0; i < nx; ++i) cvA[size_t(j)] += m.C(m.velocity, i) * A(i, j);
        }
        for (int l = 0; l < nu; ++l)
            for (int i = 0; i < nx; ++i) cvB[size_t(l)] += m.C(m.velocity, i) * B(i, l);
    }
    const int ffi = m.friction_input;
    const double bv = cvB[size_t(ffi)];
    const double eps = s.eps_velocity;
    // Mode: eta'' + 2 zeta w eta' + w^2 eta = w^2 u, discretised with zero-order
    // hold; the outputs see g eta'/w, a resonance with no static gain (a static
    // gain change is gain_error's job), peak g/(2 zeta) at w.
    Eigen::Matrix2d Am = Eigen::Matrix2d::Identity();
    Eigen::Vector2d Bm = Eigen::Vector2d::Zero();
    const double mode_w = 2 * M_PI * std::max(f_hz, 1e-6);
    // The mode in series at the force input: the plant is driven by eta
    // (unit static gain) instead of the actuator's a; the plant input holds
    // eta's mean over the sample, and the step adds the exact path's
    // correction (series_mode_hold; zero where the plant has no generator).
    const SeriesHold sh = series ? series_mode_hold(m, mode_w, zeta) : SeriesHold();
    const Eigen::Matrix2d& As = sh.As;
    const Eigen::Vector2d &Bs = sh.Bs, &Cs = sh.Cs;
    const double Ds = sh.Ds;
    std::vector<double> series_corr(size_t(nx), 0.0);
    double xs_m[2] = {0, 0};
    if (mode) {
        const double w = mode_w;
        Eigen::MatrixXd Ac(2, 2), Bc(2, 1), Ad, Bd;
        Ac << 0, 1, -w * w, -2 * zeta * w;
        Bc << 0, w * w;
        zoh(Ac, Bc, Ts, Ad, Bd);
        Am = Ad;
        Bm = Bd.col(0);
    }
    // c D^alpha of the position = c D^(alpha-1) of v: libfrac's
    // Grunwald-Letnikov operator (frac/fo_gl.h) of order alpha - 1, memory
    // fractional_memory samples, on v.
    std::vector<frac_real> gl_store;
    frac_gl gl_v;
    if (fractional) gl_init_or_throw(gl_v, alpha - 1.0, Ts, s.fractional_memory, gl_store);
    // Couplings (gap.coupling): in coupling i the real spring's torque minus the nominal's,
    //   D = -k clamp(q, -w/2, w/2)        (play of width w: k dz(q) - k q)
    //     + c D^alpha q                   (Grunwald-Letnikov of order alpha on q).
    // At most one coupling holds the play and one the fractional term (each
    // effect kind appears once). The fractional term is held over the
    // sample at its value at mid-sample: the Grunwald-Letnikov sum of step h
    // is centred alpha h/2 behind its newest sample (the shifted Grunwald
    // formula, D^alpha q(t) = h^-alpha sum_j w_j q(t - (j - alpha/2) h) to
    // second order, Meerschaert & Tadjeran 2004), so it is fed
    // q(k + (1 + alpha)/2), interpolated between q(k) and the nominal
    // q(k+1) (pushed with the end state once known). Fed the plain midpoint,
    // it lags alpha/2 samples: at 0.165 rad per sample that biased c by 10 %
    // (test_gap_sites_kv). Its memory covers 20/w of the block's slowest mode
    // (coupling_gl_memory). The play is applied on sub-steps of its
    // coupling's state block (nominal.hpp, Coupling), each an implicit
    // trapezoid D(q at mid-sub-step) solved by fixed-point iteration
    // (contraction |twist . torque_m| k/2). One explicit step per 1.2 ms
    // sample misses the gap-bench gear's contacts completely (its free play
    // gets a spurious eigenvalue of 0.944 per step); one implicit step leaves
    // 40 % of the effect as error, 8 sub-steps 3 % (driven by the recorded
    // torque, against RK4 with 32 sub-steps per sample).
    const int ncp = int(m.couplings.size());
    const int ibl = T.cbl >= 0 && T.bl_coupling >= 0 && T.bl_coupling < ncp ? T.bl_coupling : -1;
    const int ifr = T.frac_coupling >= 0 && T.frac_coupling < ncp ? T.frac_coupling : -1;
    const double cbl = T.cbl;
    const Coupling* cb = ibl >= 0 ? &m.couplings[size_t(ibl)] : nullptr;
    const Coupling* cf = ifr >= 0 ? &m.couplings[size_t(ifr)] : nullptr;
    const double ck = cb ? cb->stiffness : 0.0;
    const Eigen::Index ns = cb ? Eigen::Index(cb->states.size()) : 0;
    Eigen::VectorXd zs(ns), zp(ns), gs(ns), drive(ns);
    // The gear site (gear.cpp): z = [q, s], q the motor's lead over the load
    // in the position state's units, s its rate in the velocity state's;
    //   q' = kappa s,  s' = a/(1 - r) + (A_jj - 2 zeta w_g) s - (w_g^2/kappa) dz(q),
    // the contact's linear part stepped exactly (zero-order hold of a over
    // each sub-step) and the play's -(w_g^2/kappa) clamp(q) by
    // play_substeps. The sensors read r q on the position state and r s on
    // the velocity state. From rest in the middle of the play.
    const bool gear = T.gear;
    GearSite G;
    Eigen::MatrixXd g_Phi, g_Gam;
    Eigen::VectorXd g_z = Eigen::VectorXd::Zero(2), g_drive(2), g_torque(2);
    Eigen::RowVectorXd g_twist = Eigen::RowVectorXd::Zero(2);
    double g_k = 0;
    int g_n = 1;
    if (gear) {
        G = gear_site(m);
        if (!G.ok) throw std::logic_error("gear site on this model: " + G.why);
        const double wg = 2 * M_PI * T.gear_f;
        Eigen::Matrix2d Ag;
        Ag << 0, G.kappa, -wg * wg / G.kappa, m.Ac(G.j, G.j) - 2 * T.gear_zeta * wg;
        g_n = gear_substeps(wg, Ts, T.gear_w);
        zoh(Ag, Eigen::MatrixXd::Identity(2, 2), Ts / g_n, g_Phi, g_Gam);
        g_torque = -g_Gam.col(1);
        g_twist(0) = 1;
        g_k = wg * wg / G.kappa;
    }
    // c D^alpha q: libfrac's Grunwald-Letnikov operator of order alpha on the
    // mid-sample deflections; the sample's term is g qmid + y0 with the
    // operator's feedthrough g and free response y0 (fo_gl.h), and qmid is
    // pushed once the sample's end state is known.
    std::vector<frac_real> cgl_store;
    frac_gl gl_q;
    const double fshift = 0.5 * (1.0 + calpha);
    if (cf) gl_init_or_throw(gl_q, calpha, Ts, coupling_gl_memory(*cf, Ts, s.fractional_memory, long(N)), cgl_store);
    // Deflection twist . x of a plant state in coupling c.
    auto twist_of = [&](const Coupling& c, const std::vector<double>& xs) {
        double q = 0;
        for (int j = 0; j < nx; ++j) q += c.twist(j) * xs[size_t(j)];
        return q;
    };

    ReplayTrace tr;
    tr.y.resize(N, ncmp);
    tr.twist = Eigen::VectorXd::Zero(N);
    tr.twists = Eigen::MatrixXd::Zero(N, ncp);
    tr.u.resize(N);
    tr.u_static = Eigen::VectorXd::Zero(N);
    tr.v.resize(N);
    double static_in = 0.0;  // this step's command entering the static path (gain x the delayed command)
    std::vector<double> x(s.x0.data(), s.x0.data() + nx), xn(static_cast<size_t>(nx));
    // A fitted start goes through the first sample as the sensors read it:
    // with sensor offsets, through the first sample less them (x0 - Cc^+ o).
    // Else an offset on the sensor a loop reads replays a start transient the
    // record does not have (the record's start was fitted with the offset in
    // it), and only a second sensor's opposite offset, never the loop's own,
    // matched such a record.
    if (s.x0_fit.size() && std::any_of(T.offset.begin(), T.offset.end(), [](double o) { return o != 0.0; })) {
        Eigen::VectorXd oc(ncmp);
        for (int c = 0; c < ncmp; ++c) oc(c) = T.offset[size_t(s.compared[size_t(c)])];
        const Eigen::VectorXd dx = s.x0_fit * oc;
        for (int j = 0; j < nx; ++j) x[size_t(j)] -= dx(j);
    }
    std::unique_ptr<Controller> ctl = m.closed_loop ? s.controller0->clone() : nullptr;
    std::vector<double> ytrue(static_cast<size_t>(ny)), ysens(static_cast<size_t>(ny)), yraw(static_cast<size_t>(ny)),
        u(static_cast<size_t>(nu)),
        up(static_cast<size_t>(nu));
    std::vector<double> rk(m.closed_loop ? m.loop.references.size() : 0), ym(m.closed_loop ? m.loop.measured.size() : 0),
        cvec(static_cast<size_t>(nu));
    double eta[2] = {0, 0};
    // The mode in one sensor's reading (unmodelled_mode at Site::sensor):
    // b'' + 2 zeta w b' + w^2 b = m 2 zeta w y' + w^2 y, i.e.
    // H(s) = (m 2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2), unit static
    // gain. m = 1: a sensor on a compliant mount (base excitation's
    // transmissibility, peak about 1/(2 zeta) at w, nearly 1 below it);
    // m = 0: the sensor's own second-order low-pass (below w a lag of
    // 2 zeta / w). Realised as z' = [[0, 1], [-w^2, -2 zeta w]] z + [0; 1] y,
    // b = w^2 z1 + m 2 zeta w z2. The true output is continuous, so it is held first order
    // (linear between samples): z(k+1) = F z(k) + G0 y(k) + G1 (y(k+1) - y(k)),
    // [F G0 G1] the top rows of exp([[Af, Bf, 0], [0, 0, 1/Ts], [0, 0, 0]] Ts).
    // From rest at the first sample's value.
    const int sensor_out = T.sensor_mode;
    const double sm_w = 2 * M_PI * std::max(T.f_hz, 1e-6), sm_z = T.zeta, sm_m = T.sensor_zero;
    Eigen::Matrix2d sm_F = Eigen::Matrix2d::Identity();
    Eigen::Vector2d sm_G0 = Eigen::Vector2d::Zero(), sm_G1 = Eigen::Vector2d::Zero(), sm_x = Eigen::Vector2d::Zero();
    double sm_prev = 0.0;
    bool sm_first = true;
    if (sensor_out >= 0) {
        Eigen::MatrixXd M = Eigen::MatrixXd::Zero(4, 4), E, unused;
        M(0, 1) = 1;
        M(1, 0) = -sm_w * sm_w;
        M(1, 1) = -2 * sm_z * sm_w;
        M(1, 2) = 1;
        M(2, 3) = 1 / Ts;
        zoh(M, Eigen::MatrixXd::Zero(4, 1), Ts, E, unused);
        sm_F = E.topLeftCorner(2, 2);
        sm_G0 = E.block(0, 2, 2, 1);
        sm_G1 = E.block(0, 3, 2, 1);
    }
    double bl_out = 0.0, series_in = 0.0;
    bool first_sample = true;
    History h_out, h_in, h_ctl;
    const int nr = m.closed_loop ? int(m.loop.references.size()) : 0;

    // gap.output_hold: a held output's stream is its sample output's (through the held
    // channel's own effects); between readings it repeats its last reading.
    std::vector<double> held_sens(m.holds.size(), 0.0), held_raw(m.holds.size(), 0.0);
    auto plant_outputs = [&](bool with_d, Eigen::Index k) {
        // y = C x (+ D u) (matvec.hpp: Eigen's sums, without its dispatch).
        matvec(m.C, x.data(), ytrue.data(), false);
        if (with_d) matvec(m.D, up.data(), ytrue.data(), true);
        for (int i = 0; i < ny; ++i) ytrue[size_t(i)] += mode_gain[size_t(i)] * eta[1] / mode_w;
        if (gear)
            for (int i = 0; i < ny; ++i) ytrue[size_t(i)] += T.gear_r * (m.C(i, G.p) * g_z(0) + m.C(i, G.j) * g_z(1));
        if (sensor_out >= 0) {
            const double yk = ytrue[size_t(sensor_out)];
            if (sm_first)
                sm_x << yk / (sm_w * sm_w), 0.0;
            else
                sm_x = sm_F * sm_x + sm_G0 * sm_prev + sm_G1 * (yk - sm_prev);
            sm_first = false;
            sm_prev = yk;
            ytrue[size_t(sensor_out)] = sm_w * sm_w * sm_x(0) + sm_m * 2 * sm_z * sm_w * sm_x(1);
        }
        for (const NominalModel::OutputHold& h : m.holds) ytrue[size_t(h.output)] = ytrue[size_t(h.sample)];
        if (h_out.len == 0) h_out.init(ny, dout_max + 2, ytrue.data());
        h_out.push(ytrue.data());
        for (int i = 0; i < ny; ++i) {
            const int n = int(dout[size_t(i)]);
            const double f = dout[size_t(i)] - n;
            double y = (1 - f) * h_out.lagged(n + 1)[i] + (f > 0 ? f * h_out.lagged(n + 2)[i] : 0.0) + offset[size_t(i)];
            if (sensor_noise) y += (*sensor_noise)(k, i);
            yraw[size_t(i)] = y;
            if (step[size_t(i)] > 0) y = step[size_t(i)] * std::round(y / step[size_t(i)]);
            ysens[size_t(i)] = y;
        }
        for (size_t j = 0; j < m.holds.size(); ++j) {
            const NominalModel::OutputHold& h = m.holds[j];
            const size_t o = size_t(h.output);
            if (k == 0 || (k - s.hold_phase[j]) % h.every == 0) {
                held_sens[j] = ysens[o];
                held_raw[j] = yraw[o];
            }
            ysens[o] = held_sens[j];
            yraw[o] = held_raw[j];
        }
    };
    auto input_path = [&](double v) {
        if (h_in.len == 0) h_in.init(nu, int(din) + 2, u.data());
        h_in.push(u.data());
        const int n = din_n;
        const double fr = din_f;
        for (int j = 0; j < nu; ++j) up[size_t(j)] = (1 - fr) * h_in.lagged(n + 1)[j] + (fr > 0 ? fr * h_in.lagged(n + 2)[j] : 0.0);
        // The force input's static path: gain, limits, dead zone.
        const auto static_path = [&](double v) {
            double a = gain * v;
            a = std::min(std::max(a, sat_lo), sat_hi);
            if (deadzone) a = a > dz_hi ? a - dz_hi : (a < dz_lo ? a - dz_lo : 0.0);
            return a;
        };
        if (!dfrac.empty())
            for (int j = 0; j < nu; ++j) {
                const double older = h_in.lagged(n + 2)[j], newer = h_in.lagged(n + 1)[j];
                dfrac[size_t(j)] = j != fi ? older - newer : (bl >= 0 || series ? 0.0 : static_path(older) - static_path(newer));
            }
        static_in = gain * up[size_t(fi)];
        double a = static_path(up[size_t(fi)]);
        if (bl >= 0) {
            bl_out = std::min(std::max(bl_out, a - 0.5 * bl), a + 0.5 * bl);
            a = bl_out;
        }
        if (series) {
            if (first_sample) xs_m[0] = a, xs_m[1] = 0.0;  // the mode starts at rest under the first input
            series_in = a;
            const double mean = Cs(0) * xs_m[0] + Cs(1) * xs_m[1] + Ds * a;
            if (sh.exact)
                for (int i = 0; i < nx; ++i)
                    series_corr[size_t(i)] = sh.Pxm(i, 0) * xs_m[0] + sh.Pxm(i, 1) * xs_m[1] + sh.Gxa(i) * a - B(i, fi) * mean;
            a = mean;
        }
        up[size_t(fi)] = a;
        double f = 0.0;
        if (m.velocity >= 0) {
            // The nominal's known friction (gap.friction) and the effects' beyond it.
            f = Foff + (Fv + m.friction.viscous) * v;
            // v(k+1) without this step's friction force, linear in the state and the inputs
            // (friction then moves it by -bv f); computed once, used by both friction steps below.
            double vnext = std::numeric_limits<double>::quiet_NaN();
            auto velocity_next = [&]() {
                if (std::isnan(vnext)) vnext = dot(cv, series_corr, dot(cvB, up, dot(cvA, x)));
                return vnext;
            };
            // A smooth Coulomb term b0 tanh(k v) near rest is a damper b0 k, stiff against the
            // sample (arm_wang: bv b0 k = 0.094 per sample, where the plant integrates it in
            // sub-steps): held over the sample at the midpoint velocity (v(k) + v(k+1))/2, the
            // trapezoidal rule, with v(k+1) = vlin - bv f_k linear in it; f_k is the one root of
            // f - b0 tanh(k (v + vlin - bv f)/2), increasing in f for bv >= 0 (Newton, from the
            // explicit value; a few steps).
            // The Coulomb effect's Fc then adds to b0 (friction beyond the known, of its law).
            const bool known_smooth = m.friction.coulomb != 0.0 && m.friction.tanh_k > 0;
            if (known_smooth) {
                const double b0 = m.friction.coulomb + Fc, kk = m.friction.tanh_k;
                double fk = b0 * std::tanh(kk * v);
                if (bv > 0.0) {
                    const double vlin = velocity_next() - bv * f;
                    for (int it = 0; it < 20; ++it) {
                        const double th = std::tanh(0.5 * kk * (v + vlin - bv * fk)), r = fk - b0 * th;
                        const double step = r / (1.0 + 0.5 * b0 * kk * bv * (1.0 - th * th));
                        fk -= step;
                        if (std::fabs(step) <= 1e-13 * b0) break;
                    }
                }
                f += fk;
            }
            if (fractional) {
                frac_real d = 0;
                if (frac_gl_step(&gl_v, frac_real(v), &d) != FRAC_OK) d = std::numeric_limits<double>::quiet_NaN();
                f += fc * double(d);
            }
            // Dry friction of level L(v) (Coulomb, plus the Stribeck curve),
            // discrete stick-slip: the force is the one that stops the
            // velocity within this step, limited to +-L(v); so sliding gets
            // L sign(v) exactly and sticking holds without chattering.
            double level = known_smooth ? 0.0 : Fc;
            if (stribeck) level += Sc + (Ss - Sc) * std::exp(-(v / Svs) * (v / Svs));
            if (!known_smooth) level += m.friction.coulomb;  // known dry friction (no tanh_k)
            if (level != 0.0) {
                if (bv != 0.0) {
                    const double vfree = velocity_next() - bv * f;
                    const double stop = vfree / bv, lv = std::fabs(level);
                    f += std::min(std::max(stop, -lv), lv);
                } else {
                    f += level * tanh_sign(v, eps);
                }
            }
        }
        if (ffi == fi)
            up[size_t(fi)] = a - f;
        else
            up[size_t(ffi)] -= f;
    };

    for (Eigen::Index k = 0; k < N; ++k) {
        const double v = dot(cv, x);
        if (m.closed_loop) {
            plant_outputs(false, k);
            for (int j = 0; j < nr; ++j) rk[size_t(j)] = s.exo(k, j);
            // The outputs the controller reads: the model's (its sensors'
            // effects applied), or the record's (ReplaySetup::loop_measured).
            if (s.loop_measured.rows() > 0)
                for (size_t j = 0; j < ym.size(); ++j) ym[j] = s.loop_measured(k, Eigen::Index(j));
            else
                for (size_t j = 0; j < ym.size(); ++j) ym[j] = ysens[size_t(m.loop.measured[j])];
            ctl->step(rk.data(), ym.data(), cvec.data());
            if (h_ctl.len == 0) h_ctl.init(nu, m.loop.delay_samples + 1, cvec.data());
            h_ctl.push(cvec.data());
            const double* cd = m.loop.delay_samples > 0 ? h_ctl.lagged(m.loop.delay_samples + 1) : cvec.data();
            for (int i = 0; i < nu; ++i) {
                u[size_t(i)] = std::min(std::max(cd[i], m.loop.saturation_min), m.loop.saturation_max);
                if (i < int(m.loop.additive.size())) u[size_t(i)] += s.exo(k, nr + i);
            }
            if (k == 0) bl_out = gain * u[size_t(fi)];
            input_path(v);
        } else {
            // The actuator's limits the document states (gap.input_limits).
            for (int i = 0; i < nu; ++i)
                u[size_t(i)] = m.limit_input(size_t(i), s.exo(k, i));
            if (k == 0) bl_out = gain * u[size_t(fi)];
            input_path(v);
            plant_outputs(true, k);
        }
        for (int c = 0; c < ncmp; ++c) {
            const size_t i = size_t(s.compared[size_t(c)]);
            tr.y(k, c) = ysens[i];
            // A quantizing sensor reports the cell [m - q/2, m + q/2] around
            // its reading m: the residual is the model value's distance to
            // that cell (zero inside it), so the trace holds m shifted by
            // that distance (the feedback above gets the rounded value).
            if (step[i] > 0 && k < s.measured.rows()) {
                const double m = s.measured(k, c), h = 0.5 * step[i];
                tr.y(k, c) = m + (yraw[i] - std::min(std::max(yraw[i], m - h), m + h));
            }
        }
        tr.u(k) = up[size_t(fi)] + (ffi != fi ? up[size_t(ffi)] : 0.0);  // the net force: the actuator's less the friction
        tr.u_static(k) = static_in;
        tr.v(k) = v;
        {
            // x(k+1) = A x + B u (+ the series mode's correction), by
            // matvec.hpp (Eigen's sums, without its dispatch).
            matvec(A, x.data(), xn.data(), false);
            matvec(B, up.data(), xn.data(), true);
            if (series)
                for (int i = 0; i < nx; ++i) xn[size_t(i)] += series_corr[size_t(i)];
            if (!dfrac.empty()) matvec(Bfrac, dfrac.data(), xn.data(), true);
        }
        for (int c = 0; c < ncp; ++c) {
            tr.twists(k, c) = twist_of(m.couplings[size_t(c)], x);
            if (c == 0) tr.twist(k) = tr.twists(k, c);
        }
        double q0f = 0.0;
        if (cf) {
            // The fractional torque held over the sample, added to the
            // sample's forcing (a play's sub-steps below take their forcing
            // from xn, so they carry it).
            q0f = twist_of(*cf, x);
            const double qp = twist_of(*cf, xn);  // the nominal q(k+1)
            frac_real y0 = 0;
            frac_gl_free_response(&gl_q, &y0);
            const double Dfr = cfc * (double(frac_gl_feedthrough(&gl_q)) * (q0f + fshift * (qp - q0f)) + double(y0));
            for (int i = 0; i < nx; ++i) xn[size_t(i)] += cf->torque(i) * Dfr;
        }
        if (cb) {
            // Sub-steps: z+ = Phi_m z + Gamma_m g + torque_m D, g the sample's forcing.
            for (Eigen::Index i = 0; i < ns; ++i) {
                const size_t si = size_t(cb->states[size_t(i)]);
                zs(i) = x[si];
                zp(i) = xn[si];
            }
            zp.noalias() -= cb->Phi * zs;
            gs.noalias() = cb->Gamma_inv * zp;
            drive.noalias() = cb->Gamma_m * gs;
            play_substeps(zs, drive, cb->Phi_m, cb->torque_m, cb->twist_s, ck, cbl, cb->substeps);
            for (Eigen::Index i = 0; i < ns; ++i) xn[size_t(cb->states[size_t(i)])] = zs(i);
        }
        if (gear) {
            // The gear's relative motion over the sample, driven by the
            // nominal's force per inertia at mid-sample (gear.cpp).
            double acc = 0;
            for (int i = 0; i < nx; ++i)
                if (i != G.j) acc += m.Ac(G.j, i) * 0.5 * (x[size_t(i)] + xn[size_t(i)]);
            for (int l = 0; l < nu; ++l) acc += m.Bc(G.j, l) * up[size_t(l)];
            g_drive.noalias() = g_Gam.col(1) * (acc / (1 - T.gear_r));
            play_substeps(g_z, g_drive, g_Phi, g_torque, g_twist, g_k, T.gear_w, g_n);
        }
        if (cf) {
            frac_real dummy = 0;
            frac_gl_step(&gl_q, frac_real(q0f + fshift * (twist_of(*cf, xn) - q0f)), &dummy);
        }
        x.swap(xn);
        if (series) {
            const double e0 = As(0, 0) * xs_m[0] + As(0, 1) * xs_m[1] + Bs(0) * series_in;
            const double e1 = As(1, 0) * xs_m[0] + As(1, 1) * xs_m[1] + Bs(1) * series_in;
            xs_m[0] = e0;
            xs_m[1] = e1;
        }
        first_sample = false;
        if (mode) {
            const double e0 = Am(0, 0) * eta[0] + Am(0, 1) * eta[1] + Bm(0) * up[size_t(fi)];
            const double e1 = Am(1, 0) * eta[0] + Am(1, 1) * eta[1] + Bm(1) * up[size_t(fi)];
            eta[0] = e0;
            eta[1] = e1;
        }
    }
    return tr;
}

}  // namespace gap
}  // namespace fracdesign
