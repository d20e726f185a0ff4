/* fo_oustaloup.c - (refined) Oustaloup filter, Tustin with prewarped band edges (see frac/fo_oustaloup.h). */
#include "frac/fo_oustaloup.h"
#include "frac_zpk.h"

#define OU_PI 3.14159265358979323846
#define OU_B 10.0 /* refined Oustaloup constants b, d (Xue, Zhao & Chen 2006) */
#define OU_D 9.0

static int validate(const frac_oustaloup_params *p)
{
    if (p == NULL) return FRAC_E_NULL;
    if (!FRAC_ISFINITE(p->order) || p->order < -FRAC_R(2.0) || p->order > FRAC_R(2.0)) return FRAC_E_ORDER;
    if (p->refined && !(p->order > FRAC_R(0.0) && p->order < FRAC_R(1.0))) return FRAC_E_ORDER;
    if (!FRAC_ISFINITE(p->ts) || p->ts <= FRAC_R(0.0)) return FRAC_E_TS;
    if (!FRAC_ISFINITE(p->wb) || !FRAC_ISFINITE(p->wh) || p->wb <= FRAC_R(0.0) || p->wh <= p->wb) return FRAC_E_BAND;
    if ((double)p->wh * (double)p->ts >= OU_PI) return FRAC_E_BAND;
    if (p->n == 0 || p->n > FRAC_OUSTALOUP_NMAX) return FRAC_E_DIM;
    return FRAC_OK;
}

/* |prod (jw + z_i)/(jw + p_i)| for s-plane factors s + a. */
static double mag_ratio(double w, const double *za, int nz, const double *pa, int np)
{
    double m = 1.0;
    int i;
    for (i = 0; i < nz; i++) m *= sqrt(w * w + za[i] * za[i]);
    for (i = 0; i < np; i++) m /= sqrt(w * w + pa[i] * pa[i]);
    return m;
}

int frac_oustaloup_design(const frac_oustaloup_params *p, frac_real *coeffs)
{
    double za[2 * FRAC_OUSTALOUP_NMAX + 3], pa[2 * FRAC_OUSTALOUP_NMAX + 3];
    double r, c, Wb, Wh, Wg, ratio, gain, K, lead = 1.0;
    frac_zpk_roots zeros, poles;
    int st, k, n2, nz, np;
    size_t nsec;
    st = validate(p);
    if (st != FRAC_OK) return st;
    if (coeffs == NULL) return FRAC_E_NULL;
    r = (double)p->order;
    c = 2.0 / (double)p->ts;
    /* prewarped band edges: the digital band is exactly [wb, wh] */
    Wb = c * tan(0.5 * (double)p->wb * (double)p->ts);
    Wh = c * tan(0.5 * (double)p->wh * (double)p->ts);
    Wg = sqrt(Wb * Wh);
    ratio = Wh / Wb;
    n2 = 2 * (int)p->n + 1;
    /* Oustaloup corners, seed 002 note section 11 */
    for (k = 0; k < n2; k++) {
        za[k] = Wb * pow(ratio, ((double)k + 0.5 * (1.0 - r)) / (double)n2);
        pa[k] = Wb * pow(ratio, ((double)k + 0.5 * (1.0 + r)) / (double)n2);
    }
    nz = np = n2;
    if (p->refined) {
        /* (d s^2 + b Wh s) / (d (1-r) s^2 + b Wh s + d r Wb Wh), as real factors */
        double A = OU_D * (1.0 - r), B = OU_B * Wh, C = OU_D * r * Wb * Wh;
        double q = -0.5 * (B + sqrt(B * B - 4.0 * A * C)); /* discriminant > 0 since Wh > Wb */
        za[nz++] = 0.0;
        za[nz++] = OU_B * Wh / OU_D;
        pa[np++] = -q / A; /* roots of A s^2 + B s + C are q/A and C/q, both negative */
        pa[np++] = -C / q;
        lead = OU_D / A;
    }
    /* gain: |H(j Wg)| = Wg^r at the geometric band centre */
    K = pow(Wg, r) / (lead * mag_ratio(Wg, za, nz, pa, np));
    /* bilinear map of each factor s + a: root (c - a)/(c + a), gain c + a */
    zeros.n = poles.n = 0;
    gain = K * lead;
    for (k = 0; k < nz; k++) {
        frac_zpk_add_real(&zeros, frac_zpk_bilinear_root(za[k], c));
        gain *= c + za[k];
    }
    for (k = 0; k < np; k++) {
        frac_zpk_add_real(&poles, frac_zpk_bilinear_root(pa[k], c));
        gain /= c + pa[k];
    }
    nsec = FRAC_OUSTALOUP_NSEC(p->n, p->refined);
    return frac_zpk_to_sos(&zeros, &poles, gain, coeffs, nsec);
}

int frac_oustaloup_init(frac_oustaloup *o, const frac_oustaloup_params *p, frac_real *storage, size_t len)
{
    size_t nsec;
    int st;
    if (o == NULL) return FRAC_E_NULL;
    o->ready = 0;
    st = validate(p);
    if (st != FRAC_OK) return st;
    if (storage == NULL) return FRAC_E_NULL;
    nsec = FRAC_OUSTALOUP_NSEC(p->n, p->refined);
    if (len < FRAC_OUSTALOUP_STORAGE(p->n, p->refined)) return FRAC_E_STORAGE;
    st = frac_oustaloup_design(p, storage);
    if (st != FRAC_OK) return st;
    st = frac_sos_init(&o->sos, nsec, storage, storage + FRAC_SOS_NCOEF * nsec);
    if (st != FRAC_OK) return st;
    o->p = *p;
    o->ready = 1;
    return FRAC_OK;
}

int frac_oustaloup_step(frac_oustaloup *o, frac_real x, frac_real *y)
{
    if (o == NULL) return FRAC_E_NULL;
    if (!o->ready) return FRAC_E_NOT_INIT;
    return frac_sos_step(&o->sos, x, y); /* checks y and x */
}

int frac_oustaloup_reset(frac_oustaloup *o)
{
    if (o == NULL) return FRAC_E_NULL;
    if (!o->ready) return FRAC_E_NOT_INIT;
    return frac_sos_reset(&o->sos);
}

int frac_oustaloup_freqresp(const frac_oustaloup *o, frac_real w, frac_real *re, frac_real *im)
{
    if (o == NULL || re == NULL || im == NULL) return FRAC_E_NULL;
    if (!o->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(w) || w < FRAC_R(0.0)) return FRAC_E_PARAM;
    return frac_sos_freqresp(o->sos.coeffs, o->sos.nsec, w * o->p.ts, re, im);
}
