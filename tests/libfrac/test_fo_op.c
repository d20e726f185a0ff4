/* Common front of the s^r realizations (frac/fo_op.h). */
#include "frac_test.h"
#include "frac/fo_op.h"

static frac_fo_params params(int method, double r)
{
    frac_fo_params p;
    p.method = method;
    p.order = (frac_real)r;
    p.ts = FRAC_R(1e-3);
    p.memory = 200;
    p.wb = FRAC_R(0.1);
    p.wh = FRAC_R(1000.0);
    p.n = 5;
    return p;
}

static void test_fo_op_runs_the_chosen_realization(void **state)
{
    static frac_real st[FRAC_GL_STORAGE(200)], st2[FRAC_GL_STORAGE(200)];
    int m;
    (void)state;
    for (m = FRAC_FO_GL; m <= FRAC_FO_CFE_ALALAOUI; m++) {
        frac_fo_params p = params(m, 0.6);
        frac_fo op;
        frac_gl gl;
        frac_oustaloup ou;
        frac_oustaloup_params op_;
        frac_cfe cf;
        frac_cfe_params cp;
        frac_real y, y2 = 0, re, im, re2 = 0, im2 = 0;
        int k;
        assert_true(frac_fo_storage_len(&p) > 0 && frac_fo_storage_len(&p) <= FRAC_GL_STORAGE(200));
        assert_int_equal(frac_fo_init(&op, &p, st, frac_fo_storage_len(&p)), FRAC_OK);
        op_.order = p.order; op_.wb = p.wb; op_.wh = p.wh; op_.ts = p.ts; op_.n = p.n;
        op_.refined = m == FRAC_FO_OUSTALOUP_REFINED;
        cp.order = p.order; cp.ts = p.ts; cp.n = p.n;
        cp.rule = m == FRAC_FO_CFE_TUSTIN ? FRAC_CFE_TUSTIN : FRAC_CFE_ALALAOUI;
        if (m == FRAC_FO_GL) assert_int_equal(frac_gl_init(&gl, p.order, p.ts, p.memory, st2, sizeof st2 / sizeof st2[0]), FRAC_OK);
        else if (m <= FRAC_FO_OUSTALOUP_REFINED) assert_int_equal(frac_oustaloup_init(&ou, &op_, st2, sizeof st2 / sizeof st2[0]), FRAC_OK);
        else assert_int_equal(frac_cfe_init(&cf, &cp, st2, sizeof st2 / sizeof st2[0]), FRAC_OK);
        for (k = 0; k < 300; k++) {
            frac_real x = (frac_real)sin(0.05 * k), y0, g = frac_fo_feedthrough(&op);
            assert_int_equal(frac_fo_free_response(&op, &y0), FRAC_OK);
            assert_int_equal(frac_fo_step(&op, x, &y), FRAC_OK);
            if (m == FRAC_FO_GL) frac_gl_step(&gl, x, &y2);
            else if (m <= FRAC_FO_OUSTALOUP_REFINED) frac_oustaloup_step(&ou, x, &y2);
            else frac_cfe_step(&cf, x, &y2);
            assert_true(y == y2);
            assert_close(y, g * x + y0, 1e-9 * (1.0 + fabs(y)));
            assert_true(frac_fo_output(&op) == y);
        }
        assert_int_equal(frac_fo_freqresp(&op, FRAC_R(30.0), &re, &im), FRAC_OK);
        if (m == FRAC_FO_GL) frac_gl_freqresp(&gl, FRAC_R(30.0), &re2, &im2);
        else if (m <= FRAC_FO_OUSTALOUP_REFINED) frac_oustaloup_freqresp(&ou, FRAC_R(30.0), &re2, &im2);
        else frac_cfe_freqresp(&cf, FRAC_R(30.0), &re2, &im2);
        assert_true(re == re2 && im == im2);
    }
}

static void test_fo_op_order_zero_is_the_identity_without_storage(void **state)
{
    frac_fo op;
    frac_fo_params p = params(FRAC_FO_OUSTALOUP_REFINED, 0.0);
    frac_real y, re, im;
    (void)state;
    assert_int_equal((int)frac_fo_storage_len(&p), 0);
    assert_int_equal(frac_fo_init(&op, &p, NULL, 0), FRAC_OK);
    assert_int_equal(frac_fo_step(&op, FRAC_R(-4.5), &y), FRAC_OK);
    assert_close(y, -4.5, 0.0);
    assert_close(frac_fo_feedthrough(&op), 1.0, 0.0);
    assert_int_equal(frac_fo_freqresp(&op, FRAC_R(10.0), &re, &im), FRAC_OK);
    assert_close(re, 1.0, 0.0);
    assert_close(im, 0.0, 0.0);
}

