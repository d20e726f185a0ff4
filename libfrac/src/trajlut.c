/*
 * trajlut.c - multi-channel reference playback with per-channel lead/lag
 * (seed 004 Sec. 8.6, see frac/trajlut.h), one frac_lut1 per channel.
 */
#include "frac/trajlut.h"

int frac_trajlut_init(frac_trajlut *tl, const frac_trajlut_params *p, frac_real *slopes)
{
    size_t c;
    int st;
    if (tl == NULL || p == NULL) return FRAC_E_NULL;
    tl->ready = 0;
    if (p->data == NULL) return FRAC_E_NULL;
    if (p->channels == 0 || p->channels > FRAC_TRAJLUT_MAX_CH || p->n < 2) return FRAC_E_DIM;
    if (!FRAC_ISFINITE(p->dt) || !(p->dt > FRAC_R(0.0)) || !FRAC_ISFINITE(p->Ts) || !(p->Ts > FRAC_R(0.0)))
        return FRAC_E_TS;
    if (!FRAC_ISFINITE(p->t0) || !FRAC_ISFINITE(p->t_motion_start) || !FRAC_ISFINITE(p->t_motion_end) ||
        p->t_motion_start < p->t0 || p->t_motion_end < p->t_motion_start)
        return FRAC_E_PARAM;
    if (p->interp == FRAC_LUT_CUBIC && slopes == NULL) return FRAC_E_STORAGE;
    for (c = 0; c < p->channels; c++) {
        if (p->data[c] == NULL) return FRAC_E_NULL;
        st = frac_lut1_init_uniform(&tl->lut[c], p->t0, p->dt, p->data[c], p->n, p->interp, FRAC_LUT_CLAMP,
                                    slopes != NULL ? slopes + c * p->n : NULL);
        if (st != FRAC_OK) return st;
        tl->lead[c] = p->lead != NULL ? p->lead[c] : 0;
    }
    tl->channels = p->channels;
    tl->Ts = p->Ts;
    tl->t_lo = tl->lut[0].ax.lo;
    tl->t_hi = tl->lut[0].ax.hi;
    tl->t_ms = p->t_motion_start;
    tl->t_me = p->t_motion_end;
    tl->k = 0;
    tl->ready = 1;
    return FRAC_OK;
}

int frac_trajlut_eval(frac_trajlut *tl, unsigned long k, frac_real *out, int *segment)
{
    size_t c;
    frac_real t;
    int status = FRAC_OK;
    if (tl == NULL || out == NULL) return FRAC_E_NULL;
    if (!tl->ready) return FRAC_E_NOT_INIT;
    t = (frac_real)k * tl->Ts;
    for (c = 0; c < tl->channels; c++) {
        /* (k + lead) Ts: the integer sum is exact, so knots are hit up to one rounding */
        frac_real tc = ((frac_real)k + (frac_real)tl->lead[c]) * tl->Ts;
        if (frac_lut1_eval(&tl->lut[c], tc, &out[c]) != FRAC_OK) status = FRAC_W_CLAMPED;
    }
    if (segment != NULL) {
        if (t < tl->t_lo) *segment = FRAC_TRAJLUT_BEFORE;
        else if (t < tl->t_ms) *segment = FRAC_TRAJLUT_PRE;
        else if (t <= tl->t_me) *segment = FRAC_TRAJLUT_MOTION;
        else if (t <= tl->t_hi) *segment = FRAC_TRAJLUT_POST;
        else *segment = FRAC_TRAJLUT_AFTER;
    }
    return status;
}

int frac_trajlut_step(frac_trajlut *tl, frac_real *out, int *segment)
{
    int st;
    if (tl == NULL || out == NULL) return FRAC_E_NULL;
    if (!tl->ready) return FRAC_E_NOT_INIT;
    st = frac_trajlut_eval(tl, tl->k, out, segment);
    tl->k++;
    return st;
}

int frac_trajlut_seek(frac_trajlut *tl, unsigned long k)
{
    if (tl == NULL) return FRAC_E_NULL;
    if (!tl->ready) return FRAC_E_NOT_INIT;
    tl->k = k;
    return FRAC_OK;
}
