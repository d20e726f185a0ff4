/* Watchdog block (FracCtrl.fun): stale-sensor detection, torque ramp to
 * zero, Acknowledge, Enable/Update edges, parameter errors. */
#include "frac_test.h"
#include "FracCtrl.h"

#include <string.h>

static void setup_block(struct Watchdog *wd)
{
    memset(wd, 0, sizeof *wd);
    wd->Parameters.MaxStaleCycles = 3;
    wd->Parameters.RampRate = 1000.0f;   /* Nm/s */
    wd->Parameters.CycleTime = 0.0012f;  /* Cyclic #1, Table 2.3 */
    wd->Enable = 1;
}

static void test_watchdog_passes_torque_while_sensor_fresh(void **state)
{
    struct Watchdog wd;
    UDINT k;
    (void)state;
    setup_block(&wd);
    for (k = 0; k < 20; k++) {
        wd.SampleCounter = k;
        wd.TorqueIn = 0.5f * (REAL)k;
        Watchdog(&wd);
        assert_true(wd.Active);
        assert_true(wd.Busy);
        assert_false(wd.Error);
        assert_int_equal(wd.StatusID, fracSTAT_OK);
        assert_true(wd.TorqueOut == wd.TorqueIn);
    }
}

static void test_watchdog_stale_sensor_ramps_torque_to_zero(void **state)
{
    struct Watchdog wd;
    int k;
    REAL prev;
    (void)state;
    setup_block(&wd);
    wd.TorqueIn = 6.0f;
    wd.SampleCounter = 7;
    Watchdog(&wd);
    /* counter frozen: stale after more than 3 cycles without a new sample */
    for (k = 1; k <= 3; k++) {
        Watchdog(&wd);
        assert_false(wd.Stale);
        assert_true(wd.TorqueOut == 6.0f);
    }
    Watchdog(&wd);
    assert_true(wd.Stale);
    assert_true(wd.Error);
    assert_false(wd.Active);
    assert_int_equal(wd.StatusID, fracERR_SENSOR_STALE);
    assert_true(wd.RampActive);
    assert_close(wd.TorqueOut, 6.0 - 1.2, 1e-5); /* 1000 Nm/s x 1.2 ms per cycle */
    prev = wd.TorqueOut;
    for (k = 0; k < 10; k++) {
        Watchdog(&wd);
        assert_true(wd.TorqueOut <= prev && wd.TorqueOut >= 0.0f);
        prev = wd.TorqueOut;
    }
    assert_true(wd.TorqueOut == 0.0f);
    assert_false(wd.RampActive);
    /* the sensor comes back: the fault stays latched until Acknowledge */
    wd.SampleCounter = 8;
    Watchdog(&wd);
    assert_true(wd.Error);
    assert_true(wd.TorqueOut == 0.0f);
    wd.SampleCounter = 9;
    wd.Acknowledge = 1;
    Watchdog(&wd);
    assert_false(wd.Error);
    assert_true(wd.Active);
    assert_int_equal(wd.StatusID, fracSTAT_OK);
    assert_true(wd.TorqueOut == 6.0f);
}

static void test_watchdog_negative_torque_ramps_up_to_zero(void **state)
{
    struct Watchdog wd;
    int k;
    (void)state;
    setup_block(&wd);
    wd.TorqueIn = -2.0f;
    for (k = 0; k < 5; k++) {
        Watchdog(&wd);
    }
    assert_true(wd.Stale);
    assert_close(wd.TorqueOut, -0.8, 1e-5);
    Watchdog(&wd);
    assert_true(wd.TorqueOut == 0.0f);
}

static void test_watchdog_nan_torque_holds_last_finite_and_ramps(void **state)
{
    struct Watchdog wd;
    (void)state;
    setup_block(&wd);
    wd.SampleCounter = 1;
    wd.TorqueIn = 3.0f;
    Watchdog(&wd);
    wd.SampleCounter = 2;
    wd.TorqueIn = (REAL)NAN;
    Watchdog(&wd);
    assert_true(wd.Error);
    assert_int_equal(wd.StatusID, fracERR_TORQUE_NONFINITE);
    assert_close(wd.TorqueOut, 3.0 - 1.2, 1e-5);
    /* Acknowledge while the torque is still NaN does not clear the fault */
    wd.SampleCounter = 3;
    wd.Acknowledge = 1;
    Watchdog(&wd);
    assert_true(wd.Error);
}

