/*
 * frac_zpk.h - internal (not installed): building biquad tables from
 * z-plane roots, and polynomial roots, for the rational realizations of
 * s^r (fo_oustaloup.c, fo_cfe.c, fodamp.c). Double precision throughout;
 * the tables are rounded to frac_real once, at the end.
 */
#ifndef FRAC_ZPK_H
#define FRAC_ZPK_H

#include "frac/frac_types.h"
#include "frac/sos.h"

#define FRAC_ZPK_MAXROOTS 40

/* A list of z-plane roots of a real polynomial in factored form
 * prod (1 - r_i z^-1): real roots, and complex pairs given once by the
 * member with positive imaginary part. */
typedef struct frac_zpk_roots {
    double re[FRAC_ZPK_MAXROOTS];
    double im[FRAC_ZPK_MAXROOTS]; /* 0 for a real root, > 0 for a pair */
    int n;                        /* entries used */
} frac_zpk_roots;

/*
 * Roots of the real polynomial c[0] z^deg + c[1] z^(deg-1) + ... + c[deg]
 * (c[0] != 0, deg <= FRAC_ZPK_MAXROOTS) by the Aberth–Ehrlich iteration,
 * appended to `out` (pairs stored once). Returns FRAC_OK or
 * FRAC_E_NUMERIC (no convergence, or roots not in conjugate pairs).
 */
int frac_zpk_polyroots(const double *c, int deg, frac_zpk_roots *out);

/* Adds a real root. Returns FRAC_E_DIM when full. */
int frac_zpk_add_real(frac_zpk_roots *r, double x);

/* Largest root modulus (0 for an empty list). */
double frac_zpk_maxabs(const frac_zpk_roots *r);

/*
 * Number of sections frac_zpk_to_sos() needs for these zeros and poles:
 * max over zeros/poles of (pairs + ceil(reals / 2)).
 */
size_t frac_zpk_nsec(const frac_zpk_roots *zeros, const frac_zpk_roots *poles);

/*
 * Writes H(z) = gain prod(1 - z_i z^-1) / prod(1 - p_i z^-1) as `nsec`
 * sections {b0,b1,b2,a1,a2} into coeffs (frac_real). Complex pairs form
 * one quadratic each; real roots are sorted and paired from the two ends
 * (smallest with largest), which keeps clustered roots near z = 1 in
 * different sections and the coefficients well conditioned. Sections are
 * padded with identities when nsec exceeds the need; |gain| is spread
 * evenly, its sign goes to the first section. FRAC_OK, FRAC_E_STORAGE
 * (nsec too small), FRAC_E_NUMERIC (a coefficient not finite in frac_real).
 */
int frac_zpk_to_sos(const frac_zpk_roots *zeros, const frac_zpk_roots *poles, double gain,
                    frac_real *coeffs, size_t nsec);

/* Bilinear map of an s-plane real root s = -a (factor s + a) with c = 2/Ts:
 * z-plane root (c - a)/(c + a), and the factor's gain (c + a). */
double frac_zpk_bilinear_root(double a, double c);

/*
 * Bilinear map (c = 2/Ts) of the s-plane root s0 = sre + j sim of a
 * factor (s - s0), sim >= 0 (sim > 0: the conjugate pair): appends the
 * z-plane root (c + s0)/(c - s0) and multiplies *gain by the factor's
 * gain c - s0 (|c - s0|^2 for a pair). FRAC_E_DIM when full.
 */
int frac_zpk_add_bilinear(frac_zpk_roots *r, double sre, double sim, double c, double *gain);

#endif /* FRAC_ZPK_H */
