// statespace.cpp - controller kind "statespace": a linear state space with
// inputs [references; measured] and outputs the plant inputs,
//   xc(k+1) = Ac xc(k) + Bc w(k),   u(k) = Cc xc(k) + Dc w(k),
// continuous (discretised with zero-order hold at the record's Ts) or
// discrete at Ts (docs/gap.md "Closed loop"). It starts in the steady state
// (I - Ac) xc = Bc w(0) of the first sample when I - Ac is invertible, else
// at rest. Limits: the loop's (gap.closed_loop.saturation) and the common
// "limits" stage (pipeline.cpp).
#include <stdexcept>

#include "fracdesign/gap/matvec.hpp"
#include "fracdesign/gap/nominal.hpp"
#include "kinds.hpp"

namespace fracdesign {
namespace gap {

namespace {

class LinearLaw final : public Controller {
public:
    LinearLaw(Eigen::MatrixXd A, Eigen::MatrixXd B, Eigen::MatrixXd C, Eigen::MatrixXd D, int nr)
        : A_(std::move(A)), B_(std::move(B)), C_(std::move(C)), D_(std::move(D)), nr_(nr),
          x_(Eigen::VectorXd::Zero(A_.rows())), xn_(A_.rows()), w_(B_.cols()), u_(C_.rows())
    {
    }
    std::unique_ptr<Controller> clone() const override { return std::make_unique<LinearLaw>(*this); }
    std::string kind() const override { return "statespace"; }
    void start(const double* r0, const double* y0) override
    {
        load(r0, y0);
        const Eigen::Index nc = A_.rows();
        x_.setZero();
        if (nc == 0) return;
        Eigen::FullPivLU<Eigen::MatrixXd> lu(Eigen::MatrixXd::Identity(nc, nc) - A_);
        if (lu.isInvertible()) x_ = lu.solve(B_ * w_);
    }
    void step(const double* r, const double* y, double* u) override
    {
        load(r, y);
        matvec(C_, x_.data(), u_.data(), false);
        matvec(D_, w_.data(), u_.data(), true);
        matvec(A_, x_.data(), xn_.data(), false);
        matvec(B_, w_.data(), xn_.data(), true);
        x_.swap(xn_);
        for (Eigen::Index i = 0; i < u_.size(); ++i) u[i] = u_(i);
    }
    bool small_signal(Eigen::MatrixXd& A, Eigen::MatrixXd& B, Eigen::MatrixXd& C, Eigen::MatrixXd& D) const override
    {
        A = A_;
        B = B_;
        C = C_;
        D = D_;
        return true;
    }

private:
    void load(const double* r, const double* y)
    {
        for (int j = 0; j < nr_; ++j) w_(j) = r[j];
        for (Eigen::Index j = nr_; j < w_.size(); ++j) w_(j) = y[j - nr_];
    }
    Eigen::MatrixXd A_, B_, C_, D_;
    int nr_;
    Eigen::VectorXd x_, xn_, w_, u_;  // xn_: the step's next state (no allocation per sample)
};

}  // namespace

std::unique_ptr<Controller> make_statespace_controller(const nlohmann::json& doc, const ControllerContext& ctx)
{
    check_fields(doc, ctx.where, "statespace", {"time", "Ts", "A", "B", "C", "D"});
    Eigen::MatrixXd A, B, C, D;
    read_statespace(doc, Eigen::Index(ctx.references.size() + ctx.measured.size()), Eigen::Index(ctx.outputs), ctx.Ts,
                    ctx.where, A, B, C, D);
    return std::make_unique<LinearLaw>(A, B, C, D, int(ctx.references.size()));
}

}  // namespace gap
}  // namespace fracdesign
