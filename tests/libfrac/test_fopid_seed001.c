/*
 * Seed 001 robot (notes 001 sections 6-8): G(s) = e^{-tau s}/(1 + T s^l),
 * l = 1.92, T = 1/w0^2, w0 = 5.8434 rad/s, tau = 0.1613 s, K = 1, closed
 * with the FO-PI (52) and the FO-PD with positive feedback delta = 1/K
 * (41), all fractional operators by Grünwald–Letnikov at Ts = 2 ms (the
 * paper's realization, section 5.3). The plant runs on frac_foprocess.
 */
#include "frac_test.h"
#include <complex.h>
#include "frac/foprocess.h"
#include "frac/fopid.h"

#define W0 5.8434
#define TAU 0.1613
#define LAMBDA 1.92
#define PLANT_T (1.0 / (W0 * W0))

enum { NMAX = 30001 };
static frac_real plant_st[FRAC_GL_STORAGE(NMAX) + 200], ctrl_st[2 * FRAC_GL_STORAGE(NMAX)];
static double ybuf[NMAX];

static void plant_init(frac_foprocess *g, double ts, size_t mem)
{
    frac_foprocess_params p;
    p.k = FRAC_R(1.0);
    p.t = (frac_real)PLANT_T;
    p.lambda = (frac_real)LAMBDA;
    p.tau = (frac_real)TAU;
    p.ts = (frac_real)ts;
    p.op.method = FRAC_FO_GL;
    p.op.memory = mem;
    p.op.wb = p.op.wh = FRAC_R(0.0);
    p.op.n = 0;
    assert_int_equal(frac_foprocess_init(g, &p, plant_st, sizeof plant_st / sizeof plant_st[0]), FRAC_OK);
}

static void ctrl_init(frac_fopid *c, double kp, double ki, double kd, double delta, double ts, size_t mem)
{
    frac_fopid_params p;
    p.kp = (frac_real)kp;
    p.ki = (frac_real)ki;
    p.kd = (frac_real)kd;
    p.lambda = p.mu = FRAC_R(0.88); /* alpha = mu = 0.88 */
    p.tf = FRAC_R(0.0);
    p.b = p.c = FRAC_R(1.0);
    p.delta = (frac_real)delta;
    p.umin = -FRAC_REAL_MAX;
    p.umax = FRAC_REAL_MAX;
    p.antiwindup = FRAC_FOPID_AW_NONE;
    p.tt = FRAC_R(1.0);
    p.ts = (frac_real)ts;
    p.op.method = FRAC_FO_GL;
    p.op.memory = mem;
    p.op.wb = p.op.wh = FRAC_R(0.0);
    p.op.n = 0;
    assert_int_equal(frac_fopid_init(c, &p, ctrl_st, sizeof ctrl_st / sizeof ctrl_st[0]), FRAC_OK);
}

/* closed loop: r step of 0.5 at t = 0, n samples into ybuf */
static void run_pi(double ts, int n)
{
    frac_foprocess g;
    frac_fopid c;
    frac_real y = 0, u = 0;
    int k;
    plant_init(&g, ts, (size_t)(20.0 / ts)); /* 20 s of plant memory: its weights decay as j^-2.92 */
    ctrl_init(&c, 0.1219, 0.1255, 0.0, 0.0, ts, (size_t)n + 1);
    for (k = 0; k < n; k++) {
        assert_int_equal(frac_fopid_step(&c, FRAC_R(0.5), y, &u), FRAC_OK);
        assert_int_equal(frac_foprocess_step(&g, u, &y), FRAC_OK);
        ybuf[k] = y;
    }
}

/* dominant root of 1 + C(s) G(s) = 0 by Newton from s0 (exact irrational loop) */
static double complex char_fn(double complex s)
{
    double complex C = 0.1219 + 0.1255 * cpow(s, -0.88);
    return 1.0 + C * cexp(-TAU * s) / (1.0 + PLANT_T * cpow(s, LAMBDA));
}
static double complex newton(double complex s)
{
    int it;
    for (it = 0; it < 100; it++) {
        double complex f = char_fn(s), d = (char_fn(s + 1e-7) - char_fn(s - 1e-7)) / 2e-7, ds = f / d;
        s -= ds;
        if (cabs(ds) < 1e-13) break;
    }
    return s;
}

/*
 * Ripple of y around its one-period moving average on [t0, t1]: angular
 * frequency from the up-crossings, decay rate from a least-squares line
 * through the log of the peak-to-peak amplitude of each period.
 */
static void ripple(const double *y, int n, double ts, double wguess, double t0, double t1, double *w, double *sigma)
{
    int m = (int)(2.0 * M_PI / wguess / ts + 0.5), k, nz = 0, i;
    static double r[NMAX], tz[4000];
    double sx = 0, sy = 0, sxx = 0, sxy = 0, np = 0, acc = 0;
    for (k = 0; k < n; k++) r[k] = 0.0;
    for (k = 0; k < m; k++) acc += y[k];
    for (k = m / 2; k + m / 2 + 1 < n; k++) {
        r[k] = y[k] - acc / m;
        acc += y[k + m / 2 + 1] - y[k - m / 2];
    }
    for (k = (int)(t0 / ts); k < (int)(t1 / ts) && k + 1 < n; k++)
        if (r[k] < 0.0 && r[k + 1] >= 0.0 && nz < 4000) tz[nz++] = ts * (k + r[k] / (r[k] - r[k + 1]));
    *w = 2.0 * M_PI * (nz - 1) / (tz[nz - 1] - tz[0]);
    for (i = 0; i + 1 < nz; i++) {
        double lo = 1e300, hi = -1e300, tc = 0.5 * (tz[i] + tz[i + 1]), la;
        for (k = (int)(tz[i] / ts) + 1; k <= (int)(tz[i + 1] / ts); k++) {
            if (r[k] < lo) lo = r[k];
            if (r[k] > hi) hi = r[k];
        }
        la = log(hi - lo);
        sx += tc; sy += la; sxx += tc * tc; sxy += tc * la; np += 1;
    }
    *sigma = (np * sxy - sx * sy) / (np * sxx - sx * sx);
}

