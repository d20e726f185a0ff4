/* frac_zpk.c - z-plane roots to biquad tables, polynomial roots (internal). */
#include "frac_zpk.h"

typedef struct cplx {
    double re, im;
} cplx;

static cplx c_make(double re, double im)
{
    cplx z;
    z.re = re;
    z.im = im;
    return z;
}
static cplx c_add(cplx a, cplx b) { return c_make(a.re + b.re, a.im + b.im); }
static cplx c_sub(cplx a, cplx b) { return c_make(a.re - b.re, a.im - b.im); }
static cplx c_mul(cplx a, cplx b) { return c_make(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re); }
static cplx c_div(cplx a, cplx b)
{
    /* Smith's algorithm: no overflow for large |b| */
    double t, d;
    if (fabs(b.re) >= fabs(b.im)) {
        t = b.im / b.re;
        d = b.re + b.im * t;
        return c_make((a.re + a.im * t) / d, (a.im - a.re * t) / d);
    }
    t = b.re / b.im;
    d = b.re * t + b.im;
    return c_make((a.re * t + a.im) / d, (a.im * t - a.re) / d);
}
static double c_abs(cplx a)
{
    double x = fabs(a.re), y = fabs(a.im), t;
    if (x < y) {
        t = x;
        x = y;
        y = t;
    }
    if (x == 0.0) return 0.0;
    t = y / x;
    return x * sqrt(1.0 + t * t);
}

int frac_zpk_add_real(frac_zpk_roots *r, double x)
{
    if (r->n >= FRAC_ZPK_MAXROOTS) return FRAC_E_DIM;
    r->re[r->n] = x;
    r->im[r->n] = 0.0;
    r->n++;
    return FRAC_OK;
}

double frac_zpk_maxabs(const frac_zpk_roots *r)
{
    int i;
    double m = 0.0, a;
    for (i = 0; i < r->n; i++) {
        a = c_abs(c_make(r->re[i], r->im[i]));
        if (a > m) m = a;
    }
    return m;
}

double frac_zpk_bilinear_root(double a, double c)
{
    return (c - a) / (c + a);
}

int frac_zpk_add_bilinear(frac_zpk_roots *r, double sre, double sim, double c, double *gain)
{
    cplx z;
    if (r->n >= FRAC_ZPK_MAXROOTS) return FRAC_E_DIM;
    z = c_div(c_make(c + sre, sim), c_make(c - sre, -sim));
    r->re[r->n] = z.re;
    r->im[r->n] = sim > 0.0 ? fabs(z.im) : 0.0;
    r->n++;
    *gain *= sim > 0.0 ? (c - sre) * (c - sre) + sim * sim : c - sre;
    return FRAC_OK;
}

int frac_zpk_polyroots(const double *c, int deg, frac_zpk_roots *out)
{
    cplx z[FRAC_ZPK_MAXROOTS];
    double a[FRAC_ZPK_MAXROOTS + 1], rad, maxstep;
    int i, j, it, npos = 0, nneg = 0;
    if (deg <= 0) return FRAC_OK;
    if (deg > FRAC_ZPK_MAXROOTS || c[0] == 0.0) return FRAC_E_NUMERIC;
    for (i = 0; i <= deg; i++) a[i] = c[i] / c[0];
    /* start on a circle of the geometric-mean root radius, rotated off the axes */
    rad = pow(fabs(a[deg]) > 0.0 ? fabs(a[deg]) : 1.0, 1.0 / deg);
    if (!(rad > 1e-3)) rad = 1e-3;
    for (i = 0; i < deg; i++) {
        double ang = 2.0 * 3.14159265358979323846 * ((double)i + 0.25) / (double)deg + 0.4;
        z[i] = c_make(rad * cos(ang), rad * sin(ang));
    }
    for (it = 0; it < 500; it++) {
        maxstep = 0.0;
        for (i = 0; i < deg; i++) {
            cplx p = c_make(1.0, 0.0), dp = c_make(0.0, 0.0), ratio, sum = c_make(0.0, 0.0), w, den;
            for (j = 1; j <= deg; j++) {
                dp = c_mul(dp, z[i]);
                dp.re += p.re;
                dp.im += p.im;
                p = c_mul(p, z[i]);
                p.re += a[j];
            }
            if (c_abs(p) == 0.0) continue;
            ratio = c_div(p, dp);
            for (j = 0; j < deg; j++)
                if (j != i) sum = c_add(sum, c_div(c_make(1.0, 0.0), c_sub(z[i], z[j])));
            den = c_sub(c_make(1.0, 0.0), c_mul(ratio, sum));
            w = c_div(ratio, den);
            if (!(c_abs(w) < 1e300)) return FRAC_E_NUMERIC;
            z[i] = c_sub(z[i], w);
            if (c_abs(w) > maxstep * (1.0 + c_abs(z[i]))) maxstep = c_abs(w) / (1.0 + c_abs(z[i]));
        }
        if (maxstep < 1e-13) break;
    }
    if (it == 500) {
        /* not converged to 1e-13: accept only roots with a small backward error */
        for (i = 0; i < deg; i++) {
            cplx p = c_make(1.0, 0.0);
            double scale = 1.0, zi = c_abs(z[i]), zp = 1.0;
            for (j = 1; j <= deg; j++) {
                p = c_mul(p, z[i]);
                p.re += a[j];
                zp *= zi;
                scale = scale * zi + fabs(a[j]);
            }
            if (!(c_abs(p) <= 1e-10 * scale)) return FRAC_E_NUMERIC;
        }
    }
    for (i = 0; i < deg; i++) {
        double tol = 1e-9 * (1.0 + c_abs(z[i]));
        if (fabs(z[i].im) <= tol) {
            if (frac_zpk_add_real(out, z[i].re) != FRAC_OK) return FRAC_E_NUMERIC;
        } else if (z[i].im > 0.0) {
            npos++;
            if (out->n >= FRAC_ZPK_MAXROOTS) return FRAC_E_NUMERIC;
            out->re[out->n] = z[i].re;
            out->im[out->n] = z[i].im;
            out->n++;
        } else {
            nneg++;
        }
    }
    return npos == nneg ? FRAC_OK : FRAC_E_NUMERIC;
}

