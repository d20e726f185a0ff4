/* PI^l D^m controller: law, anti-windup, bumpless transfer, limits, bad input (frac/fopid.h). */
#include "frac_test.h"
#include "frac/fopid.h"
#include "frac/fo_gl.h"

static frac_real st[2 * FRAC_GL_STORAGE(4001)];

static frac_fopid_params base(double kp, double ki, double kd, double l, double m, double ts, size_t mem)
{
    frac_fopid_params p;
    p.kp = (frac_real)kp;
    p.ki = (frac_real)ki;
    p.kd = (frac_real)kd;
    p.lambda = (frac_real)l;
    p.mu = (frac_real)m;
    p.tf = FRAC_R(0.0);
    p.b = p.c = FRAC_R(1.0);
    p.delta = FRAC_R(0.0);
    p.umin = -FRAC_REAL_MAX;
    p.umax = FRAC_REAL_MAX;
    p.antiwindup = FRAC_FOPID_AW_NONE;
    p.tt = FRAC_R(1.0);
    p.ts = (frac_real)ts;
    p.op.method = FRAC_FO_GL;
    p.op.memory = mem;
    p.op.wb = FRAC_R(0.01);
    p.op.wh = FRAC_R(100.0);
    p.op.n = 5;
    return p;
}

/* integrator after D^(1-l) is exactly the GL operator of order -l (same generating function) */
static void test_fopid_integral_is_the_gl_operator_of_order_minus_lambda(void **state)
{
    static frac_real gst[FRAC_GL_STORAGE(4001)];
    frac_fopid_params p = base(0.0, 1.0, 0.0, 0.7, 0.0, 1e-3, 4001);
    frac_fopid c;
    frac_gl gl;
    frac_real u, v;
    int k;
    (void)state;
    assert_int_equal(frac_fopid_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_gl_init(&gl, -FRAC_R(0.7), FRAC_R(1e-3), 4001, gst, sizeof gst / sizeof gst[0]), FRAC_OK);
    for (k = 0; k < 4000; k++) {
        frac_real e = (frac_real)(1.0 + sin(0.01 * k));
        assert_int_equal(frac_fopid_step(&c, e, FRAC_R(0.0), &u), FRAC_OK);
        assert_int_equal(frac_gl_step(&gl, e, &v), FRAC_OK);
        assert_close(u, v, 1e-12 * (1.0 + fabs(v)));
    }
}

/* step of e: kp + ki t^l/Gamma(1+l) + kd t^-m/Gamma(1-m) */
static void test_fopid_step_response_is_the_power_law(void **state)
{
    frac_fopid_params p = base(0.5, 2.0, 0.3, 0.6, 0.4, 5e-4, 4001);
    frac_fopid c;
    frac_real u = 0;
    int k;
    (void)state;
    assert_int_equal(frac_fopid_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (k = 0; k < 4000; k++) {
        double t = (k + 1) * 5e-4 - 5e-4;
        assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), FRAC_R(0.0), &u), FRAC_OK);
        if (k == 999 || k == 3999) {
            double exact = 0.5 + 2.0 * pow(t, 0.6) / tgamma(1.6) + 0.3 * pow(t, -0.4) / tgamma(0.6);
            assert_rel(u, exact, 2e-3);
        }
    }
}

static void test_fopid_derivative_filter_and_setpoint_weights(void **state)
{
    frac_fopid_params p = base(2.0, 0.0, 1.0, 0.5, 1.0, 1e-3, 4);
    frac_fopid c;
    frac_real u;
    double af = 1.0 - exp(-1e-3 / 0.05), df = 0.0;
    int k;
    (void)state;
    /* GL of order 1 is the backward difference: a unit step gives 1/h once, then the filter decays it */
    p.tf = FRAC_R(0.05);
    p.b = FRAC_R(0.0);
    assert_int_equal(frac_fopid_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (k = 0; k < 50; k++) {
        double d = k == 0 ? 1e3 : 0.0;
        df += af * (d - df);
        assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), FRAC_R(0.0), &u), FRAC_OK);
        assert_close(u, df, 1e-9 * (1.0 + df)); /* b = 0: no proportional kick from r */
    }
    /* c = 0: no derivative kick either; P acts on -y only */
    p.c = FRAC_R(0.0);
    assert_int_equal(frac_fopid_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), FRAC_R(0.0), &u), FRAC_OK);
    assert_close(u, 0.0, 0.0);
    assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), FRAC_R(0.25), &u), FRAC_OK);
    assert_close(u, -2.0 * 0.25 - af * 0.25e3, 1e-9);
}

