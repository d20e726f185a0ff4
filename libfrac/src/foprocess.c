/* foprocess.c - K e^{-tau s}/(1 + T s^l) simulator (see frac/foprocess.h). */
#include "frac/foprocess.h"

#define FOP_MAX_DELAY 1e7

static frac_fo_params op_params(const frac_foprocess_params *p)
{
    frac_fo_params o = p->op;
    o.order = p->lambda;
    o.ts = p->ts;
    return o;
}

static size_t delay_samples(const frac_foprocess_params *p)
{
    return (size_t)((double)p->tau / (double)p->ts);
}

size_t frac_foprocess_storage_len(const frac_foprocess_params *p)
{
    frac_fo_params o;
    if (p == NULL || !FRAC_ISFINITE(p->tau) || !FRAC_ISFINITE(p->ts) || p->ts <= FRAC_R(0.0) || p->tau < FRAC_R(0.0)
        || (double)p->tau / (double)p->ts > FOP_MAX_DELAY)
        return 0;
    o = op_params(p);
    return frac_fo_storage_len(&o) + delay_samples(p) + 1;
}

int frac_foprocess_init(frac_foprocess *g, const frac_foprocess_params *p, frac_real *storage, size_t len)
{
    frac_fo_params o;
    size_t d, nop;
    int st;
    if (g == NULL || p == NULL) return FRAC_E_NULL;
    g->ready = 0;
    if (!FRAC_ISFINITE(p->k) || !FRAC_ISFINITE(p->t) || p->t <= FRAC_R(0.0)) return FRAC_E_GAIN;
    if (!FRAC_ISFINITE(p->lambda) || p->lambda <= FRAC_R(0.0) || p->lambda > FRAC_R(2.0)) return FRAC_E_ORDER;
    if (!FRAC_ISFINITE(p->ts) || p->ts <= FRAC_R(0.0)) return FRAC_E_TS;
    if (!FRAC_ISFINITE(p->tau) || p->tau < FRAC_R(0.0) || (double)p->tau / (double)p->ts > FOP_MAX_DELAY) return FRAC_E_PARAM;
    if (storage == NULL) return FRAC_E_NULL;
    if (len < frac_foprocess_storage_len(p)) return FRAC_E_STORAGE;
    o = op_params(p);
    nop = frac_fo_storage_len(&o);
    d = delay_samples(p);
    st = frac_fo_init(&g->op, &o, storage, nop);
    if (st != FRAC_OK) return st;
    st = frac_delayline_init(&g->dl, storage + nop, d + 1, d);
    if (st != FRAC_OK) return st;
    if (!(FRAC_FABS(FRAC_R(1.0) + p->t * frac_fo_feedthrough(&g->op)) > FRAC_R(0.0))) return FRAC_E_NUMERIC;
    g->k = p->k;
    g->t = p->t;
    g->mu = (frac_real)((double)p->tau / (double)p->ts - (double)d);
    g->last = FRAC_R(0.0);
    g->ready = 1;
    return FRAC_OK;
}

int frac_foprocess_step(frac_foprocess *g, frac_real u, frac_real *y)
{
    frac_real v, vprev, f, yk, dummy;
    if (g == NULL || y == NULL) return FRAC_E_NULL;
    if (!g->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(u)) {
        *y = g->last;
        return FRAC_E_NONFINITE;
    }
    frac_delayline_step(&g->dl, u, &v);
    frac_delayline_tap(&g->dl, frac_delayline_delay(&g->dl) + 1, &vprev);
    v += g->mu * (vprev - v);
    /* y + T D^l y = K v with D^l y = g y + f: solve for y */
    frac_fo_free_response(&g->op, &f);
    yk = (g->k * v - g->t * f) / (FRAC_R(1.0) + g->t * frac_fo_feedthrough(&g->op));
    frac_fo_step(&g->op, yk, &dummy);
    g->last = yk;
    *y = yk;
    return FRAC_OK;
}

int frac_foprocess_reset(frac_foprocess *g)
{
    int st;
    if (g == NULL) return FRAC_E_NULL;
    if (!g->ready) return FRAC_E_NOT_INIT;
    st = frac_fo_reset(&g->op);
    if (st == FRAC_OK) st = frac_delayline_reset(&g->dl, FRAC_R(0.0));
    g->last = FRAC_R(0.0);
    return st;
}
