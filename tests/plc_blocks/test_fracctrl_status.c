/* fracctrl_status.h, the PLCopen sequence shared by the FracCtrl bodies:
 * FRACCTRL_ENTER (the steady-state shortcut or fracctrl_enter) gives the
 * outputs and state of the Enable/Update rules (docs/plc_blocks.md) for
 * every input and state, FRACCTRL_OUTPUTS those of fracctrl_report, and
 * the two shortcuts together equal the full rules over long call
 * sequences. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "fracctrl_status.h"

#include <string.h>

/* A block with the standard pins whose load and hold only record calls. */
struct fake {
    BOOL Enable;
    BOOL Update;
    BOOL Valid;
    BOOL Busy;
    BOOL Error;
    UINT StatusID;
    FracFbStateType Fb;
    int load_status;
    int loads, load_edge;
    int holds, hold_disabled;
};

static int fake_load(void *inst, int enable_edge)
{
    struct fake *f = (struct fake *)inst;
    f->loads++;
    f->load_edge = enable_edge;
    return f->load_status;
}

static void fake_hold(void *inst, int disabled)
{
    struct fake *f = (struct fake *)inst;
    f->holds++;
    f->hold_disabled = disabled;
}

static const fracctrl_block fake_block = {fake_load, fake_hold};

/* The rules written out once more, step by step: returns 1 when the step
 * runs, 2 when it runs after an Enable edge, 0 when the block holds. */
static int rules(struct fake *f)
{
    int enable_edge, load;
    if (!f->Enable) {
        f->Fb.EnableOld = 0;
        f->Fb.UpdateOld = 0;
        f->Fb.ParOk = 0;
        f->Fb.ParStatus = fracSTAT_DISABLED;
        f->Valid = 0;
        f->Busy = 0;
        f->Error = 0;
        f->StatusID = fracSTAT_DISABLED;
        fake_hold(f, 1);
        return 0;
    }
    enable_edge = !f->Fb.EnableOld;
    load = enable_edge || (f->Update && !f->Fb.UpdateOld);
    f->Fb.EnableOld = 1;
    f->Fb.UpdateOld = f->Update ? 1 : 0;
    if (load) {
        int st = fake_load(f, enable_edge);
        f->Fb.ParStatus = st == FRAC_OK ? fracSTAT_OK : (UINT)(fracERR_LIBFRAC + (UINT)(-st));
        if (st == FRAC_OK) {
            f->Fb.ParOk = 1;
        } else if (enable_edge) {
            f->Fb.ParOk = 0;
        }
    }
    if (!f->Fb.ParOk) {
        f->Valid = 0;
        f->Busy = 0;
        f->Error = 1;
        f->StatusID = f->Fb.ParStatus;
        fake_hold(f, 0);
        return 0;
    }
    return enable_edge ? 2 : 1;
}

static void assert_same(const struct fake *a, const struct fake *b)
{
    assert_int_equal(a->Valid, b->Valid);
    assert_int_equal(a->Busy, b->Busy);
    assert_int_equal(a->Error, b->Error);
    assert_int_equal(a->StatusID, b->StatusID);
    assert_int_equal(a->Fb.EnableOld, b->Fb.EnableOld);
    assert_int_equal(a->Fb.UpdateOld, b->Fb.UpdateOld);
    assert_int_equal(a->Fb.ParOk, b->Fb.ParOk);
    assert_int_equal(a->Fb.ParStatus, b->Fb.ParStatus);
    assert_int_equal(a->loads, b->loads);
    assert_int_equal(a->load_edge, b->load_edge);
    assert_int_equal(a->holds, b->holds);
    assert_int_equal(a->hold_disabled, b->hold_disabled);
}

