/* Oustaloup and refined Oustaloup realizations of s^r (frac/fo_oustaloup.h). */
#include "frac_test.h"
#include <complex.h>
#include "frac/fo_oustaloup.h"

#define NSTORE FRAC_OUSTALOUP_STORAGE(FRAC_OUSTALOUP_NMAX, 1)

static frac_oustaloup_params params(double r, double wb, double wh, double ts, unsigned n, int refined)
{
    frac_oustaloup_params p;
    p.order = (frac_real)r;
    p.wb = (frac_real)wb;
    p.wh = (frac_real)wh;
    p.ts = (frac_real)ts;
    p.n = n;
    p.refined = refined;
    return p;
}

/* max |dB| and |deg| of H/(jw)^r over [w1, w2] (200 log points) */
static void band_error(const frac_oustaloup *o, double r, double w1, double w2, double *db, double *deg)
{
    int i;
    *db = *deg = 0.0;
    for (i = 0; i <= 200; i++) {
        double w = w1 * pow(w2 / w1, i / 200.0);
        frac_real re, im;
        double complex q;
        assert_int_equal(frac_oustaloup_freqresp(o, (frac_real)w, &re, &im), FRAC_OK);
        q = (re + I * im) / cpow(I * w, r);
        if (fabs(20.0 * log10(cabs(q))) > *db) *db = fabs(20.0 * log10(cabs(q)));
        if (fabs(carg(q) * 180.0 / M_PI) > *deg) *deg = fabs(carg(q) * 180.0 / M_PI);
    }
}

static void test_refined_oustaloup_n5_within_1deg_05db_over_inner_band(void **state)
{
    static frac_real st[NSTORE];
    double orders[5] = {0.1, 0.2, 0.5, 0.8, 0.88};
    double bands[3][3] = {{1e-2, 1e2, 1e-3}, {1e-3, 1e3, 2e-3}, {0.1, 2000.0, 5e-4}};
    frac_oustaloup o;
    int i, b;
    (void)state;
    printf("  refined Oustaloup N = 5, error vs (jw)^r over [10 wb, wh/10]\n");
    for (b = 0; b < 3; b++)
        for (i = 0; i < 5; i++) {
            frac_oustaloup_params p = params(orders[i], bands[b][0], bands[b][1], bands[b][2], 5, 1);
            double db, deg;
            assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_OK);
            band_error(&o, orders[i], 10.0 * p.wb, p.wh / 10.0, &db, &deg);
            printf("    r = %4.2f  band [%g, %g]  Ts = %g  max %.4f dB  %.4f deg\n", orders[i], bands[b][0],
                   bands[b][1], bands[b][2], db, deg);
            assert_true(db <= 0.5 && deg <= 1.0);
        }
}

static void test_plain_oustaloup_n5_edge_phase_error_is_r_times_w_over_wh(void **state)
{
    static frac_real st[NSTORE];
    double orders[8] = {-2.0, -1.5, -0.88, -0.5, 0.2, 0.5, 0.88, 1.92};
    frac_oustaloup o;
    int i;
    (void)state;
    printf("  plain Oustaloup N = 5, band [1e-3, 1e3] rad/s, Ts = 1 ms\n");
    printf("    %6s  %-22s  %-22s  %s\n", "r", "[10 wb, wh/10]", "[100 wb, wh/100]", "edge estimate 5.7 r deg");
    for (i = 0; i < 8; i++) {
        frac_oustaloup_params p = params(orders[i], 1e-3, 1e3, 1e-3, 5, 0);
        double db1, deg1, db2, deg2;
        assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_OK);
        band_error(&o, orders[i], 1e-2, 1e2, &db1, &deg1);
        band_error(&o, orders[i], 1e-1, 1e1, &db2, &deg2);
        printf("    %6.2f  %.3f dB %6.3f deg      %.3f dB %6.3f deg      %.2f deg\n", orders[i], db1, deg1, db2,
               deg2, 5.73 * fabs(orders[i]));
        /* magnitude is accurate; the phase misses about |r| (w/wh) rad near the edges whatever N */
        assert_true(db1 <= 0.5);
        assert_true(deg1 <= 7.0 * fabs(orders[i]) + 0.5 && deg1 >= 4.0 * fabs(orders[i]));
        assert_true(deg2 <= 0.8 * fabs(orders[i]) + 0.3);
    }
}

