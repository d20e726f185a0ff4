/* FOPID block (FracCtrl.fun): bit-identical to frac_fopid (FO-PI, FO-PD
 * with Delta = 1/K, limits and anti-windup, manual mode), Enable/Update/
 * Reset edges, NaN input, out-of-range parameters. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "frac/fopid.h"

#include <string.h>

/* seed 001 (52): FO-PI 0.1219 + 0.1255 s^-0.88, Ts = 2 ms, GL memory */
static void pi_52(FOPIDParType *p)
{
    memset(p, 0, sizeof *p);
    p->Kp = 0.1219f;
    p->Ki = 0.1255f;
    p->Lambda = 0.88f;
    p->B = 1.0f;
    p->C = 1.0f;
    p->Y_min = -0.3f;
    p->Y_max = 0.3f;
    p->AntiWindup = fracAW_CLAMP;
    p->Ts = 0.002f;
    p->Method = fracFO_GL;
    p->Memory = 200;
}

/* (53) reading (c): C = 1 + 0.0256 s^0.88 with Delta = 1, filtered derivative, back-calculation */
static void pd_53(FOPIDParType *p)
{
    memset(p, 0, sizeof *p);
    p->Kp = 1.0f;
    p->Kd = 0.0256f;
    p->Mu = 0.88f;
    p->Tf = 0.01f;
    p->B = 1.0f;
    p->C = 1.0f;
    p->Delta = 1.0f;
    p->Y_min = -0.9f; /* below the unit step: the limit and back-calculation act */
    p->Y_max = 0.9f;
    p->AntiWindup = fracAW_BACKCALC;
    p->Tt = 0.05f;
    p->Ts = 0.002f;
    p->Method = fracFO_OUSTALOUP;
    p->Wb = 0.1f;
    p->Wh = 500.0f;
    p->N = 5;
}

static void ref_init(frac_fopid *c, const FOPIDParType *p, frac_real *st, size_t len)
{
    frac_fopid_params q;
    q.kp = (frac_real)p->Kp;
    q.ki = (frac_real)p->Ki;
    q.kd = (frac_real)p->Kd;
    q.lambda = (frac_real)p->Lambda;
    q.mu = (frac_real)p->Mu;
    q.tf = (frac_real)p->Tf;
    q.b = (frac_real)p->B;
    q.c = (frac_real)p->C;
    q.delta = (frac_real)p->Delta;
    q.umin = (frac_real)p->Y_min;
    q.umax = (frac_real)p->Y_max;
    q.antiwindup = (int)p->AntiWindup;
    q.tt = (frac_real)p->Tt;
    q.ts = (frac_real)p->Ts;
    q.op.method = (int)p->Method;
    q.op.order = 0;
    q.op.ts = (frac_real)p->Ts;
    q.op.memory = (size_t)p->Memory;
    q.op.wb = (frac_real)p->Wb;
    q.op.wh = (frac_real)p->Wh;
    q.op.n = (unsigned)p->N;
    assert_int_equal(frac_fopid_init(c, &q, st, len), FRAC_OK);
}

static void drive(struct FOPID *b, int k)
{
    b->W = k >= 20 ? 1.0f : 0.0f;
    b->X = 0.8f * (REAL)sin(0.01 * k) + 0.05f * (REAL)cos(0.7 * k);
}

static void compare_run(FOPIDParType *p, int with_manual)
{
    static struct FOPID b;
    static frac_real st[2048];
    frac_fopid ref;
    int k, sat = 0;
    memset(&b, 0, sizeof b);
    b.Parameters = *p;
    b.Enable = 1;
    ref_init(&ref, p, st, 2048);
    for (k = 0; k < 1500; k++) {
        frac_real u;
        int s;
        drive(&b, k);
        if (with_manual) {
            b.Manual = k >= 500 && k < 800;
            b.Y_manual = 0.25f;
            if (k == 500) {
                assert_int_equal(frac_fopid_set_mode(&ref, FRAC_FOPID_MANUAL), FRAC_OK);
            }
            if (k == 800) {
                assert_int_equal(frac_fopid_set_mode(&ref, FRAC_FOPID_AUTO), FRAC_OK);
            }
            if (b.Manual) {
                assert_int_equal(frac_fopid_set_manual(&ref, (frac_real)b.Y_manual), FRAC_OK);
            }
        }
        s = frac_fopid_step(&ref, (frac_real)b.W, (frac_real)b.X, &u);
        FOPID(&b);
        if (b.Y != (REAL)u) {
            fail_msg("sample %d: block %.9g, libfrac %.9g", k, (double)b.Y, (double)u);
        }
        assert_int_equal(b.Saturated, s == FRAC_W_SATURATED);
        assert_int_equal(b.StatusID, s == FRAC_W_SATURATED ? fracWRN_SATURATED : fracSTAT_OK);
        assert_true(b.Valid);
        sat += b.Saturated;
    }
    assert_true(sat > 0); /* the limits and the anti-windup were exercised */
}

