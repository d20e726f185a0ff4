/* Status strings, version and the portable finite test of frac_types.h. */
#include "frac_test.h"
#include <string.h>
#include "frac/frac_types.h"

static void test_every_status_has_a_distinct_name(void **state)
{
    int codes[] = {FRAC_OK, FRAC_W_CLAMPED, FRAC_W_EXTRAPOLATED, FRAC_W_MEAS_SKIPPED, FRAC_W_COV_RESET,
                   FRAC_W_SATURATED, FRAC_E_NULL, FRAC_E_NONFINITE, FRAC_E_NOT_INIT, FRAC_E_STORAGE,
                   FRAC_E_DIM, FRAC_E_ORDER, FRAC_E_BAND, FRAC_E_TS, FRAC_E_GAIN, FRAC_E_LIMITS,
                   FRAC_E_PARAM, FRAC_E_NOT_MONOTONE, FRAC_E_NOT_POSDEF, FRAC_E_UNSTABLE, FRAC_E_NUMERIC,
                   FRAC_E_MAGIC, FRAC_E_VERSION, FRAC_E_CRC, FRAC_E_SIZE, FRAC_E_FORMAT, FRAC_E_NOT_FOUND};
    size_t n = sizeof codes / sizeof codes[0], i, j;
    (void)state;
    for (i = 0; i < n; i++) {
        assert_string_not_equal(frac_status_str(codes[i]), "unknown status");
        for (j = 0; j < i; j++) assert_string_not_equal(frac_status_str(codes[i]), frac_status_str(codes[j]));
    }
    assert_string_equal(frac_status_str(12345), "unknown status");
}

static void test_isfinite_rejects_nan_and_inf(void **state)
{
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero), inf = (frac_real)(1.0 / zero), x = FRAC_R(1.5);
    (void)state;
    assert_false(FRAC_ISFINITE(nan));
    assert_false(FRAC_ISFINITE(inf));
    assert_false(FRAC_ISFINITE(-inf));
    assert_true(FRAC_ISFINITE(x));
    assert_true(FRAC_ISFINITE(FRAC_REAL_MAX));
}

static void test_version_is_semver(void **state)
{
    int a, b, c;
    (void)state;
    assert_int_equal(sscanf(frac_version(), "%d.%d.%d", &a, &b, &c), 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_status_has_a_distinct_name),
        cmocka_unit_test(test_isfinite_rejects_nan_and_inf),
        cmocka_unit_test(test_version_is_semver),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
