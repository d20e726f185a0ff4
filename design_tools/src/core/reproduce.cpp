// reproduce.cpp - the check registry behind `fracdesign reproduce`.
#include "fracdesign/reproduce.hpp"

#include <cmath>

namespace fracdesign {

bool CheckOutcome::pass() const
{
    if (expected.empty() || expected.size() != got.size()) return false;
    for (size_t i = 0; i < expected.size(); ++i) {
        if (!std::isfinite(got[i]) || !std::isfinite(expected[i])) return false;
        const double lim = relative ? tol * std::fabs(expected[i]) : tol;
        if (!(std::fabs(got[i] - expected[i]) <= lim)) return false;
    }
    return true;
}

std::vector<Check>& check_registry()
{
    static std::vector<Check> reg;
    return reg;
}

CheckRegistrar::CheckRegistrar(Check c) { check_registry().push_back(std::move(c)); }

}  // namespace fracdesign
