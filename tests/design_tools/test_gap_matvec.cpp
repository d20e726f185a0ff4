// test_gap_matvec.cpp - matvec.hpp's invariant: y (+)= M x is bit-identical
// to Eigen's product on every path (a row of one or two columns, the
// 2..8-row loop, the 9..64-row blocks in AVX2 (every tail of 1 to 4 rows) and
// without it, and Eigen's own for longer single rows and larger blocks), for
// y = M x and y += M x. A reordered sum (the first version added column by
// column) fails here; it changed two servo-bench verdicts (docs/gap.md
// "Threads and progress").
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fracdesign/gap/matvec.hpp"

namespace {

using fracdesign::gap::matvec;

// The same bits (a NaN-free input: == would also pass -0 against +0).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(GapMatvec, is_bit_identical_to_eigens_product_on_every_path)
{
    std::mt19937_64 rng(20261207);
    // Magnitudes over ten decades so that the order of the additions shows.
    std::uniform_real_distribution<double> mant(-1.0, 1.0), expo(-5.0, 5.0);
    auto draw = [&]() { return mant(rng) * std::pow(10.0, expo(rng)); };
    const std::vector<int> rows = {1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 31, 32, 33, 40, 48, 50, 64, 65, 100};
    const std::vector<int> cols = {0, 1, 2, 3, 7, 8, 9, 48, 127, 128, 200};
    int checked = 0, portable = 0;
    for (int r : rows)
        for (int c : cols) {
            Eigen::MatrixXd M(r, c);
            for (Eigen::Index i = 0; i < M.size(); ++i) M.data()[i] = draw();
            Eigen::VectorXd x(c), y0(r);
            for (int j = 0; j < c; ++j) x(j) = draw();
            for (int i = 0; i < r; ++i) y0(i) = draw();
            Eigen::VectorXd ref_set(r), ref_add = y0;
            ref_set.noalias() = M * x;
            ref_add.noalias() += M * x;
            std::vector<double> got_set(size_t(r), 123.0), got_add(y0.data(), y0.data() + r);
            matvec(M, x.data(), got_set.data(), false);
            matvec(M, x.data(), got_add.data(), true);
            // The mid-size path without AVX2 (what a CPU without it runs).
            if (r > 8 && r <= 64 && c < 128) {
                std::vector<double> p_set(size_t(r), 123.0), p_add(y0.data(), y0.data() + r);
                fracdesign::gap::matvec_mid_portable(M.data(), r, c, x.data(), p_set.data(), false);
                fracdesign::gap::matvec_mid_portable(M.data(), r, c, x.data(), p_add.data(), true);
                for (int i = 0; i < r; ++i) {
                    ASSERT_TRUE(same_bits(p_set[size_t(i)], ref_set(i))) << r << "x" << c << " portable y = M x, row " << i;
                    ASSERT_TRUE(same_bits(p_add[size_t(i)], ref_add(i))) << r << "x" << c << " portable y += M x, row " << i;
                }
                ++portable;
            }
            for (int i = 0; i < r; ++i) {
                ASSERT_TRUE(same_bits(got_set[size_t(i)], ref_set(i)))
                    << r << "x" << c << " y = M x, row " << i << ": " << got_set[size_t(i)] << " vs " << ref_set(i);
                ASSERT_TRUE(same_bits(got_add[size_t(i)], ref_add(i)))
                    << r << "x" << c << " y += M x, row " << i << ": " << got_add[size_t(i)] << " vs " << ref_add(i);
            }
            ++checked;
        }
    EXPECT_EQ(checked, int(rows.size() * cols.size()));
    EXPECT_EQ(portable, 11 * 9);  // rows 9..64: 11 sizes; columns < 128: 9 sizes
}

// A reordered sum is not the same: the check above can fail (column by
// column into y, as the first version did, differs from Eigen on some row).
TEST(GapMatvec, a_column_by_column_sum_is_told_apart)
{
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> mant(-1.0, 1.0), expo(-5.0, 5.0);
    bool differs = false;
    for (int trial = 0; trial < 200 && !differs; ++trial) {
        Eigen::MatrixXd M(3, 4);
        for (Eigen::Index i = 0; i < M.size(); ++i) M.data()[i] = mant(rng) * std::pow(10.0, expo(rng));
        Eigen::VectorXd x = Eigen::VectorXd::Random(4), y = Eigen::VectorXd::Random(3), ref = y;
        ref.noalias() += M * x;
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 3; ++i) y(i) += M(i, j) * x(j);
        for (int i = 0; i < 3; ++i) differs = differs || !same_bits(y(i), ref(i));
    }
    EXPECT_TRUE(differs);
}

}  // namespace