static void test_watchdog_rejects_out_of_range_parameters_at_enable(void **state)
{
    struct Watchdog wd;
    (void)state;
    setup_block(&wd);
    wd.Parameters.MaxStaleCycles = 0;
    wd.TorqueIn = 4.0f;
    Watchdog(&wd);
    assert_true(wd.Error);
    assert_false(wd.Active);
    assert_false(wd.Busy);
    assert_int_equal(wd.StatusID, fracERR_PARAM);
    assert_true(wd.TorqueOut == 0.0f);
    setup_block(&wd);
    wd.Parameters.RampRate = (REAL)NAN;
    Watchdog(&wd);
    assert_int_equal(wd.StatusID, fracERR_PARAM);
    setup_block(&wd);
    wd.Parameters.CycleTime = -0.0012f;
    Watchdog(&wd);
    assert_int_equal(wd.StatusID, fracERR_PARAM);
}

static void test_watchdog_update_validates_before_replacing(void **state)
{
    struct Watchdog wd;
    UDINT k;
    (void)state;
    setup_block(&wd);
    wd.TorqueIn = 1.0f;
    Watchdog(&wd);
    /* a bad Update is reported, the block keeps running on the old set */
    wd.Parameters.MaxStaleCycles = 0;
    wd.Update = 1;
    wd.SampleCounter = 1;
    Watchdog(&wd);
    assert_true(wd.Error);
    assert_true(wd.Active);
    assert_int_equal(wd.StatusID, fracERR_PARAM);
    assert_true(wd.TorqueOut == 1.0f);
    /* Update held high is not an edge; a new edge with a valid set clears it */
    wd.Parameters.MaxStaleCycles = 10;
    wd.SampleCounter = 2;
    Watchdog(&wd);
    assert_true(wd.Error);
    wd.Update = 0;
    wd.SampleCounter = 3;
    Watchdog(&wd);
    wd.Update = 1;
    wd.SampleCounter = 4;
    Watchdog(&wd);
    assert_false(wd.Error);
    /* the new limit (10) is in effect: 10 frozen cycles are not stale yet */
    for (k = 0; k < 10; k++) {
        Watchdog(&wd);
    }
    assert_false(wd.Stale);
    Watchdog(&wd);
    assert_true(wd.Stale);
}

static void test_watchdog_enable_edges_reset_outputs_and_fault(void **state)
{
    struct Watchdog wd;
    int k;
    (void)state;
    setup_block(&wd);
    wd.TorqueIn = 5.0f;
    for (k = 0; k < 6; k++) {
        Watchdog(&wd);
    }
    assert_true(wd.Error);
    wd.Enable = 0;
    Watchdog(&wd);
    assert_false(wd.Active);
    assert_false(wd.Busy);
    assert_false(wd.Error);
    assert_int_equal(wd.StatusID, fracSTAT_DISABLED);
    assert_true(wd.TorqueOut == 0.0f);
    /* rising edge: fresh start, the frozen counter is the new reference */
    wd.Enable = 1;
    Watchdog(&wd);
    assert_true(wd.Active);
    assert_false(wd.Error);
    assert_true(wd.TorqueOut == 5.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_watchdog_passes_torque_while_sensor_fresh),
        cmocka_unit_test(test_watchdog_stale_sensor_ramps_torque_to_zero),
        cmocka_unit_test(test_watchdog_negative_torque_ramps_up_to_zero),
        cmocka_unit_test(test_watchdog_nan_torque_holds_last_finite_and_ramps),
        cmocka_unit_test(test_watchdog_rejects_out_of_range_parameters_at_enable),
        cmocka_unit_test(test_watchdog_update_validates_before_replacing),
        cmocka_unit_test(test_watchdog_enable_edges_reset_outputs_and_fault),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
