/* LUT1D and LUT2D blocks (FracCtrl.fun): bit-identical to frac_lut1/frac_lut2
 * on the same inputs, Enable edges, Update, NaN input, bad parameters. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "frac/lut.h"

#include <string.h>

static frac_real xs[6] = {0.0, 0.1, 0.3, 0.35, 0.8, 1.0};
static frac_real ys[6] = {0.0, 0.2, 0.25, 0.9, 1.5, 1.6};
static frac_real slopes_blk[6], slopes_ref[6];

static void lut1_params(LUT1DParType *p, FracInterpEnum interp)
{
    memset(p, 0, sizeof *p);
    p->pX = xs;
    p->pY = ys;
    p->N = 6;
    p->Interpolation = interp;
    p->Range = fracRANGE_CLAMP;
    p->pSlopes = slopes_blk;
}

static void test_lut1d_matches_frac_lut1_bit_for_bit(void **state)
{
    struct LUT1D b;
    frac_lut1 ref;
    int interp, k;
    (void)state;
    for (interp = 0; interp < 2; interp++) {
        memset(&b, 0, sizeof b);
        lut1_params(&b.Parameters, (FracInterpEnum)interp);
        b.Enable = 1;
        assert_int_equal(frac_lut1_init(&ref, xs, ys, 6, interp, FRAC_LUT_CLAMP, slopes_ref), FRAC_OK);
        for (k = -20; k <= 140; k++) {
            REAL x = (REAL)k * 0.00731f;
            frac_real y;
            int st = frac_lut1_eval(&ref, (frac_real)x, &y);
            b.X = x;
            LUT1D(&b);
            assert_true(b.Y == (REAL)y);
            assert_true(b.Valid);
            assert_false(b.Error);
            assert_int_equal(b.StatusID, st == FRAC_W_CLAMPED ? fracWRN_CLAMPED : fracSTAT_OK);
        }
    }
}

static void test_lut1d_uniform_grid_without_breakpoints(void **state)
{
    struct LUT1D b;
    frac_lut1 ref;
    frac_real y;
    (void)state;
    memset(&b, 0, sizeof b);
    b.Parameters.X0 = -1.0;
    b.Parameters.Dx = 0.4;
    b.Parameters.pY = ys;
    b.Parameters.N = 6;
    b.Parameters.Range = fracRANGE_EXTRAPOLATE;
    b.Enable = 1;
    b.X = 1.37f;
    LUT1D(&b);
    assert_int_equal(frac_lut1_init_uniform(&ref, FRAC_R(-1.0), FRAC_R(0.4), ys, 6, FRAC_LUT_LINEAR,
                                            FRAC_LUT_EXTRAPOLATE, NULL), FRAC_OK);
    assert_int_equal(frac_lut1_eval(&ref, (frac_real)1.37f, &y), FRAC_W_EXTRAPOLATED);
    assert_true(b.Y == (REAL)y);
    assert_int_equal(b.StatusID, fracWRN_LIBFRAC + FRAC_W_EXTRAPOLATED);
    assert_true(b.Valid);
}

static void test_lut1d_nan_input_holds_last_output_and_recovers(void **state)
{
    struct LUT1D b;
    REAL held;
    (void)state;
    memset(&b, 0, sizeof b);
    lut1_params(&b.Parameters, fracINTERP_LINEAR);
    b.Enable = 1;
    b.X = 0.5f;
    LUT1D(&b);
    held = b.Y;
    b.X = (REAL)NAN;
    LUT1D(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_int_equal(b.StatusID, fracERR_NONFINITE);
    assert_true(b.Y == held);
    b.X = 0.5f;
    LUT1D(&b);
    assert_false(b.Error);
    assert_true(b.Valid);
    assert_true(b.Y == held);
}

static void test_lut1d_bad_tables_are_rejected_with_their_status(void **state)
{
    static frac_real bad_x[3] = {0.0, 0.5, 0.5};
    struct LUT1D b;
    (void)state;
    memset(&b, 0, sizeof b);
    lut1_params(&b.Parameters, fracINTERP_LINEAR);
    b.Parameters.N = 1;
    b.Enable = 1;
    LUT1D(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_false(b.Busy);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_DIM);
    assert_true(b.Y == 0.0f);

    memset(&b, 0, sizeof b);
    lut1_params(&b.Parameters, fracINTERP_LINEAR);
    b.Parameters.pX = bad_x;
    b.Parameters.N = 3;
    b.Enable = 1;
    LUT1D(&b);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_NOT_MONOTONE);

    memset(&b, 0, sizeof b);
    lut1_params(&b.Parameters, fracINTERP_LINEAR);
    b.Parameters.pY = NULL;
    b.Enable = 1;
    LUT1D(&b);
    assert_int_equal(b.StatusID, fracERR_NULL);

    memset(&b, 0, sizeof b);
    lut1_params(&b.Parameters, (FracInterpEnum)7);
    b.Enable = 1;
    LUT1D(&b);
    assert_int_equal(b.StatusID, fracERR_PARAM);
}

static void test_lut1d_update_swaps_table_only_when_valid(void **state)
{
    static frac_real y2[6] = {10, 20, 30, 40, 50, 60};
    struct LUT1D b;
    (void)state;
    memset(&b, 0, sizeof b);
    lut1_params(&b.Parameters, fracINTERP_LINEAR);
    b.Enable = 1;
    b.X = 0.0f;
    LUT1D(&b);
    assert_true(b.Y == 0.0f);
    /* bad Update (N = 1): reported, the old table stays in effect */
    b.Parameters.N = 1;
    b.Parameters.pY = y2;
    b.Update = 1;
    LUT1D(&b);
    assert_true(b.Error);
    assert_true(b.Valid);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_DIM);
    assert_true(b.Y == 0.0f);
    /* valid Update on the next rising edge */
    b.Update = 0;
    LUT1D(&b);
    b.Parameters.N = 6;
    b.Update = 1;
    LUT1D(&b);
    assert_false(b.Error);
    assert_int_equal(b.StatusID, fracSTAT_OK);
    assert_true(b.Y == 10.0f);
    /* Update without Enable does nothing; Enable FALSE resets */
    b.Enable = 0;
    LUT1D(&b);
    assert_int_equal(b.StatusID, fracSTAT_DISABLED);
    assert_false(b.Valid || b.Busy || b.Error);
    assert_true(b.Y == 0.0f);
    /* rising Enable edge loads the current Parameters */
    b.Parameters.pY = ys;
    b.X = 1.0f;
    b.Enable = 1;
    LUT1D(&b);
    assert_true(b.Valid);
    assert_true(b.Y == (REAL)ys[5]);
}

