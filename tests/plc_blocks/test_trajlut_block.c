/* TrajLUT block (FracCtrl.fun): bit-identical to frac_trajlut, Run/hold,
 * Restart, lead/lag, Update, error paths; all eight channels; the Y of the
 * channels a new set does not play; the steady-pin shortcut (SteadyPins)
 * against the rules over random pin sequences. */
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

/* NCH channels of N_SAMPLES samples, each its own shape, and leads derived
 * from the channel index (none of them the seed's) */
#define NCH 8
static frac_real chs[NCH][N_SAMPLES];

static void fill_channels(void)
{
    int c, i;
    for (c = 0; c < NCH; c++) {
        for (i = 0; i < N_SAMPLES; i++) {
            chs[c][i] = FRAC_COS(FRAC_R(0.07) * (frac_real)((c + 1) * i)) + (frac_real)c;
        }
    }
}

static long lead_of(int c)
{
    return (long)(c % 3) * 2 - (long)(c % 2) * 5;
}

static void params_n(TrajLUTParType *p, int channels, FracInterpEnum interp)
{
    int c;
    memset(p, 0, sizeof *p);
    p->Channels = (UDINT)channels;
    p->N = N_SAMPLES;
    for (c = 0; c < channels; c++) {
        p->pData[c] = chs[c];
        p->Lead[c] = (DINT)lead_of(c);
    }
    p->T0 = 0.004;
    p->Dt = 0.0015;
    p->Ts = 0.001;
    p->TMotionStart = 0.02;
    p->TMotionEnd = 0.05;
    p->Interpolation = interp;
}

static frac_real slopes[NCH * N_SAMPLES];

static int reference_n(frac_trajlut *tl, const TrajLUTParType *b)
{
    const frac_real *data[NCH];
    long lead[NCH];
    frac_trajlut_params p;
    int c;
    for (c = 0; c < NCH; c++) {
        data[c] = b->pData[c];
        lead[c] = (long)b->Lead[c];
    }
    p.channels = (size_t)b->Channels;
    p.n = (size_t)b->N;
    p.data = data;
    p.t0 = (frac_real)b->T0;
    p.dt = (frac_real)b->Dt;
    p.Ts = (frac_real)b->Ts;
    p.lead = lead;
    p.t_motion_start = (frac_real)b->TMotionStart;
    p.t_motion_end = (frac_real)b->TMotionEnd;
    p.interp = (int)b->Interpolation;
    return frac_trajlut_init(tl, &p, b->Interpolation == fracINTERP_CUBIC ? slopes : NULL);
}

static UINT status_id(int st)
{
    if (st < 0) {
        return (UINT)(fracERR_LIBFRAC + (UINT)(-st));
    }
    return st > 0 ? (UINT)(fracWRN_LIBFRAC + (UINT)st) : fracSTAT_OK;
}

/* Every channel count 1..8 (the fixed halves of the copy Out -> Y), linear
 * and cubic: Y[c] is frac_trajlut's value for the channels played, 0 for
 * the others. */
static void test_trajlut_block_plays_every_channel_count_bit_for_bit(void **state)
{
    static struct TrajLUT b;
    frac_trajlut ref;
    frac_real y[NCH];
    int n, k, c, seg, st, interp;
    (void)state;
    fill_channels();
    for (interp = 0; interp < 2; interp++) {
        for (n = 1; n <= NCH; n++) {
            memset(&b, 0, sizeof b);
            params_n(&b.Parameters, n, interp ? fracINTERP_CUBIC : fracINTERP_LINEAR);
            b.Parameters.pSlopes = interp ? slopes : NULL;
            b.Enable = 1;
            b.Run = 1;
            TrajLUT(&b);
            assert_true(b.Valid);
            assert_int_equal(reference_n(&ref, &b.Parameters), FRAC_OK);
            (void)frac_trajlut_step(&ref, y, &seg);
            for (k = 1; k < 70; k++) {
                st = frac_trajlut_step(&ref, y, &seg);
                TrajLUT(&b);
                assert_int_equal(b.Cycle, k);
                for (c = 0; c < NCH; c++) {
                    assert_true(b.Y[c] == (c < n ? (REAL)y[c] : 0.0f));
                }
                assert_int_equal((int)b.Segment, seg);
                assert_int_equal(b.StatusID, status_id(st));
            }
        }
    }
}

