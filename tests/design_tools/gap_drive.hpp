// gap_drive.hpp - the synthetic records of the gap tests: a multisine on the
// first column, the other columns zero (filled by each test's replay).
#pragma once

#include <cmath>
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
