/*
 * lut.c - 1-D/2-D lookup tables: O(1) uniform index, cached binary search,
 * linear and Fritsch-Carlson monotone cubic interpolation, inverse lookup
 * (see frac/lut.h).
 */
#include "frac/lut.h"

static int axis_init(frac_lut_axis *a, const frac_real *x, size_t n, frac_real x0, frac_real h)
{
    size_t i;
    if (n < 2) return FRAC_E_DIM;
    a->x = x;
    a->n = n;
    a->cache = 0;
    a->smax = (frac_real)(n - 1);
    a->pow2 = 1;
    while (a->pow2 * 2 <= n - 1) a->pow2 *= 2;
    if (x == NULL) {
        if (!FRAC_ISFINITE(x0) || !FRAC_ISFINITE(h) || !(h > FRAC_R(0.0))) return FRAC_E_PARAM;
        a->lo = x0;
        a->hi = x0 + h * (frac_real)(n - 1);
        a->h = h;
        a->inv_h = FRAC_R(1.0) / h;
        if (!FRAC_ISFINITE(a->hi) || !FRAC_ISFINITE(a->inv_h)) return FRAC_E_PARAM;
        return FRAC_OK;
    }
    for (i = 0; i < n; i++) {
        if (!FRAC_ISFINITE(x[i])) return FRAC_E_NONFINITE;
    }
    for (i = 0; i + 1 < n; i++) {
        if (!(x[i + 1] > x[i])) return FRAC_E_NOT_MONOTONE;
    }
    a->lo = x[0];
    a->hi = x[n - 1];
    a->h = FRAC_R(0.0);
    a->inv_h = FRAC_R(0.0);
    return FRAC_OK;
}

/* knot i of an axis */
static frac_real axis_knot(const frac_lut_axis *a, size_t i)
{
    return a->x != NULL ? a->x[i] : a->lo + a->h * (frac_real)i;
}

/*
 * Segment i (0..n-2) and local coordinate t of xq. In range: t in [0, 1],
 * FRAC_OK. Outside: t < 0 or t > 1 on the end segment (extrapolate) or
 * t clamped to 0 / 1 (clamp). NaN: FRAC_E_NONFINITE.
 */
static int axis_locate(frac_lut_axis *a, frac_real xq, int range, size_t *seg, frac_real *t)
{
    size_t i;
    frac_real u;
    if (a->x == NULL) {
        frac_real s = (xq - a->lo) * a->inv_h;
        /* the common case first; NaN fails both comparisons */
        if (s >= FRAC_R(0.0) && s < a->smax) {
            long il = (long)s;
            *seg = (size_t)il;
            *t = s - (frac_real)il;
            return FRAC_OK;
        }
        if (xq != xq) return FRAC_E_NONFINITE;
        i = a->n - 2;
        u = s < FRAC_R(0.0) ? s : s - (frac_real)i;
        if (s < FRAC_R(0.0)) i = 0;
    } else {
        const frac_real *x = a->x;
        i = a->cache;
        if (xq >= x[i] && xq < x[i + 1]) {
            *seg = i;
            *t = (xq - x[i]) / (x[i + 1] - x[i]);
            return FRAC_OK;
        }
        if (xq >= a->lo && xq < a->hi) {
            /* largest i in 0..m-1 (m = n - 1 segments) with x[i] <= xq:
             * the first probe picks one of the two overlapping blocks
             * [0, P) and [m - P, m) (P = pow2 > m/2), then P/2, ..., 1 */
            size_t step = a->pow2;
            i = (x[step] <= xq) ? a->n - 1 - step : 0;
            for (step >>= 1; step > 0; step >>= 1) i = (x[i + step] <= xq) ? i + step : i;
            a->cache = i;
            *seg = i;
            *t = (xq - x[i]) / (x[i + 1] - x[i]);
            return FRAC_OK;
        }
        if (xq != xq) return FRAC_E_NONFINITE;
        if (xq < a->lo) {
            i = 0;
        } else {
            i = a->n - 2;
        }
        u = (xq - x[i]) / (x[i + 1] - x[i]);
    }
    *seg = i;
    if (xq >= a->lo && xq <= a->hi) {
        /* the last knot itself, or a rounding of the uniform index at an end */
        *t = u < FRAC_R(0.0) ? FRAC_R(0.0) : (u > FRAC_R(1.0) ? FRAC_R(1.0) : u);
        return FRAC_OK;
    }
    if (range == FRAC_LUT_EXTRAPOLATE) {
        *t = u;
        return FRAC_W_EXTRAPOLATED;
    }
    *t = u < FRAC_R(0.0) ? FRAC_R(0.0) : FRAC_R(1.0);
    return FRAC_W_CLAMPED;
}

