/* TrajLUT block (FracCtrl.fun): bit-identical to frac_trajlut, Run/hold,
 * Restart, lead/lag, Update, error paths. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "frac/trajlut.h"

#include <string.h>

#define N_SAMPLES 50
static frac_real ch0[N_SAMPLES], ch1[N_SAMPLES], ch2[N_SAMPLES];

static void fill(void)
{
    int i;
    for (i = 0; i < N_SAMPLES; i++) {
        ch0[i] = FRAC_SIN(FRAC_R(0.1) * (frac_real)i);
        ch1[i] = (frac_real)(i * i) * FRAC_R(0.01);
        ch2[i] = (frac_real)i;
    }
}

static void params(TrajLUTParType *p)
{
    memset(p, 0, sizeof *p);
    p->Channels = 3;
    p->N = N_SAMPLES;
    p->pData[0] = ch0;
    p->pData[1] = ch1;
    p->pData[2] = ch2;
    p->T0 = 0.01;
    p->Dt = 0.002;
    p->Ts = 0.0012;
    p->Lead[1] = 4;
    p->Lead[2] = -3;
    p->TMotionStart = 0.03;
    p->TMotionEnd = 0.08;
    p->Interpolation = fracINTERP_LINEAR;
}

static void reference(frac_trajlut *tl)
{
    static const frac_real *data[3] = {ch0, ch1, ch2};
    static const long lead[3] = {0, 4, -3};
    frac_trajlut_params p;
    p.channels = 3;
    p.n = N_SAMPLES;
    p.data = data;
    p.t0 = FRAC_R(0.01);
    p.dt = FRAC_R(0.002);
    p.Ts = FRAC_R(0.0012);
    p.lead = lead;
    p.t_motion_start = FRAC_R(0.03);
    p.t_motion_end = FRAC_R(0.08);
    p.interp = FRAC_LUT_LINEAR;
    assert_int_equal(frac_trajlut_init(tl, &p, NULL), FRAC_OK);
}

static void test_trajlut_block_matches_frac_trajlut_bit_for_bit(void **state)
{
    static struct TrajLUT b;
    frac_trajlut ref;
    frac_real y[8];
    int k, seg, st, c, segs_seen = 0;
    (void)state;
    fill();
    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Enable = 1;
    b.Run = 1;
    reference(&ref);
    for (k = 0; k < 120; k++) {
        st = frac_trajlut_step(&ref, y, &seg);
        TrajLUT(&b);
        assert_int_equal(b.Cycle, k);
        for (c = 0; c < 3; c++) {
            assert_true(b.Y[c] == (REAL)y[c]);
        }
        assert_int_equal((int)b.Segment, seg);
        assert_true(b.Valid);
        assert_int_equal(b.StatusID, st == FRAC_W_CLAMPED ? fracWRN_CLAMPED : fracSTAT_OK);
        segs_seen |= 1 << seg;
    }
    assert_int_equal(segs_seen, 0x1F); /* before, pre, motion, post, after */
}

static void test_trajlut_block_holds_without_run_and_restarts(void **state)
{
    static struct TrajLUT b;
    REAL held[3];
    int k;
    (void)state;
    fill();
    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Enable = 1;
    b.Run = 1;
    for (k = 0; k < 30; k++) {
        TrajLUT(&b);
    }
    b.Run = 0;
    TrajLUT(&b);
    assert_int_equal(b.Cycle, 30);
    memcpy(held, b.Y, sizeof held);
    TrajLUT(&b);
    assert_int_equal(b.Cycle, 30);
    assert_memory_equal(held, b.Y, sizeof held);
    b.Restart = 1;
    TrajLUT(&b);
    assert_int_equal(b.Cycle, 0);
    assert_true(b.Y[0] == (REAL)ch0[0]);
}

static void test_trajlut_block_parameter_errors(void **state)
{
    static struct TrajLUT b;
    (void)state;
    fill();
    memset(&b, 0, sizeof b);
    params(&b.Parameters);
    b.Parameters.Channels = 9;
    b.Enable = 1;
    TrajLUT(&b);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_DIM);
    params(&b.Parameters);
    b.Parameters.Dt = -1.0;
    b.Update = 1;
    TrajLUT(&b);
    assert_int_equal(b.StatusID, fracERR_LIBFRAC - FRAC_E_TS);
    b.Update = 0;
    TrajLUT(&b);
    params(&b.Parameters);
    b.Parameters.pData[2] = NULL;
    b.Update = 1;
    TrajLUT(&b);
    assert_int_equal(b.StatusID, fracERR_NULL);
    b.Update = 0;
    TrajLUT(&b);
    params(&b.Parameters);
    ch1[7] = (frac_real)NAN;
    b.Update = 1;
    TrajLUT(&b);
    assert_int_equal(b.StatusID, fracERR_NONFINITE);
    ch1[7] = 0;
    b.Update = 0;
    TrajLUT(&b);
    b.Update = 1;
    TrajLUT(&b);
    assert_false(b.Error);
    assert_true(b.Valid);
    b.Enable = 0;
    TrajLUT(&b);
    assert_int_equal(b.StatusID, fracSTAT_DISABLED);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trajlut_block_matches_frac_trajlut_bit_for_bit),
        cmocka_unit_test(test_trajlut_block_holds_without_run_and_restarts),
        cmocka_unit_test(test_trajlut_block_parameter_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
