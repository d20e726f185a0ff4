/*
 * 1-D lookup with 4096 knots (frac_lut1_eval, linear interpolation) against
 * a straightforward reference written the textbook way: floor() index with
 * clamping (uniform) and a lo/hi bisection from scratch on every call
 * (breakpoints).
 *
 * usage: bench_lut {frac|ref} {uniform|nonuniform|sequential} CALLS [time]
 *   uniform:    uniform grid, random queries
 *   nonuniform: breakpoints, random queries (binary search every call)
 *   sequential: breakpoints, queries advancing 0.3 knot per call, as the
 *               feedforward playback does (cached segment)
 * With "time" prints the wall-clock ns per call.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include "frac/lut.h"

#define NK 4096
#define NQ 4096

static frac_real xs[NK], ys[NK], qs[NQ];

#if defined(__GNUC__)
#define NOINLINE __attribute__((noinline))
#else
#define NOINLINE
#endif

NOINLINE frac_real ref_lut_uniform(frac_real x0, frac_real h, const frac_real *y, size_t n, frac_real x)
{
    double s = floor((double)((x - x0) / h));
    size_t i;
    frac_real t;
    if (s < 0.0) return y[0];
    if (s >= (double)(n - 1)) return y[n - 1];
    i = (size_t)s;
    t = (x - (x0 + h * (frac_real)i)) / h;
    return y[i] + t * (y[i + 1] - y[i]);
}

NOINLINE frac_real ref_lut_nonuniform(const frac_real *x, const frac_real *y, size_t n, frac_real q)
{
    size_t lo = 0, hi = n - 1;
    if (q <= x[0]) return y[0];
    if (q >= x[n - 1]) return y[n - 1];
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (x[mid] <= q) lo = mid;
        else hi = mid;
    }
    return y[lo] + (q - x[lo]) / (x[lo + 1] - x[lo]) * (y[lo + 1] - y[lo]);
}

int main(int argc, char **argv)
{
    frac_lut1 t;
    unsigned long s = 7;
    long calls, k;
    int use_frac, mode, timing, i;
    double sum = 0.0, ns;
    struct timespec t0, t1;
    frac_real v;
    if (argc < 4) {
        fprintf(stderr, "usage: %s {frac|ref} {uniform|nonuniform|sequential} CALLS [time]\n", argv[0]);
        return 2;
    }
    use_frac = strcmp(argv[1], "frac") == 0;
    mode = strcmp(argv[2], "uniform") == 0 ? 0 : (strcmp(argv[2], "nonuniform") == 0 ? 1 : 2);
    calls = atol(argv[3]);
    timing = argc > 4 && strcmp(argv[4], "time") == 0;
    xs[0] = 0;
    for (i = 0; i < NK; i++) {
        if (i > 0) xs[i] = xs[i - 1] + (frac_real)(1.0 + 0.5 * sin(0.37 * i)); /* spacing 0.5..1.5 */
        ys[i] = (frac_real)sin(0.01 * i);
    }
    for (i = 0; i < NQ; i++) {
        s = s * 1103515245UL + 12345UL;
        if (mode == 0) qs[i] = (frac_real)((double)((s >> 8) % 1000000) / 1000000.0 * (NK - 1));
        else if (mode == 1) qs[i] = (frac_real)((double)((s >> 8) % 1000000) / 1000000.0 * (double)xs[NK - 1]);
        else qs[i] = (frac_real)(0.3 * i);
    }
    if (mode == 0) frac_lut1_init_uniform(&t, FRAC_R(0.0), FRAC_R(1.0), ys, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL);
    else frac_lut1_init(&t, xs, ys, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (k = 0; k < calls; k++) {
        frac_real q = qs[k & (NQ - 1)];
        if (use_frac) {
            frac_lut1_eval(&t, q, &v);
        } else if (mode == 0) {
            v = ref_lut_uniform(FRAC_R(0.0), FRAC_R(1.0), ys, NK, q);
        } else {
            v = ref_lut_nonuniform(xs, ys, NK, q);
        }
        sum += (double)v;
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    ns = ((double)(t1.tv_sec - t0.tv_sec) * 1e9 + (double)(t1.tv_nsec - t0.tv_nsec)) / (double)calls;
    if (timing) printf("%.1f\n", ns);
    return sum == sum ? 0 : 1;
}
