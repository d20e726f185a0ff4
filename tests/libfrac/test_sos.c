/* Biquad cascade, direct form II transposed (frac/sos.h). */
#include "frac_test.h"
#include <complex.h>
#include "frac/sos.h"

/* two sections: a resonant pair and a first-order section */
static const frac_real COEF[10] = {0.2, 0.3, 0.1, -1.2, 0.5, 1.5, -0.7, 0.0, -0.6, 0.0};

static double lcg_uniform(unsigned long *s)
{
    *s = (*s * 1103515245UL + 12345UL) & 0x7fffffffUL;
    return (double)*s / 2147483648.0 - 0.5;
}

static void test_sos_matches_the_difference_equation(void **state)
{
    frac_real st[4], y;
    frac_sos f;
    double x[3] = {0, 0, 0}, v[3] = {0, 0, 0}, w[3] = {0, 0, 0};
    unsigned long seed = 7;
    int k;
    (void)state;
    assert_int_equal(frac_sos_init(&f, 2, COEF, st), FRAC_OK);
    for (k = 0; k < 500; k++) {
        /* direct form I reference per section: y = b0 x + b1 x1 + b2 x2 - a1 y1 - a2 y2 */
        x[2] = x[1]; x[1] = x[0]; x[0] = lcg_uniform(&seed);
        v[2] = v[1]; v[1] = v[0];
        v[0] = 0.2 * x[0] + 0.3 * x[1] + 0.1 * x[2] + 1.2 * v[1] - 0.5 * v[2];
        w[2] = w[1]; w[1] = w[0];
        w[0] = 1.5 * v[0] - 0.7 * v[1] + 0.6 * w[1];
        assert_int_equal(frac_sos_step(&f, (frac_real)x[0], &y), FRAC_OK);
        assert_close(y, w[0], 1e-12);
    }
}

static void test_sos_freqresp_is_the_transform_of_the_impulse_response(void **state)
{
    frac_real st[4], y, re, im;
    frac_sos f;
    double complex acc[3] = {0, 0, 0};
    double th[3] = {0.05, 0.7, 2.9};
    int k, i;
    (void)state;
    assert_int_equal(frac_sos_init(&f, 2, COEF, st), FRAC_OK);
    for (k = 0; k < 400; k++) {
        assert_int_equal(frac_sos_step(&f, k == 0 ? FRAC_R(1.0) : FRAC_R(0.0), &y), FRAC_OK);
        for (i = 0; i < 3; i++) acc[i] += y * cexp(-I * th[i] * k);
    }
    for (i = 0; i < 3; i++) {
        assert_int_equal(frac_sos_freqresp(COEF, 2, (frac_real)th[i], &re, &im), FRAC_OK);
        assert_close(re, creal(acc[i]), 1e-10);
        assert_close(im, cimag(acc[i]), 1e-10);
    }
}

static void test_sos_steady_state_holds_a_constant_input(void **state)
{
    frac_real st[4], y, re, im;
    frac_sos f;
    int k;
    (void)state;
    assert_int_equal(frac_sos_init(&f, 2, COEF, st), FRAC_OK);
    assert_int_equal(frac_sos_freqresp(COEF, 2, FRAC_R(0.0), &re, &im), FRAC_OK);
    assert_int_equal(frac_sos_set_steady(&f, FRAC_R(2.0)), FRAC_OK);
    for (k = 0; k < 20; k++) {
        assert_int_equal(frac_sos_step(&f, FRAC_R(2.0), &y), FRAC_OK);
        assert_close(y, 2.0 * re, 1e-12);
    }
}

static void test_sos_free_response_predicts_the_next_output(void **state)
{
    frac_real st[4], y, y0, g;
    frac_sos f;
    unsigned long seed = 3;
    int k;
    (void)state;
    assert_int_equal(frac_sos_init(&f, 2, COEF, st), FRAC_OK);
    g = frac_sos_feedthrough(&f);
    assert_close(g, 0.2 * 1.5, 1e-15);
    for (k = 0; k < 50; k++) {
        frac_real x = (frac_real)lcg_uniform(&seed);
        assert_int_equal(frac_sos_free_response(&f, &y0), FRAC_OK);
        assert_int_equal(frac_sos_step(&f, x, &y), FRAC_OK);
        assert_close(y, g * x + y0, 1e-14);
    }
}

static void test_sos_process_equals_repeated_steps_in_place(void **state)
{
    frac_real st1[4], st2[4], buf[64], y;
    frac_sos f1, f2;
    unsigned long seed = 11;
    int k;
    (void)state;
    assert_int_equal(frac_sos_init(&f1, 2, COEF, st1), FRAC_OK);
    assert_int_equal(frac_sos_init(&f2, 2, COEF, st2), FRAC_OK);
    for (k = 0; k < 64; k++) buf[k] = (frac_real)lcg_uniform(&seed);
    seed = 11;
    assert_int_equal(frac_sos_process(&f1, buf, buf, 64), FRAC_OK);
    for (k = 0; k < 64; k++) {
        assert_int_equal(frac_sos_step(&f2, (frac_real)lcg_uniform(&seed), &y), FRAC_OK);
        assert_true(y == buf[k]);
    }
}

