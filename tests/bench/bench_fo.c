/*
 * bench_fo - per-sample cost of the s^r realizations and the PI^l D^m
 * (make bench; driven by bench_fo.sh, which adds callgrind instruction
 * counts and the scipy reference of bench_fo_ref.py).
 *
 *   bench_fo time                 ns/sample of every kind over 1e6 samples
 *   bench_fo run KIND N           N steps of one kind (for callgrind)
 *   bench_fo input FILE           write the 1e6-sample input (float64, raw)
 *   bench_fo sos FILE             write the Oustaloup N = 5 table (b0 b1 b2 1 a1 a2 per row, text)
 *   bench_fo filter IN OUT        frac_sos_process IN -> OUT (float64, raw), prints ns/sample
 *   bench_fo naive                naive direct form of the same transfer function: cost and error
 *
 * KIND: oustaloup5 | gl256 | gl1024 | gl4096 | cfe5 | pid | naive
 * Operator settings: r = 0.5, Ts = 1 ms; Oustaloup band [0.01, 1000] rad/s
 * (plain, N = 5: 6 biquads); CFE Tustin n = 5; PI^0.8 D^0.5 with both
 * operators Oustaloup N = 5, derivative filter, limits and back-calculation.
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include "frac/fo_op.h"
#include "frac/fopid.h"

#define NS 1000000
#define TS 1e-3
#define ORDER 0.5

static frac_real gstore[FRAC_GL_STORAGE(4096)];
static double xin[NS];
static frac_real xr[NS], yr[NS];

static void make_input(void)
{
    unsigned long s = 12345UL;
    int k;
    for (k = 0; k < NS; k++) {
        s = (s * 1103515245UL + 12345UL) & 0x7fffffffUL;
        xin[k] = (double)s / 2147483648.0 - 0.5 + sin(0.01 * k);
        xr[k] = (frac_real)xin[k];
    }
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static frac_fo_params fo_params(int method, size_t L)
{
    frac_fo_params p;
    p.method = method;
    p.order = (frac_real)ORDER;
    p.ts = (frac_real)TS;
    p.memory = L;
    p.wb = FRAC_R(0.01);
    p.wh = FRAC_R(1000.0);
    p.n = 5;
    return p;
}

static void pid_params(frac_fopid_params *p)
{
    memset(p, 0, sizeof *p);
    p->kp = FRAC_R(1.0);
    p->ki = FRAC_R(2.0);
    p->kd = FRAC_R(0.1);
    p->lambda = FRAC_R(0.8);
    p->mu = FRAC_R(0.5);
    p->tf = FRAC_R(0.01);
    p->b = p->c = FRAC_R(1.0);
    p->umin = -FRAC_R(100.0);
    p->umax = FRAC_R(100.0);
    p->antiwindup = FRAC_FOPID_AW_BACKCALC;
    p->tt = FRAC_R(0.1);
    p->ts = (frac_real)TS;
    p->op = fo_params(FRAC_FO_OUSTALOUP, 0);
}

/* naive realization: the cascade multiplied out into one polynomial pair, DF2T of order 2N+1 */
#define NAIVE_MAX 16
static double nb[NAIVE_MAX], na[NAIVE_MAX];
static int norder;
static frac_real nbr[NAIVE_MAX], nar[NAIVE_MAX], nst[NAIVE_MAX];

