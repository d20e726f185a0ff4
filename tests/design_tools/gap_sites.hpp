// gap_sites.hpp - shared pieces of the test_gap_sites_*.cpp tests (issue 17
// item 3: effects where real machines have them): the record's sensor noise
// and the verdict checks every site test makes.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "fracdesign/gap/diagnosis.hpp"

namespace gap_sites {

// White noise of `rel` x each column's std on the named columns.
inline void add_noise(fracdesign::gap::Signals& s, const std::vector<std::string>& cols, double rel, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, 1.0);
    for (const std::string& c : cols) {
        for (size_t j = 0; j < s.names.size(); ++j) {
            if (s.names[j] != c) continue;
            const Eigen::VectorXd y = s.values.col(Eigen::Index(j));
            const double sd = std::sqrt((y.array() - y.mean()).square().mean());
            for (Eigen::Index k = 0; k < y.size(); ++k) s.values(k, Eigen::Index(j)) += rel * sd * n(rng);
        }
    }
}

// The verdict's first effect as result.json names it ("none" without one).
inline std::string first_effect(const fracdesign::gap::GapResult& r)
{
    return r.verdict.effects.empty() ? "none" : fracdesign::gap::effect_name(r.verdict.effects[0].kind);
}

// One line per candidate (effect, site, shrink, parameters): the failure message.
inline std::string candidates_text(const nlohmann::json& j)
{
    std::string t = "gap before " + j["gap_before_total"].dump() + "\n";
    for (const nlohmann::json& c : j["candidates"])
        t += "  " + c["effect"].get<std::string>() + " " + c["site"].get<std::string>() + " " + c["coupling"].get<std::string>() +
             " shrink " + c["shrink"].dump() + " " + c["params"].dump() + "\n";
    return t;
}

// The verdict names `effect` first at `site` (and in coupling `coupling`
// when that is not empty), removes >= 80 % of the held-out gap, and
// recovers each `truth` parameter (name -> value) within `tol` (relative).
inline void expect_verdict(const fracdesign::gap::GapResult& r, const std::string& effect, const std::string& site,
                           const std::string& coupling, const std::vector<std::pair<std::string, double>>& truth,
                           double tol = 0.1)
{
    const nlohmann::json j = fracdesign::gap::result_json(r);
    ASSERT_EQ(first_effect(r), effect) << candidates_text(j);
    EXPECT_EQ(j["verdict"]["sites"][0], site);
    if (!coupling.empty()) EXPECT_EQ(j["verdict"]["couplings"][0], coupling);
    EXPECT_GE(r.verdict.shrink, 0.8);
    const std::string prefix = r.verdict.effects.size() > 1 ? effect + "." : "";
    for (const auto& t : truth) {
        ASSERT_TRUE(j["verdict"]["params"].contains(prefix + t.first)) << t.first;
        const double got = j["verdict"]["params"][prefix + t.first].get<double>();
        EXPECT_NEAR(got, t.second, tol * std::fabs(t.second)) << t.first << "\n" << candidates_text(j);
    }
}

}  // namespace gap_sites
