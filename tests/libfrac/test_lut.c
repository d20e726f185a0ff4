/* Lookup tables (frac/lut.h): knots, monotonicity, inverse, range handling, 2-D. */
#include <string.h>
#include "frac_test.h"
#include "frac/lut.h"

#define NK 9
/* non-uniform breakpoints and monotone data with flat and steep parts */
static const frac_real XB[NK] = {0.0, 0.5, 0.7, 1.0, 2.0, 2.1, 3.0, 4.5, 5.0};
static const frac_real YM[NK] = {0.0, 0.0, 0.1, 0.1, 3.0, 3.05, 8.0, 8.0, 8.5};
/* strictly increasing and strictly decreasing data */
static const frac_real YS[NK] = {-2.0, -1.0, -0.9, 0.0, 4.0, 4.2, 9.0, 9.5, 12.0};
static const frac_real YD[NK] = {5.0, 4.0, 1.0, 0.5, 0.4, -3.0, -3.1, -8.0, -9.0};

static void test_lut_exact_at_knots_all_modes(void **state)
{
    frac_lut1 t;
    frac_real d[NK], y;
    int interp, k;
    (void)state;
    for (interp = FRAC_LUT_LINEAR; interp <= FRAC_LUT_CUBIC; interp++) {
        assert_int_equal(frac_lut1_init(&t, XB, YS, NK, interp, FRAC_LUT_CLAMP, d), FRAC_OK);
        for (k = 0; k < NK; k++) {
            assert_int_equal(frac_lut1_eval(&t, XB[k], &y), FRAC_OK);
            assert_close(y, YS[k], 1e-12);
        }
        assert_int_equal(frac_lut1_init_uniform(&t, FRAC_R(-1.0), FRAC_R(0.25), YD, NK, interp,
                                                FRAC_LUT_EXTRAPOLATE, d), FRAC_OK);
        for (k = NK - 1; k >= 0; k--) {
            assert_int_equal(frac_lut1_eval(&t, FRAC_R(-1.0) + FRAC_R(0.25) * k, &y), FRAC_OK);
            assert_close(y, YD[k], 1e-12);
        }
    }
    /* linear between knots */
    frac_lut1_init(&t, XB, YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL);
    frac_lut1_eval(&t, FRAC_R(1.5), &y);
    assert_close(y, 2.0, 1e-12);
}

static void test_lut_monotone_cubic_keeps_monotone_data_monotone(void **state)
{
    frac_lut1 t;
    frac_real d[NK], y, prev;
    double x;
    int seg;
    (void)state;
    assert_int_equal(frac_lut1_init(&t, XB, YM, NK, FRAC_LUT_CUBIC, FRAC_LUT_CLAMP, d), FRAC_OK);
    frac_lut1_eval(&t, XB[0], &prev);
    for (x = 0.001; x <= 5.0; x += 0.001) {
        frac_lut1_eval(&t, (frac_real)x, &y);
        assert_true(y >= prev - 1e-12);
        prev = y;
    }
    /* flat data stay flat: no overshoot on [0, 0.5] and [3, 4.5] */
    for (seg = 0; seg < 100; seg++) {
        frac_lut1_eval(&t, FRAC_R(3.0) + FRAC_R(0.015) * seg, &y);
        assert_close(y, 8.0, 1e-12);
    }
}

static void test_lut_cubic_is_third_order_accurate_on_smooth_data(void **state)
{
    frac_real xs[41], ys[41], d[41], y;
    frac_lut1 t;
    double x, err = 0.0;
    int k;
    (void)state;
    for (k = 0; k < 41; k++) {
        xs[k] = (frac_real)(1.5 * k / 40.0 + 0.01 * (k % 3)); /* perturbed, still increasing */
        ys[k] = (frac_real)sin((double)xs[k]);
    }
    assert_int_equal(frac_lut1_init(&t, xs, ys, 41, FRAC_LUT_CUBIC, FRAC_LUT_CLAMP, d), FRAC_OK);
    for (x = 0.02; x < 1.5; x += 0.0037) {
        frac_lut1_eval(&t, (frac_real)x, &y);
        if (fabs((double)y - sin(x)) > err) err = fabs((double)y - sin(x));
    }
    /* linear interpolation would be off by h^2/8 ~ 2e-4 here */
    assert_true(err < 2e-5);
}

