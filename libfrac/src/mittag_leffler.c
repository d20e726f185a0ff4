/* mittag_leffler.c - E_{a,b}(z) for real z (see frac/mittag_leffler.h). */
#include "frac/mittag_leffler.h"

#define ML_PI 3.14159265358979323846
#define ML_MAXPANEL 400

/* Lanczos approximation, g = 7, n = 9 (relative error ~1e-15) */
static const double LANCZOS[9] = {0.99999999999980993, 676.5203681218851, -1259.1392167224028,
                                  771.32342877765313, -176.61502916214059, 12.507343278686905,
                                  -0.13857109526572012, 9.9843695780195716e-6, 1.5056327351493116e-7};

/* ln|Gamma(x)| and the sign of Gamma(x), x not a pole */
static double lgamma_sign(double x, int *sign)
{
    double s, t;
    int k;
    if (x < 0.5) {
        /* reflection: Gamma(x) Gamma(1-x) = pi / sin(pi x) */
        double sp = sin(ML_PI * x);
        double l = lgamma_sign(1.0 - x, sign);
        *sign = sp < 0.0 ? -1 : 1;
        return log(ML_PI / fabs(sp)) - l;
    }
    x -= 1.0;
    s = LANCZOS[0];
    for (k = 1; k < 9; k++) s += LANCZOS[k] / (x + (double)k);
    t = x + 7.5;
    *sign = 1;
    return 0.5 * log(2.0 * ML_PI) + (x + 0.5) * log(t) - t + log(s);
}

/* 1/Gamma(x), exactly 0 at x = 0, -1, -2, ... */
static double rgamma(double x)
{
    int sg;
    double l;
    if (x <= 0.0 && x == floor(x)) return 0.0;
    l = lgamma_sign(x, &sg);
    return (double)sg * exp(-l);
}

static double series(double a, double b, double z)
{
    double sum = 0.0, lz = z != 0.0 ? log(fabs(z)) : 0.0, t;
    int k, sg;
    if (z == 0.0) return rgamma(b);
    for (k = 0; k < 100000; k++) {
        double x = a * (double)k + b;
        if (x <= 0.0 && x == floor(x)) continue;
        t = exp((double)k * lz - lgamma_sign(x, &sg)) * (double)sg;
        if (z < 0.0 && (k & 1)) t = -t;
        sum += t;
        /* past the peak of |terms| (a k + b > |z|^(1/a)) and negligible */
        if (x > 1.0 && k * lz < lgamma_sign(x, &sg) && fabs(t) <= 1e-17 * fabs(sum)) break;
    }
    return sum;
}

/* integrand in v = r^c on the ray s = r e^{i theta}: (1/c) Im[e^s e^{i(a-b+1)theta} / (s^a - z)] */
typedef struct ml_ray {
    double a, b, z, c, th, cth, sth;
} ml_ray;

static double ray_f(const ml_ray *q, double v)
{
    double r, ra, dr, di, ph, mag, d2;
    if (v <= 0.0) return 0.0;
    r = pow(v, 1.0 / q->c);
    ra = pow(r, q->a);
    dr = ra * cos(q->a * q->th) - q->z;
    di = ra * sin(q->a * q->th);
    d2 = dr * dr + di * di;
    if (d2 == 0.0) return 0.0;
    ph = r * q->sth + (q->a - q->b + 1.0) * q->th;
    mag = exp(r * q->cth);
    return mag * (sin(ph) * dr - cos(ph) * di) / (d2 * q->c);
}