/* analog Oustaloup filter (unit gain at the centre) at jW: the independent reference */
static double complex analog(double r, double Wb, double Wh, int n, int refined, double W)
{
    double complex s = I * W, h = 1.0, hc = 1.0, sc = I * sqrt(Wb * Wh);
    int k, n2 = 2 * n + 1;
    for (k = 0; k < n2; k++) {
        double wz = Wb * pow(Wh / Wb, (k + 0.5 * (1 - r)) / n2), wp = Wb * pow(Wh / Wb, (k + 0.5 * (1 + r)) / n2);
        h *= (s + wz) / (s + wp);
        hc *= (sc + wz) / (sc + wp);
    }
    if (refined) {
        h *= (9 * s * s + 10 * Wh * s) / (9 * (1 - r) * s * s + 10 * Wh * s + 9 * r * Wb * Wh);
        hc *= (9 * sc * sc + 10 * Wh * sc) / (9 * (1 - r) * sc * sc + 10 * Wh * sc + 9 * r * Wb * Wh);
    }
    return h * pow(sqrt(Wb * Wh), r) / cabs(hc);
}

static void test_oustaloup_digital_response_is_the_prewarped_analog_one(void **state)
{
    static frac_real st[NSTORE];
    double ts = 1e-3, c = 2.0 / ts;
    frac_oustaloup o;
    int refined, i;
    (void)state;
    for (refined = 0; refined < 2; refined++) {
        frac_oustaloup_params p = params(0.6, 0.05, 2500.0, ts, 7, refined);
        double Wb = c * tan(0.05 * ts / 2), Wh = c * tan(2500.0 * ts / 2);
        assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_OK);
        for (i = 0; i <= 60; i++) {
            double w = 0.01 * pow(3000.0 / 0.01, i / 60.0);
            frac_real re, im;
            double complex ha = analog(0.6, Wb, Wh, 7, refined, c * tan(w * ts / 2));
            assert_int_equal(frac_oustaloup_freqresp(&o, (frac_real)w, &re, &im), FRAC_OK);
            assert_true(cabs((re + I * im) - ha) <= 1e-9 * cabs(ha));
        }
    }
}

static void test_oustaloup_step_response_follows_its_frequency_response(void **state)
{
    static frac_real st[NSTORE];
    frac_oustaloup_params p = params(0.5, 0.1, 1000.0, 1e-3, 5, 0);
    frac_oustaloup o;
    frac_real re, im, y;
    double w = 20.0, ts = 1e-3, sc = 0.0, ss = 0.0;
    int k, n0 = 20000, n1 = 20000 + 10 * 3142; /* ten periods after the transient */
    (void)state;
    assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_OK);
    assert_int_equal(frac_oustaloup_freqresp(&o, (frac_real)w, &re, &im), FRAC_OK);
    for (k = 0; k < n1; k++) {
        assert_int_equal(frac_oustaloup_step(&o, (frac_real)sin(w * ts * k), &y), FRAC_OK);
        if (k >= n0) {
            sc += y * cos(w * ts * k);
            ss += y * sin(w * ts * k);
        }
    }
    /* y = |H| sin(wt + phi) = Re H sin + Im H cos */
    assert_close(2.0 * ss / (n1 - n0), re, 2e-3 * sqrt(re * re + im * im));
    assert_close(2.0 * sc / (n1 - n0), im, 2e-3 * sqrt(re * re + im * im));
}

/*
 * float builds: the coefficient table rounded to float keeps the response
 * to about 6e-8/(wb Ts) relative (the lowest pole sits 2 wb Ts/2 below
 * z = 1 and float resolves 6e-8 there).
 */
