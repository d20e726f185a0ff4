/* fo_cfe.c - CFE (diagonal Padé) of the Tustin / Al-Alaoui generating function (see frac/fo_cfe.h). */
#include "frac/fo_cfe.h"
#include "frac_zpk.h"

static int validate(const frac_cfe_params *p)
{
    if (p == NULL) return FRAC_E_NULL;
    if (p->rule != FRAC_CFE_TUSTIN && p->rule != FRAC_CFE_ALALAOUI) return FRAC_E_PARAM;
    if (!FRAC_ISFINITE(p->order) || p->order < -FRAC_R(2.0) || p->order > FRAC_R(2.0)) return FRAC_E_ORDER;
    if (!FRAC_ISFINITE(p->ts) || p->ts <= FRAC_R(0.0)) return FRAC_E_TS;
    if (p->n == 0 || p->n > FRAC_CFE_NMAX) return FRAC_E_DIM;
    if (p->rule == FRAC_CFE_TUSTIN && p->order >= FRAC_R(1.0)) return FRAC_E_UNSTABLE;
    return FRAC_OK;
}

/*
 * [n/n] Padé approximant of (1 - x)^r (1 + a x)^-r: numerator p[0..n],
 * denominator q[0..n], p[0] = q[0] = 1, ascending powers of x.
 */
static int pade(double r, double a, int n, double *p, double *q)
{
    double c1[2 * FRAC_CFE_NMAX + 1], c2[2 * FRAC_CFE_NMAX + 1], c[2 * FRAC_CFE_NMAX + 1];
    double A[FRAC_CFE_NMAX][FRAC_CFE_NMAX + 1];
    int k, i, j, piv, m = 2 * n;
    c1[0] = c2[0] = 1.0;
    for (k = 1; k <= m; k++) {
        /* binomial series: (1 - x)^r and (1 + a x)^-r */
        c1[k] = c1[k - 1] * ((double)(k - 1) - r) / (double)k;
        c2[k] = c2[k - 1] * (-r - (double)(k - 1)) / (double)k * a;
    }
    for (k = 0; k <= m; k++) {
        c[k] = 0.0;
        for (i = 0; i <= k; i++) c[k] += c1[i] * c2[k - i];
    }
    /* sum_{j=1..n} q_j c_{n+i-j} = -c_{n+i}, i = 1..n */
    for (i = 0; i < n; i++) {
        for (j = 0; j < n; j++) {
            k = n + (i + 1) - (j + 1);
            A[i][j] = k >= 0 ? c[k] : 0.0;
        }
        A[i][n] = -c[n + i + 1];
    }
    for (k = 0; k < n; k++) { /* Gaussian elimination, partial pivoting */
        double best = fabs(A[k][k]), t;
        piv = k;
        for (i = k + 1; i < n; i++)
            if (fabs(A[i][k]) > best) {
                best = fabs(A[i][k]);
                piv = i;
            }
        if (!(best > 1e-300)) return FRAC_E_NUMERIC;
        if (piv != k)
            for (j = k; j <= n; j++) {
                t = A[k][j];
                A[k][j] = A[piv][j];
                A[piv][j] = t;
            }
        for (i = k + 1; i < n; i++) {
            t = A[i][k] / A[k][k];
            for (j = k; j <= n; j++) A[i][j] -= t * A[k][j];
        }
    }
    q[0] = 1.0;
    for (k = n - 1; k >= 0; k--) {
        double s = A[k][n];
        for (j = k + 1; j < n; j++) s -= A[k][j] * q[j + 1];
        q[k + 1] = s / A[k][k];
    }
    for (i = 0; i <= n; i++) {
        p[i] = 0.0;
        for (j = 0; j <= i; j++) p[i] += q[j] * c[i - j];
    }
    for (i = 0; i <= n; i++)
        if (!(fabs(p[i]) < 1e300) || !(fabs(q[i]) < 1e300)) return FRAC_E_NUMERIC;
    return FRAC_OK;
}

