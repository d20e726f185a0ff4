/*
 * cdriver.c - the plain C loop over libfrac that the fracarm binding is
 * compared with bit for bit (python/tests/test_libfrac.py) and timed against
 * (tests/bench/bench_python.sh).
 *
 * Reads one job from stdin as whitespace-separated tokens (numbers in any
 * strtod form; Python writes repr(), which round-trips), runs the libfrac
 * step once per sample, and prints every output as a C99 hex float ("%a",
 * exact) on its own line. Jobs (method: gl oustaloup oustaloup_refined
 * cfe_tustin cfe_alalaoui; OP = METHOD MEMORY WB WH N):
 *   fo ORDER TS OP  NS x...
 *   fopid KP KI KD LAM MU TF B C DELTA UMIN UMAX AW TT TS OP  NS (r y)...
 *   fodamp KC ALPHA M N1 N2 D1 D2 FA FBETA FB TS OP  NS (ref meas)...
 *   lut1 INTERP RANGE N x... y...  NQ xq...
 *   lut2 INTERP RANGE N1 x1... N2 x2... z(N1*N2)...  NQ (x1q x2q)...
 *   kalman N M P A B C Q R P0  NS (u(M) y(P))...   prints x a posteriori (N per sample)
 *   lqg N DI P DO(P) A B C K(NB) L((NB+1)*P)  NS (u_star y_ref(P) y(P))...
 * "time REPS <job>" runs the job's loop REPS times (state reset between
 * repetitions), prints "ns_per_sample X" and no outputs.
 * Exit 1 with a message on a malformed job or an init error.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "frac/fo_op.h"
#include "frac/fodamp.h"
#include "frac/fopid.h"
#include "frac/kalman.h"
#include "frac/lqg.h"
#include "frac/lut.h"

static char tok[256];

static const char *next(void)
{
    if (scanf("%255s", tok) != 1) {
        fprintf(stderr, "cdriver: unexpected end of input\n");
        exit(1);
    }
    return tok;
}
static double num(void) { return strtod(next(), NULL); }
static size_t cnt(void) { return (size_t)strtoul(next(), NULL, 10); }
static double *nums(size_t n)
{
    double *v = malloc((n ? n : 1) * sizeof *v);
    size_t i;
    for (i = 0; i < n; ++i) v[i] = num();
    return v;
}
static void ok(int st, const char *fn)
{
    if (st < 0) {
        fprintf(stderr, "cdriver: %s: %s\n", fn, frac_status_str(st));
        exit(1);
    }
}
static int method(const char *m)
{
    if (!strcmp(m, "gl")) return FRAC_FO_GL;
    if (!strcmp(m, "oustaloup")) return FRAC_FO_OUSTALOUP;
    if (!strcmp(m, "oustaloup_refined")) return FRAC_FO_OUSTALOUP_REFINED;
    if (!strcmp(m, "cfe_tustin")) return FRAC_FO_CFE_TUSTIN;
    if (!strcmp(m, "cfe_alalaoui")) return FRAC_FO_CFE_ALALAOUI;
    fprintf(stderr, "cdriver: unknown method %s\n", m);
    exit(1);
}
static void op_params(frac_fo_params *p, double order, double ts)
{
    p->method = method(next());
    p->order = order;
    p->ts = ts;
    p->memory = cnt();
    p->wb = num();
    p->wh = num();
    p->n = (unsigned)cnt();
}
static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
}
static void print(const double *y, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) printf("%a\n", y[i]);
}

int main(void)
{
    long reps = 0, r;
    const char *job = next();
    char name[32];
    double t0 = 0, t1 = 0;
    size_t ns = 0, i;
    double *y = NULL;
    if (!strcmp(job, "time")) {
        reps = strtol(next(), NULL, 10);
        job = next();
    }
    strncpy(name, job, sizeof name - 1);
    name[sizeof name - 1] = 0;
    if (!strcmp(name, "fo")) {
        frac_fo op;
        frac_fo_params p;
        double order = num(), ts = num(), *x, *st;
        op_params(&p, order, ts);
        st = malloc((frac_fo_storage_len(&p) + 1) * sizeof *st);
        ok(frac_fo_init(&op, &p, st, frac_fo_storage_len(&p) + 1), "frac_fo_init");
        ns = cnt();
        x = nums(ns);
        y = malloc((ns ? ns : 1) * sizeof *y);
        t0 = now_ns();
        for (r = 0; r < (reps ? reps : 1); ++r) {
            frac_fo_reset(&op);
            for (i = 0; i < ns; ++i) frac_fo_step(&op, x[i], &y[i]);
        }
        t1 = now_ns();
    } else if (!strcmp(name, "fopid")) {
        frac_fopid c;
        frac_fopid_params p;
        double *in, *st;
        p.kp = num(); p.ki = num(); p.kd = num(); p.lambda = num(); p.mu = num(); p.tf = num();
        p.b = num(); p.c = num(); p.delta = num(); p.umin = num(); p.umax = num();
        p.antiwindup = (int)cnt(); p.tt = num(); p.ts = num();
        op_params(&p.op, 0, p.ts);
        st = malloc((frac_fopid_storage_len(&p) + 1) * sizeof *st);
        ok(frac_fopid_init(&c, &p, st, frac_fopid_storage_len(&p) + 1), "frac_fopid_init");
        ns = cnt();
        in = nums(2 * ns);
        y = malloc((ns ? ns : 1) * sizeof *y);
        for (i = 0; i < ns; ++i) frac_fopid_step(&c, in[2 * i], in[2 * i + 1], &y[i]);
    } else if (!strcmp(name, "fodamp")) {
        frac_fodamp c;
        frac_fodamp_params p;
        double *in, *st;
        p.kc = num(); p.alpha = num(); p.m = (unsigned)cnt(); p.n1 = num(); p.n2 = num(); p.d1 = num();
        p.d2 = num(); p.fa = num(); p.fbeta = num(); p.fb = num(); p.ts = num();
        op_params(&p.op, 0, p.ts);
        st = malloc((frac_fodamp_storage_len(&p) + 1) * sizeof *st);
        ok(frac_fodamp_init(&c, &p, st, frac_fodamp_storage_len(&p) + 1), "frac_fodamp_init");
        ns = cnt();
        in = nums(2 * ns);
        y = malloc((ns ? ns : 1) * sizeof *y);
        for (i = 0; i < ns; ++i) frac_fodamp_step(&c, in[2 * i], in[2 * i + 1], &y[i]);
    } else if (!strcmp(name, "lut1")) {
        frac_lut1 t;
        int interp = (int)cnt(), range = (int)cnt();
        size_t n = cnt();
        double *x = nums(n), *v = nums(n), *d = malloc(n * sizeof *d), *q;
        ok(frac_lut1_init(&t, x, v, n, interp, range, d), "frac_lut1_init");
        ns = cnt();
        q = nums(ns);
        y = malloc((ns ? ns : 1) * sizeof *y);
        for (i = 0; i < ns; ++i) frac_lut1_eval(&t, q[i], &y[i]);
    } else if (!strcmp(name, "lut2")) {
        frac_lut2 t;
        frac_lut_axis_params a1, a2;
        int interp = (int)cnt(), range = (int)cnt();
        double *x1, *x2, *z, *q;
        a1.n = cnt(); x1 = nums(a1.n); a1.x = x1; a1.x0 = a1.h = 0;
        a2.n = cnt(); x2 = nums(a2.n); a2.x = x2; a2.x0 = a2.h = 0;
        z = nums(a1.n * a2.n);
        ok(frac_lut2_init_interp(&t, &a1, &a2, z, range, interp), "frac_lut2_init_interp");
        ns = cnt();
        q = nums(2 * ns);
        y = malloc((ns ? ns : 1) * sizeof *y);
        for (i = 0; i < ns; ++i) frac_lut2_eval(&t, q[2 * i], q[2 * i + 1], &y[i]);
    } else if (!strcmp(name, "kalman")) {
        frac_kalman kf;
        frac_kalman_params p;
        double *in, *st;
        size_t k;
        p.n = cnt(); p.m = cnt(); p.p = cnt();
        p.A = nums(p.n * p.n); p.B = nums(p.n * p.m); p.C = nums(p.p * p.n);
        p.Q = nums(p.n * p.n); p.R = nums(p.p * p.p); p.P0 = nums(p.n * p.n); p.x0 = NULL;
        if (p.m == 0) p.B = NULL;
        st = malloc(FRAC_KALMAN_STORAGE(p.n, p.p) * sizeof *st);
        ok(frac_kalman_init(&kf, &p, st, FRAC_KALMAN_STORAGE(p.n, p.p)), "frac_kalman_init");
        ns = cnt();
        in = nums(ns * (p.m + p.p));
        y = malloc((ns * p.n ? ns * p.n : 1) * sizeof *y);
        for (i = 0; i < ns; ++i) {
            const double *u = in + i * (p.m + p.p);
            frac_kalman_update(&kf, u + p.m);
            for (k = 0; k < p.n; ++k) y[i * p.n + k] = kf.x[k];
            frac_kalman_predict(&kf, p.m ? u : NULL);
        }
        ns *= p.n;
    } else if (!strcmp(name, "lqg")) {
        frac_lqg c;
        frac_lqg_params p;
        size_t d_o[FRAC_MAT_MAX], nb, k;
        double *in, *st;
        p.n = cnt(); p.d_i = cnt(); p.p = cnt();
        nb = p.n + p.d_i;
        for (k = 0; k < p.p; ++k) { d_o[k] = cnt(); nb += d_o[k]; }
        p.d_o = d_o;
        p.A = nums(p.n * p.n); p.B = nums(p.n); p.C = nums(p.p * p.n); p.K = nums(nb); p.L = nums((nb + 1) * p.p);
        st = malloc(FRAC_LQG_STORAGE(nb + 1, p.p) * sizeof *st);
        ok(frac_lqg_init(&c, &p, st, FRAC_LQG_STORAGE(nb + 1, p.p)), "frac_lqg_init");
        ns = cnt();
        in = nums(ns * (1 + 2 * p.p));
        y = malloc((ns ? ns : 1) * sizeof *y);
        for (i = 0; i < ns; ++i) {
            const double *v = in + i * (1 + 2 * p.p);
            frac_lqg_step(&c, v[0], v + 1, v + 1 + p.p, &y[i]);
        }
    } else {
        fprintf(stderr, "cdriver: unknown job %s\n", name);
        return 1;
    }
    if (reps) printf("ns_per_sample %.3f\n", (t1 - t0) / ((double)reps * (double)(ns ? ns : 1)));
    else print(y, ns);
    return 0;
}