/* Quadratic factors 1 + q1 z^-1 + q2 z^-2 of a root list, in section order. */
static int group(const frac_zpk_roots *r, double *q1, double *q2, size_t maxq, size_t *nq)
{
    double reals[FRAC_ZPK_MAXROOTS], t;
    int nr = 0, i, j, lo, hi;
    size_t k = 0;
    for (i = 0; i < r->n; i++) {
        if (r->im[i] != 0.0) {
            if (k >= maxq) return FRAC_E_STORAGE;
            q1[k] = -2.0 * r->re[i];
            q2[k] = r->re[i] * r->re[i] + r->im[i] * r->im[i];
            k++;
        } else {
            reals[nr++] = r->re[i];
        }
    }
    for (i = 1; i < nr; i++) /* insertion sort, nr <= 40 */
        for (j = i; j > 0 && reals[j - 1] > reals[j]; j--) {
            t = reals[j];
            reals[j] = reals[j - 1];
            reals[j - 1] = t;
        }
    for (lo = 0, hi = nr - 1; lo <= hi; lo++, hi--) {
        if (k >= maxq) return FRAC_E_STORAGE;
        if (lo == hi) {
            q1[k] = -reals[lo];
            q2[k] = 0.0;
        } else {
            q1[k] = -(reals[lo] + reals[hi]);
            q2[k] = reals[lo] * reals[hi];
        }
        k++;
    }
    *nq = k;
    return FRAC_OK;
}

size_t frac_zpk_nsec(const frac_zpk_roots *zeros, const frac_zpk_roots *poles)
{
    size_t nz = 0, np = 0, rz = 0, rp = 0;
    int i;
    for (i = 0; i < zeros->n; i++) {
        if (zeros->im[i] != 0.0) nz++;
        else rz++;
    }
    for (i = 0; i < poles->n; i++) {
        if (poles->im[i] != 0.0) np++;
        else rp++;
    }
    nz += (rz + 1) / 2;
    np += (rp + 1) / 2;
    return nz > np ? nz : np;
}

int frac_zpk_to_sos(const frac_zpk_roots *zeros, const frac_zpk_roots *poles, double gain,
                    frac_real *coeffs, size_t nsec)
{
    double z1[FRAC_ZPK_MAXROOTS], z2[FRAC_ZPK_MAXROOTS], p1[FRAC_ZPK_MAXROOTS], p2[FRAC_ZPK_MAXROOTS];
    double g, v[FRAC_SOS_NCOEF];
    size_t nz, np, i, j;
    int st;
    if (nsec > FRAC_ZPK_MAXROOTS) return FRAC_E_STORAGE;
    st = group(zeros, z1, z2, nsec, &nz);
    if (st != FRAC_OK) return st;
    st = group(poles, p1, p2, nsec, &np);
    if (st != FRAC_OK) return st;
    g = pow(fabs(gain), 1.0 / (double)nsec);
    for (i = 0; i < nsec; i++) {
        double gi = (i == 0 && gain < 0.0) ? -g : g;
        v[0] = gi;
        v[1] = i < nz ? gi * z1[i] : 0.0;
        v[2] = i < nz ? gi * z2[i] : 0.0;
        v[3] = i < np ? p1[i] : 0.0;
        v[4] = i < np ? p2[i] : 0.0;
        for (j = 0; j < FRAC_SOS_NCOEF; j++) {
            if (!(fabs(v[j]) <= (double)FRAC_REAL_MAX)) return FRAC_E_NUMERIC;
            coeffs[FRAC_SOS_NCOEF * i + j] = (frac_real)v[j];
        }
    }
    return FRAC_OK;
}