static void test_oustaloup_survives_float_coefficients(void **state)
{
    static frac_real st[NSTORE];
    frac_real cf[FRAC_SOS_NCOEF * (FRAC_OUSTALOUP_NMAX + 2)];
    double wbs[3] = {1e-3, 1e-2, 1e-1}, ts = 2e-3;
    frac_oustaloup o;
    size_t nsec = FRAC_OUSTALOUP_NSEC(5, 0), i;
    int k, b;
    (void)state;
    for (b = 0; b < 3; b++) {
        frac_oustaloup_params p = params(-0.88, wbs[b], 1e3, ts, 5, 0);
        double worst = 0.0;
        assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_OK);
        for (i = 0; i < FRAC_SOS_NCOEF * nsec; i++) cf[i] = (frac_real)(float)st[i];
        for (k = 0; k <= 60; k++) {
            double w = 10.0 * wbs[b] * pow(1e2 / wbs[b], k / 60.0);
            frac_real re, im, rf, imf;
            double complex q;
            assert_int_equal(frac_oustaloup_freqresp(&o, (frac_real)w, &re, &im), FRAC_OK);
            assert_int_equal(frac_sos_freqresp(cf, nsec, (frac_real)(w * ts), &rf, &imf), FRAC_OK);
            q = (rf + I * imf) / (re + I * im);
            if (cabs(q - 1.0) > worst) worst = cabs(q - 1.0);
        }
        printf("  float-rounded coefficients, wb Ts = %.0e: worst relative response change %.2e (bound %.1e)\n",
               wbs[b] * ts, worst, 6e-8 / (wbs[b] * ts));
        assert_true(worst < 6e-8 / (wbs[b] * ts));
    }
}

static void test_oustaloup_rejects_bad_parameters_and_input(void **state)
{
    static frac_real st[NSTORE];
    frac_oustaloup o;
    frac_oustaloup_params p = params(0.5, 0.1, 100.0, 1e-3, 5, 0);
    frac_real y, y1, cf[5 * 20];
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero);
    (void)state;
    assert_int_equal(frac_oustaloup_init(NULL, &p, st, NSTORE), FRAC_E_NULL);
    assert_int_equal(frac_oustaloup_init(&o, NULL, st, NSTORE), FRAC_E_NULL);
    assert_int_equal(frac_oustaloup_init(&o, &p, NULL, NSTORE), FRAC_E_NULL);
    p.order = FRAC_R(2.5); assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_ORDER);
    p.order = nan; assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_ORDER);
    p.order = FRAC_R(1.2); p.refined = 1; assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_ORDER);
    p.order = -FRAC_R(0.5); assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_ORDER);
    p = params(0.5, 0.1, 100.0, 1e-3, 5, 0);
    p.ts = FRAC_R(0.0); assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_TS);
    p.ts = FRAC_R(1e-3); p.wb = FRAC_R(0.0); assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_BAND);
    p.wb = FRAC_R(200.0); assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_BAND);
    p.wb = FRAC_R(0.1); p.wh = FRAC_R(3142.0); assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_BAND);
    p.wh = FRAC_R(100.0); p.n = 0; assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_DIM);
    p.n = FRAC_OUSTALOUP_NMAX + 1; assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_E_DIM);
    p.n = 5; assert_int_equal(frac_oustaloup_init(&o, &p, st, FRAC_OUSTALOUP_STORAGE(5, 0) - 1), FRAC_E_STORAGE);
    assert_int_equal(frac_oustaloup_design(NULL, cf), FRAC_E_NULL);
    assert_int_equal(frac_oustaloup_step(&o, FRAC_R(1.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_oustaloup_init(&o, &p, st, NSTORE), FRAC_OK);
    assert_int_equal(frac_oustaloup_step(&o, FRAC_R(1.0), &y), FRAC_OK);
    assert_int_equal(frac_oustaloup_step(&o, nan, &y1), FRAC_E_NONFINITE);
    assert_true(y1 == y);
    assert_int_equal(frac_oustaloup_freqresp(&o, nan, &y, &y1), FRAC_E_PARAM);
    assert_int_equal(frac_oustaloup_reset(&o), FRAC_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refined_oustaloup_n5_within_1deg_05db_over_inner_band),
        cmocka_unit_test(test_plain_oustaloup_n5_edge_phase_error_is_r_times_w_over_wh),
        cmocka_unit_test(test_oustaloup_digital_response_is_the_prewarped_analog_one),
        cmocka_unit_test(test_oustaloup_step_response_follows_its_frequency_response),
        cmocka_unit_test(test_oustaloup_survives_float_coefficients),
        cmocka_unit_test(test_oustaloup_rejects_bad_parameters_and_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
