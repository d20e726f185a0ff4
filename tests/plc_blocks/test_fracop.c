/* FracOp block (FracCtrl.fun): bit-identical to frac_fo for every
 * realization, Enable/Update/Reset edges, NaN input, bad parameters. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "frac/fo_op.h"

#include <string.h>

static void params(FracOpParType *p, FracFoMethodEnum m)
{
    memset(p, 0, sizeof *p);
    p->Method = m;
    p->Order = 0.5;
    p->Ts = 1.2e-3;
    p->Memory = 200;
    p->Wb = 0.1;
    p->Wh = 500.0;
    p->N = 4;
}

static void ref_params(frac_fo_params *q, const FracOpParType *p)
{
    q->method = (int)p->Method;
    q->order = (frac_real)p->Order;
    q->ts = (frac_real)p->Ts;
    q->memory = (size_t)p->Memory;
    q->wb = (frac_real)p->Wb;
    q->wh = (frac_real)p->Wh;
    q->n = (unsigned)p->N;
}

static REAL input(int k)
{
    return (REAL)(sin(0.02 * k) + 0.3 * cos(0.31 * k));
}

static void test_fracop_matches_frac_fo_bit_for_bit_for_every_method(void **state)
{
    static struct FracOp b;
    static frac_real st[1024];
    frac_fo ref;
    frac_fo_params q;
    int m, k;
    (void)state;
    for (m = fracFO_GL; m <= fracFO_CFE_ALALAOUI; m++) {
        memset(&b, 0, sizeof b);
        params(&b.Parameters, (FracFoMethodEnum)m);
        b.Enable = 1;
        ref_params(&q, &b.Parameters);
        assert_int_equal(frac_fo_init(&ref, &q, st, 1024), FRAC_OK);
        for (k = 0; k < 400; k++) {
            frac_real y;
            b.X = input(k);
            assert_int_equal(frac_fo_step(&ref, (frac_real)b.X, &y), FRAC_OK);
            FracOp(&b);
            if (b.Y != (REAL)y) {
                fail_msg("method %d, sample %d: block %.9g, libfrac %.9g", m, k, (double)b.Y, (double)y);
            }
            assert_true(b.Valid);
            assert_int_equal(b.StatusID, fracSTAT_OK);
        }
    }
}

static void expect_param_error(FracOpParType *p, UINT status)
{
    static struct FracOp b;
    memset(&b, 0, sizeof b);
    b.Parameters = *p;
    b.Enable = 1;
    FracOp(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_false(b.Busy);
    assert_int_equal(b.StatusID, status);
    assert_true(b.Y == 0.0f);
}

static void test_fracop_rejects_out_of_range_parameters(void **state)
{
    FracOpParType p;
    (void)state;
    params(&p, fracFO_GL);
    p.Order = 3.0;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_ORDER);
    params(&p, fracFO_GL);
    p.Memory = 400; /* 3 L > fracFO_STORAGE_LEN */
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_STORAGE);
    params(&p, fracFO_OUSTALOUP);
    p.Wb = 1000.0;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_BAND);
    params(&p, fracFO_CFE_TUSTIN);
    p.Ts = 0.0;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_TS);
    params(&p, (FracFoMethodEnum)9);
    expect_param_error(&p, fracERR_PARAM);
}

static void test_fracop_nan_input_update_and_reset(void **state)
{
    static struct FracOp b;
    static frac_real st[1024];
    frac_fo ref;
    frac_fo_params q;
    frac_real y;
    REAL held;
    int k;
    (void)state;
    memset(&b, 0, sizeof b);
    params(&b.Parameters, fracFO_OUSTALOUP);
    b.Enable = 1;
    for (k = 0; k < 50; k++) {
        b.X = input(k);
        FracOp(&b);
    }
    held = b.Y;
    b.X = (REAL)NAN;
    FracOp(&b);
    assert_true(b.Error);
    assert_int_equal(b.StatusID, fracERR_NONFINITE);
    assert_true(b.Y == held);
    /* rejected Update: the running operator goes on */
    b.Parameters.Order = 5.0;
    b.Update = 1;
    b.X = input(50);
    FracOp(&b);
    assert_true(b.Error);
    assert_true(b.Valid);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_ORDER);
    /* accepted Update: GL of order -0.5 from zero history */
    b.Update = 0;
    FracOp(&b);
    params(&b.Parameters, fracFO_GL);
    b.Parameters.Order = -0.5;
    b.Update = 1;
    ref_params(&q, &b.Parameters);
    assert_int_equal(frac_fo_init(&ref, &q, st, 1024), FRAC_OK);
    for (k = 0; k < 30; k++) {
        b.X = input(k);
        (void)frac_fo_step(&ref, (frac_real)b.X, &y);
        FracOp(&b);
        assert_false(b.Error);
        assert_true(b.Y == (REAL)y);
    }
    /* Reset edge: zero history */
    b.Reset = 1;
    assert_int_equal(frac_fo_reset(&ref), FRAC_OK);
    for (k = 0; k < 30; k++) {
        b.X = input(k + 7);
        (void)frac_fo_step(&ref, (frac_real)b.X, &y);
        FracOp(&b);
        assert_true(b.Y == (REAL)y);
    }
    b.Enable = 0;
    FracOp(&b);
    assert_int_equal(b.StatusID, fracSTAT_DISABLED);
    assert_true(b.Y == 0.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fracop_matches_frac_fo_bit_for_bit_for_every_method),
        cmocka_unit_test(test_fracop_rejects_out_of_range_parameters),
        cmocka_unit_test(test_fracop_nan_input_update_and_reset),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
