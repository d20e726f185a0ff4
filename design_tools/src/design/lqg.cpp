// lqg.cpp - seed 004 state-difference LQG with delays (Ch. 6-7).
#include "fracdesign/design/lqg.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

namespace fracdesign::design {
namespace {

using Eigen::MatrixXd;
using cplx = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

nlohmann::json mat(const MatrixXd& M)
{
    nlohmann::json j = nlohmann::json::array();
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
        std::vector<double> row(M.cols());
        for (Eigen::Index k = 0; k < M.cols(); ++k) row[k] = M(i, k);
        j.push_back(row);
    }
    return j;
}

}  // namespace

StateSpace arm_measured_model(const PhSystem& arm)
{
    const StateSpace s = arm.state_space();
    if (s.nx() < 1 || s.nu() < 1 || s.ny() < 3) throw std::invalid_argument("arm model needs >= 1 input and 3 outputs");
    StateSpace m;
    m.A = s.A;
    m.B = s.B.col(0);  // tau_M (3.103)
    m.C = MatrixXd::Zero(3, s.nx());
    m.C(0, 0) = 1.0;        // theta_M, the first drive state (3.35)
    m.C.row(1) = s.C.row(0);  // theta_M'
    m.C.row(2) = s.C.row(2);  // psi'(L) (IMU)
    m.D = MatrixXd::Zero(3, 1);
    m.inputs = {"tau_M [N m]"};
    m.outputs = {"theta_M [rad]", "theta_M_dot [rad/s]", "psi_dot(L) [rad/s]"};
    m.states = s.states;
    return m;
}

MatrixXd modal_basis(const MatrixXd& A)
{
    const Eigen::Index n = A.rows();
    Eigen::EigenSolver<MatrixXd> es(A);
    const Eigen::VectorXcd lam = es.eigenvalues();
    const Eigen::MatrixXcd vec = es.eigenvectors();
    std::vector<Eigen::Index> idx;
    for (Eigen::Index i = 0; i < n; ++i)
        if (lam(i).imag() >= 0.0) idx.push_back(i);  // one representative per conjugate pair
    std::stable_sort(idx.begin(), idx.end(), [&](Eigen::Index a, Eigen::Index b) { return std::abs(lam(a)) < std::abs(lam(b)); });
    MatrixXd V(n, n);
    Eigen::Index c = 0;
    for (Eigen::Index i : idx) {
        const Eigen::VectorXcd v = vec.col(i).normalized();
        if (lam(i).imag() > 0.0) {
            V.col(c++) = v.real();
            V.col(c++) = v.imag();
        } else {
            V.col(c++) = v.real().normalized();
        }
    }
    if (c != n) throw std::runtime_error("modal_basis: unpaired complex eigenvalue");
    // The rigid-body mode with damping (r_t > 0): two real eigenvalues 0 and -r (angle and the
    // damped velocity), whose eigenvectors are nearly parallel (both are mostly "all angles
    // equal"). Weighting those two coordinates directly puts a huge weight on their difference,
    // i.e. on the velocity, and almost none on the angle: the LQR then leaves the angle error a
    // closed-loop pole near -0.03 rad/s (time constant 30 s). Use an orthonormal basis of their
    // invariant subspace instead (Gram-Schmidt: angle, then velocity), which is what the Jordan
    // chain below gives in the undamped limit, so the weights are continuous in r_t -> 0.
    if (n >= 2 && std::fabs(lam(idx[0]).imag()) == 0.0 && std::fabs(lam(idx[1]).imag()) == 0.0) {
        V.col(1) -= V.col(0) * V.col(0).dot(V.col(1));
        V.col(1).normalize();
    }
    Eigen::JacobiSVD<MatrixXd> sv(V);
    if (sv.singularValues()(n - 1) > 1e-10 * sv.singularValues()(0)) return V;
    // Dependent eigenvectors: the rigid-body double zero eigenvalue forms a Jordan block.
    Eigen::JacobiSVD<MatrixXd> sa(A, Eigen::ComputeFullV);
    const Eigen::VectorXd v1 = sa.matrixV().col(n - 1);
    Eigen::VectorXd v2 = A.colPivHouseholderQr().solve(v1);
    v2 -= v1 * v1.dot(v2);
    V.col(0) = v1.normalized();
    V.col(1) = v2.normalized();
    return V;
}

