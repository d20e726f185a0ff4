/*
 * delayline.c - pure delay z^-d in a caller-owned ring buffer.
 *
 * Invariant after the step of sample k: `latest` = u[k] (tap 0) and the
 * ring holds u[k-1] ... u[k-len]; buf[head] is u[k-len] (the slot the next
 * step overwrites) and tap i >= 1 sits at buf[(head - i) mod len].
 * Keeping tap 0 outside the ring is what lets len = d suffice for d >= 1.
 */
#include "frac/delayline.h"

int frac_delayline_init(frac_delayline *dl, frac_real *storage, size_t len, size_t delay)
{
    size_t i;
    if (dl == NULL) return FRAC_E_NULL;
    dl->ready = 0;
    if (storage == NULL && len > 0) return FRAC_E_NULL;
    if (len < delay) return FRAC_E_STORAGE;
    dl->buf = storage;
    dl->len = len;
    dl->delay = delay;
    dl->head = 0;
    for (i = 0; i < len; i++) storage[i] = FRAC_R(0.0);
    dl->last = FRAC_R(0.0);
    dl->latest = FRAC_R(0.0);
    dl->ready = 1;
    return FRAC_OK;
}

int frac_delayline_reset(frac_delayline *dl, frac_real value)
{
    size_t i;
    if (dl == NULL) return FRAC_E_NULL;
    if (!dl->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(value)) return FRAC_E_NONFINITE;
    for (i = 0; i < dl->len; i++) dl->buf[i] = value;
    dl->head = 0;
    dl->last = value;
    dl->latest = value;
    return FRAC_OK;
}

/* Ring index of tap i, 1 <= i <= len. */
static size_t tap_index(const frac_delayline *dl, size_t i)
{
    return dl->head >= i ? dl->head - i : dl->head + dl->len - i;
}

int frac_delayline_step(frac_delayline *dl, frac_real u, frac_real *y)
{
    if (dl == NULL || y == NULL) return FRAC_E_NULL;
    if (!dl->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(u)) {
        *y = dl->last;
        return FRAC_E_NONFINITE;
    }
    if (dl->len > 0) {
        dl->buf[dl->head] = dl->latest;
        dl->head++;
        if (dl->head == dl->len) dl->head = 0;
    }
    dl->latest = u;
    dl->last = dl->delay == 0 ? u : dl->buf[tap_index(dl, dl->delay)];
    *y = dl->last;
    return FRAC_OK;
}

int frac_delayline_tap(const frac_delayline *dl, size_t i, frac_real *value)
{
    if (dl == NULL || value == NULL) return FRAC_E_NULL;
    if (!dl->ready) return FRAC_E_NOT_INIT;
    if (i > dl->len) return FRAC_E_DIM;
    *value = i == 0 ? dl->latest : dl->buf[tap_index(dl, i)];
    return FRAC_OK;
}

int frac_delayline_set_tap(frac_delayline *dl, size_t i, frac_real value)
{
    if (dl == NULL) return FRAC_E_NULL;
    if (!dl->ready) return FRAC_E_NOT_INIT;
    if (i > dl->len) return FRAC_E_DIM;
    if (!FRAC_ISFINITE(value)) return FRAC_E_NONFINITE;
    if (i == 0) dl->latest = value;
    else dl->buf[tap_index(dl, i)] = value;
    return FRAC_OK;
}

size_t frac_delayline_delay(const frac_delayline *dl)
{
    return (dl != NULL && dl->ready) ? dl->delay : 0;
}