static void test_lut_inverse_of_lookup_is_identity(void **state)
{
    frac_lut1 t;
    frac_real d[NK], y, xi;
    const frac_real *data[2];
    double x;
    int interp, which, uni;
    (void)state;
    data[0] = YS;
    data[1] = YD;
    for (uni = 0; uni < 2; uni++) {
        for (which = 0; which < 2; which++) {
            for (interp = FRAC_LUT_LINEAR; interp <= FRAC_LUT_CUBIC; interp++) {
                if (uni) {
                    assert_int_equal(frac_lut1_init_uniform(&t, FRAC_R(0.0), FRAC_R(0.625), data[which], NK,
                                                            interp, FRAC_LUT_CLAMP, d), FRAC_OK);
                } else {
                    assert_int_equal(frac_lut1_init(&t, XB, data[which], NK, interp, FRAC_LUT_CLAMP, d), FRAC_OK);
                }
                for (x = 0.0; x <= 5.0; x += 0.0173) {
                    assert_int_equal(frac_lut1_eval(&t, (frac_real)x, &y), FRAC_OK);
                    assert_int_equal(frac_lut1_inverse(&t, y, &xi), FRAC_OK);
                    assert_close(xi, x, 1e-9);
                }
            }
        }
    }
}

static void test_lut_rejects_non_monotone_breakpoints_at_init(void **state)
{
    frac_lut1 t;
    frac_lut2 t2;
    frac_lut_axis_params a1, a2;
    const frac_real xeq[4] = {0, 1, 1, 2}, xdec[4] = {0, 2, 1, 3}, y4[4] = {0, 1, 2, 3};
    frac_real z[16] = {0};
    (void)state;
    assert_int_equal(frac_lut1_init(&t, xeq, y4, 4, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_NOT_MONOTONE);
    assert_int_equal(frac_lut1_init(&t, xdec, y4, 4, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_NOT_MONOTONE);
    a1.x = xdec; a1.n = 4; a1.x0 = 0; a1.h = 0;
    a2.x = NULL; a2.n = 4; a2.x0 = 0; a2.h = 1;
    assert_int_equal(frac_lut2_init(&t2, &a1, &a2, z, FRAC_LUT_CLAMP), FRAC_E_NOT_MONOTONE);
    assert_int_equal(frac_lut2_eval(&t2, 0, 0, z), FRAC_E_NOT_INIT);
}

static void test_lut_outside_range_clamps_or_extrapolates_with_flag(void **state)
{
    frac_lut1 t;
    frac_real d[NK], y, x;
    (void)state;
    frac_lut1_init(&t, XB, YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(-1.0), &y), FRAC_W_CLAMPED);
    assert_close(y, -2.0, 0.0);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(9.0), &y), FRAC_W_CLAMPED);
    assert_close(y, 12.0, 0.0);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(5.0), &y), FRAC_OK);
    assert_int_equal(frac_lut1_inverse(&t, FRAC_R(20.0), &x), FRAC_W_CLAMPED);
    assert_close(x, 5.0, 0.0);
    frac_lut1_init(&t, XB, YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_EXTRAPOLATE, NULL);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(-1.0), &y), FRAC_W_EXTRAPOLATED);
    assert_close(y, -4.0, 1e-12); /* slope 2 on the first segment */
    assert_int_equal(frac_lut1_inverse(&t, FRAC_R(-4.0), &x), FRAC_W_EXTRAPOLATED);
    assert_close(x, -1.0, 1e-12);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(6.0), &y), FRAC_W_EXTRAPOLATED);
    assert_close(y, 17.0, 1e-12); /* slope 5 on the last segment */
    frac_lut1_init_uniform(&t, FRAC_R(0.0), FRAC_R(1.0), YS, NK, FRAC_LUT_CUBIC, FRAC_LUT_EXTRAPOLATE, d);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(-0.5), &y), FRAC_W_EXTRAPOLATED);
    assert_close(y, -2.0 - 0.5 * d[0], 1e-12);
    assert_int_equal(frac_lut1_inverse(&t, y, &x), FRAC_W_EXTRAPOLATED);
    assert_close(x, -0.5, 1e-12);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(8.5), &y), FRAC_W_EXTRAPOLATED);
    assert_close(y, 12.0 + 0.5 * d[NK - 1], 1e-12);
    assert_int_equal(frac_lut1_inverse(&t, y, &x), FRAC_W_EXTRAPOLATED);
    assert_close(x, 8.5, 1e-12);
    /* two knots: the cubic is the straight line */
    frac_lut1_init_uniform(&t, FRAC_R(0.0), FRAC_R(2.0), YS, 2, FRAC_LUT_CUBIC, FRAC_LUT_CLAMP, d);
    assert_close(d[0], 0.5, 1e-15);
    assert_close(d[1], 0.5, 1e-15);
    frac_lut1_eval(&t, FRAC_R(0.5), &y);
    assert_close(y, -1.75, 1e-12);
    frac_lut1_init_uniform(&t, FRAC_R(0.0), FRAC_R(1.0), YS, NK, FRAC_LUT_CUBIC, FRAC_LUT_CLAMP, d);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(-0.5), &y), FRAC_W_CLAMPED);
    assert_close(y, -2.0, 0.0);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(1e30), &y), FRAC_W_CLAMPED);
    assert_close(y, 12.0, 0.0);
}

