// test_gap_fit_windows.cpp - the windows of the fit's continuation in record
// length (fit.cpp fit_continued, docs/gap.md "Continuation in record
// length"): the first ends where the nominal's misfit begins, each next is
// kWindowGrowth times as long, all shorter than the record.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../../design_tools/src/gap/stages.hpp"

using namespace fracdesign::gap;

TEST(GapFitWindows, the_first_window_ends_where_the_misfit_begins_and_each_next_grows)
{
    // No misfit for 3000 rows, then a residual growing like a limit cycle's onset.
    const Eigen::Index N = 10000, onset = 3000;
    std::vector<double> e(size_t(N), 0.0);
    for (Eigen::Index k = onset; k < N; ++k) e[size_t(k)] = std::pow(1.002, double(k - onset));
    double total = 0;
    for (double v : e) total += v;
    Eigen::Index previous_first = 0;
    for (const double share : kFirstWindowShares) {
        const std::vector<Eigen::Index> w = growing_windows(e, N / kMinWindowDiv, share);
        ASSERT_FALSE(w.empty());
        // The first window holds `share` of the energy, no more.
        double cum = 0;
        for (Eigen::Index k = 0; k < w[0]; ++k) cum += e[size_t(k)];
        EXPECT_GE(cum, share * total);
        EXPECT_LT(cum - e[size_t(w[0] - 1)], share * total);
        EXPECT_GT(w[0], onset);
        EXPECT_GT(w[0], previous_first);  // the later path starts later
        previous_first = w[0];
        for (size_t i = 1; i < w.size(); ++i) EXPECT_EQ(w[i], Eigen::Index(std::ceil(double(w[i - 1]) * kWindowGrowth)));
        EXPECT_LT(w.back(), N);
        EXPECT_GE(double(w.back()) * kWindowGrowth, double(N));
    }
}

TEST(GapFitWindows, a_misfit_at_the_start_gives_the_shortest_window_and_none_without_misfit)
{
    const Eigen::Index N = 6400;
    std::vector<double> flat(size_t(N), 1.0);
    const std::vector<Eigen::Index> w = growing_windows(flat, N / kMinWindowDiv, kFirstWindowShares[0]);
    ASSERT_FALSE(w.empty());
    EXPECT_EQ(w[0], N / kMinWindowDiv);  // 1/1024 of a flat energy lies inside the minimum window
    EXPECT_EQ(growing_windows(flat, N / kMinWindowDiv, kFirstWindowShares[1])[0], N / 16);  // 1/16 of it ends at N/16
    EXPECT_TRUE(growing_windows(std::vector<double>(size_t(N), 0.0), N / kMinWindowDiv, kFirstWindowShares[0]).empty());
    EXPECT_TRUE(growing_windows(std::vector<double>(100, 1.0), 60, kFirstWindowShares[0]).empty());  // N < 2 min_rows
}