LqgParams LqgParams::exp_c()
{
    LqgParams p;
    p.di = 0;
    p.dout = 0;
    p.q_low = 3e3;  // Table 8.7
    p.q_high = 5e-3;
    p.qo_drive = 0.0;
    p.qo_beam = 1e-4;
    p.qo_dist = 5e2;
    return p;
}

LqgParams LqgParams::exp_d() { return LqgParams(); }

void delay_augment(const MatrixXd& Ad, const MatrixXd& Bd, const MatrixXd& Cd, int di, int dout, MatrixXd& A,
                   MatrixXd& B, MatrixXd& E, MatrixXd& C)
{
    const Eigen::Index n = Ad.rows(), N = n + di + dout;
    A = MatrixXd::Zero(N, N);
    B = MatrixXd::Zero(N, 1);
    E = MatrixXd::Zero(N, 1);
    C = MatrixXd::Zero(3, N);
    A.topLeftCorner(n, n) = Ad;
    if (di > 0) {
        A.block(0, n, n, 1) = Bd;  // B' C_xi: the plant sees xi_1 = u[k] (7.12)
        for (int j = 0; j + 1 < di; ++j) A(n + j, n + j + 1) = 1.0;  // A_xi: upper shift (7.11)
        B(n + di - 1, 0) = 1.0;   // B_xi
        E(n + di - 1, 0) = -1.0;  // E_xi: fictitious friction at the chain input (7.10)
    } else {
        B.topRows(n) = Bd;
        E.topRows(n) = -Bd;  // friction at the torque input, e_z = -tau_f
    }
    C.block(0, 0, 2, n) = Cd.topRows(2);  // encoder channels, not delayed
    if (dout > 0) {
        const Eigen::Index b0 = n + di;
        A.block(b0 + dout - 1, 0, 1, n) = Cd.row(2);  // beta_do[k+1] = y_3[k] (7.14)
        for (int j = 0; j + 1 < dout; ++j) A(b0 + j, b0 + j + 1) = 1.0;  // A_beta
        C(2, b0) = 1.0;  // y3_bar = beta_1 (7.15)
    } else {
        C.block(2, 0, 1, n) = Cd.row(2);
    }
}

LqgDesign design_lqg(const StateSpace& plant, const LqgParams& p)
{
    if (!(std::isfinite(p.T) && p.T > 0.0)) throw std::invalid_argument("sample time T must be > 0");
    if (p.di < 0 || p.dout < 0) throw std::invalid_argument("delays d_i, d_o must be >= 0 samples");
    if (plant.nu() != 1 || plant.ny() != 3) throw std::invalid_argument("plant must have 1 input and 3 outputs");
    const Eigen::Index n = plant.nx();
    if (p.n_low < 0 || p.n_low > n) throw std::invalid_argument("n_low must lie in [0, n]");
    for (double s : p.s_o)
        if (!(std::isfinite(s) && s > 0.0)) throw std::invalid_argument("S_o must be positive on every channel");
    LqgDesign d;
    d.params = p;
    d.plant = plant;
    const StateSpace disc = c2d_zoh(plant, p.T);
    delay_augment(disc.A, disc.B, disc.C, p.di, p.dout, d.Ad, d.Bd, d.Ed, d.Cd);
    const Eigen::Index N = d.Ad.rows();

    // Modal weights (8.2)-(8.5): Q_c = V^-T Q_tilde V^-1.
    const MatrixXd V = modal_basis(plant.A);
    Eigen::VectorXd qt = Eigen::VectorXd::Constant(n, p.q_high);
    qt.head(p.n_low).setConstant(p.q_low);
    const MatrixXd Vi = V.inverse();
    d.Qc = Vi.transpose() * qt.asDiagonal() * Vi;
    d.Qc = 0.5 * (d.Qc + d.Qc.transpose());
    d.Qbar = MatrixXd::Zero(N, N);
    d.Qbar.topLeftCorner(n, n) = d.Qc;
    d.Qbar.bottomRightCorner(N - n, N - n) = p.q_delay * MatrixXd::Identity(N - n, N - n);
    d.ctrl = solve_dare(d.Ad, d.Bd, d.Qbar, MatrixXd::Constant(1, 1, p.s_c));  // (7.23)
    d.K = d.ctrl.K;                                                             // (7.24)

    // Observer model with the integrating disturbance state (7.25)-(7.26), a_s = 1.
    d.Ae = MatrixXd::Zero(N + 1, N + 1);
    d.Ae.topLeftCorner(N, N) = d.Ad;
    d.Ae.block(0, N, N, 1) = d.Ed;
    d.Ae(N, N) = 1.0;
    d.Be = MatrixXd::Zero(N + 1, 1);
    d.Be.topRows(N) = d.Bd;
    d.Ce = MatrixXd::Zero(3, N + 1);
    d.Ce.leftCols(N) = d.Cd;
    Eigen::VectorXd qo(N + 1);
    for (Eigen::Index i = 0; i < N + 1; ++i)
        qo(i) = i == N ? p.qo_dist : i < 4 ? p.qo_drive : i < n ? p.qo_beam : p.qo_delay;
    d.Qo = qo.asDiagonal();
    d.So = Eigen::Vector3d(p.s_o[0], p.s_o[1], p.s_o[2]).asDiagonal();
    d.obs = solve_dare(d.Ae.transpose(), d.Ce.transpose(), d.Qo, d.So);  // dual problem
    const MatrixXd P = d.obs.X;
    d.Le = d.Ae * P * d.Ce.transpose() * (d.So + d.Ce * P * d.Ce.transpose()).inverse();  // predictor gain (7.27)
    return d;
}