/* first-order plant y' = (u - y)/0.2 with |u| <= 1 and a PI^0.8 asked for an unreachable level */
static double windup_overshoot(int aw, double *xi_sat)
{
    frac_fopid_params p = base(0.5, 2.0, 0.0, 0.8, 0.0, 1e-2, 2001);
    frac_fopid c;
    frac_real u = 0;
    double y = 0.0;
    int k, krec = -1;
    p.umin = -FRAC_R(1.0);
    p.umax = FRAC_R(1.0);
    p.antiwindup = aw;
    p.tt = FRAC_R(0.3);
    assert_int_equal(frac_fopid_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (k = 0; k < 5000; k++) {
        double r = k < 1000 ? 2.0 : 0.5; /* 2 is out of reach, then a reachable 0.5 */
        int s = frac_fopid_step(&c, (frac_real)r, (frac_real)y, &u);
        assert_true(u >= -1.0 && u <= 1.0);
        assert_true(s == FRAC_OK || s == FRAC_W_SATURATED);
        if (k == 900) assert_true(u > 0.99); /* held at (clamping: just below) the limit */
        if (k == 999) *xi_sat = c.xi;
        y += 1e-2 * (u - y) / 0.2;
        if (k >= 1000 && krec < 0 && y < 0.6) krec = k - 1000;
    }
    return krec < 0 ? 1e9 : krec * 1e-2;
}

static void test_fopid_antiwindup_limits_the_integral_during_saturation(void **state)
{
    double x0, x1, x2, o0 = windup_overshoot(FRAC_FOPID_AW_NONE, &x0);
    double o1 = windup_overshoot(FRAC_FOPID_AW_CLAMP, &x1), o2 = windup_overshoot(FRAC_FOPID_AW_BACKCALC, &x2);
    (void)state;
    printf("  integral state after 10 s of saturation: none %.3f, clamping %.3f, back-calculation %.3f\n", x0, x1, x2);
    printf("  time for y to come down to 0.6 after the set point drops to 0.5: none %.2f s, clamping %.2f s, back-calculation %.2f s\n", o0, o1, o2);
    assert_true(x0 > 10.0);                 /* wound up */
    assert_true(x1 < 1.5 && x2 < 1.5);      /* held near what the limit needs */
    assert_true(o1 < 0.5 * o0 && o2 < 0.5 * o0);
    assert_true(o0 < 1e9);
}

static void test_fopid_manual_auto_transfer_is_bumpless(void **state)
{
    frac_fopid_params p = base(1.5, 3.0, 0.2, 0.7, 0.5, 1e-2, 1001);
    frac_fopid c;
    frac_real u, ulast = 0;
    double y = 0.0;
    int k;
    (void)state;
    p.tf = FRAC_R(0.05);
    assert_int_equal(frac_fopid_init(&c, &p, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (k = 0; k < 300; k++) {
        assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), (frac_real)y, &u), FRAC_OK);
        y += 1e-2 * (u - y);
        ulast = u;
    }
    /* auto -> manual: the output holds */
    assert_int_equal(frac_fopid_set_mode(&c, FRAC_FOPID_MANUAL), FRAC_OK);
    assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), (frac_real)y, &u), FRAC_OK);
    assert_close(u, ulast, 1e-12);
    /* the operator moves the output by hand */
    assert_int_equal(frac_fopid_set_manual(&c, FRAC_R(0.3)), FRAC_OK);
    for (k = 0; k < 200; k++) {
        assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), (frac_real)y, &u), FRAC_OK);
        assert_close(u, 0.3, 0.0);
        y += 1e-2 * (u - y);
    }
    /* manual -> auto: the first automatic output continues from 0.3 (only this sample's increments) */
    assert_int_equal(frac_fopid_set_mode(&c, FRAC_FOPID_AUTO), FRAC_OK);
    assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), (frac_real)y, &u), FRAC_OK);
    assert_close(u, 0.3, 0.05);
    assert_int_equal(frac_fopid_set_mode(&c, 7), FRAC_E_PARAM);
}

