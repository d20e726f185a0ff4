/* FracDamp block (FracCtrl.fun): bit-identical to frac_fodamp with the
 * seed 002 law, Enable/Update/Reset edges, NaN input, bad parameters. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "fracctrl_seed_params.h"
#include "frac/fodamp.h"

#include <string.h>

/* seed 002 (51)/(52): C = 5.31 (1 + 0.0142 s)/s^1.2, F = (1 + 0.116 s^0.55)/(1 + 0.011 s), Ts = 0.4 ms */
/* The seed 002 law with realization m (GL memory 150, Oustaloup/CFE N = 4 up to 2000 rad/s). */
static void seed002(FracDampParType *p, FracFoMethodEnum m)
{
    seed002_law(p);
    p->Method = m;
    p->Memory = 150;
    p->Wh = 2000.0f;
    p->N = 4;
}

static void ref_init(frac_fodamp *c, const FracDampParType *p, frac_real *st, size_t len)
{
    frac_fodamp_params q;
    q.kc = (frac_real)p->Kc;
    q.alpha = (frac_real)p->Alpha;
    q.m = (unsigned)p->M;
    q.n1 = (frac_real)p->N1;
    q.n2 = (frac_real)p->N2;
    q.d1 = (frac_real)p->D1;
    q.d2 = (frac_real)p->D2;
    q.fa = (frac_real)p->Fa;
    q.fbeta = (frac_real)p->Fbeta;
    q.fb = (frac_real)p->Fb;
    q.ts = (frac_real)p->Ts;
    q.op.method = (int)p->Method;
    q.op.order = 0;
    q.op.ts = (frac_real)p->Ts;
    q.op.memory = (size_t)p->Memory;
    q.op.wb = (frac_real)p->Wb;
    q.op.wh = (frac_real)p->Wh;
    q.op.n = (unsigned)p->N;
    assert_int_equal(frac_fodamp_init(c, &q, st, len), FRAC_OK);
}

static void drive(struct FracDamp *b, int k)
{
    b->W = k >= 10 ? 0.5f : 0.0f;
    b->X = 0.02f * (REAL)sin(0.003 * k * 6.28);
}

static void test_fracdamp_matches_frac_fodamp_bit_for_bit(void **state)
{
    static struct FracDamp b;
    static frac_real st[1024];
    static frac_fodamp ref;
    int m, k;
    (void)state;
    for (m = fracFO_GL; m <= fracFO_OUSTALOUP; m++) {
        memset(&b, 0, sizeof b);
        seed002(&b.Parameters, (FracFoMethodEnum)m);
        b.Enable = 1;
        ref_init(&ref, &b.Parameters, st, 1024);
        for (k = 0; k < 2000; k++) {
            frac_real u;
            drive(&b, k);
            assert_int_equal(frac_fodamp_step(&ref, (frac_real)b.W, (frac_real)b.X, &u), FRAC_OK);
            FracDamp(&b);
            if (b.Y != (REAL)u) {
                fail_msg("method %d sample %d: block %.9g, libfrac %.9g", m, k, (double)b.Y, (double)u);
            }
            assert_true(b.Valid);
            assert_int_equal(b.StatusID, fracSTAT_OK);
        }
    }
}

static void expect_param_error(FracDampParType *p, UINT status)
{
    static struct FracDamp b;
    memset(&b, 0, sizeof b);
    b.Parameters = *p;
    b.Enable = 1;
    FracDamp(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_int_equal(b.StatusID, status);
    assert_true(b.Y == 0.0f);
}

static void test_fracdamp_rejects_out_of_range_parameters(void **state)
{
    FracDampParType p;
    (void)state;
    seed002(&p, fracFO_OUSTALOUP);
    p.Alpha = 2.5f;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_ORDER);
    seed002(&p, fracFO_OUSTALOUP);
    p.M = 3;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_DIM);
    seed002(&p, fracFO_OUSTALOUP);
    p.D1 = -0.01f;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_UNSTABLE);
    seed002(&p, fracFO_OUSTALOUP);
    p.Kc = 0.0f;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_GAIN);
    seed002(&p, fracFO_GL);
    p.Memory = 1000;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_STORAGE);
}

static void test_fracdamp_nan_update_and_reset(void **state)
{
    static struct FracDamp b;
    static frac_real st[1024];
    static frac_fodamp ref;
    frac_real u;
    REAL held;
    int k;
    (void)state;
    memset(&b, 0, sizeof b);
    seed002(&b.Parameters, fracFO_OUSTALOUP);
    b.Enable = 1;
    for (k = 0; k < 100; k++) {
        drive(&b, k);
        FracDamp(&b);
    }
    held = b.Y;
    b.X = (REAL)NAN;
    FracDamp(&b);
    assert_true(b.Error);
    assert_int_equal(b.StatusID, fracERR_NONFINITE);
    assert_true(b.Y == held);
    /* rejected Update keeps the law in effect; accepted Update restarts it */
    b.Parameters.Kc = -1.0f;
    b.Update = 1;
    drive(&b, 100);
    FracDamp(&b);
    assert_true(b.Error);
    assert_true(b.Valid);
    b.Update = 0;
    FracDamp(&b);
    seed002(&b.Parameters, fracFO_GL);
    b.Update = 1;
    ref_init(&ref, &b.Parameters, st, 1024);
    for (k = 0; k < 300; k++) {
        drive(&b, k);
        (void)frac_fodamp_step(&ref, (frac_real)b.W, (frac_real)b.X, &u);
        FracDamp(&b);
        assert_false(b.Error);
        assert_true(b.Y == (REAL)u);
    }
    b.Reset = 1;
    assert_int_equal(frac_fodamp_reset(&ref), FRAC_OK);
    for (k = 0; k < 100; k++) {
        drive(&b, k + 5);
        (void)frac_fodamp_step(&ref, (frac_real)b.W, (frac_real)b.X, &u);
        FracDamp(&b);
        assert_true(b.Y == (REAL)u);
    }
    b.Enable = 0;
    FracDamp(&b);
    assert_int_equal(b.StatusID, fracSTAT_DISABLED);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fracdamp_matches_frac_fodamp_bit_for_bit),
        cmocka_unit_test(test_fracdamp_rejects_out_of_range_parameters),
        cmocka_unit_test(test_fracdamp_nan_update_and_reset),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
