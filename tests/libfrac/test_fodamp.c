/* Collocated fractional damping law and prefilter (frac/fodamp.h). */
#include "frac_test.h"
#include <complex.h>
#include "frac/fodamp.h"

static frac_real st[4096];

static frac_fodamp_params params(double ts)
{
    frac_fodamp_params p;
    p.kc = FRAC_R(5.31);
    p.alpha = FRAC_R(0.8);
    p.m = 2;
    p.n1 = FRAC_R(0.0142);
    p.n2 = p.d1 = p.d2 = FRAC_R(0.0);
    p.fa = FRAC_R(0.116);
    p.fbeta = FRAC_R(0.55);
    p.fb = FRAC_R(0.011);
    p.ts = (frac_real)ts;
    p.op.method = FRAC_FO_OUSTALOUP;
    p.op.wb = FRAC_R(0.01);
    p.op.wh = FRAC_R(1000.0);
    p.op.n = 6;
    p.op.memory = 0;
    return p;
}

static void test_fodamp_discrete_laws_follow_the_continuous_ones(void **state)
{
    frac_fodamp c;
    frac_fodamp_params p = params(1e-3);
    int k;
    (void)state;
    assert_int_equal(frac_fodamp_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal((int)c.k, 1);
    assert_close(c.r, -0.2, 1e-15);
    for (k = 0; k <= 20; k++) {
        double w = 0.5 * pow(100.0, k / 20.0); /* 0.5 .. 50 rad/s: 1.7 decades inside the band */
        double complex Cx = 5.31 * (1.0 + 0.0142 * I * w) / cpow(I * w, 1.2);
        double complex Fx = (1.0 + 0.116 * cpow(I * w, 0.55)) / (1.0 + 0.011 * I * w);
        frac_real re, im;
        assert_int_equal(frac_fodamp_freqresp_c(&c, (frac_real)w, &re, &im), FRAC_OK);
        /* Oustaloup ripple and band-edge error, bilinear warping */
        if (!(cabs((re + I * im) / Cx - 1.0) < 0.02)) fail_msg("C at %g: %g", w, cabs((re + I * im) / Cx - 1.0));
        assert_int_equal(frac_fodamp_freqresp_f(&c, (frac_real)w, &re, &im), FRAC_OK);
        if (!(cabs((re + I * im) / Fx - 1.0) < 0.02)) fail_msg("F at %g: %g", w, cabs((re + I * im) / Fx - 1.0));
    }
}

static void test_fodamp_time_response_follows_its_frequency_response(void **state)
{
    frac_fodamp c;
    frac_fodamp_params p = params(1e-3);
    frac_real u, re, im;
    double w = 15.0, ts = 1e-3, sc = 0.0, ss = 0.0, period = 2.0 * M_PI / w;
    int k, n0 = 30000, n1 = n0 + (int)(20 * period / ts + 0.5);
    (void)state;
    /* C alone (ref = 0): u = -C meas, meas = sin(w t) */
    assert_int_equal(frac_fodamp_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_fodamp_freqresp_c(&c, (frac_real)w, &re, &im), FRAC_OK);
    for (k = 0; k < n1; k++) {
        assert_int_equal(frac_fodamp_step(&c, FRAC_R(0.0), (frac_real)sin(w * ts * k), &u), FRAC_OK);
        if (k >= n0) {
            sc += -u * cos(w * ts * k);
            ss += -u * sin(w * ts * k);
        }
    }
    /* the integrator's start-up offset averages out over whole periods */
    assert_close(2.0 * ss / (n1 - n0), re, 1e-2 * sqrt(re * re + im * im));
    assert_close(2.0 * sc / (n1 - n0), im, 1e-2 * sqrt(re * re + im * im));
}

static void test_fodamp_prefilter_has_unit_dc_gain(void **state)
{
    frac_fodamp c;
    frac_fodamp_params p = params(1e-3);
    frac_real u = 0;
    int k;
    (void)state;
    p.op.wb = FRAC_R(1e-4);
    assert_int_equal(frac_fodamp_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (k = 0; k < 200000; k++) assert_int_equal(frac_fodamp_step(&c, FRAC_R(1.0), FRAC_R(0.0), &u), FRAC_OK);
    /* F(0) = 1 (spec 3 of seed 002), approached as 1 + 0.116 t^-0.55/Gamma(0.45) (the step response of s^0.55) */
    assert_close(u, 1.0 + 0.116 * pow(200.0, -0.55) / tgamma(0.45), 2e-4);
}

static void test_fodamp_accepts_the_exact_inverse(void **state)
{
    frac_fodamp c;
    frac_fodamp_params p = params(1e-3);
    frac_real re, im;
    double w = 30.0;
    (void)state;
    /* (47): (1 + 0.0071 s)^2 s^0.8 / s^2: two integrators, r = 0.8 */
    p.n1 = FRAC_R(0.0142);
    p.n2 = FRAC_R(0.0071 * 0.0071);
    p.op.method = FRAC_FO_OUSTALOUP_REFINED;
    assert_int_equal(frac_fodamp_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal((int)c.k, 2);
    assert_close(c.r, 0.8, 1e-15);
    assert_int_equal(frac_fodamp_freqresp_c(&c, (frac_real)w, &re, &im), FRAC_OK);
    {
        double complex ex = 5.31 * (1.0 + 0.0071 * I * w) * (1.0 + 0.0071 * I * w) / cpow(I * w, 1.2);
        assert_true(cabs((re + I * im) / ex - 1.0) < 0.01);
    }
    /* a complex-pair denominator D(s) = 1 + 0.01 s + 0.0004 s^2 maps through the bilinear transform */
    p.d1 = FRAC_R(0.01);
    p.d2 = FRAC_R(0.0004);
    p.op.method = FRAC_FO_OUSTALOUP; /* k = 1, r = -0.2: outside the refined method's (0, 1) */
    assert_int_equal(frac_fodamp_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_fodamp_freqresp_c(&c, (frac_real)w, &re, &im), FRAC_OK);
    {
        double complex s = I * w, ex = 5.31 * (1.0 + 0.0142 * s + 0.0071 * 0.0071 * s * s) / cpow(s, 1.2)
                                       / (1.0 + 0.01 * s + 0.0004 * s * s);
        assert_true(cabs((re + I * im) / ex - 1.0) < 0.01);
    }
}

static void test_fodamp_rejects_bad_parameters_and_input(void **state)
{
    frac_fodamp c;
    frac_fodamp_params p = params(1e-3);
    frac_real u, u1;
    size_t n = frac_fodamp_storage_len(&p);
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero);
    (void)state;
    assert_int_equal((int)n, 2 * FRAC_OUSTALOUP_STORAGE(6, 0));
    assert_int_equal(frac_fodamp_init(NULL, &p, st, n), FRAC_E_NULL);
    assert_int_equal(frac_fodamp_init(&c, &p, NULL, n), FRAC_E_NULL);
    assert_int_equal(frac_fodamp_init(&c, &p, st, n - 1), FRAC_E_STORAGE);
    p.kc = FRAC_R(0.0); assert_int_equal(frac_fodamp_init(&c, &p, st, n), FRAC_E_GAIN);
    p.kc = FRAC_R(5.31); p.fb = -FRAC_R(1.0); assert_int_equal(frac_fodamp_init(&c, &p, st, n), FRAC_E_GAIN);
    p.fb = FRAC_R(0.011); p.alpha = FRAC_R(2.0); assert_int_equal(frac_fodamp_init(&c, &p, st, n), FRAC_E_ORDER);
    p.alpha = FRAC_R(0.8); p.fbeta = FRAC_R(2.5); assert_int_equal(frac_fodamp_init(&c, &p, st, n), FRAC_E_ORDER);
    p.fbeta = FRAC_R(0.55); p.m = 3; assert_int_equal(frac_fodamp_init(&c, &p, st, n), FRAC_E_DIM);
    p.m = 2; p.d1 = -FRAC_R(0.1); assert_int_equal(frac_fodamp_init(&c, &p, st, n), FRAC_E_UNSTABLE);
    p.d1 = FRAC_R(0.0); p.ts = FRAC_R(0.0); assert_int_equal(frac_fodamp_init(&c, &p, st, n), FRAC_E_TS);
    p.ts = FRAC_R(1e-3); p.op.wh = FRAC_R(1e4); assert_int_equal(frac_fodamp_init(&c, &p, st, 4096), FRAC_E_BAND);
    p.op.wh = FRAC_R(1000.0);
    assert_int_equal(frac_fodamp_step(&c, FRAC_R(0.0), FRAC_R(0.0), &u), FRAC_E_NOT_INIT);
    assert_int_equal(frac_fodamp_init(&c, &p, st, n), FRAC_OK);
    assert_int_equal(frac_fodamp_step(&c, FRAC_R(1.0), FRAC_R(0.5), &u), FRAC_OK);
    assert_int_equal(frac_fodamp_step(&c, nan, FRAC_R(0.5), &u1), FRAC_E_NONFINITE);
    assert_true(u1 == u);
    assert_int_equal(frac_fodamp_step(&c, FRAC_R(1.0), nan, &u1), FRAC_E_NONFINITE);
    assert_true(u1 == u);
    assert_int_equal(frac_fodamp_freqresp_c(&c, FRAC_R(0.0), &u, &u1), FRAC_E_PARAM);
    assert_int_equal(frac_fodamp_reset(&c), FRAC_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fodamp_discrete_laws_follow_the_continuous_ones),
        cmocka_unit_test(test_fodamp_time_response_follows_its_frequency_response),
        cmocka_unit_test(test_fodamp_prefilter_has_unit_dc_gain),
        cmocka_unit_test(test_fodamp_accepts_the_exact_inverse),
        cmocka_unit_test(test_fodamp_rejects_bad_parameters_and_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