/* Gauss–Kronrod 7/15 on [lo, hi]: integral and error estimate */
static const double XGK[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                              0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                              0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                              0.207784955007898467600689403773245, 0.0};
static const double WGK[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                              0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                              0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                              0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double WG[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                             0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

static void gk15(const ml_ray *q, double lo, double hi, double *res, double *err)
{
    double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo), fc = ray_f(q, c), rk = fc * WGK[7], rg = fc * WG[3];
    int j;
    for (j = 0; j < 7; j++) {
        double x = h * XGK[j], f1 = ray_f(q, c - x), f2 = ray_f(q, c + x);
        rk += WGK[j] * (f1 + f2);
        if (j & 1) rg += WG[j / 2] * (f1 + f2);
    }
    *res = rk * h;
    *err = fabs((rk - rg) * h);
}

/* adaptive: split the panel with the largest error until the total is small */
static int integrate(const ml_ray *q, const double *brk, int nbrk, double *out)
{
    double lo[ML_MAXPANEL], hi[ML_MAXPANEL], val[ML_MAXPANEL], er[ML_MAXPANEL];
    int n = 0, i, worst;
    double tot, etot;
    for (i = 0; i + 1 < nbrk; i++) {
        lo[n] = brk[i];
        hi[n] = brk[i + 1];
        gk15(q, lo[n], hi[n], &val[n], &er[n]);
        n++;
    }
    for (;;) {
        double mid, scale = 0.0;
        tot = etot = 0.0;
        worst = 0;
        for (i = 0; i < n; i++) {
            tot += val[i];
            etot += er[i];
            scale += fabs(val[i]);
            if (er[i] > er[worst]) worst = i;
        }
        /* relative 1e-14, or 1e-16 of sum |panels| when the result cancels to a tiny value */
        if (etot <= 1e-14 * fabs(tot) || etot <= 1e-16 * scale || etot < 1e-300) break;
        if (n == ML_MAXPANEL) {
            if (!(etot <= 1e-12 * scale)) return FRAC_E_NUMERIC;
            break;
        }
        mid = 0.5 * (lo[worst] + hi[worst]);
        lo[n] = mid;
        hi[n] = hi[worst];
        hi[worst] = mid;
        gk15(q, lo[worst], hi[worst], &val[worst], &er[worst]);
        gk15(q, lo[n], hi[n], &val[n], &er[n]);
        n++;
    }
    *out = tot / ML_PI;
    return FRAC_OK;
}

static int contour(double a, double b, double z, double *e)
{
    ml_ray q;
    double brk[6], rmax, rs, res = 0.0, I = 0.0, psi, rho, f[3] = {0.5, 1.0, 2.0};
    int nbrk = 0, i, st;
    q.a = a;
    q.b = b;
    q.z = z;
    q.c = a - b + 1.0;
    q.th = (z < 0.0 && fabs(a - 1.0) <= 0.1) ? 0.75 * ML_PI : ML_PI;
    q.cth = cos(q.th);
    q.sth = sin(q.th);
    rmax = 42.0 / fabs(q.cth);
    rs = pow(fabs(z), 1.0 / a);
    brk[nbrk++] = 0.0;
    for (i = 0; i < 3; i++)
        if (f[i] * rs < rmax) brk[nbrk++] = pow(f[i] * rs, q.c);
    brk[nbrk++] = pow(rmax, q.c);
    st = integrate(&q, brk, nbrk, &I);
    if (st != FRAC_OK) return st;
    /* poles s^a = z inside the contour (|arg s| < theta, principal sheet) */
    rho = rs;
    if (z > 0.0) {
        if (rho > 700.0) return FRAC_E_NUMERIC;
        res = pow(rho, 1.0 - b) * exp(rho) / a;
    } else {
        psi = ML_PI / a;
        if (psi < q.th) res = 2.0 / a * pow(rho, 1.0 - b) * exp(rho * cos(psi)) * cos(rho * sin(psi) + (1.0 - b) * psi);
    }
    *e = res + I;
    return FRAC_OK;
}

int frac_mittag_leffler(frac_real a_, frac_real b_, frac_real z_, frac_real *e)
{
    double a = (double)a_, b = (double)b_, z = (double)z_, v, bb;
    int m, st;
    if (e == NULL) return FRAC_E_NULL;
    if (!FRAC_ISFINITE(a_) || !(a > 0.0 && a <= 2.0) || !FRAC_ISFINITE(b_) || fabs(b) > 50.0) return FRAC_E_PARAM;
    if (!FRAC_ISFINITE(z_)) return FRAC_E_NONFINITE;
    if (a == 1.0 && b == 1.0) {
        v = exp(z); /* E_1 = exp: the contour integral would only give it to 1e-16 absolute */
    } else if (fabs(z) <= 1.0 || (z > 0.0 && pow(z, 1.0 / a) <= 30.0)) {
        v = series(a, b, z);
    } else {
        /* reduce b below a + 1, evaluate, and climb back up */
        for (m = 0, bb = b; bb >= a + 1.0; m++) bb -= a;
        st = contour(a, bb, z, &v);
        if (st != FRAC_OK) return st;
        for (; m > 0; m--) {
            v = (v - rgamma(bb)) / z; /* E_{a,bb+a} = (E_{a,bb} - 1/Gamma(bb)) / z */
            bb += a;
        }
    }
    if (!(fabs(v) <= (double)FRAC_REAL_MAX)) return FRAC_E_NUMERIC;
    *e = (frac_real)v;
    return FRAC_OK;
}