static void test_seed001_pi_loop_reproduces_the_note_and_the_exact_closed_loop_poles(void **state)
{
    double complex p = newton(-0.05 + 6.36 * I);
    double h80 = TAU / 80.0, w2, s2, w1, s1, sx;
    int n40 = (int)(40.0 / h80 + 0.5);
    (void)state;
    /* note 001 section 8.3 [D]: GL full memory, h = tau/80, 0.5 step: y(40 s) = 0.4544 */
    run_pi(h80, n40 + 1);
    printf("  PI (52), h = tau/80: y(40 s) = %.5f (note 001, sec. 8.3: 0.4544)\n", ybuf[n40 - 1]);
    assert_close(ybuf[n40 - 1], 0.4544, 1e-3);
    assert_true(ybuf[n40 - 1] < 0.5); /* slow fractional creep from below */
    /* the ripple is the dominant closed-loop pole pair of the exact loop */
    run_pi(2e-3, 15000);
    ripple(ybuf, 15000, 2e-3, 6.4, 8.0, 29.0, &w2, &s2);
    run_pi(1e-3, 30000);
    ripple(ybuf, 30000, 1e-3, 6.4, 8.0, 29.0, &w1, &s1);
    sx = 2.0 * s1 - s2; /* GL is first order in Ts: Richardson extrapolation */
    printf("  exact dominant poles of 1 + C G = 0: %.5f +- %.5fj\n", creal(p), cimag(p));
    printf("  simulated ripple: Ts = 2 ms: w = %.5f, sigma = %.5f; Ts = 1 ms: w = %.5f, sigma = %.5f; "
           "extrapolated sigma = %.5f\n", w2, s2, w1, s1, sx);
    assert_close(creal(p), -0.0320, 1e-4);
    assert_close(cimag(p), 6.4529, 1e-4);
    assert_true(fabs(w2 - cimag(p)) < 2e-3 * cimag(p));
    assert_true(fabs(w1 - cimag(p)) < 1e-3 * cimag(p));
    assert_true(s2 < 0.0 && s1 < 0.0);   /* stable at Ts = 2 ms */
    assert_true(fabs(sx - creal(p)) < 0.05 * fabs(creal(p)));
}

/*
 * PD (41), delta = 1: y_ss = a/(K^p + delta) for an input step a and
 * -a K^p/(K^p + delta) for a sensor step a (seed 001 (43), (45)). The
 * D^m term makes the loop approach y_ss as t^-m (exactly like the
 * continuous loop: the PD acts on an error whose m-th derivative decays
 * as t^-m), so y_ss is read by fitting y = y_ss + c t^-m to the means of
 * two windows of whole ripple periods.
 */
static void pd_disturbance(double kph, int sensor, double *yss, double *yend)
{
    frac_foprocess g;
    frac_fopid c;
    frac_real y = 0, u = 0;
    double ts = 2e-3, a = 1.0, m1 = 0, m2 = 0, t1 = 0, t2 = 0;
    int n = 30000, k, n1 = 0, n2 = 0;
    plant_init(&g, ts, 10000); /* 20 s of plant memory: DC error ~1e-5 */
    ctrl_init(&c, kph + 1.0, 0.0, 0.02556009, 1.0, ts, (size_t)n + 1);
    for (k = 0; k < n; k++) {
        frac_real ym = sensor ? y + (frac_real)a : y;
        double t = (k + 1) * ts;
        assert_int_equal(frac_fopid_step(&c, FRAC_R(0.0), ym, &u), FRAC_OK);
        assert_int_equal(frac_foprocess_step(&g, u + (sensor ? FRAC_R(0.0) : (frac_real)a), &y), FRAC_OK);
        if (t > 30.0 && t <= 40.0) { m1 += y; t1 += pow(t, -0.88); n1++; }
        if (t > 50.0) { m2 += y; t2 += pow(t, -0.88); n2++; }
    }
    m1 /= n1; m2 /= n2; t1 /= n1; t2 /= n2;
    *yss = (m2 * t1 - m1 * t2) / (t1 - t2);
    *yend = y;
}

static void test_seed001_pd_positive_feedback_steady_state_errors(void **state)
{
    /* K^p: reading (a) of note 001 section 6.4 (spec-consistent, w_c = 6.86) and (c) (K^p = 0) */
    double kphs[2] = {0.1552108, 0.0};
    int i, sensor;
    (void)state;
    for (i = 0; i < 2; i++)
        for (sensor = 0; sensor < 2; sensor++) {
            double kph = kphs[i], want = sensor ? -kph / (kph + 1.0) : 1.0 / (kph + 1.0), yss, yend;
            pd_disturbance(kph, sensor, &yss, &yend);
            printf("  PD K^p = %.7f, %s step a = 1: y_ss = %.7f (y(60 s) = %.7f), exact %.7f, error %.1e\n", kph,
                   sensor ? "sensor" : "input ", yss, yend, want, yss - want);
            assert_close(yss, want, 1e-4);
            assert_close(yend, want, 3e-4);
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_seed001_pi_loop_reproduces_the_note_and_the_exact_closed_loop_poles),
        cmocka_unit_test(test_seed001_pd_positive_feedback_steady_state_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