static void test_enter_follows_the_enable_update_rules_in_every_state(void **state)
{
    static const UINT par_status[2] = {fracSTAT_OK, fracERR_PARAM};
    static const int load_status[2] = {FRAC_OK, FRAC_E_PARAM};
    int en, up, en_old, up_old, par_ok, ps, ls, steady = 0, n = 0;
    (void)state;
    for (en = 0; en < 3; en++) {
        for (up = 0; up < 3; up++) {
            for (en_old = 0; en_old < 2; en_old++) {
                for (up_old = 0; up_old < 2; up_old++) {
                    for (par_ok = 0; par_ok < 2; par_ok++) {
                        for (ps = 0; ps < 2; ps++) {
                            for (ls = 0; ls < 2; ls++) {
                                struct fake got, want;
                                int run, want_run;
                                memset(&got, 0, sizeof got);
                                got.Enable = (BOOL)en;
                                got.Update = (BOOL)up;
                                got.Valid = 7;
                                got.Busy = 7;
                                got.Error = 7;
                                got.StatusID = 777;
                                got.Fb.EnableOld = (BOOL)en_old;
                                got.Fb.UpdateOld = (BOOL)up_old;
                                got.Fb.ParOk = (BOOL)par_ok;
                                got.Fb.ParStatus = par_status[ps];
                                /* the derived fields as the previous fracctrl_enter left them */
                                got.Fb.Steady = en_old && par_ok ? FRACCTRL_KEY(1, up_old) : 0;
                                got.Fb.Reported = FRACCTRL_UNREPORTED;
                                got.load_status = load_status[ls];
                                want = got;
                                if (FRACCTRL_STEADY(&got.Fb, got.Enable, got.Update)) {
                                    steady++;
                                }
                                run = FRACCTRL_ENTER(&fake_block, &got);
                                want_run = rules(&want);
                                assert_int_equal(run != 0, want_run != 0);
                                assert_same(&got, &want);
                                n++;
                            }
                        }
                    }
                }
            }
        }
    }
    assert_int_equal(n, 3 * 3 * 2 * 2 * 2 * 2 * 2);
    /* Enable exactly 1 and held, Update 0 or 1 held, parameters in effect
     * (x 2 parameter statuses, x 2 load statuses, which do not matter) */
    assert_int_equal(steady, 2 * 2 * 2);
}

/* The report rules written out once more (fracctrl_report's contract). */
static void report_rules(struct fake *f, int st)
{
    f->Busy = 1;
    if (st < 0) {
        f->Valid = 0;
        f->Error = 1;
        f->StatusID = fracctrl_status_id(st);
    } else {
        f->Valid = 1;
        f->Error = f->Fb.ParStatus != fracSTAT_OK;
        f->StatusID = f->Error ? f->Fb.ParStatus : fracctrl_status_id(st);
    }
}

static unsigned lcg(unsigned long *x)
{
    *x = *x * 1103515245ul + 12345ul;
    return (unsigned)((*x >> 16) & 0x7FFFu);
}

/* A block called as the bodies do (FRACCTRL_ENTER, step, FRACCTRL_OUTPUTS)
 * against the rules, over 20,000 calls with random pins, parameter
 * checks and step statuses: the steady-path key and the skipped status
 * writes never make an output or state differ. */
static void test_steady_shortcuts_equal_the_rules_over_random_sequences(void **state)
{
    static const int step_status[3] = {FRAC_OK, FRAC_W_CLAMPED, FRAC_E_NONFINITE};
    struct fake got, want;
    unsigned long x = 12345;
    int k, steady = 0, skipped = 0;
    (void)state;
    memset(&got, 0, sizeof got);
    want = got;
    for (k = 0; k < 20000; k++) {
        unsigned r = lcg(&x);
        int st = step_status[r % 8 < 6 ? 0 : 1 + (int)(r % 2)], run, want_run;
        BOOL en = (BOOL)(r % 16 == 0 ? 0 : r % 16 == 1 ? 2 : 1);
        BOOL up = (BOOL)((r / 16) % 16 == 0 ? 2 : (r / 16) % 16 < 13 ? want.Fb.UpdateOld : 1 - want.Fb.UpdateOld);
        got.Enable = want.Enable = en;
        got.Update = want.Update = up;
        got.load_status = want.load_status = (r / 256) % 4 == 0 ? FRAC_E_PARAM : FRAC_OK;
        steady += FRACCTRL_STEADY(&got.Fb, got.Enable, got.Update) ? 1 : 0;
        run = FRACCTRL_ENTER(&fake_block, &got);
        want_run = rules(&want);
        assert_int_equal(run != 0, want_run != 0);
        if (run) {
            skipped += st == got.Fb.Reported;
            FRACCTRL_OUTPUTS(&got, st);
            report_rules(&want, st);
        }
        if (got.Valid != want.Valid || got.Busy != want.Busy || got.Error != want.Error
            || got.StatusID != want.StatusID) {
            fail_msg("call %d (Enable %d Update %d step %d): outputs %d %d %d %u, rules %d %d %d %u", k, en, up, st,
                     got.Valid, got.Busy, got.Error, got.StatusID, want.Valid, want.Busy, want.Error, want.StatusID);
        }
        assert_same(&got, &want);
    }
    /* both shortcuts were taken on many calls */
    print_message("steady calls %d, status writes skipped %d of 20000\n", steady, skipped);
    assert_true(steady > 5000);
    assert_true(skipped > 5000);
}

