/*
 * fo_op.h - one front for the discrete realizations of s^r: choose
 * Grünwald–Letnikov (fo_gl.h), Oustaloup or refined Oustaloup
 * (fo_oustaloup.h) or CFE of Tustin / Al-Alaoui (fo_cfe.h) by a parameter.
 * The controllers (fopid.h, fodamp.h), the process simulator
 * (foprocess.h) and the PLC block FracOp are written against this front.
 *
 * Order 0 is the identity for every method (no storage needed).
 *
 * Which to use:
 *   GL          any r in [-2, 2], no band to choose, exact in the limit
 *               L -> inf; cost L multiply-adds per sample, memory 3 L.
 *   Oustaloup   a fixed cost (N + 1 biquads) and a finite band [wb, wh];
 *               refined for 0 < r < 1 when the band edges matter.
 *   CFE         the lowest order for mid/high-frequency accuracy; poor
 *               towards DC.
 *
 * Storage: frac_fo_storage_len(p) reals of caller storage.
 */
#ifndef FRAC_FO_OP_H
#define FRAC_FO_OP_H

#include "frac/frac_types.h"
#include "frac/sos.h"
#include "frac/fo_gl.h"
#include "frac/fo_oustaloup.h"
#include "frac/fo_cfe.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum frac_fo_method {
    FRAC_FO_GL = 1,
    FRAC_FO_OUSTALOUP = 2,
    FRAC_FO_OUSTALOUP_REFINED = 3,
    FRAC_FO_CFE_TUSTIN = 4,
    FRAC_FO_CFE_ALALAOUI = 5
} frac_fo_method;

typedef struct frac_fo_params {
    int method;      /* frac_fo_method */
    frac_real order; /* r */
    frac_real ts;    /* sampling time, s */
    size_t memory;   /* GL: memory length L (terms) */
    frac_real wb;    /* Oustaloup: band, rad/s */
    frac_real wh;
    unsigned n;      /* Oustaloup: N; CFE: expansion order */
} frac_fo_params;

typedef struct frac_fo {
    frac_fo_params p;
    frac_gl gl;      /* FRAC_FO_GL */
    frac_sos sos;    /* Oustaloup and CFE */
    frac_real last;  /* identity (order 0): last output */
    int kind;        /* 0 identity (or not initialised), 1 GL, 2 SOS */
    int ready;
} frac_fo;

/* Reals of storage frac_fo_init needs for p (0 for order 0 or an unknown method). */
size_t frac_fo_storage_len(const frac_fo_params *p);

/*
 * Validates p (codes of the chosen realization's init, FRAC_E_PARAM for
 * an unknown method) and builds it in storage (len >=
 * frac_fo_storage_len(p); storage may be NULL when that is 0).
 */
int frac_fo_init(frac_fo *op, const frac_fo_params *p, frac_real *storage, size_t len);

/* One sample of y = s^r x. FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE (state untouched, *y = last). */
int frac_fo_step(frac_fo *op, frac_real x, frac_real *y);

/* Zero state (zero input history). */
int frac_fo_reset(frac_fo *op);

/*
 * State of a constant input x applied forever (GL: the whole memory;
 * rational: the DC steady state). FRAC_E_NUMERIC for a rational
 * realization with a pole at z = 1 (integer integrator part).
 */
int frac_fo_set_steady(frac_fo *op, frac_real x);

/* The next output is exactly feedthrough * x + *y0 (solves algebraic loops). */
int frac_fo_free_response(const frac_fo *op, frac_real *y0);
frac_real frac_fo_feedthrough(const frac_fo *op);

/* Last output. */
frac_real frac_fo_output(const frac_fo *op);

/* Frequency response of the discrete realization at w rad/s (<= pi/ts). */
int frac_fo_freqresp(const frac_fo *op, frac_real w, frac_real *re, frac_real *im);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_FO_OP_H */