static void test_lut2d_matches_frac_lut2_bit_for_bit(void **state)
{
    static frac_real x1[3] = {0.0, 1.0, 3.0};
    static frac_real z[12];
    struct LUT2D b;
    frac_lut2 ref;
    frac_lut_axis_params a1, a2;
    int i, j;
    (void)state;
    for (i = 0; i < 12; i++) {
        z[i] = FRAC_SIN((frac_real)i);
    }
    memset(&b, 0, sizeof b);
    b.Parameters.pX1 = x1;
    b.Parameters.N1 = 3;
    b.Parameters.X20 = -0.5;
    b.Parameters.Dx2 = 0.25;
    b.Parameters.N2 = 4;
    b.Parameters.pZ = z;
    b.Parameters.Range = fracRANGE_CLAMP;
    b.Enable = 1;
    a1.x = x1; a1.n = 3; a1.x0 = 0; a1.h = 0;
    a2.x = NULL; a2.n = 4; a2.x0 = FRAC_R(-0.5); a2.h = FRAC_R(0.25);
    assert_int_equal(frac_lut2_init(&ref, &a1, &a2, z, FRAC_LUT_CLAMP), FRAC_OK);
    for (i = -3; i < 20; i++) {
        for (j = -3; j < 12; j++) {
            frac_real y;
            b.X1 = 0.17f * (REAL)i;
            b.X2 = 0.0913f * (REAL)j - 0.5f;
            (void)frac_lut2_eval(&ref, (frac_real)b.X1, (frac_real)b.X2, &y);
            LUT2D(&b);
            assert_true(b.Y == (REAL)y);
            assert_true(b.Valid);
        }
    }
    b.X2 = (REAL)NAN;
    LUT2D(&b);
    assert_int_equal(b.StatusID, fracERR_NONFINITE);
    b.Enable = 0;
    LUT2D(&b);
    b.Parameters.N2 = 1;
    b.Enable = 1;
    LUT2D(&b);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_DIM);
    assert_false(b.Valid);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lut1d_matches_frac_lut1_bit_for_bit),
        cmocka_unit_test(test_lut1d_uniform_grid_without_breakpoints),
        cmocka_unit_test(test_lut1d_nan_input_holds_last_output_and_recovers),
        cmocka_unit_test(test_lut1d_bad_tables_are_rejected_with_their_status),
        cmocka_unit_test(test_lut1d_update_swaps_table_only_when_valid),
        cmocka_unit_test(test_lut2d_matches_frac_lut2_bit_for_bit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
