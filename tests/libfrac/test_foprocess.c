/* Fractional process K e^{-tau s}/(1 + T s^l) simulator (frac/foprocess.h). */
#include "frac_test.h"
#include "frac/foprocess.h"
#include "frac/mittag_leffler.h"

enum { NSTEP = 20000 };
static frac_real storage[FRAC_GL_STORAGE(NSTEP + 1) + 4096];
static double yout[NSTEP + 1];

static frac_foprocess_params gl_process(double K, double T, double l, double tau, double ts, size_t mem)
{
    frac_foprocess_params p;
    p.k = (frac_real)K;
    p.t = (frac_real)T;
    p.lambda = (frac_real)l;
    p.tau = (frac_real)tau;
    p.ts = (frac_real)ts;
    p.op.method = FRAC_FO_GL;
    p.op.memory = mem;
    p.op.wb = FRAC_R(0.0);
    p.op.wh = FRAC_R(0.0);
    p.op.n = 0;
    return p;
}

/* relative RMS error of the simulated step response against 1 - E_l(-t^l/T) */
static double step_error(frac_foprocess *g, double l, double T, double h, int n)
{
    double num = 0.0, den = 0.0;
    frac_real y;
    int k;
    for (k = 0; k <= n; k++) {
        assert_int_equal(frac_foprocess_step(g, FRAC_R(1.0), &y), FRAC_OK);
        yout[k] = y;
    }
    for (k = 0; k <= n; k += 10) {
        frac_real e;
        double t = k * h;
        assert_int_equal(frac_mittag_leffler((frac_real)l, FRAC_R(1.0), (frac_real)(-pow(t, l) / T), &e), FRAC_OK);
        num += (yout[k] - (1.0 - e)) * (yout[k] - (1.0 - e));
        den += (1.0 - e) * (1.0 - e);
    }
    return sqrt(num / den);
}

/* settings: GL, full memory, h = 5e-4 T^(1/l), horizon 10 T^(1/l) */
static void test_foprocess_step_response_matches_mittag_leffler(void **state)
{
    double ls[3] = {0.5, 1.2, 1.92}, T = 0.0292866; /* T = 1/w0^2 of the seed 001 robot */
    int i;
    (void)state;
    printf("  step of 1/(1 + T s^l), T = %g, GL full memory, h = 5e-4 T^(1/l), t in [0, 10 T^(1/l)]\n", T);
    for (i = 0; i < 3; i++) {
        double tn = pow(T, 1.0 / ls[i]), h = 5e-4 * tn, err;
        frac_foprocess_params p = gl_process(1.0, T, ls[i], 0.0, h, NSTEP + 1);
        frac_foprocess g;
        assert_int_equal(frac_foprocess_init(&g, &p, storage, sizeof storage / sizeof storage[0]), FRAC_OK);
        err = step_error(&g, ls[i], T, h, NSTEP);
        printf("    l = %4.2f  h = %.3e s  relative RMS error %.2e\n", ls[i], h, err);
        assert_true(err <= 1e-3);
    }
}

/* the rational realizations: Oustaloup over a wide band, reported for comparison */
static void test_foprocess_runs_on_oustaloup(void **state)
{
    double ls[2] = {0.5, 1.2}, T = 1.0;
    int i;
    (void)state;
    for (i = 0; i < 2; i++) {
        double h = 5e-3, err;
        frac_foprocess_params p = gl_process(1.0, T, ls[i], 0.0, h, 0);
        frac_foprocess g;
        p.op.method = FRAC_FO_OUSTALOUP;
        p.op.wb = FRAC_R(1e-4);
        p.op.wh = FRAC_R(500.0);
        p.op.n = 12;
        assert_int_equal(frac_foprocess_init(&g, &p, storage, sizeof storage / sizeof storage[0]), FRAC_OK);
        err = step_error(&g, ls[i], T, h, 4000);
        printf("    Oustaloup N = 12 on [1e-4, 500] rad/s, h = %g: l = %4.2f relative RMS error %.2e\n", h, ls[i], err);
        assert_true(err <= 2e-2);
    }
}

