/* LQGDelay block (FracCtrl.fun): bit-identical to frac_lqg on the same
 * inputs, Enable/Update/Reset edges, NaN inputs, bad parameters. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "frac/lqg.h"

#include <string.h>

/* A small delay-augmented loop: n = 2, d_i = 2, p = 2, d_o = {0, 1}:
 * n_bar = 5, estimate 6 states. Values are arbitrary but finite. */
static frac_real A[4] = {1.0, 0.0012, -0.05, 0.98};
static frac_real B[2] = {0.0, 0.0012};
static frac_real C[4] = {1.0, 0.0, 0.0, 1.0};
static frac_real K[5] = {30.0, 4.0, 0.2, 0.1, 0.3};
static frac_real L[12] = {0.5, 0.01, 0.1, 0.4, 0.0, 0.02, 0.01, 0.0, 0.0, 0.3, 0.2, 0.05};
static size_t d_o_ref[2] = {0, 1};

static void params(LQGDelayParType *p)
{
    memset(p, 0, sizeof *p);
    p->N = 2;
    p->Di = 2;
    p->P = 2;
    p->Do[0] = 0;
    p->Do[1] = 1;
    p->pA = A;
    p->pB = B;
    p->pC = C;
    p->pK = K;
    p->pL = L;
}

static void reference(frac_lqg *c, frac_real *storage, size_t len)
{
    frac_lqg_params prm;
    prm.n = 2;
    prm.d_i = 2;
    prm.p = 2;
    prm.d_o = d_o_ref;
    prm.A = A;
    prm.B = B;
    prm.C = C;
    prm.K = K;
    prm.L = L;
    assert_int_equal(frac_lqg_init(c, &prm, storage, len), FRAC_OK);
}

static void inputs(struct LQGDelay *b, int k)
{
    b->UStar = 2.0f * (REAL)sin(0.01 * k);
    b->YRef[0] = 0.3f * (REAL)sin(0.005 * k);
    b->YRef[1] = 0.0015f * (REAL)cos(0.005 * k);
    b->Y[0] = b->YRef[0] + 0.01f * (REAL)sin(0.37 * k);
    b->Y[1] = b->YRef[1] - 0.02f * (REAL)cos(0.21 * k);
}

static int ref_step(frac_lqg *c, const struct LQGDelay *b, frac_real *u)
{
    frac_real yr[2], y[2];
    yr[0] = (frac_real)b->YRef[0];
    yr[1] = (frac_real)b->YRef[1];
    y[0] = (frac_real)b->Y[0];
    y[1] = (frac_real)b->Y[1];
    return frac_lqg_step(c, (frac_real)b->UStar, yr, y, u);
}

static void test_lqg_delay_matches_frac_lqg_bit_for_bit(void **state)
{
    static struct LQGDelay b;
    frac_lqg ref;
    frac_real st[FRAC_LQG_STORAGE(6, 2)], u;
    int k;
    (void)state;
    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Enable = 1;
    reference(&ref, st, FRAC_LQG_STORAGE(6, 2));
    for (k = 0; k < 500; k++) {
        inputs(&b, k);
        assert_int_equal(ref_step(&ref, &b, &u), FRAC_OK);
        LQGDelay(&b);
        assert_true(b.U == (REAL)u);
        assert_true(b.FrictionEstimate == (REAL)frac_lqg_friction_estimate(&ref));
        assert_true(b.Valid);
        assert_int_equal(b.StatusID, fracSTAT_OK);
    }
    assert_true(b.U != 0.0f);
}

