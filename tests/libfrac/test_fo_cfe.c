/* CFE of the Tustin / Al-Alaoui generating functions (frac/fo_cfe.h). */
#include "frac_test.h"
#include <complex.h>
#include "frac/fo_cfe.h"
#include "fixtures/cfe_reference.h"

#define NSTORE FRAC_CFE_STORAGE(FRAC_CFE_NMAX)

static frac_cfe_params params(double r, double ts, unsigned n, int rule)
{
    frac_cfe_params p;
    p.order = (frac_real)r;
    p.ts = (frac_real)ts;
    p.n = n;
    p.rule = rule;
    return p;
}

static double complex poly(const double *c, unsigned n, double complex x)
{
    double complex s = 0.0;
    int i;
    for (i = (int)n; i >= 0; i--) s = s * x + c[i];
    return s;
}

/* the Padé route reproduces the continued fraction expanded in exact arithmetic */
static void test_cfe_equals_the_continued_fraction_convergent(void **state)
{
    static frac_real st[NSTORE];
    frac_cfe f;
    size_t i;
    int k;
    (void)state;
    for (i = 0; i < sizeof CFE_REFS / sizeof CFE_REFS[0]; i++) {
        const cfe_ref *c = &CFE_REFS[i];
        double ts = 1e-3, kk = c->a == 1.0 ? 2.0 / ts : 8.0 / (7.0 * ts);
        frac_cfe_params p = params(c->r, ts, c->n, c->a == 1.0 ? FRAC_CFE_TUSTIN : FRAC_CFE_ALALAOUI);
        assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_OK);
        for (k = 0; k <= 20; k++) {
            double th = 0.001 + 3.1 * k / 20.0;
            double complex x = cexp(-I * th), want = pow(kk, c->r) * poly(c->p, c->n, x) / poly(c->q, c->n, x);
            frac_real re, im;
            assert_int_equal(frac_cfe_freqresp(&f, (frac_real)(th / ts), &re, &im), FRAC_OK);
            if (!(cabs(re + I * im - want) <= 1e-9 * cabs(want)))
                fail_msg("%s at theta %.3f: got %g%+gj want %g%+gj", c->name, th, (double)re, (double)im, creal(want), cimag(want));
        }
    }
}

/* the truncation error against the exact generating function falls with n */
static void test_cfe_converges_to_the_generating_function(void **state)
{
    static frac_real st[NSTORE];
    double orders[4] = {0.5, -0.5, 0.88, 1.5}, ts = 1e-3;
    int rules[2] = {FRAC_CFE_TUSTIN, FRAC_CFE_ALALAOUI}, ir, io, n, k;
    frac_cfe f;
    (void)state;
    printf("  CFE, Ts = 1 ms: max relative error vs the exact generating function^r over [10, 0.9 pi/Ts] rad/s\n");
    for (ir = 0; ir < 2; ir++)
        for (io = 0; io < 4; io++) {
            double prev = 1e300, a = rules[ir] == FRAC_CFE_TUSTIN ? 1.0 : 1.0 / 7.0;
            double kk = rules[ir] == FRAC_CFE_TUSTIN ? 2.0 / ts : 8.0 / (7.0 * ts);
            if (rules[ir] == FRAC_CFE_TUSTIN && orders[io] >= 1.0) continue;
            printf("    %-9s r = %5.2f:", rules[ir] == FRAC_CFE_TUSTIN ? "Tustin" : "Al-Alaoui", orders[io]);
            for (n = 1; n <= 9; n += 2) {
                frac_cfe_params p = params(orders[io], ts, (unsigned)n, rules[ir]);
                double err = 0.0;
                assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_OK);
                for (k = 0; k <= 100; k++) {
                    double w = 10.0 * pow(0.9 * M_PI / ts / 10.0, k / 100.0);
                    double complex x = cexp(-I * w * ts), ex = pow(kk, orders[io]) * cpow((1.0 - x) / (1.0 + a * x), orders[io]);
                    frac_real re, im;
                    assert_int_equal(frac_cfe_freqresp(&f, (frac_real)w, &re, &im), FRAC_OK);
                    if (cabs(re + I * im - ex) / cabs(ex) > err) err = cabs(re + I * im - ex) / cabs(ex);
                }
                printf("  n=%d %.2e", n, err);
                assert_true(err < prev);
                prev = err;
            }
            printf("\n");
        }
}