/* reference: brute-force segment search */
static double ref_linear(const frac_real *x, const frac_real *y, int n, double q)
{
    int i = 0;
    while (i < n - 2 && q >= x[i + 1]) i++;
    return y[i] + (q - x[i]) / (x[i + 1] - x[i]) * (y[i + 1] - y[i]);
}

static void test_lut_cached_search_agrees_with_brute_force_in_any_order(void **state)
{
    frac_real x[200], y[200], v;
    frac_lut1 t;
    unsigned long s = 12345;
    int k;
    (void)state;
    x[0] = 0;
    for (k = 0; k < 200; k++) {
        if (k > 0) x[k] = x[k - 1] + (frac_real)(0.01 + 0.001 * (k % 7));
        y[k] = (frac_real)cos(0.05 * k);
    }
    assert_int_equal(frac_lut1_init(&t, x, y, 200, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_OK);
    for (k = 0; k < 3000; k++) {
        double q;
        s = s * 1103515245UL + 12345UL;
        q = (k % 2) ? (double)x[199] * (double)((s >> 8) % 100000) / 100000.0 : 0.0005 * (k % 4000);
        assert_int_equal(frac_lut1_eval(&t, (frac_real)q, &v), FRAC_OK);
        assert_close(v, ref_linear(x, y, 200, q), 1e-12);
    }
}

static void test_lut_nan_query_holds_last_output(void **state)
{
    frac_lut1 t;
    frac_lut2 t2;
    frac_lut_axis_params a1, a2;
    frac_real y, x, z[4] = {1, 2, 3, 4};
    (void)state;
    frac_lut1_init_uniform(&t, FRAC_R(0.0), FRAC_R(1.0), YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL);
    frac_lut1_eval(&t, FRAC_R(3.0), &y);
    y = 99;
    assert_int_equal(frac_lut1_eval(&t, (frac_real)NAN, &y), FRAC_E_NONFINITE);
    assert_close(y, 0.0, 0.0);
    frac_lut1_inverse(&t, FRAC_R(0.0), &x);
    assert_int_equal(frac_lut1_inverse(&t, (frac_real)NAN, &x), FRAC_E_NONFINITE);
    assert_close(x, 3.0, 1e-12);
    frac_lut1_init(&t, XB, YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_EXTRAPOLATE, NULL);
    frac_lut1_eval(&t, FRAC_R(1.0), &y);
    assert_int_equal(frac_lut1_eval(&t, (frac_real)NAN, &y), FRAC_E_NONFINITE);
    assert_close(y, 0.0, 0.0);
    a1.x = NULL; a1.n = 2; a1.x0 = 0; a1.h = 1;
    a2 = a1;
    frac_lut2_init(&t2, &a1, &a2, z, FRAC_LUT_CLAMP);
    frac_lut2_eval(&t2, FRAC_R(1.0), FRAC_R(1.0), &y);
    assert_int_equal(frac_lut2_eval(&t2, FRAC_R(0.5), (frac_real)NAN, &y), FRAC_E_NONFINITE);
    assert_close(y, 4.0, 0.0);
}

static void test_lut_inverse_needs_monotone_data(void **state)
{
    frac_lut1 t;
    frac_real x;
    (void)state;
    assert_int_equal(frac_lut1_init(&t, XB, YM, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_OK);
    assert_int_equal(frac_lut1_inverse(&t, FRAC_R(1.0), &x), FRAC_E_NOT_MONOTONE);
}

static void test_lut_bad_init_arguments(void **state)
{
    frac_lut1 t;
    frac_real ybad[3] = {0, 1, 0}, y;
    (void)state;
    memset(&t, 0, sizeof t);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(0.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_lut1_inverse(&t, FRAC_R(0.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_lut1_init_uniform(&t, 0, 1, YS, 1, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_DIM);
    assert_int_equal(frac_lut1_init_uniform(&t, 0, 0, YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_PARAM);
    assert_int_equal(frac_lut1_init_uniform(&t, (frac_real)NAN, 1, YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_PARAM);
    assert_int_equal(frac_lut1_init_uniform(&t, 0, 1, YS, NK, 5, FRAC_LUT_CLAMP, NULL), FRAC_E_PARAM);
    assert_int_equal(frac_lut1_init_uniform(&t, 0, 1, YS, NK, FRAC_LUT_LINEAR, 5, NULL), FRAC_E_PARAM);
    assert_int_equal(frac_lut1_init_uniform(&t, 0, 1, YS, NK, FRAC_LUT_CUBIC, FRAC_LUT_CLAMP, NULL), FRAC_E_STORAGE);
    assert_int_equal(frac_lut1_init_uniform(&t, 0, 1, NULL, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_NULL);
    ybad[1] = (frac_real)INFINITY;
    assert_int_equal(frac_lut1_init_uniform(&t, 0, 1, ybad, 3, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_NONFINITE);
    assert_int_equal(frac_lut1_eval(&t, FRAC_R(0.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_lut1_init(&t, NULL, YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_NULL);
    assert_int_equal(frac_lut1_init(NULL, XB, YS, NK, FRAC_LUT_LINEAR, FRAC_LUT_CLAMP, NULL), FRAC_E_NULL);
    assert_int_equal(frac_lut1_eval(NULL, FRAC_R(0.0), &y), FRAC_E_NULL);
}

static void test_lut2_bilinear_exact_on_bilinear_function_with_flags(void **state)
{
    frac_lut2 t;
    frac_lut_axis_params a1, a2;
    const frac_real x1[4] = {0.0, 0.3, 1.0, 2.5};
    frac_real z[4 * 5], v;
    int i, j;
    double p, q;
    (void)state;
    a1.x = x1; a1.n = 4; a1.x0 = 0; a1.h = 0;
    a2.x = NULL; a2.n = 5; a2.x0 = FRAC_R(-1.0); a2.h = FRAC_R(0.5);
    for (i = 0; i < 4; i++) {
        for (j = 0; j < 5; j++) {
            double xa = x1[i], xb = -1.0 + 0.5 * j;
            z[i * 5 + j] = (frac_real)(1.0 + 2.0 * xa - 3.0 * xb + 0.5 * xa * xb);
        }
    }
    assert_int_equal(frac_lut2_init(&t, &a1, &a2, z, FRAC_LUT_CLAMP), FRAC_OK);
    for (p = 0.0; p <= 2.5; p += 0.11) {
        for (q = -1.0; q <= 1.0; q += 0.07) {
            assert_int_equal(frac_lut2_eval(&t, (frac_real)p, (frac_real)q, &v), FRAC_OK);
            assert_close(v, 1.0 + 2.0 * p - 3.0 * q + 0.5 * p * q, 1e-12);
        }
    }
    assert_int_equal(frac_lut2_eval(&t, FRAC_R(3.0), FRAC_R(0.0), &v), FRAC_W_CLAMPED);
    assert_close(v, 1.0 + 5.0, 1e-12);
    assert_int_equal(frac_lut2_eval(&t, FRAC_R(1.0), FRAC_R(-2.0), &v), FRAC_W_CLAMPED);
    assert_close(v, 1.0 + 2.0 + 3.0 - 0.5, 1e-12);
    assert_int_equal(frac_lut2_init(&t, &a1, &a2, z, FRAC_LUT_EXTRAPOLATE), FRAC_OK);
    assert_int_equal(frac_lut2_eval(&t, FRAC_R(3.0), FRAC_R(1.5), &v), FRAC_W_EXTRAPOLATED);
    assert_close(v, 1.0 + 6.0 - 4.5 + 0.5 * 4.5, 1e-12);
    a2.h = FRAC_R(-0.5);
    assert_int_equal(frac_lut2_init(&t, &a1, &a2, z, FRAC_LUT_CLAMP), FRAC_E_PARAM);
    a2.h = FRAC_R(0.5);
    a2.n = 1;
    assert_int_equal(frac_lut2_init(&t, &a1, &a2, z, FRAC_LUT_CLAMP), FRAC_E_DIM);
    a2.n = 5;
    z[7] = (frac_real)NAN;
    assert_int_equal(frac_lut2_init(&t, &a1, &a2, z, FRAC_LUT_CLAMP), FRAC_E_NONFINITE);
    assert_int_equal(frac_lut2_init(&t, &a1, &a2, z, 9), FRAC_E_PARAM);
    assert_int_equal(frac_lut2_init(&t, NULL, &a2, z, FRAC_LUT_CLAMP), FRAC_E_NULL);
}

/* 2-D monotone cubic: exact at the grid, monotone along both axes for data
 * monotone along both, more accurate than bilinear on smooth data. */
static void test_lut2_cubic_exact_monotone_and_accurate(void **state)
{
    enum { N1 = 6, N2 = 7 };
    const frac_real x1[N1] = {0.0, 0.2, 0.5, 1.1, 1.3, 2.0};
    frac_lut2 tc, tl;
    frac_lut_axis_params a1, a2;
    frac_real z[N1 * N2], zs[N1 * N2], v, prev, vl;
    /* steps, plateaus and a steep rise, increasing in both directions */
    const frac_real g[N2] = {0.0, 0.0, 0.1, 3.0, 3.0, 3.05, 9.0};
    const frac_real f[N1] = {0.0, 1.0, 1.0, 1.2, 6.0, 6.5};
    double p, q, ec = 0.0, el = 0.0;
    int i, j;
    (void)state;
    a1.x = x1; a1.n = N1; a1.x0 = 0; a1.h = 0;
    a2.x = NULL; a2.n = N2; a2.x0 = FRAC_R(-1.0); a2.h = FRAC_R(0.5);
    for (i = 0; i < N1; i++) {
        for (j = 0; j < N2; j++) {
            z[i * N2 + j] = f[i] + g[j] + FRAC_R(0.1) * f[i] * g[j];
            zs[i * N2 + j] = (frac_real)(exp(0.5 * (double)x1[i]) * atan(-0.7 + 0.5 * j));
        }
    }
    assert_int_equal(frac_lut2_init_interp(&tc, &a1, &a2, z, FRAC_LUT_CLAMP, FRAC_LUT_CUBIC), FRAC_OK);
    for (i = 0; i < N1; i++) {
        for (j = 0; j < N2; j++) {
            assert_int_equal(frac_lut2_eval(&tc, x1[i], FRAC_R(-1.0) + FRAC_R(0.5) * j, &v), FRAC_OK);
            assert_close(v, z[i * N2 + j], 1e-12);
        }
    }
    for (p = 0.0; p <= 2.0; p += 0.05) {
        frac_lut2_eval(&tc, (frac_real)p, FRAC_R(-1.0), &prev);
        for (q = -1.0; q <= 2.0; q += 0.01) {
            frac_lut2_eval(&tc, (frac_real)p, (frac_real)q, &v);
            assert_true(v >= prev - 1e-12);
            prev = v;
        }
    }
    for (q = -1.0; q <= 2.0; q += 0.05) {
        frac_lut2_eval(&tc, FRAC_R(0.0), (frac_real)q, &prev);
        for (p = 0.0; p <= 2.0; p += 0.005) {
            frac_lut2_eval(&tc, (frac_real)p, (frac_real)q, &v);
            assert_true(v >= prev - 1e-12);
            prev = v;
        }
    }
    /* smooth data */
    assert_int_equal(frac_lut2_init_interp(&tc, &a1, &a2, zs, FRAC_LUT_CLAMP, FRAC_LUT_CUBIC), FRAC_OK);
    assert_int_equal(frac_lut2_init(&tl, &a1, &a2, zs, FRAC_LUT_CLAMP), FRAC_OK);
    for (p = 0.0; p <= 2.0; p += 0.013) {
        for (q = -1.0; q <= 2.0; q += 0.017) {
            double ex = exp(0.5 * p) * atan(q + 0.3);
            frac_lut2_eval(&tc, (frac_real)p, (frac_real)q, &v);
            frac_lut2_eval(&tl, (frac_real)p, (frac_real)q, &vl);
            ec += ((double)v - ex) * ((double)v - ex);
            el += ((double)vl - ex) * ((double)vl - ex);
        }
    }
    /* mean-square error over the table */
    assert_true(ec < 0.25 * el);
    /* outside: clamped, or the edge cell continued bilinearly */
    assert_int_equal(frac_lut2_eval(&tc, FRAC_R(3.0), FRAC_R(0.0), &v), FRAC_W_CLAMPED);
    frac_lut2_eval(&tc, FRAC_R(2.0), FRAC_R(0.0), &vl);
    assert_close(v, vl, 1e-12);
    assert_int_equal(frac_lut2_init_interp(&tc, &a1, &a2, zs, FRAC_LUT_EXTRAPOLATE, FRAC_LUT_CUBIC), FRAC_OK);
    assert_int_equal(frac_lut2_init_interp(&tl, &a1, &a2, zs, FRAC_LUT_EXTRAPOLATE, FRAC_LUT_LINEAR), FRAC_OK);
    assert_int_equal(frac_lut2_eval(&tc, FRAC_R(2.5), FRAC_R(0.2), &v), FRAC_W_EXTRAPOLATED);
    frac_lut2_eval(&tl, FRAC_R(2.5), FRAC_R(0.2), &vl);
    assert_close(v, vl, 0.0);
    assert_int_equal(frac_lut2_init_interp(&tc, &a1, &a2, zs, FRAC_LUT_CLAMP, 7), FRAC_E_PARAM);
    /* two knots on an axis: linear along it (z read as 6 x 2) */
    a2.n = 2;
    assert_int_equal(frac_lut2_init_interp(&tc, &a1, &a2, zs, FRAC_LUT_CLAMP, FRAC_LUT_CUBIC), FRAC_OK);
    frac_lut2_eval(&tc, x1[3], FRAC_R(-0.75), &v);
    assert_close(v, 0.5 * (zs[3 * 2] + zs[3 * 2 + 1]), 1e-12);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lut_exact_at_knots_all_modes),
        cmocka_unit_test(test_lut_monotone_cubic_keeps_monotone_data_monotone),
        cmocka_unit_test(test_lut_cubic_is_third_order_accurate_on_smooth_data),
        cmocka_unit_test(test_lut_inverse_of_lookup_is_identity),
        cmocka_unit_test(test_lut_rejects_non_monotone_breakpoints_at_init),
        cmocka_unit_test(test_lut_outside_range_clamps_or_extrapolates_with_flag),
        cmocka_unit_test(test_lut_cached_search_agrees_with_brute_force_in_any_order),
        cmocka_unit_test(test_lut_nan_query_holds_last_output),
        cmocka_unit_test(test_lut_inverse_needs_monotone_data),
        cmocka_unit_test(test_lut_bad_init_arguments),
        cmocka_unit_test(test_lut2_bilinear_exact_on_bilinear_function_with_flags),
        cmocka_unit_test(test_lut2_cubic_exact_monotone_and_accurate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
