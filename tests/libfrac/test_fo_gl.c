/* Grünwald–Letnikov short-memory operator (frac/fo_gl.h). */
#include "frac_test.h"
#include <complex.h>
#include <stdlib.h>
#include "frac/fo_gl.h"

static void test_gl_weights_are_signed_binomials(void **state)
{
    static frac_real st[FRAC_GL_STORAGE(40)];
    frac_gl gl;
    double r[4] = {0.5, -0.88, 1.5, 1.92}, h = 0.01;
    int i, j;
    (void)state;
    for (i = 0; i < 4; i++) {
        assert_int_equal(frac_gl_init(&gl, (frac_real)r[i], (frac_real)h, 40, st, FRAC_GL_STORAGE(40)), FRAC_OK);
        for (j = 0; j < 40; j++) {
            /* (-1)^j binom(r, j) = Gamma(j - r) / (Gamma(-r) Gamma(j + 1)) */
            double w = tgamma(j - r[i]) / (tgamma(-r[i]) * tgamma(j + 1.0));
            assert_rel(gl.wrev[39 - j], pow(h, -r[i]) * w, 1e-11);
        }
    }
}

/* D^a t^b = Gamma(b+1)/Gamma(b+1-a) t^(b-a): GL with full memory, first order in h */
static void test_gl_matches_power_law_derivative(void **state)
{
    enum { NSTEP = 2000 };
    static frac_real st[FRAC_GL_STORAGE(NSTEP + 1)];
    double alpha[6] = {0.5, 0.88, 1.5, 1.92, -0.5, -1.2}, beta[3] = {1.0, 1.5, 2.0};
    double h = 1.0 / NSTEP;
    frac_gl gl;
    frac_real y = 0;
    int i, j, k;
    (void)state;
    printf("  D^a t^b at t = 1, h = %g, full memory: relative error\n", h);
    for (i = 0; i < 6; i++)
        for (j = 0; j < 3; j++) {
            double exact = tgamma(beta[j] + 1.0) / tgamma(beta[j] + 1.0 - alpha[i]), err;
            assert_int_equal(frac_gl_init(&gl, (frac_real)alpha[i], (frac_real)h, NSTEP + 1, st,
                                          FRAC_GL_STORAGE(NSTEP + 1)), FRAC_OK);
            for (k = 0; k <= NSTEP; k++) assert_int_equal(frac_gl_step(&gl, (frac_real)pow(k * h, beta[j]), &y), FRAC_OK);
            err = fabs(y - exact) / fabs(exact);
            printf("    a = %5.2f  b = %3.1f  exact %.6f  GL %.6f  rel err %.2e\n", alpha[i], beta[j], exact, (double)y, err);
            /* the GL truncation error is ~ |a| b h / 2 relative for these smooth inputs */
            assert_true(err < 2.0 * fabs(alpha[i]) * h + 1e-9);
        }
}

/* exact L -> infinity GL operator ((1 - e^{-jwh})/h)^r */
static double complex gl_exact(double r, double w, double h)
{
    return cpow((1.0 - cexp(-I * w * h)) / h, r);
}

static void test_gl_short_memory_error_shrinks_with_memory(void **state)
{
    static frac_real st[FRAC_GL_STORAGE(16384)];
    size_t Ls[6] = {16, 64, 256, 1024, 4096, 16384};
    double orders[3] = {0.5, -0.5, 1.5}, h = 2e-3;
    frac_gl gl;
    int io, il, iw;
    (void)state;
    printf("  GL short memory, h = %g s: max relative error over w in [1, 100] rad/s\n", h);
    printf("    %6s %8s  %12s  %12s\n", "r", "L", "vs GL(L=inf)", "vs (jw)^r");
    for (io = 0; io < 3; io++) {
        double prev = 1e300, bound;
        for (il = 0; il < 6; il++) {
            double etr = 0.0, eall = 0.0;
            assert_int_equal(frac_gl_init(&gl, (frac_real)orders[io], (frac_real)h, Ls[il], st, FRAC_GL_STORAGE(Ls[il])), FRAC_OK);
            for (iw = 0; iw <= 40; iw++) {
                double w = pow(10.0, iw / 20.0);
                frac_real re, im;
                double complex H, ex = gl_exact(orders[io], w, h), pw = cpow(I * w, orders[io]);
                assert_int_equal(frac_gl_freqresp(&gl, (frac_real)w, &re, &im), FRAC_OK);
                H = re + I * im;
                if (cabs(H - ex) / cabs(ex) > etr) etr = cabs(H - ex) / cabs(ex);
                if (cabs(H - pw) / cabs(pw) > eall) eall = cabs(H - pw) / cabs(pw);
            }
            /* tail of the weights, w_j ~ j^(-r-1)/Gamma(-r): relative error at w ~ (L h w)^-(1+r)/|Gamma(-r)| */
            bound = pow(Ls[il] * h * 1.0, -(1.0 + orders[io])) / fabs(tgamma(-orders[io]));
            printf("    %6.2f %8lu  %12.3e  %12.3e  (tail estimate %.3e)\n", orders[io], (unsigned long)Ls[il], etr, eall, bound);
            assert_true(etr < prev);
            if (Ls[il] * h >= 8.0) assert_true(etr < 1.5 * bound);
            prev = etr;
        }
    }
}