LoopCheck check_closed_loop(const LqgDesign& d, const StateSpace& plant, int plant_di, int plant_do)
{
    const LqgParams& p = d.params;
    LoopCheck r;
    r.plant_di = plant_di < 0 ? p.di : plant_di;
    r.plant_do = plant_do < 0 ? p.dout : plant_do;
    const StateSpace disc = c2d_zoh(plant, p.T);
    MatrixXd Ap, Bp, Ep, Cp;
    delay_augment(disc.A, disc.B, disc.C, r.plant_di, r.plant_do, Ap, Bp, Ep, Cp);
    const Eigen::Index np = Ap.rows(), ne = d.Ae.rows();
    // Controller: e_hat[k+1] = (A_e - L_e C_e + B_e F) e_hat + L_e e_y,  e_u = F e_hat, F = [-K, 1].
    MatrixXd F(1, ne);
    F << -d.K, MatrixXd::Ones(1, 1);
    const MatrixXd Ac = d.Ae - d.Le * d.Ce + d.Be * F;
    MatrixXd Acl(np + ne, np + ne);
    Acl << Ap, Bp * F, d.Le * Cp, Ac;
    r.plant_states = static_cast<int>(np);
    Eigen::EigenSolver<MatrixXd> es(Acl, false);
    for (Eigen::Index i = 0; i < Acl.rows(); ++i) {
        const cplx z = es.eigenvalues()(i);
        if (std::abs(z) > r.spectral_radius) {
            r.spectral_radius = std::abs(z);
            r.critical_w = std::fabs(std::arg(z)) / p.T;
        }
    }
    // Frequencies: a log grid, plus each lightly damped plant pole's aliased frequency and its
    // neighbourhood in units of the half-power width, so that a resonance of width 1e-6 rad/s is
    // not stepped over.
    const double wmax = kPi / p.T;
    std::vector<double> ws;
    const int pts = 3000;
    for (int i = 0; i < pts; ++i) ws.push_back(0.1 * std::pow(wmax / 0.1, i / (pts - 1.0)));
    Eigen::EigenSolver<MatrixXd> ep(Ap, false);
    for (Eigen::Index i = 0; i < np; ++i) {
        const cplx z = ep.eigenvalues()(i);
        if (std::abs(z) < 0.9 || z.imag() < 0.0) continue;
        const double w0 = std::arg(z) / p.T, bw = std::max((1.0 - std::abs(z)) / p.T, 1e-9 * wmax);
        for (double m : {-16.0, -8.0, -4.0, -2.0, -1.0, 0.0, 1.0, 2.0, 4.0, 8.0, 16.0}) {
            const double w = w0 + m * bw;
            if (w > 0.1 && w < wmax) ws.push_back(w);
        }
    }
    std::sort(ws.begin(), ws.end());
    // Loop broken at the plant input: L = -C(z) P(z) (the loop is u = C y, y = P u).
    const Eigen::MatrixXcd Apc = Ap.cast<cplx>(), Acc = Ac.cast<cplx>();
    r.gain_margin_db = std::numeric_limits<double>::infinity();
    r.phase_margin_deg = std::numeric_limits<double>::infinity();
    r.modulus_margin = std::numeric_limits<double>::infinity();
    cplx prev(0.0, 0.0);
    for (size_t i = 0; i < ws.size(); ++i) {
        const cplx z = std::polar(1.0, ws[i] * p.T);
        const Eigen::MatrixXcd Pz =
            Cp.cast<cplx>() * (z * Eigen::MatrixXcd::Identity(np, np) - Apc).partialPivLu().solve(Bp.cast<cplx>());
        const Eigen::MatrixXcd Cz =
            F.cast<cplx>() * (z * Eigen::MatrixXcd::Identity(ne, ne) - Acc).partialPivLu().solve(d.Le.cast<cplx>());
        const cplx L = -(Cz * Pz)(0, 0);
        r.modulus_margin = std::min(r.modulus_margin, std::abs(1.0 + L));
        if (i > 0) {
            // phase crossing of -180 deg: Im L changes sign with Re L < 0
            if ((prev.imag() > 0.0) != (L.imag() > 0.0) && L.real() < 0.0)
                r.gain_margin_db = std::min(r.gain_margin_db, std::fabs(20.0 * std::log10(std::abs(L))));
            if ((std::abs(prev) > 1.0) != (std::abs(L) > 1.0))
                r.phase_margin_deg = std::min(r.phase_margin_deg, 180.0 - std::fabs(std::arg(L)) * 180.0 / kPi);
        }
        prev = L;
    }
    return r;
}