static void test_sos_accepts_an_integrator_but_has_no_steady_state(void **state)
{
    /* (Ts/2)(1 + z^-1)/(1 - z^-1): trapezoidal integrator, pole at z = 1 */
    const frac_real integ[5] = {0.5, 0.5, 0.0, -1.0, 0.0};
    frac_real st[2], y;
    frac_sos f;
    int k;
    (void)state;
    assert_int_equal(frac_sos_init(&f, 1, integ, st), FRAC_OK);
    for (k = 0; k < 10; k++) assert_int_equal(frac_sos_step(&f, FRAC_R(1.0), &y), FRAC_OK);
    assert_close(y, 9.5, 1e-12);
    assert_int_equal(frac_sos_set_steady(&f, FRAC_R(1.0)), FRAC_E_NUMERIC);
    assert_close(f.state[0], 9.5 + 0.5, 1e-12);
}

static void test_sos_rejects_bad_input_and_keeps_state(void **state)
{
    frac_real st[4], st2[4], bad[10], y, y2, buf[4], re, im;
    const frac_real unstable[5] = {1.0, 0.0, 0.0, 0.0, 1.01};
    const frac_real unstable1[5] = {1.0, 0.0, 0.0, -2.1, 1.0};
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero), inf = (frac_real)(1.0 / zero);
    frac_sos f, f2;
    int k;
    (void)state;
    assert_int_equal(frac_sos_init(NULL, 2, COEF, st), FRAC_E_NULL);
    assert_int_equal(frac_sos_init(&f, 2, NULL, st), FRAC_E_NULL);
    assert_int_equal(frac_sos_init(&f, 2, COEF, NULL), FRAC_E_NULL);
    assert_int_equal(frac_sos_init(&f, 0, COEF, st), FRAC_E_DIM);
    for (k = 0; k < 10; k++) bad[k] = COEF[k];
    bad[7] = nan;
    assert_int_equal(frac_sos_init(&f, 2, bad, st), FRAC_E_PARAM);
    assert_int_equal(frac_sos_init(&f, 1, unstable, st), FRAC_E_UNSTABLE);
    assert_int_equal(frac_sos_init(&f, 1, unstable1, st), FRAC_E_UNSTABLE);
    assert_int_equal(frac_sos_step(&f, FRAC_R(1.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_sos_reset(&f), FRAC_E_NOT_INIT);
    assert_int_equal(frac_sos_init(&f, 2, COEF, st), FRAC_OK);
    assert_int_equal(frac_sos_init(&f2, 2, COEF, st2), FRAC_OK);
    for (k = 0; k < 5; k++) {
        assert_int_equal(frac_sos_step(&f, FRAC_R(1.0), &y), FRAC_OK);
        assert_int_equal(frac_sos_step(&f2, FRAC_R(1.0), &y2), FRAC_OK);
    }
    assert_int_equal(frac_sos_step(&f, nan, &y2), FRAC_E_NONFINITE);
    assert_true(y2 == y);
    assert_int_equal(frac_sos_step(&f, -inf, &y2), FRAC_E_NONFINITE);
    assert_true(y2 == y);
    for (k = 0; k < 5; k++) {
        assert_int_equal(frac_sos_step(&f, FRAC_R(0.5), &y), FRAC_OK);
        assert_int_equal(frac_sos_step(&f2, FRAC_R(0.5), &y2), FRAC_OK);
        assert_true(y == y2);
    }
    buf[0] = FRAC_R(1.0); buf[1] = nan; buf[2] = FRAC_R(1.0); buf[3] = FRAC_R(1.0);
    assert_int_equal(frac_sos_process(&f, buf, buf, 4), FRAC_E_NONFINITE);
    assert_true(buf[1] == buf[0] && buf[3] == buf[0]);
    assert_int_equal(frac_sos_set_steady(&f, nan), FRAC_E_NONFINITE);
    assert_int_equal(frac_sos_step(&f, FRAC_R(1.0), NULL), FRAC_E_NULL);
    assert_int_equal(frac_sos_free_response(&f, NULL), FRAC_E_NULL);
    assert_int_equal(frac_sos_freqresp(COEF, 0, FRAC_R(0.1), &re, &im), FRAC_E_DIM);
    assert_int_equal(frac_sos_freqresp(NULL, 1, FRAC_R(0.1), &re, &im), FRAC_E_NULL);
    assert_true(frac_sos_feedthrough(NULL) == FRAC_R(0.0));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sos_matches_the_difference_equation),
        cmocka_unit_test(test_sos_freqresp_is_the_transform_of_the_impulse_response),
        cmocka_unit_test(test_sos_steady_state_holds_a_constant_input),
        cmocka_unit_test(test_sos_free_response_predicts_the_next_output),
        cmocka_unit_test(test_sos_process_equals_repeated_steps_in_place),
        cmocka_unit_test(test_sos_accepts_an_integrator_but_has_no_steady_state),
        cmocka_unit_test(test_sos_rejects_bad_input_and_keeps_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
