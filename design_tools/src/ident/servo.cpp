// servo.cpp - IDIM-LS for servo axes and the servo error measure (see servo.hpp).
#include "fracdesign/ident/servo.hpp"

#include <stdexcept>

#include "fracdesign/ident/filters.hpp"

namespace fracdesign {
namespace ident {

const char* const kServoParamNames[kServoParams] = {"M", "Fv", "Fc", "offset", "Fs", "vs"};

double relative_error_percent(const std::vector<double>& y, const std::vector<double>& yhat, std::size_t skip)
{
    if (y.size() != yhat.size()) throw std::invalid_argument("relative_error_percent: length mismatch");
    if (skip >= y.size()) throw std::invalid_argument("relative_error_percent: nothing left after skip");
    double num = 0.0, den = 0.0;
    for (std::size_t k = skip; k < y.size(); ++k) {
        num += (y[k] - yhat[k]) * (y[k] - yhat[k]);
        den += y[k] * y[k];
    }
    if (!(den > 0.0)) throw std::invalid_argument("relative_error_percent: reference signal is zero");
    return 100.0 * std::sqrt(num / den);
}

IdimResult idim_ls_servo(const std::vector<double>& q, const std::vector<double>& F, double dt,
                         const IdimOptions& opt)
{
    const std::size_t n = q.size();
    if (F.size() != n)
        throw std::invalid_argument("IDIM-LS: position has " + std::to_string(n) + " samples, force has " +
                                    std::to_string(F.size()));
    if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("IDIM-LS: sample time must be > 0");
    if (opt.decimation < 1) throw std::invalid_argument("IDIM-LS: decimation must be >= 1");
    for (std::size_t k = 0; k < n; ++k)
        if (!std::isfinite(q[k]) || !std::isfinite(F[k]))
            throw std::invalid_argument("IDIM-LS: non-finite sample at index " + std::to_string(k));
    // Enough rows that the 4-parameter fit is over-determined ten times after
    // decimation, besides the borders.
    const std::size_t need = 2 * opt.border + 40 * std::size_t(opt.decimation);
    if (n < need)
        throw std::invalid_argument("IDIM-LS: record too short: " + std::to_string(n) + " samples, need at least " +
                                    std::to_string(need) + " (border " + std::to_string(opt.border) +
                                    ", decimation " + std::to_string(opt.decimation) + ")");
    const double fs = 1.0 / dt;
    if (!(opt.filter_fc_hz < 0.5 * fs))
        throw std::invalid_argument("IDIM-LS: filter cut-off " + std::to_string(opt.filter_fc_hz) +
                                    " Hz is not below the Nyquist frequency " + std::to_string(0.5 * fs) +
                                    " Hz (sample time in s?)");
    const auto qf = filtfilt(butter_lowpass(opt.filter_order, opt.filter_fc_hz, fs), q);
    const auto dq = central_difference(qf, dt);
    const auto ddq = central_difference(dq, dt);
    std::vector<std::vector<double>> cols = {ddq, dq, std::vector<double>(n), F};
    for (std::size_t k = 0; k < n; ++k) cols[2][k] = dq[k] > 0.0 ? 1.0 : (dq[k] < 0.0 ? -1.0 : 0.0);
    if (opt.decimation > 1) {
        const auto dec = butter_lowpass(opt.decimation_order, 0.8 * 0.5 * fs / opt.decimation, fs);
        for (auto& c : cols) c = filtfilt(dec, c);
    }
    std::vector<std::size_t> rows;
    for (std::size_t k = opt.border; k + opt.border < n; k += std::size_t(opt.decimation)) rows.push_back(k);
    const Eigen::Index r = Eigen::Index(rows.size());
    Eigen::MatrixXd W(r, 4);
    Eigen::VectorXd Y(r);
    for (Eigen::Index i = 0; i < r; ++i) {
        const std::size_t k = rows[std::size_t(i)];
        W(i, 0) = cols[0][k];
        W(i, 1) = cols[1][k];
        W(i, 2) = cols[2][k];
        W(i, 3) = 1.0;
        Y(i) = cols[3][k];
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(W, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const auto& sv = svd.singularValues();
    if (!(sv(3) > 1e-12 * sv(0)))
        throw std::invalid_argument("IDIM-LS: observation matrix is rank deficient (no motion, or motion in one "
                                    "direction only?)");
    IdimResult res;
    res.theta = svd.solve(Y);
    res.rows = rows.size();
    res.cond = sv(0) / sv(3);
    const Eigen::VectorXd resid = Y - W * res.theta;
    res.rel_error = 100.0 * resid.norm() / Y.norm();
    const double sigma2 = resid.squaredNorm() / double(r - 4);
    // (W'W)^-1 = V S^-2 V'
    const Eigen::Matrix4d V = svd.matrixV();
    const Eigen::Vector4d s2inv = sv.cwiseInverse().cwiseAbs2();
    const Eigen::Matrix4d cov = sigma2 * V * s2inv.asDiagonal() * V.transpose();
    res.std_dev = cov.diagonal().cwiseSqrt();
    return res;
}

}  // namespace ident
}  // namespace fracdesign