nlohmann::json to_json(const LoopCheck& c)
{
    auto fin = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    return {{"plant_states", c.plant_states}, {"plant_di", c.plant_di}, {"plant_do", c.plant_do},
            {"spectral_radius", c.spectral_radius}, {"critical_w", c.critical_w},
            {"stable", c.spectral_radius < 1.0}, {"gain_margin_db", fin(c.gain_margin_db)},
            {"phase_margin_deg", fin(c.phase_margin_deg)}, {"modulus_margin", fin(c.modulus_margin)}};
}

nlohmann::json to_json(const LqgDesign& d)
{
    const LqgParams& p = d.params;
    return {{"schema", "frac.design.lqg"},
            {"version", 1},
            {"source", "seed 004 (Wang) (6.36)-(6.45), (7.3)-(7.27), Tables 8.7/8.8; a_s = 1 in (7.26)"},
            {"T", p.T},
            {"di", p.di},
            {"do", p.dout},
            {"weights",
             {{"n_low", p.n_low}, {"q_low", p.q_low}, {"q_high", p.q_high}, {"q_delay", p.q_delay}, {"S_c", p.s_c},
              {"Qo", {p.qo_drive, p.qo_beam, p.qo_delay, p.qo_dist}}, {"S_o", p.s_o}}},
            {"modal_convention", "real modal form, modes by |lambda| ascending, unit 2-norm eigenvectors, "
                                 "rigid-body pair orthonormalised (Jordan chain when defective); first n_low coordinates "
                                 "weighted q_low"},
            {"K", mat(d.K)},
            {"Le", mat(d.Le)},
            {"Ae", mat(d.Ae)},
            {"Be", mat(d.Be)},
            {"Ce", mat(d.Ce)},
            {"controller_residual", d.ctrl.residual},
            {"observer_residual", d.obs.residual},
            {"controller_spectral_radius", d.ctrl.stability},
            {"observer_spectral_radius", d.obs.stability}};
}

}  // namespace fracdesign::design
