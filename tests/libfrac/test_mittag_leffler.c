/* Mittag-Leffler function E_{a,b}(z) for real z (frac/mittag_leffler.h). */
#include "frac_test.h"
#include "frac/mittag_leffler.h"
#include "fixtures/mittag_leffler_reference.h"

static double ml(double a, double b, double z)
{
    frac_real e = 0;
    int st = frac_mittag_leffler((frac_real)a, (frac_real)b, (frac_real)z, &e);
    if (st != FRAC_OK) fail_msg("E_{%g,%g}(%g): status %d", a, b, z, st);
    return e;
}

static void test_mittag_leffler_matches_40_digit_reference(void **state)
{
    size_t i, n = sizeof ML_REFS / sizeof ML_REFS[0];
    double worst = 0.0;
    (void)state;
    for (i = 0; i < n; i++) {
        const ml_ref *r = &ML_REFS[i];
        double got = ml(r->a, r->b, r->z), err = fabs(got - r->e);
        /* relative 1e-12, absolute 1e-14 where |E| < 1e-2 */
        double tol = fabs(r->e) < 1e-2 ? 1e-14 : 1e-12 * fabs(r->e);
        if (err / (fabs(r->e) < 1e-2 ? 1e-2 : fabs(r->e)) > worst) worst = err / (fabs(r->e) < 1e-2 ? 1e-2 : fabs(r->e));
        if (!(err <= tol)) fail_msg("E_{%g,%g}(%g) = %.17g, reference %.17g", r->a, r->b, r->z, got, r->e);
    }
    printf("  %lu reference values, worst scaled error %.2e\n", (unsigned long)n, worst);
}

static void test_mittag_leffler_closed_forms(void **state)
{
    double x;
    (void)state;
    for (x = 0.05; x < 60.0; x *= 1.3) {
        /* E_1(z) = e^z, E_{1,2}(z) = (e^z - 1)/z */
        assert_rel(ml(1.0, 1.0, -x), exp(-x), 1e-12 + (x > 20 ? 1e-14 / exp(-x) : 0.0));
        assert_rel(ml(1.0, 2.0, -x), (1.0 - exp(-x)) / x, 1e-12);
        assert_rel(ml(1.0, 1.0, x / 10.0), exp(x / 10.0), 1e-13);
        /* E_2(-x^2) = cos x, E_{2,2}(-x^2) = sin(x)/x */
        assert_close(ml(2.0, 1.0, -x * x), cos(x), 1e-12);
        assert_close(ml(2.0, 2.0, -x * x), sin(x) / x, 1e-12);
        /* E_{1/2}(-x) = e^{x^2} erfc(x), E_{1/2}(x) = e^{x^2} erfc(-x) */
        if (x < 25.0) assert_rel(ml(0.5, 1.0, -x), exp(x * x) * erfc(x), 1e-11);
        if (x < 5.0) assert_rel(ml(0.5, 1.0, x), exp(x * x) * erfc(-x), 1e-12);
    }
    /* large negative argument: E_{a,b}(z) ~ -sum_{k=1}^{3} z^-k / Gamma(b - a k) for a < 2 */
    {
        double a = 0.88, z = -1e6;
        double asym = -1.0 / (z * tgamma(1.0 - a)) - 1.0 / (z * z * tgamma(1.0 - 2 * a)) - 1.0 / (z * z * z * tgamma(1.0 - 3 * a));
        assert_rel(ml(a, 1.0, z), asym, 1e-10);
    }
    assert_close(ml(0.7, 1.3, 0.0), 1.0 / tgamma(1.3), 1e-15);
    assert_close(ml(0.7, 0.0, 0.0), 0.0, 0.0);
}

/* the step response of 1/(1 + T s^l) rises from 0 to 1: 1 - E_l(-t^l/T) */
static void test_mittag_leffler_step_response_shape(void **state)
{
    double t;
    (void)state;
    for (t = 0.0; t < 50.0; t += 0.25) {
        double y = 1.0 - ml(0.5, 1.0, -pow(t, 0.5));
        assert_true(y >= -1e-15 && y < 1.0);
    }
    /* lightly damped l = 1.92: overshoot close to that of the undamped 1 - cos t */
    assert_true(1.0 - ml(1.92, 1.0, -pow(M_PI, 1.92)) > 1.8);
}

static void test_mittag_leffler_rejects_bad_input(void **state)
{
    frac_real e = FRAC_R(7.0);
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero), inf = (frac_real)(1.0 / zero);
    (void)state;
    assert_int_equal(frac_mittag_leffler(FRAC_R(0.5), FRAC_R(1.0), FRAC_R(1.0), NULL), FRAC_E_NULL);
    assert_int_equal(frac_mittag_leffler(FRAC_R(0.0), FRAC_R(1.0), FRAC_R(1.0), &e), FRAC_E_PARAM);
    assert_int_equal(frac_mittag_leffler(FRAC_R(2.5), FRAC_R(1.0), FRAC_R(1.0), &e), FRAC_E_PARAM);
    assert_int_equal(frac_mittag_leffler(nan, FRAC_R(1.0), FRAC_R(1.0), &e), FRAC_E_PARAM);
    assert_int_equal(frac_mittag_leffler(FRAC_R(0.5), inf, FRAC_R(1.0), &e), FRAC_E_PARAM);
    assert_int_equal(frac_mittag_leffler(FRAC_R(0.5), FRAC_R(1.0), nan, &e), FRAC_E_NONFINITE);
    assert_int_equal(frac_mittag_leffler(FRAC_R(0.5), FRAC_R(1.0), -inf, &e), FRAC_E_NONFINITE);
    /* e^{z^{1/a}} overflows */
    assert_int_equal(frac_mittag_leffler(FRAC_R(0.5), FRAC_R(1.0), FRAC_R(100.0), &e), FRAC_E_NUMERIC);
    assert_close(e, 7.0, 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mittag_leffler_matches_40_digit_reference),
        cmocka_unit_test(test_mittag_leffler_closed_forms),
        cmocka_unit_test(test_mittag_leffler_step_response_shape),
        cmocka_unit_test(test_mittag_leffler_rejects_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
