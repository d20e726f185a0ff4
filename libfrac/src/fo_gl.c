/* fo_gl.c - Grünwald–Letnikov short-memory operator (see frac/fo_gl.h). */
#include "frac/fo_gl.h"

/*
 * sum a[i] b[i] with eight partial sums: independent accumulators let the
 * compiler keep several multiply-adds in flight and pair them into SIMD
 * lanes (gcc's SLP vectorizer: 2 double or 4 float per instruction)
 * without reassociating one floating-point sum, which it may not do
 * without -ffast-math. Eight taps per iteration amortize the loop control.
 */
static frac_real dot(const frac_real *a, const frac_real *b, size_t n)
{
    frac_real s0 = FRAC_R(0.0), s1 = FRAC_R(0.0), s2 = FRAC_R(0.0), s3 = FRAC_R(0.0);
    frac_real s4 = FRAC_R(0.0), s5 = FRAC_R(0.0), s6 = FRAC_R(0.0), s7 = FRAC_R(0.0);
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        s0 += a[i] * b[i];
        s1 += a[i + 1] * b[i + 1];
        s2 += a[i + 2] * b[i + 2];
        s3 += a[i + 3] * b[i + 3];
        s4 += a[i + 4] * b[i + 4];
        s5 += a[i + 5] * b[i + 5];
        s6 += a[i + 6] * b[i + 6];
        s7 += a[i + 7] * b[i + 7];
    }
    for (; i < n; i++) s0 += a[i] * b[i];
    return ((s0 + s1) + (s2 + s3)) + ((s4 + s5) + (s6 + s7));
}

int frac_gl_init(frac_gl *gl, frac_real order, frac_real ts, size_t L, frac_real *storage, size_t len)
{
    size_t j;
    double w, scale, r;
    if (gl == NULL) return FRAC_E_NULL;
    gl->ready = 0;
    if (!FRAC_ISFINITE(order) || order < -FRAC_FO_ORDER_MAX || order > FRAC_FO_ORDER_MAX) return FRAC_E_ORDER;
    if (!FRAC_ISFINITE(ts) || ts <= FRAC_R(0.0)) return FRAC_E_TS;
    if (L == 0) return FRAC_E_DIM;
    if (storage == NULL) return FRAC_E_NULL;
    if (len < FRAC_GL_STORAGE(L)) return FRAC_E_STORAGE;
    r = (double)order;
    scale = pow((double)ts, -r);
    if (!(scale <= (double)FRAC_REAL_MAX)) return FRAC_E_NUMERIC; /* also NaN, Inf */
    w = 1.0;
    for (j = 0; j < L; j++) {
        /* w_j = w_{j-1} (1 - (r+1)/j): binomial recursion, seed 001 note section 7 */
        if (j > 0) w *= 1.0 - (r + 1.0) / (double)j;
        storage[L - 1 - j] = (frac_real)(scale * w);
    }
    gl->wrev = storage;
    gl->hist = storage + L;
    gl->L = L;
    gl->order = order;
    gl->ts = ts;
    gl->ready = 1;
    return frac_gl_set_history(gl, FRAC_R(0.0));
}

int frac_gl_set_history(frac_gl *gl, frac_real x)
{
    size_t i;
    if (gl == NULL) return FRAC_E_NULL;
    if (!gl->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(x)) return FRAC_E_NONFINITE;
    for (i = 0; i < 2 * gl->L; i++) gl->hist[i] = x;
    gl->pos = 0;
    gl->last = x == FRAC_R(0.0) ? FRAC_R(0.0) : dot(gl->wrev, gl->hist, gl->L);
    return FRAC_OK;
}

int frac_gl_step(frac_gl *gl, frac_real x, frac_real *y)
{
    size_t q;
    if (gl == NULL || y == NULL) return FRAC_E_NULL;
    if (!gl->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(x)) {
        *y = gl->last;
        return FRAC_E_NONFINITE;
    }
    /* advance the window; the newest sample goes to ring slot q = pos - 1 */
    q = gl->pos;
    gl->pos = (gl->pos + 1 == gl->L) ? 0 : gl->pos + 1;
    gl->hist[q] = x;
    gl->hist[q + gl->L] = x;
    gl->last = dot(gl->wrev, gl->hist + gl->pos, gl->L);
    *y = gl->last;
    return FRAC_OK;
}

int frac_gl_free_response(const frac_gl *gl, frac_real *y0)
{
    if (gl == NULL || y0 == NULL) return FRAC_E_NULL;
    if (!gl->ready) return FRAC_E_NOT_INIT;
    /* next output minus its x term: the L-1 newest samples against w_1..w_{L-1} */
    *y0 = dot(gl->wrev, gl->hist + gl->pos + 1, gl->L - 1);
    return FRAC_OK;
}

frac_real frac_gl_feedthrough(const frac_gl *gl)
{
    if (gl == NULL || !gl->ready) return FRAC_R(0.0);
    return gl->wrev[gl->L - 1];
}

int frac_gl_freqresp(const frac_gl *gl, frac_real w, frac_real *re, frac_real *im)
{
    size_t j;
    double th, sr = 0.0, si = 0.0;
    if (gl == NULL || re == NULL || im == NULL) return FRAC_E_NULL;
    if (!gl->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(w) || w < FRAC_R(0.0)) return FRAC_E_PARAM;
    th = (double)w * (double)gl->ts;
    for (j = 0; j < gl->L; j++) {
        double c = (double)gl->wrev[gl->L - 1 - j];
        sr += c * cos(th * (double)j);
        si -= c * sin(th * (double)j);
    }
    *re = (frac_real)sr;
    *im = (frac_real)si;
    return FRAC_OK;
}