static frac_real hermite(frac_real y0, frac_real y1, frac_real hd0, frac_real hd1, frac_real t)
{
    frac_real t2 = t * t, t3 = t2 * t;
    return (FRAC_R(2.0) * t3 - FRAC_R(3.0) * t2 + FRAC_R(1.0)) * y0 + (t3 - FRAC_R(2.0) * t2 + t) * hd0 +
           (FRAC_R(3.0) * t2 - FRAC_R(2.0) * t3) * y1 + (t3 - t2) * hd1;
}

static frac_real hermite_dt(frac_real y0, frac_real y1, frac_real hd0, frac_real hd1, frac_real t)
{
    frac_real t2 = t * t;
    return (FRAC_R(6.0) * t2 - FRAC_R(6.0) * t) * (y0 - y1) + (FRAC_R(3.0) * t2 - FRAC_R(4.0) * t + FRAC_R(1.0)) * hd0 +
           (FRAC_R(3.0) * t2 - FRAC_R(2.0) * t) * hd1;
}

/*
 * One-sided three-point end slope (exact for quadratics), kept inside the
 * monotone region: 0 when it points against the end secant, at most
 * 3 times the end secant when the data turn (the end rule of MATLAB's
 * pchip, C. Moler, "Numerical Computing with MATLAB", Sec. 3.4).
 */
