/* Friction models, seed 004 (5.2)-(5.4) with tanh(k v) smoothing (frac/friction.h). */
#include <string.h>
#include "frac_test.h"
#include "frac/friction.h"

#define PI 3.14159265358979323846

static frac_friction_params zero_params(int model)
{
    frac_friction_params p;
    memset(&p, 0, sizeof p);
    p.model = model;
    p.k = FRAC_R(60.0);
    return p;
}

static void test_friction_linear_table_8_6_gives_12_459_nm_at_cruise_speed(void **state)
{
    frac_friction f;
    frac_friction_params p = zero_params(FRAC_FRICTION_LINEAR);
    frac_real tau;
    (void)state;
    p.b1 = FRAC_R(3.04);
    p.b0 = FRAC_R(7.684);
    assert_int_equal(frac_friction_init(&f, &p), FRAC_OK);
    assert_int_equal(frac_friction_eval(&f, FRAC_R(PI / 2.0), &tau), FRAC_OK);
    assert_close(tau, 12.459, 5e-4);
    assert_close(tau, 3.04 * PI / 2.0 + 7.684 * tanh(60.0 * PI / 2.0), 1e-5);
    /* odd in v, zero at rest, smooth through zero: slope b1 + b0 k */
    frac_friction_eval(&f, FRAC_R(-PI / 2.0), &tau);
    assert_close(tau, -12.459, 5e-4);
    frac_friction_eval(&f, FRAC_R(0.0), &tau);
    assert_close(tau, 0.0, 0.0);
    frac_friction_eval(&f, FRAC_R(1e-6), &tau);
    assert_close(tau / 1e-6, 3.04 + 7.684 * 60.0, 1e-2);
}

static void test_friction_asymmetric_uses_side_parameters(void **state)
{
    frac_friction f;
    frac_friction_params p = zero_params(FRAC_FRICTION_ASYMMETRIC);
    frac_real tau;
    (void)state;
    p.b1n = FRAC_R(2.835);
    p.b1p = FRAC_R(3.341);
    p.b0n = FRAC_R(7.0);
    p.b0p = FRAC_R(7.607);
    assert_int_equal(frac_friction_init(&f, &p), FRAC_OK);
    frac_friction_eval(&f, FRAC_R(1.0), &tau);
    assert_close(tau, 3.341 + 7.607, 1e-5);
    frac_friction_eval(&f, FRAC_R(-1.0), &tau);
    assert_close(tau, -2.835 - 7.0, 1e-5);
    /* equal sides reduce to the linear model */
    p.b1n = p.b1p = FRAC_R(3.04);
    p.b0n = p.b0p = FRAC_R(7.684);
    frac_friction_init(&f, &p);
    frac_friction_eval(&f, FRAC_R(0.01), &tau);
    assert_close(tau, 3.04 * 0.01 + 7.684 * tanh(0.6), 1e-5);
    frac_friction_eval(&f, FRAC_R(-0.01), &tau);
    assert_close(tau, -3.04 * 0.01 - 7.684 * tanh(0.6), 1e-5);
}

static void test_friction_stribeck_starts_at_static_level_and_decays_to_coulomb(void **state)
{
    frac_friction f;
    frac_friction_params p = zero_params(FRAC_FRICTION_STRIBECK);
    frac_real tau;
    (void)state;
    p.b1s = FRAC_R(7.684);
    p.b2s = FRAC_R(10.66);
    p.b3s = FRAC_R(3.041);
    p.v_s = FRAC_R(0.1);
    p.delta = FRAC_R(2.0);
    p.k = FRAC_R(1000.0);
    assert_int_equal(frac_friction_init(&f, &p), FRAC_OK);
    frac_friction_eval(&f, FRAC_R(0.01), &tau);
    assert_close(tau, (7.684 + 2.976 * exp(-0.01)) * tanh(10.0) + 3.041 * 0.01, 1e-5);
    frac_friction_eval(&f, FRAC_R(2.0), &tau);
    assert_close(tau, 7.684 + 3.041 * 2.0, 1e-5);
    frac_friction_eval(&f, FRAC_R(-2.0), &tau);
    assert_close(tau, -7.684 - 3.041 * 2.0, 1e-5);
}

static void test_friction_rejects_bad_parameters_and_holds_output_on_nan(void **state)
{
    frac_friction f;
    frac_friction_params p = zero_params(FRAC_FRICTION_LINEAR);
    frac_real tau;
    (void)state;
    p.k = FRAC_R(0.0);
    assert_int_equal(frac_friction_init(&f, &p), FRAC_E_PARAM);
    assert_int_equal(frac_friction_eval(&f, FRAC_R(1.0), &tau), FRAC_E_NOT_INIT);
    p.k = FRAC_R(60.0);
    p.b0 = (frac_real)INFINITY;
    assert_int_equal(frac_friction_init(&f, &p), FRAC_E_PARAM);
    p = zero_params(FRAC_FRICTION_STRIBECK);
    assert_int_equal(frac_friction_init(&f, &p), FRAC_E_PARAM); /* v_s = 0 */
    p.v_s = FRAC_R(0.1);
    assert_int_equal(frac_friction_init(&f, &p), FRAC_E_PARAM); /* delta = 0 */
    p = zero_params(FRAC_FRICTION_ASYMMETRIC);
    p.b1p = (frac_real)NAN;
    assert_int_equal(frac_friction_init(&f, &p), FRAC_E_PARAM);
    p = zero_params(7);
    assert_int_equal(frac_friction_init(&f, &p), FRAC_E_PARAM);
    assert_int_equal(frac_friction_init(NULL, &p), FRAC_E_NULL);
    p = zero_params(FRAC_FRICTION_LINEAR);
    p.b1 = FRAC_R(2.0);
    assert_int_equal(frac_friction_init(&f, &p), FRAC_OK);
    frac_friction_eval(&f, FRAC_R(1.5), &tau);
    assert_int_equal(frac_friction_eval(&f, (frac_real)NAN, &tau), FRAC_E_NONFINITE);
    assert_close(tau, 3.0, 0.0);
    assert_int_equal(frac_friction_eval(&f, FRAC_R(1.0), NULL), FRAC_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_friction_linear_table_8_6_gives_12_459_nm_at_cruise_speed),
        cmocka_unit_test(test_friction_asymmetric_uses_side_parameters),
        cmocka_unit_test(test_friction_stribeck_starts_at_static_level_and_decays_to_coulomb),
        cmocka_unit_test(test_friction_rejects_bad_parameters_and_holds_output_on_nan),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