static void test_lqg_delay_nan_inputs(void **state)
{
    static struct LQGDelay b;
    frac_lqg ref;
    frac_real st[FRAC_LQG_STORAGE(6, 2)], u;
    REAL held;
    int k;
    (void)state;
    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Enable = 1;
    reference(&ref, st, FRAC_LQG_STORAGE(6, 2));
    for (k = 0; k < 20; k++) {
        inputs(&b, k);
        (void)ref_step(&ref, &b, &u);
        LQGDelay(&b);
    }
    held = b.U;
    b.UStar = (REAL)NAN;
    LQGDelay(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_int_equal(b.StatusID, fracERR_NONFINITE);
    assert_true(b.U == held);
    /* a lost measurement: innovation dropped, the loop goes on (warning) */
    inputs(&b, 20);
    b.Y[1] = (REAL)NAN;
    assert_int_equal(ref_step(&ref, &b, &u), FRAC_W_MEAS_SKIPPED);
    LQGDelay(&b);
    assert_true(b.Valid);
    assert_false(b.Error);
    assert_int_equal(b.StatusID, fracWRN_LIBFRAC + FRAC_W_MEAS_SKIPPED);
    assert_true(b.U == (REAL)u);
}

static void test_lqg_delay_parameter_errors(void **state)
{
    static struct LQGDelay b;
    (void)state;
    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Parameters.P = 4;
    b.Enable = 1;
    LQGDelay(&b);
    assert_true(b.Error);
    assert_false(b.Busy);
    assert_int_equal(b.StatusID, fracERR_PARAM);
    assert_true(b.U == 0.0f);

    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Parameters.N = 0;
    b.Enable = 1;
    LQGDelay(&b);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_DIM);

    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Parameters.pL = NULL;
    b.Enable = 1;
    LQGDelay(&b);
    assert_int_equal(b.StatusID, fracERR_NULL);

    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Parameters.N = 70; /* n_bar + 1 above FRAC_MAT_MAX */
    b.Enable = 1;
    LQGDelay(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
}

static void test_lqg_delay_update_and_reset_edges(void **state)
{
    static struct LQGDelay b;
    frac_lqg ref;
    frac_real st[FRAC_LQG_STORAGE(6, 2)], u;
    int k;
    (void)state;
    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Enable = 1;
    reference(&ref, st, FRAC_LQG_STORAGE(6, 2));
    for (k = 0; k < 50; k++) {
        inputs(&b, k);
        (void)ref_step(&ref, &b, &u);
        LQGDelay(&b);
    }
    /* rejected Update: the running controller (and its estimate) goes on */
    b.Parameters.P = 0;
    b.Update = 1;
    inputs(&b, 50);
    (void)ref_step(&ref, &b, &u);
    LQGDelay(&b);
    assert_true(b.Error);
    assert_true(b.Valid);
    assert_int_equal(b.StatusID, fracERR_PARAM);
    assert_true(b.U == (REAL)u);
    /* accepted Update: new controller, estimate from 0 */
    b.Update = 0;
    params(&b.Parameters);
    inputs(&b, 51);
    (void)ref_step(&ref, &b, &u);
    LQGDelay(&b);
    b.Update = 1;
    reference(&ref, st, FRAC_LQG_STORAGE(6, 2));
    for (k = 52; k < 80; k++) {
        inputs(&b, k);
        (void)ref_step(&ref, &b, &u);
        LQGDelay(&b);
        assert_false(b.Error);
        assert_true(b.U == (REAL)u);
    }
    /* Reset edge: estimate to 0 */
    b.Reset = 1;
    assert_int_equal(frac_lqg_reset(&ref), FRAC_OK);
    for (k = 80; k < 100; k++) {
        inputs(&b, k);
        (void)ref_step(&ref, &b, &u);
        LQGDelay(&b);
        assert_true(b.U == (REAL)u);
    }
    b.Enable = 0;
    LQGDelay(&b);
    assert_int_equal(b.StatusID, fracSTAT_DISABLED);
    assert_true(b.U == 0.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lqg_delay_matches_frac_lqg_bit_for_bit),
        cmocka_unit_test(test_lqg_delay_nan_inputs),
        cmocka_unit_test(test_lqg_delay_parameter_errors),
        cmocka_unit_test(test_lqg_delay_update_and_reset_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