static void naive_design(const frac_sos *s)
{
    size_t i;
    int j, k;
    nb[0] = na[0] = 1.0;
    norder = 0;
    for (i = 0; i < s->nsec; i++) {
        const frac_real *c = s->coeffs + FRAC_SOS_NCOEF * i;
        double bq[3], aq[3], tb[NAIVE_MAX] = {0}, ta[NAIVE_MAX] = {0};
        bq[0] = c[0]; bq[1] = c[1]; bq[2] = c[2];
        aq[0] = 1.0; aq[1] = c[3]; aq[2] = c[4];
        for (j = 0; j <= norder; j++)
            for (k = 0; k < 3; k++) {
                tb[j + k] += nb[j] * bq[k];
                ta[j + k] += na[j] * aq[k];
            }
        norder += 2;
        for (j = 0; j <= norder; j++) {
            nb[j] = tb[j];
            na[j] = ta[j];
        }
    }
    for (j = 0; j <= norder; j++) {
        nbr[j] = (frac_real)nb[j];
        nar[j] = (frac_real)na[j];
        nst[j] = FRAC_R(0.0);
    }
}

/* DF2T of order norder: y = b0 x + s0; s_i = b_{i+1} x - a_{i+1} y + s_{i+1} */
__attribute__((noinline)) static frac_real naive_step(frac_real x)
{
    frac_real y = nbr[0] * x + nst[0];
    int i;
    for (i = 0; i < norder - 1; i++) nst[i] = nbr[i + 1] * x - nar[i + 1] * y + nst[i + 1];
    nst[norder - 1] = nbr[norder] * x - nar[norder] * y;
    return y;
}

typedef struct kind {
    const char *name;
    int method;
    size_t L;
} kind;

static const kind KINDS[] = {{"oustaloup5", FRAC_FO_OUSTALOUP, 0}, {"gl256", FRAC_FO_GL, 256},
                             {"gl1024", FRAC_FO_GL, 1024},        {"gl4096", FRAC_FO_GL, 4096},
                             {"cfe5", FRAC_FO_CFE_TUSTIN, 0},     {"pid", 0, 0}};

/* runs n steps of kind k, returns the checksum (keeps the work observable) */
static double run(const char *name, int n)
{
    size_t i;
    double sum = 0.0;
    int k;
    frac_real y;
    if (strcmp(name, "pid") == 0) {
        frac_fopid c;
        frac_fopid_params p;
        pid_params(&p);
        if (frac_fopid_init(&c, &p, gstore, sizeof gstore / sizeof gstore[0]) != FRAC_OK) exit(2);
        for (k = 0; k < n; k++) {
            frac_fopid_step(&c, xr[k], FRAC_R(0.0), &y);
            sum += y;
        }
        return sum;
    }
    if (strcmp(name, "naive") == 0) {
        frac_fo op;
        frac_fo_params p = fo_params(FRAC_FO_OUSTALOUP, 0);
        if (frac_fo_init(&op, &p, gstore, sizeof gstore / sizeof gstore[0]) != FRAC_OK) exit(2);
        naive_design(&op.sos);
        for (k = 0; k < n; k++) sum += naive_step(xr[k]);
        return sum;
    }
    for (i = 0; i < sizeof KINDS / sizeof KINDS[0]; i++)
        if (strcmp(name, KINDS[i].name) == 0) {
            frac_fo op;
            frac_fo_params p = fo_params(KINDS[i].method, KINDS[i].L);
            if (frac_fo_init(&op, &p, gstore, sizeof gstore / sizeof gstore[0]) != FRAC_OK) exit(2);
            for (k = 0; k < n; k++) {
                frac_fo_step(&op, xr[k], &y);
                sum += y;
            }
            return sum;
        }
    fprintf(stderr, "unknown kind %s\n", name);
    exit(2);
}

static int write_raw(const char *path, const double *v, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL || fwrite(v, sizeof v[0], n, f) != n) return 1;
    return fclose(f) != 0;
}