static void test_enter_says_started_only_on_the_enable_edge(void **state)
{
    struct fake f;
    (void)state;
    memset(&f, 0, sizeof f);
    f.Enable = 1;
    assert_int_equal(fracctrl_enter(&fake_block, &f, &f.Fb, &f.Enable, &f.Update, &f.Valid, &f.Busy, &f.Error,
                                    &f.StatusID),
                     FRACCTRL_STARTED);
    assert_int_equal(f.load_edge, 1);
    f.Update = 1;
    assert_int_equal(fracctrl_enter(&fake_block, &f, &f.Fb, &f.Enable, &f.Update, &f.Valid, &f.Busy, &f.Error,
                                    &f.StatusID),
                     FRACCTRL_RUN);
    assert_int_equal(f.loads, 2);
    assert_int_equal(f.load_edge, 0);
    f.Enable = 0;
    assert_int_equal(fracctrl_enter(&fake_block, &f, &f.Fb, &f.Enable, &f.Update, &f.Valid, &f.Busy, &f.Error,
                                    &f.StatusID),
                     FRACCTRL_HOLD);
    assert_int_equal(f.StatusID, fracSTAT_DISABLED);
    assert_int_equal(f.hold_disabled, 1);
}

static void test_outputs_match_fracctrl_report(void **state)
{
    static const int status[4] = {FRAC_OK, FRAC_W_CLAMPED, FRAC_E_NONFINITE, FRAC_E_PARAM};
    static const UINT par_status[2] = {fracSTAT_OK, fracERR_PARAM};
    int i, j;
    (void)state;
    for (i = 0; i < 4; i++) {
        for (j = 0; j < 2; j++) {
            struct fake got, want;
            memset(&got, 0, sizeof got);
            got.Fb.ParStatus = par_status[j];
            got.Fb.Reported = FRACCTRL_UNREPORTED;
            got.Valid = 7;
            got.Error = 7;
            got.StatusID = 777;
            want = got;
            FRACCTRL_OUTPUTS(&got, status[i]);
            fracctrl_report(&want.Fb, status[i], &want.Valid, &want.Busy, &want.Error, &want.StatusID);
            assert_same(&got, &want);
            assert_int_equal(got.Fb.Reported, status[i]);
            if (i == 0 && j == 0) {
                assert_int_equal(got.Valid, 1);
                assert_int_equal(got.Busy, 1);
                assert_int_equal(got.Error, 0);
                assert_int_equal(got.StatusID, fracSTAT_OK);
            }
            /* reported already: the pins are not written again */
            got.Valid = 7;
            FRACCTRL_OUTPUTS(&got, status[i]);
            assert_int_equal(got.Valid, 7);
        }
    }
}

static void test_spare_bank_is_the_other_one_only_with_a_set_in_effect(void **state)
{
    FracFbStateType fb;
    (void)state;
    memset(&fb, 0, sizeof fb);
    assert_int_equal(fracctrl_spare_bank(&fb, 0), 0);
    assert_int_equal(fracctrl_spare_bank(&fb, 1), 1);
    fb.ParOk = 1;
    assert_int_equal(fracctrl_spare_bank(&fb, 0), 1);
    assert_int_equal(fracctrl_spare_bank(&fb, 1), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_enter_follows_the_enable_update_rules_in_every_state),
        cmocka_unit_test(test_steady_shortcuts_equal_the_rules_over_random_sequences),
        cmocka_unit_test(test_enter_says_started_only_on_the_enable_edge),
        cmocka_unit_test(test_outputs_match_fracctrl_report),
        cmocka_unit_test(test_spare_bank_is_the_other_one_only_with_a_set_in_effect),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
