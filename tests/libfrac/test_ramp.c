/* Bounded-rate ramp (frac/ramp.h): the Watchdog fault reaction's arithmetic. */
#include "frac_test.h"
#include "frac/ramp.h"

static void test_ramp_moves_by_rate_times_ts_and_lands_on_target(void **state)
{
    frac_real y = FRAC_R(10.0);
    int k;
    (void)state;
    /* 1000 Nm/s at 1.2 ms: 1.2 Nm per cycle, 10 Nm reach zero in 9 cycles. */
    for (k = 0; k < 8; k++) {
        assert_int_equal(frac_ramp_step(y, FRAC_R(0.0), FRAC_R(1000.0), FRAC_R(1.2e-3), &y), FRAC_OK);
        assert_close(y, 10.0 - 1.2 * (k + 1), 1e-12);
    }
    assert_int_equal(frac_ramp_step(y, FRAC_R(0.0), FRAC_R(1000.0), FRAC_R(1.2e-3), &y), FRAC_OK);
    assert_true(y == FRAC_R(0.0));
    assert_int_equal(frac_ramp_step(FRAC_R(-0.5), FRAC_R(0.0), FRAC_R(100.0), FRAC_R(1e-3), &y), FRAC_OK);
    assert_close(y, -0.4, 1e-12);
}

static void test_ramp_rejects_bad_input_and_leaves_output(void **state)
{
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero), y = FRAC_R(3.0);
    (void)state;
    assert_int_equal(frac_ramp_step(FRAC_R(1.0), FRAC_R(0.0), FRAC_R(1.0), FRAC_R(1.0), NULL), FRAC_E_NULL);
    assert_int_equal(frac_ramp_step(FRAC_R(1.0), FRAC_R(0.0), FRAC_R(0.0), FRAC_R(1.0), &y), FRAC_E_PARAM);
    assert_int_equal(frac_ramp_step(FRAC_R(1.0), FRAC_R(0.0), FRAC_R(1.0), -FRAC_R(1.0), &y), FRAC_E_PARAM);
    assert_int_equal(frac_ramp_step(FRAC_R(1.0), FRAC_R(0.0), nan, FRAC_R(1.0), &y), FRAC_E_PARAM);
    assert_int_equal(frac_ramp_step(nan, FRAC_R(0.0), FRAC_R(1.0), FRAC_R(1.0), &y), FRAC_E_NONFINITE);
    assert_int_equal(frac_ramp_step(FRAC_R(1.0), nan, FRAC_R(1.0), FRAC_R(1.0), &y), FRAC_E_NONFINITE);
    assert_true(y == FRAC_R(3.0));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ramp_moves_by_rate_times_ts_and_lands_on_target),
        cmocka_unit_test(test_ramp_rejects_bad_input_and_leaves_output),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