static void test_fo_op_steady_state_for_constant_input(void **state)
{
    static frac_real st[FRAC_GL_STORAGE(200)];
    frac_fo op;
    frac_fo_params p = params(FRAC_FO_OUSTALOUP, -0.5);
    frac_real y, y1, re, im;
    (void)state;
    assert_int_equal(frac_fo_init(&op, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_fo_set_steady(&op, FRAC_R(2.0)), FRAC_OK);
    assert_int_equal(frac_fo_freqresp(&op, FRAC_R(0.0), &re, &im), FRAC_OK);
    assert_int_equal(frac_fo_step(&op, FRAC_R(2.0), &y), FRAC_OK);
    assert_int_equal(frac_fo_step(&op, FRAC_R(2.0), &y1), FRAC_OK);
    assert_close(y, 2.0 * re, 1e-9 * fabs(re));
    assert_close(y1, y, 1e-9 * fabs(y));
    /* an integer integrator part has no steady state */
    p = params(FRAC_FO_CFE_ALALAOUI, -1.5);
    assert_int_equal(frac_fo_init(&op, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_fo_set_steady(&op, FRAC_R(1.0)), FRAC_E_NUMERIC);
}

static void test_fo_op_rejects_bad_parameters_and_input(void **state)
{
    static frac_real st[FRAC_GL_STORAGE(200)];
    frac_fo op;
    frac_fo_params p = params(FRAC_FO_GL, 0.5);
    frac_real y, y1;
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero);
    (void)state;
    assert_int_equal(frac_fo_init(NULL, &p, st, 600), FRAC_E_NULL);
    assert_int_equal(frac_fo_init(&op, NULL, st, 600), FRAC_E_NULL);
    assert_int_equal(frac_fo_init(&op, &p, NULL, 600), FRAC_E_NULL);
    p.method = 9; assert_int_equal(frac_fo_init(&op, &p, st, 600), FRAC_E_PARAM);
    assert_int_equal((int)frac_fo_storage_len(&p), 0);
    p.method = FRAC_FO_GL; p.order = nan; assert_int_equal(frac_fo_init(&op, &p, st, 600), FRAC_E_ORDER);
    p.order = FRAC_R(0.5); p.ts = FRAC_R(0.0); assert_int_equal(frac_fo_init(&op, &p, st, 600), FRAC_E_TS);
    p.ts = FRAC_R(1e-3); assert_int_equal(frac_fo_init(&op, &p, st, 599), FRAC_E_STORAGE);
    p.method = FRAC_FO_OUSTALOUP; p.wh = FRAC_R(5000.0); assert_int_equal(frac_fo_init(&op, &p, st, 600), FRAC_E_BAND);
    p.method = FRAC_FO_CFE_TUSTIN; p.order = FRAC_R(1.5); assert_int_equal(frac_fo_init(&op, &p, st, 600), FRAC_E_UNSTABLE);
    assert_int_equal(frac_fo_step(&op, FRAC_R(1.0), &y), FRAC_E_NOT_INIT);
    p = params(FRAC_FO_CFE_TUSTIN, 0.5);
    assert_int_equal(frac_fo_init(&op, &p, st, 600), FRAC_OK);
    assert_int_equal(frac_fo_step(&op, FRAC_R(1.0), &y), FRAC_OK);
    assert_int_equal(frac_fo_step(&op, nan, &y1), FRAC_E_NONFINITE);
    assert_true(y1 == y);
    assert_int_equal(frac_fo_set_steady(&op, nan), FRAC_E_NONFINITE);
    assert_int_equal(frac_fo_reset(&op), FRAC_OK);
    assert_true(frac_fo_output(&op) == FRAC_R(0.0));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fo_op_runs_the_chosen_realization),
        cmocka_unit_test(test_fo_op_order_zero_is_the_identity_without_storage),
        cmocka_unit_test(test_fo_op_steady_state_for_constant_input),
        cmocka_unit_test(test_fo_op_rejects_bad_parameters_and_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