static void test_fopid_pi_matches_frac_fopid_bit_for_bit(void **state)
{
    FOPIDParType p;
    (void)state;
    pi_52(&p);
    compare_run(&p, 0);
}

static void test_fopid_pd_with_positive_feedback_matches_frac_fopid(void **state)
{
    FOPIDParType p;
    (void)state;
    pd_53(&p);
    compare_run(&p, 0);
}

static void test_fopid_manual_mode_matches_frac_fopid(void **state)
{
    FOPIDParType p;
    (void)state;
    pi_52(&p);
    compare_run(&p, 1);
}

static void expect_param_error(FOPIDParType *p, UINT status)
{
    static struct FOPID b;
    memset(&b, 0, sizeof b);
    b.Parameters = *p;
    b.Enable = 1;
    FOPID(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_int_equal(b.StatusID, status);
    assert_true(b.Y == 0.0f);
}

static void test_fopid_rejects_out_of_range_parameters(void **state)
{
    FOPIDParType p;
    (void)state;
    pi_52(&p);
    p.Lambda = 2.5f;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_ORDER);
    pi_52(&p);
    p.Y_min = 1.0f;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_LIMITS);
    pi_52(&p);
    p.Kp = (REAL)NAN;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_GAIN);
    pi_52(&p);
    p.Ts = 0.0f;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_TS);
    pi_52(&p);
    p.Memory = 2000;
    expect_param_error(&p, fracERR_LIBFRAC - FRAC_E_STORAGE);
    pi_52(&p);
    p.AntiWindup = (FracAntiWindupEnum)7;
    expect_param_error(&p, fracERR_PARAM);
}

static void test_fopid_nan_update_and_reset(void **state)
{
    static struct FOPID b;
    static frac_real st[2048];
    frac_fopid ref;
    frac_real u;
    REAL held;
    int k;
    (void)state;
    memset(&b, 0, sizeof b);
    pi_52(&b.Parameters);
    b.Enable = 1;
    for (k = 0; k < 100; k++) {
        drive(&b, k);
        FOPID(&b);
    }
    held = b.Y;
    b.X = (REAL)NAN;
    FOPID(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_int_equal(b.StatusID, fracERR_NONFINITE);
    assert_true(b.Y == held);
    /* rejected Update keeps the running controller */
    b.Parameters.Lambda = 0.0f;
    b.Update = 1;
    drive(&b, 100);
    FOPID(&b);
    assert_true(b.Error);
    assert_true(b.Valid);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_ORDER);
    /* accepted Update: the PD from zero state */
    b.Update = 0;
    FOPID(&b);
    pd_53(&b.Parameters);
    b.Update = 1;
    ref_init(&ref, &b.Parameters, st, 2048);
    for (k = 0; k < 200; k++) {
        drive(&b, k);
        (void)frac_fopid_step(&ref, (frac_real)b.W, (frac_real)b.X, &u);
        FOPID(&b);
        assert_true(b.Y == (REAL)u);
    }
    b.Reset = 1;
    assert_int_equal(frac_fopid_reset(&ref), FRAC_OK);
    for (k = 0; k < 50; k++) {
        drive(&b, k + 3);
        (void)frac_fopid_step(&ref, (frac_real)b.W, (frac_real)b.X, &u);
        FOPID(&b);
        assert_true(b.Y == (REAL)u);
    }
    b.Enable = 0;
    FOPID(&b);
    assert_int_equal(b.StatusID, fracSTAT_DISABLED);
    assert_false(b.Valid || b.Busy || b.Error || b.Saturated);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fopid_pi_matches_frac_fopid_bit_for_bit),
        cmocka_unit_test(test_fopid_pd_with_positive_feedback_matches_frac_fopid),
        cmocka_unit_test(test_fopid_manual_mode_matches_frac_fopid),
        cmocka_unit_test(test_fopid_rejects_out_of_range_parameters),
        cmocka_unit_test(test_fopid_nan_update_and_reset),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