int frac_cfe_design(const frac_cfe_params *p, frac_real *coeffs, size_t *nsec)
{
    double pn[FRAC_CFE_NMAX + 1], qd[FRAC_CFE_NMAX + 1];
    double r, rf, a, k, gain, zint;
    frac_zpk_roots zeros, poles;
    int st, m, i, n;
    st = validate(p);
    if (st != FRAC_OK) return st;
    if (coeffs == NULL || nsec == NULL) return FRAC_E_NULL;
    r = (double)p->order;
    n = (int)p->n;
    a = p->rule == FRAC_CFE_TUSTIN ? 1.0 : 1.0 / 7.0;
    k = p->rule == FRAC_CFE_TUSTIN ? 2.0 / (double)p->ts : 8.0 / (7.0 * (double)p->ts);
    m = (int)r; /* trunc toward zero: |rf| < 1 */
    rf = r - (double)m;
    zeros.n = poles.n = 0;
    gain = pow(k, r);
    if (rf != 0.0) {
        st = pade(rf, a, n, pn, qd);
        if (st != FRAC_OK) return st;
        /* P(x) = prod (1 - z_i x) with z_i the roots of z^n P(1/z) = p0 z^n + ... + pn */
        st = frac_zpk_polyroots(pn, n, &zeros);
        if (st != FRAC_OK) return st;
        st = frac_zpk_polyroots(qd, n, &poles);
        if (st != FRAC_OK) return st;
        if (frac_zpk_maxabs(&poles) >= 1.0 - 1e-12) return FRAC_E_UNSTABLE;
    }
    /* integer part: the generating function itself, (1 - x)/(1 + a x) per order */
    zint = -a;
    for (i = 0; i < (m < 0 ? -m : m); i++) {
        if (m > 0) {
            st = frac_zpk_add_real(&zeros, 1.0);
            if (st == FRAC_OK) st = frac_zpk_add_real(&poles, zint);
        } else {
            st = frac_zpk_add_real(&zeros, zint);
            if (st == FRAC_OK) st = frac_zpk_add_real(&poles, 1.0);
        }
        if (st != FRAC_OK) return FRAC_E_NUMERIC;
    }
    if (zeros.n == 0 && poles.n == 0) frac_zpk_add_real(&zeros, 0.0); /* r = 0: one identity section */
    *nsec = frac_zpk_nsec(&zeros, &poles);
    if (*nsec > FRAC_CFE_NSEC(p->n)) return FRAC_E_NUMERIC;
    return frac_zpk_to_sos(&zeros, &poles, gain, coeffs, *nsec);
}

int frac_cfe_init(frac_cfe *f, const frac_cfe_params *p, frac_real *storage, size_t len)
{
    size_t nsec;
    int st;
    if (f == NULL) return FRAC_E_NULL;
    f->ready = 0;
    st = validate(p);
    if (st != FRAC_OK) return st;
    if (storage == NULL) return FRAC_E_NULL;
    if (len < FRAC_CFE_STORAGE(p->n)) return FRAC_E_STORAGE;
    st = frac_cfe_design(p, storage, &nsec);
    if (st != FRAC_OK) return st;
    st = frac_sos_init(&f->sos, nsec, storage, storage + FRAC_SOS_NCOEF * nsec);
    if (st != FRAC_OK) return st;
    f->p = *p;
    f->ready = 1;
    return FRAC_OK;
}

int frac_cfe_step(frac_cfe *f, frac_real x, frac_real *y)
{
    if (f == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    return frac_sos_step(&f->sos, x, y); /* checks y and x */
}

int frac_cfe_reset(frac_cfe *f)
{
    if (f == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    return frac_sos_reset(&f->sos);
}

int frac_cfe_freqresp(const frac_cfe *f, frac_real w, frac_real *re, frac_real *im)
{
    if (f == NULL || re == NULL || im == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(w) || w < FRAC_R(0.0)) return FRAC_E_PARAM;
    return frac_sos_freqresp(f->sos.coeffs, f->sos.nsec, w * f->p.ts, re, im);
}
