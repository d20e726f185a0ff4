// matvec.cpp - the mid-size block of matvec.hpp: 9 to 64 rows, fewer than
// 128 columns (Eigen 3.4's gemv sums those in one column block). Rows in
// blocks of up to 32 whose sums stay in registers over all columns, each
// row's sum over the columns in order from zero: the same additions as
// Eigen's kernel (per row, the packet width does not change the order), so
// the result is bit-identical whichever path runs. The AVX2 clone is chosen at run time
// (__builtin_cpu_supports); neither clone contracts to FMA (no -mfma, and
// the target attribute names AVX2 only).
#include "fracdesign/gap/matvec.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace fracdesign {
namespace gap {

namespace {

template <int B>
inline void rows_block(const double* M, long r, long c, const double* x, double* y, bool add)
{
    using V = Eigen::Matrix<double, B, 1>;
    V s = V::Zero();
    for (long j = 0; j < c; ++j) s.noalias() += Eigen::Map<const V>(M + j * r) * x[j];
    Eigen::Map<V> out(y);
    if (add)
        out += s;
    else
        out = s;
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// K groups of 4 rows in K 256-bit registers, the last group masked to its
// `tail` rows (1 to 4; rows past the matrix are neither read nor written);
// mul then add (no FMA), each row's sum in column order as
// matvec_mid_portable's. With K = 8 the adds of one column are 8
// independent chains, enough to keep both add ports busy; 4 would wait on
// the add's latency (the 16-row blocks took a third of an arm diagnosis).
template <int K>
__attribute__((target("avx2"))) inline void groups_avx2(const double* M, long r, long c, const double* x, double* y, bool add,
                                                        int tail)
{
    const __m256i mask = _mm256_set_epi64x(tail > 3 ? -1 : 0, tail > 2 ? -1 : 0, tail > 1 ? -1 : 0, -1);
    // Unrolled, so that s stays in registers (GCC 12 kept the loop over g and
    // s in memory: slower than the 16-row blocks).
    __m256d s[K];
#pragma GCC unroll 8
    for (int g = 0; g < K; ++g) s[g] = _mm256_setzero_pd();
    for (long j = 0; j < c; ++j) {
        const double* col = M + j * r;
        const __m256d xj = _mm256_set1_pd(x[j]);
#pragma GCC unroll 8
        for (int g = 0; g < K - 1; ++g) s[g] = _mm256_add_pd(s[g], _mm256_mul_pd(_mm256_loadu_pd(col + 4 * g), xj));
        s[K - 1] = _mm256_add_pd(s[K - 1], _mm256_mul_pd(_mm256_maskload_pd(col + 4 * (K - 1), mask), xj));
    }
#pragma GCC unroll 8
    for (int g = 0; g < K - 1; ++g)
        _mm256_storeu_pd(y + 4 * g, add ? _mm256_add_pd(_mm256_loadu_pd(y + 4 * g), s[g]) : s[g]);
    double* yl = y + 4 * (K - 1);
    _mm256_maskstore_pd(yl, mask, add ? _mm256_add_pd(_mm256_maskload_pd(yl, mask), s[K - 1]) : s[K - 1]);
}

// Rows in blocks of 32 (8 groups), the rest in one block of up to 8 groups
// whose last group holds the 1 to 4 rows left.
__attribute__((target("avx2"))) void mid_avx2(const double* M, long r, long c, const double* x, double* y, bool add)
{
    long i0 = 0;
    for (; r - i0 > 32; i0 += 32) groups_avx2<8>(M + i0, r, c, x, y + i0, add, 4);
    const long rest = r - i0;  // 1 .. 32
    const int k = int((rest + 3) / 4), tail = int(rest - 4 * (k - 1));
    switch (k) {
    case 1: groups_avx2<1>(M + i0, r, c, x, y + i0, add, tail); break;
    case 2: groups_avx2<2>(M + i0, r, c, x, y + i0, add, tail); break;
    case 3: groups_avx2<3>(M + i0, r, c, x, y + i0, add, tail); break;
    case 4: groups_avx2<4>(M + i0, r, c, x, y + i0, add, tail); break;
    case 5: groups_avx2<5>(M + i0, r, c, x, y + i0, add, tail); break;
    case 6: groups_avx2<6>(M + i0, r, c, x, y + i0, add, tail); break;
    case 7: groups_avx2<7>(M + i0, r, c, x, y + i0, add, tail); break;
    default: groups_avx2<8>(M + i0, r, c, x, y + i0, add, tail); break;
    }
}
const bool kAvx2 = __builtin_cpu_supports("avx2");
#endif

}  // namespace

void matvec_mid(const double* M, long r, long c, const double* x, double* y, bool add)
{
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    if (kAvx2) {
        mid_avx2(M, r, c, x, y, add);
        return;
    }
#endif
    matvec_mid_portable(M, r, c, x, y, add);
}

void matvec_mid_portable(const double* M, long r, long c, const double* x, double* y, bool add)
{
    long i0 = 0;
    for (; i0 + 16 <= r; i0 += 16) rows_block<16>(M + i0, r, c, x, y + i0, add);
    for (; i0 + 4 <= r; i0 += 4) rows_block<4>(M + i0, r, c, x, y + i0, add);
    for (; i0 < r; ++i0) rows_block<1>(M + i0, r, c, x, y + i0, add);
}

}  // namespace gap
}  // namespace fracdesign