/* An Update to a set with fewer channels leaves the Y of the channels it
 * does not play as they were (the block writes only the channels in play);
 * a set with more channels plays them again. */
static void test_trajlut_block_keeps_y_of_channels_a_new_set_does_not_play(void **state)
{
    static struct TrajLUT b;
    frac_trajlut ref;
    frac_real y[NCH];
    REAL kept[NCH];
    int k, c, seg;
    (void)state;
    fill_channels();
    memset(&b, 0, sizeof b);
    params_n(&b.Parameters, 7, fracINTERP_LINEAR);
    b.Enable = 1;
    b.Run = 1;
    for (k = 0; k < 25; k++) {
        TrajLUT(&b);
    }
    memcpy(kept, b.Y, sizeof kept);
    assert_true(kept[6] != 0.0f && kept[2] != 0.0f);
    params_n(&b.Parameters, 2, fracINTERP_LINEAR);
    b.Update = 1;
    assert_int_equal(reference_n(&ref, &b.Parameters), FRAC_OK);
    for (k = 0; k < 30; k++) {
        (void)frac_trajlut_step(&ref, y, &seg);
        TrajLUT(&b);
        assert_true(b.Valid);
        assert_int_equal(b.Cycle, k);
        for (c = 0; c < NCH; c++) {
            assert_true(b.Y[c] == (c < 2 ? (REAL)y[c] : kept[c]));
        }
    }
    params_n(&b.Parameters, 6, fracINTERP_LINEAR);
    b.Update = 0;
    TrajLUT(&b);
    b.Update = 1;
    assert_int_equal(reference_n(&ref, &b.Parameters), FRAC_OK);
    (void)frac_trajlut_step(&ref, y, &seg);
    TrajLUT(&b);
    for (c = 0; c < NCH; c++) {
        assert_true(b.Y[c] == (c < 6 ? (REAL)y[c] : kept[c]));
    }
}

/* The block's rules (FracCtrl.fun, docs/plc_blocks.md) written out on
 * frac_trajlut, with no shortcut: the expected outputs of one call. */
struct model {
    BOOL en_old, up_old, par_ok, restart_old;
    UINT par_status;
    frac_trajlut tl;
    BOOL Valid, Busy, Error;
    UINT StatusID;
    REAL Y[NCH];
    int Segment;
    UDINT Cycle;
};

static void model_call(struct model *m, const struct TrajLUT *in)
{
    int edge, st, seg, c;
    frac_real y[NCH];
    frac_trajlut fresh;
    if (!in->Enable) {
        m->en_old = m->up_old = m->par_ok = m->restart_old = 0;
        m->par_status = fracSTAT_DISABLED;
        m->Valid = m->Busy = m->Error = 0;
        m->StatusID = fracSTAT_DISABLED;
        memset(m->Y, 0, sizeof m->Y);
        m->Segment = fracSEG_BEFORE;
        m->Cycle = 0;
        return;
    }
    edge = !m->en_old;
    m->en_old = 1;
    if (edge || (in->Update && !m->up_old)) {
        st = reference_n(&fresh, &in->Parameters);
        m->par_status = status_id(st);
        if (st == FRAC_OK) {
            m->tl = fresh;
            m->par_ok = 1;
        } else if (edge) {
            m->par_ok = 0;
        }
    }
    m->up_old = in->Update ? 1 : 0;
    if (!m->par_ok) {
        m->Valid = m->Busy = 0;
        m->Error = 1;
        m->StatusID = m->par_status;
        return;
    }
    if (in->Restart && !m->restart_old) {
        m->tl.k = 0;
    }
    m->restart_old = in->Restart;
    m->Cycle = (UDINT)m->tl.k;
    st = in->Run ? frac_trajlut_step(&m->tl, y, &seg) : frac_trajlut_eval(&m->tl, m->tl.k, y, &seg);
    for (c = 0; c < (int)m->tl.channels; c++) {
        m->Y[c] = (REAL)y[c];
    }
    m->Segment = seg;
    m->Busy = 1;
    if (st < 0) {
        m->Valid = 0;
        m->Error = 1;
        m->StatusID = status_id(st);
    } else {
        m->Valid = 1;
        m->Error = m->par_status != fracSTAT_OK;
        m->StatusID = m->Error ? m->par_status : status_id(st);
    }
}

