// golden.hpp - golden-section search for the minimum of a unimodal function on a bracket,
// shared by the seed 002 prefilter search (design/collocated.cpp) and the seed 000 resonance
// peaks (models/antenna.cpp).
#pragma once

#include <cmath>

namespace fracdesign {

struct GoldenResult {
    double x;     // the better of the two interior probes at the end
    double fx;    // f(x)
    double a, b;  // the final bracket
};

// Minimum of f on [a, b], f unimodal there: the bracket shrinks by 1/phi per evaluation
// (two evaluations to start) until b - a <= tol or after max_it steps. A tie keeps [x1, b].
template <class F>
GoldenResult golden_section_min(F&& f, double a, double b, double tol, int max_it)
{
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = f(x1), f2 = f(x2);
    for (int it = 0; it < max_it && b - a > tol; ++it) {
        if (f1 < f2) {
            b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
        } else {
            a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
        }
    }
    return f1 < f2 ? GoldenResult{x1, f1, a, b} : GoldenResult{x2, f2, a, b};
}

}  // namespace fracdesign