int main(int argc, char **argv)
{
    size_t i;
    make_input();
    if (argc >= 2 && strcmp(argv[1], "time") == 0) {
        const char *names[7] = {"oustaloup5", "gl256", "gl1024", "gl4096", "cfe5", "pid", "naive"};
        for (i = 0; i < 7; i++) {
            double best = 1e300, t0, t, chk = 0.0;
            int rep, n = strncmp(names[i], "gl", 2) == 0 ? NS / 10 : NS;
            for (rep = 0; rep < 3; rep++) {
                t0 = now();
                chk = run(names[i], n);
                t = now() - t0;
                if (t < best) best = t;
            }
            printf("%s %.2f %.6g\n", names[i], 1e9 * best / n, chk);
        }
        return 0;
    }
    if (argc == 4 && strcmp(argv[1], "run") == 0) {
        printf("%.6g\n", run(argv[2], atoi(argv[3])));
        return 0;
    }
    if (argc == 3 && strcmp(argv[1], "input") == 0) return write_raw(argv[2], xin, NS);
    if (argc == 3 && strcmp(argv[1], "sos") == 0) {
        frac_fo op;
        frac_fo_params p = fo_params(FRAC_FO_OUSTALOUP, 0);
        FILE *f;
        if (frac_fo_init(&op, &p, gstore, sizeof gstore / sizeof gstore[0]) != FRAC_OK) return 2;
        f = fopen(argv[2], "w");
        if (f == NULL) return 1;
        for (i = 0; i < op.sos.nsec; i++) {
            const frac_real *c = op.sos.coeffs + FRAC_SOS_NCOEF * i;
            fprintf(f, "%.17g %.17g %.17g 1 %.17g %.17g\n", (double)c[0], (double)c[1], (double)c[2], (double)c[3], (double)c[4]);
        }
        return fclose(f) != 0;
    }
    if (argc == 4 && strcmp(argv[1], "filter") == 0) {
        frac_fo op;
        frac_fo_params p = fo_params(FRAC_FO_OUSTALOUP, 0);
        double best = 1e300, t0;
        static double yout[NS];
        int rep;
        if (frac_fo_init(&op, &p, gstore, sizeof gstore / sizeof gstore[0]) != FRAC_OK) return 2;
        for (rep = 0; rep < 5; rep++) {
            frac_sos_reset(&op.sos);
            t0 = now();
            frac_sos_process(&op.sos, xr, yr, NS);
            if (now() - t0 < best) best = now() - t0;
        }
        for (i = 0; i < NS; i++) yout[i] = (double)yr[i];
        printf("%.3f\n", 1e9 * best / NS);
        return write_raw(argv[3], yout, NS);
    }
    if (argc == 2 && strcmp(argv[1], "naive") == 0) {
        /* error of the naive direct form against the cascade, double and float coefficients */
        frac_fo op;
        frac_fo_params p = fo_params(FRAC_FO_OUSTALOUP, 0);
        double e = 0.0, ef = 0.0, m = 0.0;
        int k, j;
        float fb[NAIVE_MAX], fa[NAIVE_MAX], fs[NAIVE_MAX] = {0};
        if (frac_fo_init(&op, &p, gstore, sizeof gstore / sizeof gstore[0]) != FRAC_OK) return 2;
        naive_design(&op.sos);
        for (j = 0; j <= norder; j++) {
            fb[j] = (float)nb[j];
            fa[j] = (float)na[j];
        }
        for (k = 0; k < NS; k++) {
            frac_real y, yn = naive_step(xr[k]);
            float x = (float)xr[k], yf = fb[0] * x + fs[0];
            for (j = 0; j < norder - 1; j++) fs[j] = fb[j + 1] * x - fa[j + 1] * yf + fs[j + 1];
            fs[norder - 1] = fb[norder] * x - fa[norder] * yf;
            frac_fo_step(&op, xr[k], &y);
            if (fabs(y) > m) m = fabs(y);
            if (fabs(yn - y) > e || yn != yn) e = fabs(yn - y);
            if (fabs(yf - y) > ef || yf != yf) ef = fabs(yf - y);
        }
        printf("%d %.3e %.3e\n", norder, e / m, ef / m);
        return 0;
    }
    fprintf(stderr, "usage: see the header of tests/bench/bench_fo.c\n");
    return 2;
}
