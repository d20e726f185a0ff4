/* Pure delay z^-d in caller storage (frac/delayline.h). */
#include "frac_test.h"
#include "frac/delayline.h"

static void test_delayline_returns_input_d_samples_earlier(void **state)
{
    frac_real buf[7], y;
    frac_delayline dl;
    size_t d;
    int k;
    (void)state;
    for (d = 0; d <= 7; d++) {
        assert_int_equal(frac_delayline_init(&dl, buf, 7, d), FRAC_OK);
        for (k = 0; k < 40; k++) {
            assert_int_equal(frac_delayline_step(&dl, (frac_real)(k + 1), &y), FRAC_OK);
            assert_close(y, (k + 1 - (int)d) > 0 ? (double)(k + 1 - (int)d) : 0.0, 0.0);
        }
        assert_int_equal(frac_delayline_delay(&dl), d);
    }
}

static void test_delayline_zero_delay_needs_no_storage(void **state)
{
    frac_delayline dl;
    frac_real y, t;
    (void)state;
    assert_int_equal(frac_delayline_init(&dl, NULL, 0, 0), FRAC_OK);
    assert_int_equal(frac_delayline_step(&dl, FRAC_R(2.5), &y), FRAC_OK);
    assert_close(y, 2.5, 0.0);
    assert_int_equal(frac_delayline_tap(&dl, 0, &t), FRAC_OK);
    assert_close(t, 2.5, 0.0);
    assert_int_equal(frac_delayline_tap(&dl, 1, &t), FRAC_E_DIM);
}

static void test_delayline_taps_read_the_past_without_side_effects(void **state)
{
    frac_real buf[5], y, t;
    frac_delayline dl;
    size_t i;
    int k;
    (void)state;
    assert_int_equal(frac_delayline_init(&dl, buf, 5, 3), FRAC_OK);
    for (k = 1; k <= 12; k++) {
        assert_int_equal(frac_delayline_step(&dl, (frac_real)k, &y), FRAC_OK);
        for (i = 0; i <= 5; i++) {
            assert_int_equal(frac_delayline_tap(&dl, i, &t), FRAC_OK);
            assert_close(t, (k - (int)i) > 0 ? (double)(k - (int)i) : 0.0, 0.0);
        }
    }
    assert_int_equal(frac_delayline_tap(&dl, 6, &t), FRAC_E_DIM);
    /* tap 2 (u[k-2]) becomes tap d = 3 at the next step, so the overwrite comes out next */
    assert_int_equal(frac_delayline_set_tap(&dl, 2, FRAC_R(-1.0)), FRAC_OK);
    assert_int_equal(frac_delayline_step(&dl, FRAC_R(13.0), &y), FRAC_OK);
    assert_close(y, -1.0, 0.0);
}

static void test_delayline_reset_sets_a_steady_state(void **state)
{
    frac_real buf[4], y;
    frac_delayline dl;
    int k;
    (void)state;
    assert_int_equal(frac_delayline_init(&dl, buf, 4, 4), FRAC_OK);
    assert_int_equal(frac_delayline_reset(&dl, FRAC_R(3.0)), FRAC_OK);
    for (k = 0; k < 4; k++) {
        assert_int_equal(frac_delayline_step(&dl, FRAC_R(7.0), &y), FRAC_OK);
        assert_close(y, 3.0, 0.0);
    }
    assert_int_equal(frac_delayline_step(&dl, FRAC_R(7.0), &y), FRAC_OK);
    assert_close(y, 7.0, 0.0);
}

static void test_delayline_rejects_bad_input_and_keeps_state(void **state)
{
    frac_real buf[3], y, t;
    frac_delayline dl;
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero), inf = (frac_real)(1.0 / zero);
    (void)state;
    assert_int_equal(frac_delayline_init(NULL, buf, 3, 1), FRAC_E_NULL);
    assert_int_equal(frac_delayline_init(&dl, NULL, 3, 1), FRAC_E_NULL);
    assert_int_equal(frac_delayline_init(&dl, buf, 2, 3), FRAC_E_STORAGE);
    assert_int_equal(frac_delayline_step(&dl, FRAC_R(1.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_delayline_tap(&dl, 0, &t), FRAC_E_NOT_INIT);
    assert_int_equal(frac_delayline_reset(&dl, FRAC_R(0.0)), FRAC_E_NOT_INIT);
    assert_int_equal(frac_delayline_init(&dl, buf, 3, 1), FRAC_OK);
    assert_int_equal(frac_delayline_step(&dl, FRAC_R(1.0), &y), FRAC_OK);
    assert_int_equal(frac_delayline_step(&dl, FRAC_R(2.0), &y), FRAC_OK);
    assert_close(y, 1.0, 0.0);
    assert_int_equal(frac_delayline_step(&dl, nan, &y), FRAC_E_NONFINITE);
    assert_close(y, 1.0, 0.0);
    assert_int_equal(frac_delayline_step(&dl, inf, &y), FRAC_E_NONFINITE);
    assert_close(y, 1.0, 0.0);
    assert_int_equal(frac_delayline_step(&dl, FRAC_R(3.0), &y), FRAC_OK);
    assert_close(y, 2.0, 0.0);
    assert_int_equal(frac_delayline_step(&dl, FRAC_R(1.0), NULL), FRAC_E_NULL);
    assert_int_equal(frac_delayline_reset(&dl, inf), FRAC_E_NONFINITE);
    assert_int_equal(frac_delayline_set_tap(&dl, 1, nan), FRAC_E_NONFINITE);
    assert_int_equal(frac_delayline_set_tap(&dl, 4, FRAC_R(0.0)), FRAC_E_DIM);
    assert_int_equal(frac_delayline_tap(&dl, 0, NULL), FRAC_E_NULL);
    assert_int_equal(frac_delayline_delay(NULL), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_delayline_returns_input_d_samples_earlier),
        cmocka_unit_test(test_delayline_zero_delay_needs_no_storage),
        cmocka_unit_test(test_delayline_taps_read_the_past_without_side_effects),
        cmocka_unit_test(test_delayline_reset_sets_a_steady_state),
        cmocka_unit_test(test_delayline_rejects_bad_input_and_keeps_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