static void test_fopid_rejects_bad_parameters_and_input(void **state)
{
    frac_fopid c, c2;
    frac_fopid_params p = base(1.0, 1.0, 0.1, 0.5, 0.5, 1e-2, 100);
    static frac_real st2[2 * FRAC_GL_STORAGE(100)];
    frac_real u, u2;
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero), inf = (frac_real)(1.0 / zero);
    size_t n = frac_fopid_storage_len(&p);
    int k;
    (void)state;
    assert_int_equal((int)n, 2 * 300);
    assert_int_equal(frac_fopid_init(NULL, &p, st, n), FRAC_E_NULL);
    assert_int_equal(frac_fopid_init(&c, &p, NULL, n), FRAC_E_NULL);
    assert_int_equal(frac_fopid_init(&c, &p, st, n - 1), FRAC_E_STORAGE);
    p.kp = inf; assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_GAIN);
    p.kp = FRAC_R(1.0); p.tf = -FRAC_R(1.0); assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_GAIN);
    p.tf = FRAC_R(0.0); p.lambda = FRAC_R(2.0); assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_ORDER);
    p.lambda = FRAC_R(0.5); p.mu = FRAC_R(2.5); assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_ORDER);
    p.mu = FRAC_R(0.5); p.umin = FRAC_R(1.0); p.umax = FRAC_R(1.0); assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_LIMITS);
    p.umax = nan; assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_LIMITS);
    p.umin = -inf; p.umax = inf; p.antiwindup = 5; assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_PARAM);
    p.antiwindup = FRAC_FOPID_AW_BACKCALC; p.tt = FRAC_R(0.0); assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_GAIN);
    p.tt = FRAC_R(1.0); p.ts = FRAC_R(0.0); assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_TS);
    p.ts = FRAC_R(1e-2); p.op.memory = 0; assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_E_DIM);
    p.op.memory = 100;
    assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), FRAC_R(0.0), &u), FRAC_E_NOT_INIT);
    assert_int_equal(frac_fopid_init(&c, &p, st, n), FRAC_OK);
    assert_int_equal(frac_fopid_init(&c2, &p, st2, n), FRAC_OK);
    for (k = 0; k < 20; k++) {
        assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), FRAC_R(0.1) * k, &u), FRAC_OK);
        assert_int_equal(frac_fopid_step(&c2, FRAC_R(1.0), FRAC_R(0.1) * k, &u2), FRAC_OK);
    }
    assert_int_equal(frac_fopid_step(&c, nan, FRAC_R(0.0), &u2), FRAC_E_NONFINITE);
    assert_true(u2 == u);
    assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), -inf, &u2), FRAC_E_NONFINITE);
    assert_true(u2 == u);
    for (k = 0; k < 20; k++) {
        assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), FRAC_R(0.3), &u), FRAC_OK);
        assert_int_equal(frac_fopid_step(&c2, FRAC_R(1.0), FRAC_R(0.3), &u2), FRAC_OK);
        assert_true(u == u2);
    }
    assert_int_equal(frac_fopid_set_manual(&c, nan), FRAC_E_NONFINITE);
    assert_int_equal(frac_fopid_step(&c, FRAC_R(1.0), FRAC_R(0.0), NULL), FRAC_E_NULL);
    assert_int_equal(frac_fopid_reset(&c), FRAC_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fopid_integral_is_the_gl_operator_of_order_minus_lambda),
        cmocka_unit_test(test_fopid_step_response_is_the_power_law),
        cmocka_unit_test(test_fopid_derivative_filter_and_setpoint_weights),
        cmocka_unit_test(test_fopid_antiwindup_limits_the_integral_during_saturation),
        cmocka_unit_test(test_fopid_manual_auto_transfer_is_bumpless),
        cmocka_unit_test(test_fopid_rejects_bad_parameters_and_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