static void test_cfe_tustin_n5_within_1deg_05db_over_its_mid_band(void **state)
{
    static frac_real st[NSTORE];
    double orders[4] = {0.5, 0.88, -0.5, -0.88}, ts = 1e-3;
    frac_cfe f;
    int io, k;
    (void)state;
    printf("  Tustin CFE n = 5, Ts = 1 ms, error vs (jw)^r over [0.2/Ts, 0.7/Ts] rad/s\n");
    for (io = 0; io < 4; io++) {
        frac_cfe_params p = params(orders[io], ts, 5, FRAC_CFE_TUSTIN);
        double db = 0.0, deg = 0.0;
        assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_OK);
        for (k = 0; k <= 100; k++) {
            double w = 0.2 / ts * pow(3.5, k / 100.0);
            frac_real re, im;
            double complex q;
            assert_int_equal(frac_cfe_freqresp(&f, (frac_real)w, &re, &im), FRAC_OK);
            q = (re + I * im) / cpow(I * w, orders[io]);
            if (fabs(20 * log10(cabs(q))) > db) db = fabs(20 * log10(cabs(q)));
            if (fabs(carg(q)) * 180 / M_PI > deg) deg = fabs(carg(q)) * 180 / M_PI;
        }
        printf("    r = %5.2f  max %.3f dB  %.3f deg\n", orders[io], db, deg);
        assert_true(db <= 0.5 && deg <= 1.0);
    }
}

static void test_cfe_integer_orders_use_the_generating_function(void **state)
{
    static frac_real st[NSTORE];
    frac_cfe f;
    frac_cfe_params p = params(-1.0, 1e-3, 5, FRAC_CFE_TUSTIN);
    frac_real y;
    int k;
    (void)state;
    /* r = -1, Tustin: the trapezoidal integrator exactly */
    assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_OK);
    for (k = 0; k < 10; k++) assert_int_equal(frac_cfe_step(&f, FRAC_R(1.0), &y), FRAC_OK);
    assert_close(y, 9.5e-3, 1e-15);
    /* r = 1.5 with Al-Alaoui: stable; with Tustin: rejected (pole at z = -1) */
    p = params(1.5, 1e-3, 5, FRAC_CFE_ALALAOUI);
    assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_OK);
    p.rule = FRAC_CFE_TUSTIN;
    assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_E_UNSTABLE);
    p = params(-2.0, 1e-3, 3, FRAC_CFE_ALALAOUI);
    assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_OK);
    assert_int_equal((int)f.sos.nsec, 1);
    p = params(0.0, 1e-3, 3, FRAC_CFE_TUSTIN);
    assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_OK);
    assert_int_equal(frac_cfe_step(&f, FRAC_R(3.25), &y), FRAC_OK);
    assert_close(y, 3.25, 0.0);
}

static void test_cfe_rejects_bad_parameters_and_input(void **state)
{
    static frac_real st[NSTORE];
    frac_cfe f;
    frac_cfe_params p = params(0.5, 1e-3, 5, FRAC_CFE_TUSTIN);
    frac_real y, y1;
    size_t ns;
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero);
    (void)state;
    assert_int_equal(frac_cfe_init(NULL, &p, st, NSTORE), FRAC_E_NULL);
    assert_int_equal(frac_cfe_init(&f, &p, NULL, NSTORE), FRAC_E_NULL);
    assert_int_equal(frac_cfe_design(&p, st, NULL), FRAC_E_NULL);
    p.rule = 3; assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_E_PARAM);
    p.rule = FRAC_CFE_ALALAOUI; p.order = FRAC_R(-2.1); assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_E_ORDER);
    p.order = FRAC_R(0.5); p.ts = -FRAC_R(1.0); assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_E_TS);
    p.ts = FRAC_R(1e-3); p.n = 0; assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_E_DIM);
    p.n = FRAC_CFE_NMAX + 1; assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_E_DIM);
    p.n = 5; assert_int_equal(frac_cfe_init(&f, &p, st, FRAC_CFE_STORAGE(5) - 1), FRAC_E_STORAGE);
    assert_int_equal(frac_cfe_design(&p, st, &ns), FRAC_OK);
    assert_int_equal((int)ns, 3);
    assert_int_equal(frac_cfe_step(&f, FRAC_R(1.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_cfe_init(&f, &p, st, NSTORE), FRAC_OK);
    assert_int_equal(frac_cfe_step(&f, FRAC_R(1.0), &y), FRAC_OK);
    assert_int_equal(frac_cfe_step(&f, nan, &y1), FRAC_E_NONFINITE);
    assert_true(y1 == y);
    assert_int_equal(frac_cfe_reset(&f), FRAC_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cfe_equals_the_continued_fraction_convergent),
        cmocka_unit_test(test_cfe_converges_to_the_generating_function),
        cmocka_unit_test(test_cfe_tustin_n5_within_1deg_05db_over_its_mid_band),
        cmocka_unit_test(test_cfe_integer_orders_use_the_generating_function),
        cmocka_unit_test(test_cfe_rejects_bad_parameters_and_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