static frac_real end_slope(frac_real h0, frac_real h1, frac_real d0, frac_real d1)
{
    frac_real s = ((FRAC_R(2.0) * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (s * d0 <= FRAC_R(0.0)) return FRAC_R(0.0);
    if (d0 * d1 < FRAC_R(0.0) && FRAC_FABS(s) > FRAC_FABS(FRAC_R(3.0) * d0)) return FRAC_R(3.0) * d0;
    return s;
}

/*
 * Fritsch-Carlson slopes (SIAM J. Numer. Anal. 17, 1980): initial slopes
 * from the three-point formula d_k = (h_r delta_l + h_l delta_r)/(h_l + h_r)
 * (second-order accurate on non-uniform knots), 0 at a local extremum;
 * then every segment with (alpha, beta) = (d_k, d_k+1)/delta_k outside the
 * circle of radius 3 is scaled back onto it, and a flat secant forces both
 * end slopes to 0. The result is monotone on every monotone stretch.
 */
static void fritsch_carlson(const frac_lut_axis *a, const frac_real *y, frac_real *d)
{
    size_t n = a->n, k;
    frac_real dl, dr, hl, hr;
    hr = axis_knot(a, 1) - axis_knot(a, 0);
    dr = (y[1] - y[0]) / hr;
    if (n == 2) {
        d[0] = dr;
        d[1] = dr;
        return;
    }
    for (k = 1; k + 1 < n; k++) {
        dl = dr;
        hl = hr;
        hr = axis_knot(a, k + 1) - axis_knot(a, k);
        dr = (y[k + 1] - y[k]) / hr;
        d[k] = (dl * dr > FRAC_R(0.0)) ? (hr * dl + hl * dr) / (hl + hr) : FRAC_R(0.0);
        if (k == 1) d[0] = end_slope(hl, hr, dl, dr);
        if (k + 2 == n) d[n - 1] = end_slope(hr, hl, dr, dl);
    }
    for (k = 0; k + 1 < n; k++) {
        frac_real delta = (y[k + 1] - y[k]) / (axis_knot(a, k + 1) - axis_knot(a, k));
        if (delta == FRAC_R(0.0)) {
            d[k] = FRAC_R(0.0);
            d[k + 1] = FRAC_R(0.0);
        } else {
            frac_real al = d[k] / delta, be = d[k + 1] / delta, r2 = al * al + be * be;
            if (r2 > FRAC_R(9.0)) {
                frac_real tau = FRAC_R(3.0) / FRAC_SQRT(r2);
                d[k] = tau * al * delta;
                d[k + 1] = tau * be * delta;
            }
        }
    }
}

static int lut1_finish(frac_lut1 *t, const frac_real *y, int interp, int range, frac_real *slopes)
{
    size_t i, n = t->ax.n;
    int up = 1, down = 1;
    if (y == NULL) return FRAC_E_NULL;
    if (interp != FRAC_LUT_LINEAR && interp != FRAC_LUT_CUBIC) return FRAC_E_PARAM;
    if (range != FRAC_LUT_CLAMP && range != FRAC_LUT_EXTRAPOLATE) return FRAC_E_PARAM;
    if (interp == FRAC_LUT_CUBIC && slopes == NULL) return FRAC_E_STORAGE;
    for (i = 0; i < n; i++) {
        if (!FRAC_ISFINITE(y[i])) return FRAC_E_NONFINITE;
    }
    for (i = 0; i + 1 < n; i++) {
        if (!(y[i + 1] > y[i])) up = 0;
        if (!(y[i + 1] < y[i])) down = 0;
    }
    t->y = y;
    t->d = interp == FRAC_LUT_CUBIC ? slopes : NULL;
    if (t->d != NULL) fritsch_carlson(&t->ax, y, t->d);
    t->interp = interp;
    t->range = range;
    t->mono = up ? 1 : (down ? -1 : 0);
    t->inv_cache = 0;
    t->last = y[0];
    t->last_inv = t->ax.lo;
    t->ready = 1;
    return FRAC_OK;
}

int frac_lut1_init_uniform(frac_lut1 *t, frac_real x0, frac_real h, const frac_real *y, size_t n,
                           int interp, int range, frac_real *slopes)
{
    int st;
    if (t == NULL) return FRAC_E_NULL;
    t->ready = 0;
    st = axis_init(&t->ax, NULL, n, x0, h);
    if (st != FRAC_OK) return st;
    return lut1_finish(t, y, interp, range, slopes);
}

int frac_lut1_init(frac_lut1 *t, const frac_real *x, const frac_real *y, size_t n,
                   int interp, int range, frac_real *slopes)
{
    int st;
    if (t == NULL) return FRAC_E_NULL;
    t->ready = 0;
    if (x == NULL) return FRAC_E_NULL;
    st = axis_init(&t->ax, x, n, FRAC_R(0.0), FRAC_R(0.0));
    if (st != FRAC_OK) return st;
    return lut1_finish(t, y, interp, range, slopes);
}

/* value on segment i at local t (t may leave [0, 1] when extrapolating) */
static frac_real lut1_value(const frac_lut1 *t, size_t i, frac_real u)
{
    const frac_real *y = t->y;
    frac_real h;
    if (t->d == NULL) return y[i] + u * (y[i + 1] - y[i]);
    h = t->ax.x != NULL ? t->ax.x[i + 1] - t->ax.x[i] : t->ax.h;
    /* the tangent line outside the table */
    if (u < FRAC_R(0.0)) return y[i] + u * h * t->d[i];
    if (u > FRAC_R(1.0)) return y[i + 1] + (u - FRAC_R(1.0)) * h * t->d[i + 1];
    return hermite(y[i], y[i + 1], h * t->d[i], h * t->d[i + 1], u);
}

int frac_lut1_eval(frac_lut1 *t, frac_real xq, frac_real *y)
{
    size_t i = 0;
    frac_real u = FRAC_R(0.0);
    int st;
    if (t == NULL || y == NULL) return FRAC_E_NULL;
    if (!t->ready) return FRAC_E_NOT_INIT;
    st = axis_locate(&t->ax, xq, t->range, &i, &u);
    if (st < 0) {
        *y = t->last;
        return st;
    }
    t->last = lut1_value(t, i, u);
    *y = t->last;
    return st;
}

int frac_lut1_inverse(frac_lut1 *t, frac_real yq, frac_real *x)
{
    const frac_real *y;
    size_t n, i;
    frac_real sg, xl, xr, h, u;
    if (t == NULL || x == NULL) return FRAC_E_NULL;
    if (!t->ready) return FRAC_E_NOT_INIT;
    if (t->mono == 0) return FRAC_E_NOT_MONOTONE;
    if (yq != yq || !FRAC_ISFINITE(yq)) {
        *x = t->last_inv;
        return FRAC_E_NONFINITE;
    }
    y = t->y;
    n = t->ax.n;
    sg = (frac_real)t->mono; /* compare sg * y, increasing */
    if (sg * yq < sg * y[0] || sg * yq > sg * y[n - 1]) {
        int left = sg * yq < sg * y[0];
        if (t->range == FRAC_LUT_CLAMP) {
            t->last_inv = left ? t->ax.lo : t->ax.hi;
            *x = t->last_inv;
            return FRAC_W_CLAMPED;
        }
        i = left ? 0 : n - 2;
        xl = axis_knot(&t->ax, i);
        xr = axis_knot(&t->ax, i + 1);
        if (t->d == NULL) {
            u = (yq - y[i]) / (y[i + 1] - y[i]);
            t->last_inv = xl + u * (xr - xl);
        } else if (left) {
            t->last_inv = xl + (yq - y[0]) / t->d[0];
        } else {
            t->last_inv = xr + (yq - y[n - 1]) / t->d[n - 1];
        }
        *x = t->last_inv;
        return FRAC_W_EXTRAPOLATED;
    }
    i = t->inv_cache;
    if (!(sg * yq >= sg * y[i] && sg * yq <= sg * y[i + 1])) {
        size_t base = 0, len = n - 1;
        while (len > 1) {
            size_t half = len >> 1;
            if (sg * y[base + half] <= sg * yq) base += half;
            len -= half;
        }
        i = base;
        t->inv_cache = i;
    }
    xl = axis_knot(&t->ax, i);
    xr = axis_knot(&t->ax, i + 1);
    h = xr - xl;
    u = (yq - y[i]) / (y[i + 1] - y[i]); /* linear inverse, also the cubic's first guess */
    if (t->d != NULL) {
        /* safeguarded Newton on the monotone Hermite segment, bracket [a, b] */
        frac_real a = FRAC_R(0.0), b = FRAC_R(1.0), hd0 = h * t->d[i], hd1 = h * t->d[i + 1];
        frac_real tol = FRAC_R(4.0) * FRAC_REAL_EPSILON * (FRAC_FABS(y[i]) + FRAC_FABS(y[i + 1]));
        int it;
        for (it = 0; it < FRAC_LUT_INV_ITER; it++) {
            frac_real g = hermite(y[i], y[i + 1], hd0, hd1, u) - yq, dg, un;
            if (FRAC_FABS(g) <= tol) break;
            if (sg * g > FRAC_R(0.0)) b = u; else a = u;
            if (b - a <= FRAC_REAL_EPSILON) break;
            dg = hermite_dt(y[i], y[i + 1], hd0, hd1, u);
            un = dg != FRAC_R(0.0) ? u - g / dg : a - FRAC_R(1.0);
            if (!(un > a && un < b)) un = FRAC_R(0.5) * (a + b);
            u = un;
        }
    }
    t->last_inv = xl + u * h;
    *x = t->last_inv;
    return FRAC_OK;
}

int frac_lut2_init_interp(frac_lut2 *t, const frac_lut_axis_params *ax1, const frac_lut_axis_params *ax2,
                          const frac_real *z, int range, int interp)
{
    size_t i, n;
    int st;
    if (t == NULL) return FRAC_E_NULL;
    t->ready = 0;
    if (ax1 == NULL || ax2 == NULL || z == NULL) return FRAC_E_NULL;
    if (range != FRAC_LUT_CLAMP && range != FRAC_LUT_EXTRAPOLATE) return FRAC_E_PARAM;
    if (interp != FRAC_LUT_LINEAR && interp != FRAC_LUT_CUBIC) return FRAC_E_PARAM;
    st = axis_init(&t->a1, ax1->x, ax1->n, ax1->x0, ax1->h);
    if (st != FRAC_OK) return st;
    st = axis_init(&t->a2, ax2->x, ax2->n, ax2->x0, ax2->h);
    if (st != FRAC_OK) return st;
    n = ax1->n * ax2->n;
    for (i = 0; i < n; i++) {
        if (!FRAC_ISFINITE(z[i])) return FRAC_E_NONFINITE;
    }
    t->z = z;
    t->range = range;
    t->interp = interp;
    t->last = z[0];
    t->ready = 1;
    return FRAC_OK;
}

int frac_lut2_init(frac_lut2 *t, const frac_lut_axis_params *ax1, const frac_lut_axis_params *ax2,
                   const frac_real *z, int range)
{
    return frac_lut2_init_interp(t, ax1, ax2, z, range, FRAC_LUT_LINEAR);
}

/*
 * Fritsch-Butland slope at an interior knot from the secants delta_l,
 * delta_r over the neighbouring intervals h_l, h_r (SIAM J. Sci. Stat.
 * Comput. 5, 1984): weighted harmonic mean, 0 at an extremum. It never
 * exceeds 3 times either secant, so every segment stays monotone.
 */
static frac_real fb_slope(frac_real hl, frac_real hr, frac_real dl, frac_real dr)
{
    if (!(dl * dr > FRAC_R(0.0))) return FRAC_R(0.0);
    return FRAC_R(3.0) * (hl + hr) / ((FRAC_R(2.0) * hr + hl) / dl + (hr + FRAC_R(2.0) * hl) / dr);
}

/*
 * Monotone cubic Hermite on segment k of one axis at local t in [0, 1];
 * p points at the value of knot k, contiguous along the axis: p[-1] (if
 * k > 0), p[0], p[1], p[2] (if k + 2 < n) are read. Local slopes at k and
 * k + 1, the pchip end rule at the edges.
 */
static frac_real axis_cubic(const frac_lut_axis *a, size_t k, frac_real t, const frac_real *p)
{
    size_t n = a->n;
    frac_real x0 = axis_knot(a, k), x1 = axis_knot(a, k + 1), h = x1 - x0;
    frac_real y0 = p[0], y1 = p[1];
    frac_real dc = (y1 - y0) / h, d0, d1;
    if (n == 2) return y0 + t * (y1 - y0);
    if (k > 0) {
        frac_real hl = x0 - axis_knot(a, k - 1);
        d0 = fb_slope(hl, h, (y0 - *(p - 1)) / hl, dc);
    } else {
        frac_real h2 = axis_knot(a, 2) - x1;
        d0 = end_slope(h, h2, dc, (p[2] - y1) / h2);
    }
    if (k + 2 < n) {
        frac_real hr = axis_knot(a, k + 2) - x1;
        d1 = fb_slope(h, hr, dc, (p[2] - y1) / hr);
    } else {
        frac_real hl = x0 - axis_knot(a, k - 1);
        d1 = end_slope(h, hl, dc, (y0 - *(p - 1)) / hl);
    }
    return hermite(y0, y1, h * d0, h * d1, t);
}

int frac_lut2_eval(frac_lut2 *t, frac_real x1, frac_real x2, frac_real *z)
{
    size_t i = 0, j = 0, n2;
    frac_real u = FRAC_R(0.0), v = FRAC_R(0.0), z0, z1;
    const frac_real *r0, *r1;
    int s1, s2;
    if (t == NULL || z == NULL) return FRAC_E_NULL;
    if (!t->ready) return FRAC_E_NOT_INIT;
    s1 = axis_locate(&t->a1, x1, t->range, &i, &u);
    s2 = axis_locate(&t->a2, x2, t->range, &j, &v);
    if (s1 < 0 || s2 < 0) {
        *z = t->last;
        return FRAC_E_NONFINITE;
    }
    n2 = t->a2.n;
    if (t->interp == FRAC_LUT_CUBIC && u >= FRAC_R(0.0) && u <= FRAC_R(1.0) && v >= FRAC_R(0.0) &&
        v <= FRAC_R(1.0)) {
        /* along x2 on grid rows i-1..i+2, then along x1 through those values */
        frac_real w[4];
        size_t lo = i > 0 ? i - 1 : 0, hi = i + 2 < t->a1.n ? i + 2 : t->a1.n - 1, r;
        for (r = lo; r <= hi; r++) w[r - lo] = axis_cubic(&t->a2, j, v, t->z + r * n2 + j);
        t->last = axis_cubic(&t->a1, i, u, w + (i - lo));
    } else {
        r0 = t->z + i * n2 + j;
        r1 = r0 + n2;
        z0 = r0[0] + v * (r0[1] - r0[0]);
        z1 = r1[0] + v * (r1[1] - r1[0]);
        t->last = z0 + u * (z1 - z0);
    }
    *z = t->last;
    return s1 != FRAC_OK ? s1 : s2;
}
