/*
 * delayline.h - pure delay z^-d of a scalar signal in caller storage.
 *
 * Implements y[k] = u[k - d] for a fixed integer delay d >= 0, i.e. the
 * discrete counterpart of e^{-tau s} with d = tau / Ts samples. It is the
 * building block of the fractional process simulator (foprocess.h) and of
 * the input/output shift registers of the delay-augmented Kalman/LQG models.
 *
 * Storage: a ring buffer of `len` frac_real owned by the caller, len >= d
 * (len > d is allowed and lets tap() read further into the past than d).
 * d = 0 needs no storage (storage may be NULL, len 0): y[k] = u[k].
 *
 * Semantics: before the first step every tap holds the reset value
 * (0 after init, or the value given to frac_delayline_reset), so
 * y[k] = reset value for k < d. Tap i (0 <= i <= len) reads u[k - i] after
 * the step of sample k: tap 0 is the latest input, tap d the delayed output
 * that step returned.
 *
 * Cost: step is O(1) (one load, one store, one index update), independent
 * of d. Memory: sizeof(frac_delayline) + len * sizeof(frac_real).
 *
 * Bad input: a non-finite u returns FRAC_E_NONFINITE, leaves the buffer
 * untouched and writes the last finite output to *y.
 */
#ifndef FRAC_DELAYLINE_H
#define FRAC_DELAYLINE_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct frac_delayline {
    frac_real *buf;  /* caller storage, len entries: buf[head] is the oldest kept sample */
    size_t len;      /* ring length (>= delay) */
    size_t delay;    /* d, samples */
    size_t head;     /* next write position, holds u[k - len] before the write */
    frac_real last;  /* last output, returned on a rejected input */
    frac_real latest; /* u of the latest accepted step (tap 0) */
    int ready;       /* nonzero after a successful init */
} frac_delayline;

/*
 * Initialises a delay of `delay` samples in `storage` (len entries,
 * len >= delay). All taps and the held output are set to 0.
 * Returns FRAC_OK, FRAC_E_NULL (dl NULL, or storage NULL with len > 0),
 * FRAC_E_STORAGE (len < delay).
 */
int frac_delayline_init(frac_delayline *dl, frac_real *storage, size_t len, size_t delay);

/*
 * Sets every tap and the held output to `value` (a steady state: a
 * constant input `value` produces the output `value` from the next step on).
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE.
 */
int frac_delayline_reset(frac_delayline *dl, frac_real value);

/*
 * One sample: stores u[k], writes u[k - d] to *y.
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE.
 */
int frac_delayline_step(frac_delayline *dl, frac_real u, frac_real *y);

/*
 * Reads tap i = u[k - i] of the latest step k without changing the state,
 * 0 <= i <= len (i = 0 is the latest input). Returns FRAC_OK, FRAC_E_NULL,
 * FRAC_E_NOT_INIT, FRAC_E_DIM (i > len).
 */
int frac_delayline_tap(const frac_delayline *dl, size_t i, frac_real *value);

/*
 * Overwrites tap i (1 <= i <= len) = u[k - i], e.g. to seed a shift
 * register from a known past; i = 0 overwrites the latest input.
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_DIM, FRAC_E_NONFINITE.
 */
int frac_delayline_set_tap(frac_delayline *dl, size_t i, frac_real value);

/* Delay d in samples (0 if dl is NULL or not initialised). */
size_t frac_delayline_delay(const frac_delayline *dl);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_DELAYLINE_H */
