// matvec.cpp - the mid-size block of matvec.hpp: 9 to 64 rows, fewer than
// 128 columns (Eigen 3.4's gemv sums those in one column block). Rows in
// blocks of 16 whose sums stay in registers over all columns, each row's sum
// over the columns in order from zero: the same additions as Eigen's kernel
// (per row, the packet width does not change the order), so the result is
// bit-identical whichever path runs. The AVX2 clone is chosen at run time
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
// 16 rows in four 256-bit registers; mul then add (no FMA), each row's sum
// in column order as matvec_mid_portable's.
__attribute__((target("avx2"))) inline __m256d out4(const double* y, __m256d s, bool add)
{
    return add ? _mm256_add_pd(_mm256_loadu_pd(y), s) : s;
}

__attribute__((target("avx2"))) void mid_avx2(const double* M, long r, long c, const double* x, double* y, bool add)
{
    long i0 = 0;
    for (; i0 + 16 <= r; i0 += 16) {
        __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0, s3 = s0;
        for (long j = 0; j < c; ++j) {
            const double* col = M + j * r + i0;
            const __m256d xj = _mm256_set1_pd(x[j]);
            s0 = _mm256_add_pd(s0, _mm256_mul_pd(_mm256_loadu_pd(col), xj));
            s1 = _mm256_add_pd(s1, _mm256_mul_pd(_mm256_loadu_pd(col + 4), xj));
            s2 = _mm256_add_pd(s2, _mm256_mul_pd(_mm256_loadu_pd(col + 8), xj));
            s3 = _mm256_add_pd(s3, _mm256_mul_pd(_mm256_loadu_pd(col + 12), xj));
        }
        _mm256_storeu_pd(y + i0, out4(y + i0, s0, add));
        _mm256_storeu_pd(y + i0 + 4, out4(y + i0 + 4, s1, add));
        _mm256_storeu_pd(y + i0 + 8, out4(y + i0 + 8, s2, add));
        _mm256_storeu_pd(y + i0 + 12, out4(y + i0 + 12, s3, add));
    }
    for (; i0 + 4 <= r; i0 += 4) {
        __m256d s0 = _mm256_setzero_pd();
        for (long j = 0; j < c; ++j) s0 = _mm256_add_pd(s0, _mm256_mul_pd(_mm256_loadu_pd(M + j * r + i0), _mm256_set1_pd(x[j])));
        _mm256_storeu_pd(y + i0, out4(y + i0, s0, add));
    }
    for (; i0 < r; ++i0) rows_block<1>(M + i0, r, c, x, y + i0, add);
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
