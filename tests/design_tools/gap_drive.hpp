// gap_drive.hpp - the synthetic records of the gap tests: a multisine on the
// first column, the other columns zero (filled by each test's replay); random
// levels held for random times (a drive or a reference for a truth of the
// test's own).
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "fracdesign/gap/signals.hpp"

struct Tone {
    double amplitude, hz, phase;
};

inline fracdesign::gap::Signals multisine_record(const std::vector<std::string>& names, double Ts, Eigen::Index n,
                                                 const std::vector<Tone>& tones)
{
    fracdesign::gap::Signals s;
    s.source = "synthetic";
    s.names = names;
    s.Ts = Ts;
    s.values = Eigen::MatrixXd::Zero(n, Eigen::Index(names.size()));
    for (Eigen::Index k = 0; k < n; ++k) {
        const double t = double(k) * Ts;
        for (const Tone& w : tones) s.values(k, 0) += w.amplitude * std::sin(2 * M_PI * w.hz * t + w.phase);
    }
    return s;
}

// n samples of levels uniform in [lo, hi], each held a uniform number of
// samples in [hold_lo, hold_hi]; zero for the first `first` samples (seed fixed).
inline std::vector<double> held_levels(long n, unsigned seed, double lo, double hi, int hold_lo, int hold_hi, int first)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> level(lo, hi);
    std::uniform_int_distribution<int> hold(hold_lo, hold_hi);
    std::vector<double> v(size_t(n), 0.0);
    double u = 0;
    int left = first;
    for (long k = 0; k < n; ++k) {
        if (--left <= 0) {
            u = level(rng);
            left = hold(rng);
        }
        v[size_t(k)] = u;
    }
    return v;
}

// A record of a discrete linear system z(k+1) = Ad z(k) + Bd u(k) from rest
// under the drive u: columns u, then the states `read` (one per name after
// the first).
inline fracdesign::gap::Signals state_record(const Eigen::MatrixXd& Ad, const Eigen::MatrixXd& Bd,
                                             const std::vector<double>& drive, const std::vector<Eigen::Index>& read,
                                             const std::vector<std::string>& names, double Ts, const std::string& source)
{
    fracdesign::gap::Signals s;
    s.source = source;
    s.names = names;
    s.Ts = Ts;
    const Eigen::Index n = Eigen::Index(drive.size());
    s.values.resize(n, Eigen::Index(1 + read.size()));
    Eigen::VectorXd z = Eigen::VectorXd::Zero(Ad.rows());
    for (Eigen::Index k = 0; k < n; ++k) {
        const double u = drive[size_t(k)];
        s.values(k, 0) = u;
        for (size_t j = 0; j < read.size(); ++j) s.values(k, Eigen::Index(j + 1)) = z(read[j]);
        z = Ad * z + Bd.col(0) * u;
    }
    return s;
}

