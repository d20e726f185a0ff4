/*
 * lut.h - 1-D and 2-D lookup tables in caller storage.
 *
 * Seed 004 stores the feedforward (theta_M*, dtheta_M*, dpsi_L*, tau_M*)
 * as lookup tables interpolated every PLC cycle (thesis Sec. 5.1, 6.4;
 * notes 004b section 4.5: the interpolation scheme is not specified, so
 * both linear and shape-preserving cubic are offered here).
 *
 * Breakpoints: uniform (x_i = x0 + i h, index found in O(1)) or a
 * strictly increasing array (branch-free binary search in ceil(log2 n)
 * fixed power-of-two steps, L. E. Shar's variant; the last segment found
 * is tried first, so repeated queries in one segment, as in a slow
 * playback, cost O(1)). Non-increasing breakpoints are rejected at init
 * with FRAC_E_NOT_MONOTONE.
 *
 * Interpolation on segment i, t = (x - x_i) / (x_{i+1} - x_i) in [0, 1):
 *  - linear: y = y_i + t (y_{i+1} - y_i)
 *  - monotone cubic: the cubic Hermite interpolant with the slopes of
 *    F. N. Fritsch and R. E. Carlson, "Monotone piecewise cubic
 *    interpolation", SIAM J. Numer. Anal. 17 (1980): three-point slopes
 *    inside, a one-sided three-point slope at the ends, zero at a local
 *    extremum or flat secant, and (alpha, beta) scaled into the circle of
 *    radius 3, which keeps the interpolant monotone wherever the data
 *    are. C^1, third-order accurate on smooth data.
 * Both are exact at the knots.
 *
 * Outside [x_0, x_{n-1}]: FRAC_LUT_CLAMP returns the end value and
 * FRAC_W_CLAMPED; FRAC_LUT_EXTRAPOLATE continues the end segment (linear)
 * or the end tangent line (cubic) and returns FRAC_W_EXTRAPOLATED.
 *
 * Inverse lookup (1-D): for strictly monotone data, x with lookup(x) = y
 * (linear: closed form; cubic: safeguarded Newton-bisection on the
 * segment, at most FRAC_LUT_INV_ITER iterations). Other data: FRAC_E_NOT_MONOTONE.
 *
 * A NaN query returns FRAC_E_NONFINITE and writes the last finite output.
 * The table arrays are held by pointer and must stay alive and unchanged;
 * the object itself is mutable (cached index, last output), so one object
 * per concurrent user.
 */
#ifndef FRAC_LUT_H
#define FRAC_LUT_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum frac_lut_interp { FRAC_LUT_LINEAR = 0, FRAC_LUT_CUBIC = 1 } frac_lut_interp;
typedef enum frac_lut_range { FRAC_LUT_CLAMP = 0, FRAC_LUT_EXTRAPOLATE = 1 } frac_lut_range;

#define FRAC_LUT_INV_ITER 60

/* One axis: uniform (x == NULL) or breakpoints. Filled by the inits. */
typedef struct frac_lut_axis {
    const frac_real *x; /* n strictly increasing breakpoints, or NULL (uniform) */
    size_t n;           /* number of knots, >= 2 */
    frac_real lo, hi;   /* first and last knot */
    frac_real h, inv_h; /* uniform spacing and its inverse */
    frac_real smax;     /* n - 1 as frac_real (uniform range test) */
    size_t pow2;        /* largest power of 2 <= n - 1 (breakpoint search) */
    size_t cache;       /* last segment found (breakpoint search) */
} frac_lut_axis;

typedef struct frac_lut1 {
    frac_lut_axis ax;
    const frac_real *y; /* n values */
    frac_real *d;       /* n Fritsch-Carlson slopes (cubic), caller storage */
    int interp, range;
    int mono;           /* +1 / -1: y strictly increasing / decreasing, 0: neither */
    size_t inv_cache;   /* last segment of the inverse lookup */
    frac_real last, last_inv;
    int ready;
} frac_lut1;

/*
 * Uniform table x_i = x0 + i h, i = 0..n-1. `slopes`: n entries of
 * caller storage for FRAC_LUT_CUBIC (filled here), NULL allowed for linear.
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM (n < 2), FRAC_E_PARAM
 * (x0 or h non-finite, h <= 0, unknown interp/range), FRAC_E_NONFINITE
 * (a value non-finite).
 */
