/* sos.c - biquad cascade, direct form II transposed (see frac/sos.h). */
#include "frac/sos.h"

int frac_sos_init(frac_sos *f, size_t nsec, const frac_real *coeffs, frac_real *state)
{
    size_t i, j;
    if (f == NULL) return FRAC_E_NULL;
    f->ready = 0;
    if (coeffs == NULL || state == NULL) return FRAC_E_NULL;
    if (nsec == 0) return FRAC_E_DIM;
    for (i = 0; i < nsec; i++) {
        const frac_real *c = coeffs + FRAC_SOS_NCOEF * i;
        for (j = 0; j < FRAC_SOS_NCOEF; j++)
            if (!FRAC_ISFINITE(c[j])) return FRAC_E_PARAM;
        /* Jury test for z^2 + a1 z + a2, closed unit disk */
        if (FRAC_FABS(c[4]) > FRAC_R(1.0) || FRAC_FABS(c[3]) > FRAC_R(1.0) + c[4]) return FRAC_E_UNSTABLE;
    }
    f->coeffs = coeffs;
    f->state = state;
    f->nsec = nsec;
    f->ready = 1;
    return frac_sos_reset(f);
}

int frac_sos_reset(frac_sos *f)
{
    size_t i;
    if (f == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    for (i = 0; i < FRAC_SOS_NSTATE * f->nsec; i++) f->state[i] = FRAC_R(0.0);
    f->last = FRAC_R(0.0);
    return FRAC_OK;
}

int frac_sos_set_steady(frac_sos *f, frac_real x)
{
    size_t i;
    frac_real u, y;
    if (f == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(x)) return FRAC_E_NONFINITE;
    /* check every DC gain before touching the state */
    for (i = 0; i < f->nsec; i++) {
        const frac_real *c = f->coeffs + FRAC_SOS_NCOEF * i;
        /* a pole at z = 1 (to rounding): the DC gain is infinite */
        if (FRAC_FABS(FRAC_R(1.0) + c[3] + c[4]) <= FRAC_R(16.0) * FRAC_REAL_EPSILON * (FRAC_R(1.0) + FRAC_FABS(c[3]) + FRAC_FABS(c[4])))
            return FRAC_E_NUMERIC;
    }
    u = x;
    for (i = 0; i < f->nsec; i++) {
        const frac_real *c = f->coeffs + FRAC_SOS_NCOEF * i;
        frac_real *s = f->state + FRAC_SOS_NSTATE * i;
        y = (c[0] + c[1] + c[2]) / (FRAC_R(1.0) + c[3] + c[4]) * u;
        /* fixed point of the DF2T recursion for constant u, y */
        s[1] = c[2] * u - c[4] * y;
        s[0] = c[1] * u - c[3] * y + s[1];
        u = y;
    }
    f->last = u;
    return FRAC_OK;
}

/* one DF2T section: y = b0 x + s1; s1 = b1 x - a1 y + s2; s2 = b2 x - a2 y */
#define SOS_SECTION(c, s, x, v)                  \
    do {                                         \
        (v) = (c)[0] * (x) + (s)[0];             \
        (s)[0] = (c)[1] * (x) - (c)[3] * (v) + (s)[1]; \
        (s)[1] = (c)[2] * (x) - (c)[4] * (v);    \
    } while (0)

int frac_sos_step(frac_sos *f, frac_real x, frac_real *y)
{
    size_t n2;
    const frac_real *c;
    frac_real *s;
    frac_real v, w;
    if (f == NULL || y == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    /* x - x is exactly 0 for every finite x and NaN for NaN and +-Inf: one test */
    if (!(x - x == FRAC_R(0.0))) {
        *y = f->last;
        return FRAC_E_NONFINITE;
    }
    c = f->coeffs;
    s = f->state;
    /* two sections per iteration: halves the loop overhead of the cascade */
    for (n2 = f->nsec >> 1; n2 > 0; n2--) {
        SOS_SECTION(c, s, x, v);
        SOS_SECTION(c + FRAC_SOS_NCOEF, s + FRAC_SOS_NSTATE, v, w);
        x = w;
        c += 2 * FRAC_SOS_NCOEF;
        s += 2 * FRAC_SOS_NSTATE;
    }
    if (f->nsec & 1) {
        SOS_SECTION(c, s, x, v);
        x = v;
    }
    f->last = x;
    *y = x;
    return FRAC_OK;
}

int frac_sos_process(frac_sos *f, const frac_real *x, frac_real *y, size_t n)
{
    size_t k, i;
    const frac_real *c;
    frac_real *s;
    frac_real u, v;
    if (f == NULL || (n > 0 && (x == NULL || y == NULL))) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    for (k = 0; k < n; k++) {
        u = x[k];
        if (!(u - u == FRAC_R(0.0))) {
            for (; k < n; k++) y[k] = f->last;
            return FRAC_E_NONFINITE;
        }
        c = f->coeffs;
        s = f->state;
        for (i = f->nsec; i > 0; i--) {
            SOS_SECTION(c, s, u, v);
            u = v;
            c += FRAC_SOS_NCOEF;
            s += FRAC_SOS_NSTATE;
        }
        f->last = u;
        y[k] = u;
    }
    return FRAC_OK;
}

int frac_sos_free_response(const frac_sos *f, frac_real *y0)
{
    size_t i;
    frac_real x = FRAC_R(0.0);
    if (f == NULL || y0 == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    for (i = 0; i < f->nsec; i++) x = f->coeffs[FRAC_SOS_NCOEF * i] * x + f->state[FRAC_SOS_NSTATE * i];
    *y0 = x;
    return FRAC_OK;
}

frac_real frac_sos_feedthrough(const frac_sos *f)
{
    size_t i;
    frac_real g = FRAC_R(1.0);
    if (f == NULL || !f->ready) return FRAC_R(0.0);
    for (i = 0; i < f->nsec; i++) g *= f->coeffs[FRAC_SOS_NCOEF * i];
    return g;
}

int frac_sos_freqresp(const frac_real *coeffs, size_t nsec, frac_real theta, frac_real *re, frac_real *im)
{
    size_t i;
    double c1 = cos((double)theta), s1 = -sin((double)theta);
    double c2 = cos(2.0 * (double)theta), s2 = -sin(2.0 * (double)theta);
    double hr = 1.0, hi = 0.0;
    if (coeffs == NULL || re == NULL || im == NULL) return FRAC_E_NULL;
    if (nsec == 0) return FRAC_E_DIM;
    for (i = 0; i < nsec; i++) {
        const frac_real *c = coeffs + FRAC_SOS_NCOEF * i;
        /* num = b0 + b1 e^{-jt} + b2 e^{-2jt}, den = 1 + a1 e^{-jt} + a2 e^{-2jt} */
        double nr = (double)c[0] + (double)c[1] * c1 + (double)c[2] * c2;
        double ni = (double)c[1] * s1 + (double)c[2] * s2;
        double dr = 1.0 + (double)c[3] * c1 + (double)c[4] * c2;
        double di = (double)c[3] * s1 + (double)c[4] * s2;
        double dd = dr * dr + di * di, qr, qi, tr;
        if (dd == 0.0) return FRAC_E_NUMERIC;
        qr = (nr * dr + ni * di) / dd;
        qi = (ni * dr - nr * di) / dd;
        tr = hr * qr - hi * qi;
        hi = hr * qi + hi * qr;
        hr = tr;
    }
    *re = (frac_real)hr;
    *im = (frac_real)hi;
    return FRAC_OK;
}
