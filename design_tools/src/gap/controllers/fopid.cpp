// fopid.cpp - controller kind "fopid": the PLC's FOPID block (plc_blocks/
// FracCtrl/FOPID.c), replayed by the libfrac calls its body makes:
// frac_fopid_init with the block's parameter struct, then one
// frac_fopid_step(W, X) per sample (frac/fopid.h: ISA form with set-point
// weights b, c, derivative filter tf, output limits umin/umax with
// anti-windup none / clamp / back-calculation tt, positive feedback delta,
// fractional operators realised as `op`).
//
// One reference and one measurement: "reference" (a name of
// gap.closed_loop.references, default the first) and "measured" (a name of
// gap.closed_loop.measured, default the first); the law drives the plant
// input "output" (default the first), the other plant inputs get 0. A loop
// with several measurements is a cascade (cascade.cpp) or several laws.
//
// Start rule: at rest (zero operator memories, integrator and filter), as
// the block starts after an accepted parameter set (FOPID.c fopid_load).
// small_signal: the rational law when both operators are integer (the
// integral order l = 1 and the derivative order m in {0, 1} with GL, whose
// integer orders are exact differences) and the limits are not at work.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "document.hpp"
#include "kinds.hpp"
#include "libfrac_copy.hpp"

#include "frac/fopid.h"

namespace fracdesign {
namespace gap {

namespace {

class Fopid final : public Controller {
public:
    Fopid(const frac_fopid_params& p, int ref, int meas, int nr, int ny, int out, int nu, const std::string& where)
        : ref_(ref), meas_(meas), nr_(nr), ny_(ny), out_(out), nu_(nu), storage_(frac_fopid_storage_len(&p) + 1)
    {
        check_status(frac_fopid_init(&c_, &p, storage_.data(), storage_.size()), where, "the FO-PID parameters");
    }
    Fopid(const Fopid& o)
        : Controller(o), ref_(o.ref_), meas_(o.meas_), nr_(o.nr_), ny_(o.ny_), out_(o.out_), nu_(o.nu_), c_(o.c_),
          storage_(o.storage_)
    {
        const size_t bytes = storage_.size() * sizeof(frac_real);
        rebase_fo(c_.opi, o.storage_.data(), bytes, storage_.data());
        rebase_fo(c_.opd, o.storage_.data(), bytes, storage_.data());
    }
    std::unique_ptr<Controller> clone() const override { return std::make_unique<Fopid>(*this); }
    std::string kind() const override { return "fopid"; }
    void start(const double*, const double*) override { frac_fopid_reset(&c_); }
    void step(const double* r, const double* y, double* u) override
    {
        frac_real v = 0;
        frac_fopid_step(&c_, frac_real(r[ref_]), frac_real(y[meas_]), &v);
        for (int i = 0; i < nu_; ++i) u[i] = 0.0;
        u[out_] = double(v);
    }
    double output_limit() const override { return std::max(std::fabs(double(c_.p.umin)), std::fabs(double(c_.p.umax))); }
    bool small_signal(Eigen::MatrixXd& A, Eigen::MatrixXd& B, Eigen::MatrixXd& C, Eigen::MatrixXd& D) const override;

private:
    int ref_, meas_, nr_, ny_, out_, nu_;
    frac_fopid c_;
    std::vector<frac_real> storage_;
};

// frac_fopid_step with integer orders, inputs w = [r; y]: e = r - y,
// q = e (order 1 - l = 0 is the identity), d = (ed(k) - ed(k-1))/Ts for m = 1
// (GL weights 1, -1) or d = ed for m = 0, ed = c r - y;
// f(k) = (1 - af) f(k-1) + af d(k); u = kp (b r - y) + kd f + delta y + x_I + Ts ki e,
// then x_I += Ts ki e. States [x_I, f, ed(k-1)], the unused ones left out.
bool Fopid::small_signal(Eigen::MatrixXd& A, Eigen::MatrixXd& B, Eigen::MatrixXd& C, Eigen::MatrixXd& D) const
{
    const frac_fopid_params& p = c_.p;
    const bool integral = p.ki != 0, derivative = p.kd != 0;
    const bool diff = derivative && p.mu == 1;
    if (integral && p.lambda != 1) return false;
    if (derivative && !(p.mu == 0 || (diff && p.op.method == FRAC_FO_GL && p.op.memory >= 2))) return false;
    const double Ts = double(p.ts), af = double(c_.af), ki = double(p.ki), kd = double(p.kd);
    const Eigen::Index nw = nr_ + ny_;
    Eigen::RowVectorXd E = Eigen::RowVectorXd::Zero(nw), Ed = E, Ep = E, Y = E;
    E(ref_) = 1;
    Ed(ref_) = double(p.c);
    Ep(ref_) = double(p.b);
    Y(nr_ + meas_) = 1;
    E(nr_ + meas_) = Ed(nr_ + meas_) = Ep(nr_ + meas_) = -1;
    const double g = diff ? af / Ts : af;  // f's gain on ed(k)
    Eigen::MatrixXd Af = Eigen::MatrixXd::Zero(3, 3), Bf = Eigen::MatrixXd::Zero(3, nw);
    Eigen::RowVectorXd Cf = Eigen::RowVectorXd::Zero(3);
    Af(0, 0) = 1;
    Bf.row(0) = Ts * ki * E;
    Af(1, 1) = 1 - af;
    Bf.row(1) = g * Ed;
    if (diff) {
        Af(1, 2) = -g;
        Bf.row(2) = Ed;
    }
    Cf << 1, kd * (1 - af), diff ? -kd * g : 0.0;
    const Eigen::RowVectorXd Df = double(p.kp) * Ep + kd * g * Ed + double(p.delta) * Y + Ts * ki * E;
    std::vector<Eigen::Index> keep;
    if (integral) keep.push_back(0);
    if (derivative) keep.push_back(1);
    if (diff) keep.push_back(2);
    const Eigen::Index n = Eigen::Index(keep.size());
    A.resize(n, n);
    B.resize(n, nw);
    C = Eigen::MatrixXd::Zero(nu_, n);
    D = Eigen::MatrixXd::Zero(nu_, nw);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j < n; ++j) A(i, j) = Af(keep[size_t(i)], keep[size_t(j)]);
        B.row(i) = Bf.row(keep[size_t(i)]);
        C(out_, i) = Cf(keep[size_t(i)]);
    }
    D.row(out_) = Df;
    return true;
}

}  // namespace

