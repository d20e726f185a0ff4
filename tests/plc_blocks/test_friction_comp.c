/* FrictionComp block (FracCtrl.fun): bit-identical to frac_friction, Table
 * 8.6 parameters, error paths. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "frac/friction.h"

#include <string.h>

static void table_8_6(FrictionCompParType *p)
{
    memset(p, 0, sizeof *p);
    p->Model = fracFRICTION_LINEAR;
    p->K = 60.0f;
    p->B1 = 3.04f;
    p->B0 = 7.684f;
}

static void test_friction_comp_matches_frac_friction_bit_for_bit(void **state)
{
    struct FrictionComp b;
    frac_friction ref;
    frac_friction_params fp;
    int model, k;
    (void)state;
    for (model = 0; model < 3; model++) {
        memset(&b, 0, sizeof b);
        table_8_6(&b.Parameters);
        b.Parameters.Model = (FracFrictionModelEnum)model;
        b.Parameters.B1n = 2.835f;
        b.Parameters.B1p = 3.341f;
        b.Parameters.B0n = 7.607f;
        b.Parameters.B0p = 7.607f;
        b.Parameters.B1s = 7.684f;
        b.Parameters.B2s = 10.66f;
        b.Parameters.B3s = 3.041f;
        b.Parameters.Vs = 0.001f;
        b.Parameters.Delta = 1.0f;
        b.Enable = 1;
        memset(&fp, 0, sizeof fp);
        fp.model = model;
        fp.k = (frac_real)b.Parameters.K;
        fp.b1 = (frac_real)b.Parameters.B1;
        fp.b0 = (frac_real)b.Parameters.B0;
        fp.b1n = (frac_real)b.Parameters.B1n;
        fp.b1p = (frac_real)b.Parameters.B1p;
        fp.b0n = (frac_real)b.Parameters.B0n;
        fp.b0p = (frac_real)b.Parameters.B0p;
        fp.b1s = (frac_real)b.Parameters.B1s;
        fp.b2s = (frac_real)b.Parameters.B2s;
        fp.b3s = (frac_real)b.Parameters.B3s;
        fp.v_s = (frac_real)b.Parameters.Vs;
        fp.delta = (frac_real)b.Parameters.Delta;
        assert_int_equal(frac_friction_init(&ref, &fp), FRAC_OK);
        for (k = -100; k <= 100; k++) {
            frac_real tau;
            b.Velocity = 0.0157f * (REAL)k;
            assert_int_equal(frac_friction_eval(&ref, (frac_real)b.Velocity, &tau), FRAC_OK);
            FrictionComp(&b);
            assert_true(b.Torque == (REAL)tau);
            assert_true(b.Valid);
            assert_int_equal(b.StatusID, fracSTAT_OK);
        }
    }
}

static void test_friction_comp_table_8_6_at_cruise_speed(void **state)
{
    struct FrictionComp b;
    (void)state;
    memset(&b, 0, sizeof b);
    table_8_6(&b.Parameters);
    b.Enable = 1;
    b.Velocity = 1.5707963f; /* Table 8.5: cruise velocity pi/2 rad/s */
    FrictionComp(&b);
    /* 3.04 * pi/2 + 7.684 * tanh(60 pi/2) = 12.459 Nm (notes 9.2: ~12.5 Nm) */
    assert_close(b.Torque, 3.04 * 1.5707963 + 7.684, 1e-4);
}

static void test_friction_comp_error_paths(void **state)
{
    struct FrictionComp b;
    REAL held;
    (void)state;
    memset(&b, 0, sizeof b);
    table_8_6(&b.Parameters);
    b.Parameters.K = 0.0f;
    b.Enable = 1;
    FrictionComp(&b);
    assert_true(b.Error);
    assert_int_equal(b.StatusID, fracERR_PARAM);
    assert_true(b.Torque == 0.0f);
    /* Update with a valid set clears the error */
    b.Parameters.K = 60.0f;
    b.Update = 1;
    b.Velocity = 0.2f;
    FrictionComp(&b);
    assert_false(b.Error);
    assert_true(b.Valid);
    held = b.Torque;
    b.Velocity = (REAL)INFINITY;
    FrictionComp(&b);
    assert_true(b.Error);
    assert_int_equal(b.StatusID, fracERR_NONFINITE);
    assert_true(b.Torque == held);
    b.Enable = 0;
    FrictionComp(&b);
    assert_int_equal(b.StatusID, fracSTAT_DISABLED);
    assert_true(b.Torque == 0.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_friction_comp_matches_frac_friction_bit_for_bit),
        cmocka_unit_test(test_friction_comp_table_8_6_at_cruise_speed),
        cmocka_unit_test(test_friction_comp_error_paths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