int frac_lut1_init_uniform(frac_lut1 *t, frac_real x0, frac_real h, const frac_real *y, size_t n,
                           int interp, int range, frac_real *slopes);

/*
 * Table on breakpoints x (n entries, strictly increasing). As above, plus
 * FRAC_E_NOT_MONOTONE (x not strictly increasing) and FRAC_E_NONFINITE
 * (a breakpoint non-finite).
 */
int frac_lut1_init(frac_lut1 *t, const frac_real *x, const frac_real *y, size_t n,
                   int interp, int range, frac_real *slopes);

/*
 * y = f(xq). Returns FRAC_OK, FRAC_W_CLAMPED, FRAC_W_EXTRAPOLATED,
 * FRAC_E_NONFINITE (xq NaN: *y = last output), FRAC_E_NULL, FRAC_E_NOT_INIT.
 * Cost: O(1) uniform or cached segment, else O(log n) comparisons.
 */
int frac_lut1_eval(frac_lut1 *t, frac_real xq, frac_real *y);

/*
 * x = f^-1(yq) for strictly monotone data. Out of the value range: clamp
 * to the end knot (FRAC_W_CLAMPED) or, with FRAC_LUT_EXTRAPOLATE, invert
 * the extension line (FRAC_W_EXTRAPOLATED). Returns also FRAC_OK,
 * FRAC_E_NOT_MONOTONE, FRAC_E_NONFINITE (*x = last inverse output),
 * FRAC_E_NULL, FRAC_E_NOT_INIT.
 */
int frac_lut1_inverse(frac_lut1 *t, frac_real yq, frac_real *x);

/*
 * 2-D table z(x1, x2), row-major values z[i * n2 + j] at (x1_i, x2_j).
 * Each axis uniform or on breakpoints (as frac_lut1).
 *  - linear: bilinear on the cell.
 *  - monotone cubic: separable; along x2 on the four grid rows i-1..i+2
 *    around the cell, then along x1 through those four values, each pass
 *    a cubic Hermite with the local slopes of F. N. Fritsch and J. Butland,
 *    "A method for constructing local monotone piecewise cubic
 *    interpolants", SIAM J. Sci. Stat. Comput. 5 (1984) (weighted harmonic
 *    mean of the neighbouring secants, 0 at an extremum; the pchip end
 *    rule at the table edge). Each pass is monotone where its data are and
 *    C^1; no slope storage is needed. Exact at the grid points.
 * Out of range on either axis: clamp, or extrapolate (the edge cell
 * continued bilinearly, for both interpolations), flagged as for 1-D.
 */
typedef struct frac_lut2 {
    frac_lut_axis a1, a2;
    const frac_real *z;
    int range;
    int interp;
    frac_real last;
    int ready;
} frac_lut2;

/*
 * Axis description for frac_lut2_init: breakpoints x (n entries) or, with
 * x == NULL, the uniform grid x0 + i h.
 */
typedef struct frac_lut_axis_params {
    const frac_real *x;
    size_t n;
    frac_real x0, h;
} frac_lut_axis_params;

/*
 * Bilinear table. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM (an axis with
 * n < 2), FRAC_E_PARAM, FRAC_E_NOT_MONOTONE, FRAC_E_NONFINITE (as
 * frac_lut1_init).
 */
int frac_lut2_init(frac_lut2 *t, const frac_lut_axis_params *ax1, const frac_lut_axis_params *ax2,
                   const frac_real *z, int range);

/* As frac_lut2_init with the interpolation chosen (FRAC_LUT_LINEAR or FRAC_LUT_CUBIC). */
int frac_lut2_init_interp(frac_lut2 *t, const frac_lut_axis_params *ax1, const frac_lut_axis_params *ax2,
                          const frac_real *z, int range, int interp);

/* z = f(x1, x2). Statuses as frac_lut1_eval (the stronger of both axes). */
int frac_lut2_eval(frac_lut2 *t, frac_real x1, frac_real x2, frac_real *z);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_LUT_H */