// The FOPID block's parameter struct (FOPID.c fopid_init) from the document.
std::unique_ptr<Controller> make_fopid_controller(const json& doc, const ControllerContext& ctx)
{
    const std::string& w = ctx.where;
    check_fields(doc, w, "fopid",
                 {"kp", "ki", "kd", "lambda", "mu", "tf", "b", "c", "delta", "umin", "umax", "antiwindup", "tt", "op",
                  "reference", "measured", "output"});
    if (ctx.references.empty() || ctx.measured.empty())
        throw std::runtime_error(w + ": kind 'fopid' needs one reference and one measured output in gap.closed_loop");
    frac_fopid_params p;
    std::memset(&p, 0, sizeof p);
    p.kp = frac_real(number(doc, "kp", w, 0.0));
    p.ki = frac_real(number(doc, "ki", w, 0.0));
    p.kd = frac_real(number(doc, "kd", w, 0.0));
    p.lambda = frac_real(number(doc, "lambda", w, 1.0));
    p.mu = frac_real(number(doc, "mu", w, 1.0));
    if (p.ki != 0 && !(p.lambda > 0 && p.lambda < 2)) refuse(w, "lambda", doc.at("lambda"), "an integral order in (0, 2)");
    if (p.kd != 0 && !(p.mu >= 0 && p.mu <= 2)) refuse(w, "mu", doc.at("mu"), "a derivative order in [0, 2]");
    p.tf = frac_real(number(doc, "tf", w, 0.0));
    if (p.tf < 0) refuse(w, "tf", doc.at("tf"), "a filter time constant >= 0 s");
    p.b = frac_real(number(doc, "b", w, 1.0));
    p.c = frac_real(number(doc, "c", w, 1.0));
    p.delta = frac_real(number(doc, "delta", w, 0.0));
    const double inf = std::numeric_limits<double>::infinity();
    p.umin = frac_real(number(doc, "umin", w, -inf));
    p.umax = frac_real(number(doc, "umax", w, inf));
    if (!(p.umin < p.umax))
        refuse(w, "umin", doc.at("umin"), "umin < umax = " + (doc.contains("umax") ? shown(doc.at("umax")) : "inf"));
    p.antiwindup = choice(doc, "antiwindup", w, 0, {"none", "clamp", "backcalc"});
    p.tt = frac_real(number(doc, "tt", w, 1.0));
    if (p.antiwindup == FRAC_FOPID_AW_BACKCALC && !(p.tt > 0))
        refuse(w, "tt", doc.at("tt"), "a back-calculation time constant > 0 s");
    p.ts = frac_real(ctx.Ts);
    p.op = read_realization(doc, w, ctx.Ts);
    return std::make_unique<Fopid>(p, reference_index(doc, "reference", ctx), measured_index(doc, "measured", ctx),
                                   int(ctx.references.size()), int(ctx.measured.size()), output_index(doc, "output", ctx),
                                   ctx.outputs, w);
}

}  // namespace gap
}  // namespace fracdesign