/* Random calls: each BOOL pin held for a while, then mostly 0 or 1,
 * sometimes a non-canonical TRUE (2, 255); the Parameters pin switching between sets
 * of 3 and 8 channels and an invalid one (only Update edges take it over).
 * Every output equals the rules' after every call, so neither the
 * shortcut nor the Restart edge moved into trajlut_enter changes what a
 * call does; and over a fifth of the calls take the shortcut. */
static void test_trajlut_block_follows_the_rules_over_random_pin_sequences(void **state)
{
    static const BOOL vals[8] = {0, 1, 0, 1, 0, 1, 2, 255};
    static struct TrajLUT b;
    static struct model m;
    unsigned long rng = 12345u;
    int call, c, pin, steady = 0;
    BOOL *pins[4];
    (void)state;
    fill_channels();
    memset(&b, 0, sizeof b);
    memset(&m, 0, sizeof m);
    pins[0] = &b.Enable;
    pins[1] = &b.Update;
    pins[2] = &b.Run;
    pins[3] = &b.Restart;
    for (call = 0; call < 20000; call++) {
        for (pin = 0; pin < 4; pin++) {
            rng = rng * 1103515245u + 12345u;
            /* a change every ~12 calls; Enable mostly TRUE */
            if ((rng >> 16) % 12u == 0) {
                unsigned r = (unsigned)(rng >> 20) % 8u;
                *pins[pin] = pin == 0 && r < 4 ? 1 : vals[r];
            }
        }
        rng = rng * 1103515245u + 12345u;
        if ((rng >> 16) % 40u == 0) {
            unsigned r = (unsigned)(rng >> 22) % 3u;
            params_n(&b.Parameters, r == 0 ? 3 : 8, fracINTERP_LINEAR);
            if (r == 2) {
                b.Parameters.Dt = -1.0;
            }
        }
        steady += b.SteadyPins != 0 && (b.Enable | b.Update << 8 | b.Run << 16 | (UDINT)b.Restart << 24) == b.SteadyPins;
        model_call(&m, &b);
        TrajLUT(&b);
        assert_int_equal(b.Valid, m.Valid);
        assert_int_equal(b.Busy, m.Busy);
        assert_int_equal(b.Error, m.Error);
        assert_int_equal(b.StatusID, m.StatusID);
        assert_int_equal(b.Cycle, m.Cycle);
        assert_int_equal((int)b.Segment, m.Segment);
        for (c = 0; c < NCH; c++) {
            assert_memory_equal(&b.Y[c], &m.Y[c], sizeof(REAL));
        }
    }

    assert_true(steady > 20000 / 5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trajlut_block_matches_frac_trajlut_bit_for_bit),
        cmocka_unit_test(test_trajlut_block_holds_without_run_and_restarts),
        cmocka_unit_test(test_trajlut_block_parameter_errors),
        cmocka_unit_test(test_trajlut_block_plays_every_channel_count_bit_for_bit),
        cmocka_unit_test(test_trajlut_block_keeps_y_of_channels_a_new_set_does_not_play),
        cmocka_unit_test(test_trajlut_block_follows_the_rules_over_random_pin_sequences),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