static void test_gl_free_response_and_steady_history(void **state)
{
    static frac_real st[FRAC_GL_STORAGE(64)];
    frac_gl gl;
    frac_real y, y0, g;
    double sum = 0.0;
    int k;
    (void)state;
    assert_int_equal(frac_gl_init(&gl, FRAC_R(0.7), FRAC_R(0.01), 64, st, FRAC_GL_STORAGE(64)), FRAC_OK);
    g = frac_gl_feedthrough(&gl);
    assert_rel(g, pow(0.01, -0.7), 1e-14);
    for (k = 0; k < 100; k++) {
        frac_real x = (frac_real)sin(0.1 * k);
        assert_int_equal(frac_gl_free_response(&gl, &y0), FRAC_OK);
        assert_int_equal(frac_gl_step(&gl, x, &y), FRAC_OK);
        assert_close(y, g * x + y0, 1e-9 * fabs(g));
    }
    assert_int_equal(frac_gl_set_history(&gl, FRAC_R(2.0)), FRAC_OK);
    for (k = 0; k < 64; k++) sum += gl.wrev[k];
    assert_int_equal(frac_gl_step(&gl, FRAC_R(2.0), &y), FRAC_OK);
    assert_close(y, 2.0 * sum, 1e-9);
}

static void test_gl_rejects_bad_input_and_keeps_state(void **state)
{
    static frac_real st[FRAC_GL_STORAGE(32)], st2[FRAC_GL_STORAGE(32)];
    frac_gl gl, gl2;
    frac_real y, y2, re, im;
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero), inf = (frac_real)(1.0 / zero);
    int k;
    (void)state;
    assert_int_equal(frac_gl_init(NULL, FRAC_R(0.5), FRAC_R(0.01), 32, st, 96), FRAC_E_NULL);
    assert_int_equal(frac_gl_init(&gl, FRAC_R(0.5), FRAC_R(0.01), 32, NULL, 96), FRAC_E_NULL);
    assert_int_equal(frac_gl_init(&gl, FRAC_R(2.01), FRAC_R(0.01), 32, st, 96), FRAC_E_ORDER);
    assert_int_equal(frac_gl_init(&gl, nan, FRAC_R(0.01), 32, st, 96), FRAC_E_ORDER);
    assert_int_equal(frac_gl_init(&gl, FRAC_R(0.5), FRAC_R(0.0), 32, st, 96), FRAC_E_TS);
    assert_int_equal(frac_gl_init(&gl, FRAC_R(0.5), inf, 32, st, 96), FRAC_E_TS);
    assert_int_equal(frac_gl_init(&gl, FRAC_R(0.5), FRAC_R(0.01), 0, st, 96), FRAC_E_DIM);
    assert_int_equal(frac_gl_init(&gl, FRAC_R(0.5), FRAC_R(0.01), 32, st, 95), FRAC_E_STORAGE);
    assert_int_equal(frac_gl_init(&gl, FRAC_R(2.0), FRAC_R(1e-300), 32, st, 96), FRAC_E_NUMERIC);
    assert_int_equal(frac_gl_step(&gl, FRAC_R(1.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_gl_init(&gl, FRAC_R(0.5), FRAC_R(0.01), 32, st, 96), FRAC_OK);
    assert_int_equal(frac_gl_init(&gl2, FRAC_R(0.5), FRAC_R(0.01), 32, st2, 96), FRAC_OK);
    for (k = 0; k < 40; k++) {
        assert_int_equal(frac_gl_step(&gl, (frac_real)k, &y), FRAC_OK);
        assert_int_equal(frac_gl_step(&gl2, (frac_real)k, &y2), FRAC_OK);
    }
    assert_int_equal(frac_gl_step(&gl, nan, &y2), FRAC_E_NONFINITE);
    assert_true(y2 == y);
    assert_int_equal(frac_gl_step(&gl, inf, &y2), FRAC_E_NONFINITE);
    assert_true(y2 == y);
    for (k = 0; k < 40; k++) {
        assert_int_equal(frac_gl_step(&gl, FRAC_R(1.0), &y), FRAC_OK);
        assert_int_equal(frac_gl_step(&gl2, FRAC_R(1.0), &y2), FRAC_OK);
        assert_true(y == y2);
    }
    assert_int_equal(frac_gl_set_history(&gl, nan), FRAC_E_NONFINITE);
    assert_int_equal(frac_gl_freqresp(&gl, -FRAC_R(1.0), &re, &im), FRAC_E_PARAM);
    assert_int_equal(frac_gl_step(&gl, FRAC_R(1.0), NULL), FRAC_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gl_weights_are_signed_binomials),
        cmocka_unit_test(test_gl_matches_power_law_derivative),
        cmocka_unit_test(test_gl_short_memory_error_shrinks_with_memory),
        cmocka_unit_test(test_gl_free_response_and_steady_history),
        cmocka_unit_test(test_gl_rejects_bad_input_and_keeps_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