static void test_foprocess_delays_the_input_by_tau(void **state)
{
    frac_foprocess g, g0;
    static frac_real st0[FRAC_GL_STORAGE(500) + 16];
    frac_foprocess_params p = gl_process(2.0, 0.5, 0.8, 0.0, 0.01, 500);
    frac_real y, y0;
    double u[400];
    int k;
    (void)state;
    for (k = 0; k < 400; k++) u[k] = sin(0.05 * k) + 0.3 * (k > 40);
    /* tau = 7.4 Ts: output = delay-free output of the interpolated input */
    assert_int_equal(frac_foprocess_init(&g0, &p, st0, sizeof st0 / sizeof st0[0]), FRAC_OK);
    p.tau = FRAC_R(0.074);
    assert_int_equal(frac_foprocess_init(&g, &p, storage, sizeof storage / sizeof storage[0]), FRAC_OK);
    for (k = 0; k < 400; k++) {
        double v = k >= 8 ? 0.6 * u[k - 7] + 0.4 * u[k - 8] : (k == 7 ? 0.6 * u[0] : 0.0);
        assert_int_equal(frac_foprocess_step(&g, (frac_real)u[k], &y), FRAC_OK);
        assert_int_equal(frac_foprocess_step(&g0, (frac_real)v, &y0), FRAC_OK);
        assert_close(y, y0, 1e-12);
    }
    /* steady state: short memory leaves D^l 1 = h^-l sum_{j<L} w_j, so y = K/(1 + T h^-l sum w_j) */
    assert_int_equal(frac_foprocess_reset(&g0), FRAC_OK);
    for (k = 0; k < 40000; k++) assert_int_equal(frac_foprocess_step(&g0, FRAC_R(1.0), &y0), FRAC_OK);
    {
        double sw = 0.0;
        for (k = 0; k < 500; k++) sw += g0.op.gl.wrev[k];
        assert_close(y0, 2.0 / (1.0 + 0.5 * sw), 1e-9);
        assert_close(y0, 2.0, 0.1);
    }
}

static void test_foprocess_rejects_bad_parameters_and_input(void **state)
{
    frac_foprocess g;
    frac_foprocess_params p = gl_process(1.0, 1.0, 1.5, 0.05, 0.01, 100);
    frac_real y, y1;
    size_t n = frac_foprocess_storage_len(&p);
    volatile double zero = 0.0;
    frac_real nan = (frac_real)(zero / zero);
    (void)state;
    assert_int_equal((int)n, 300 + 6);
    assert_int_equal(frac_foprocess_init(NULL, &p, storage, n), FRAC_E_NULL);
    assert_int_equal(frac_foprocess_init(&g, &p, NULL, n), FRAC_E_NULL);
    assert_int_equal(frac_foprocess_init(&g, &p, storage, n - 1), FRAC_E_STORAGE);
    p.k = nan; assert_int_equal(frac_foprocess_init(&g, &p, storage, n), FRAC_E_GAIN);
    p.k = FRAC_R(1.0); p.t = FRAC_R(0.0); assert_int_equal(frac_foprocess_init(&g, &p, storage, n), FRAC_E_GAIN);
    p.t = FRAC_R(1.0); p.lambda = FRAC_R(2.2); assert_int_equal(frac_foprocess_init(&g, &p, storage, n), FRAC_E_ORDER);
    p.lambda = FRAC_R(0.0); assert_int_equal(frac_foprocess_init(&g, &p, storage, n), FRAC_E_ORDER);
    p.lambda = FRAC_R(1.5); p.tau = -FRAC_R(1.0); assert_int_equal(frac_foprocess_init(&g, &p, storage, n), FRAC_E_PARAM);
    p.tau = FRAC_R(0.05); p.ts = FRAC_R(0.0); assert_int_equal(frac_foprocess_init(&g, &p, storage, n), FRAC_E_TS);
    p.ts = FRAC_R(0.01); p.op.memory = 0; assert_int_equal(frac_foprocess_init(&g, &p, storage, 5000), FRAC_E_DIM);
    p.op.memory = 100;
    assert_int_equal(frac_foprocess_step(&g, FRAC_R(1.0), &y), FRAC_E_NOT_INIT);
    assert_int_equal(frac_foprocess_init(&g, &p, storage, n), FRAC_OK);
    assert_int_equal(frac_foprocess_step(&g, FRAC_R(1.0), &y), FRAC_OK);
    assert_int_equal(frac_foprocess_step(&g, nan, &y1), FRAC_E_NONFINITE);
    assert_true(y1 == y);
    assert_int_equal(frac_foprocess_step(&g, FRAC_R(1.0), NULL), FRAC_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_foprocess_step_response_matches_mittag_leffler),
        cmocka_unit_test(test_foprocess_runs_on_oustaloup),
        cmocka_unit_test(test_foprocess_delays_the_input_by_tau),
        cmocka_unit_test(test_foprocess_rejects_bad_parameters_and_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
