/* fopid.c - PI^l D^m with filter, limits, anti-windup, bumpless transfer (see frac/fopid.h). */
#include "frac/fopid.h"

static frac_fo_params op_params(const frac_fopid_params *p, frac_real order)
{
    frac_fo_params o = p->op;
    o.order = order;
    o.ts = p->ts;
    return o;
}

static frac_real order_i(const frac_fopid_params *p)
{
    return p->ki != FRAC_R(0.0) ? FRAC_R(1.0) - p->lambda : FRAC_R(0.0);
}

static frac_real order_d(const frac_fopid_params *p)
{
    return p->kd != FRAC_R(0.0) ? p->mu : FRAC_R(0.0);
}

size_t frac_fopid_storage_len(const frac_fopid_params *p)
{
    frac_fo_params oi, od;
    if (p == NULL) return 0;
    oi = op_params(p, order_i(p));
    od = op_params(p, order_d(p));
    return frac_fo_storage_len(&oi) + frac_fo_storage_len(&od);
}

int frac_fopid_init(frac_fopid *c, const frac_fopid_params *p, frac_real *storage, size_t len)
{
    frac_fo_params oi, od;
    size_t ni, nd;
    int st;
    if (c == NULL || p == NULL) return FRAC_E_NULL;
    c->ready = 0;
    if (!FRAC_ISFINITE(p->kp) || !FRAC_ISFINITE(p->ki) || !FRAC_ISFINITE(p->kd) || !FRAC_ISFINITE(p->delta)
        || !FRAC_ISFINITE(p->b) || !FRAC_ISFINITE(p->c) || !FRAC_ISFINITE(p->tf) || p->tf < FRAC_R(0.0))
        return FRAC_E_GAIN;
    if (p->ki != FRAC_R(0.0) && !(p->lambda > FRAC_R(0.0) && p->lambda < FRAC_R(2.0))) return FRAC_E_ORDER;
    if (p->kd != FRAC_R(0.0) && !(p->mu >= FRAC_R(0.0) && p->mu <= FRAC_R(2.0))) return FRAC_E_ORDER;
    if (!(p->umin < p->umax)) return FRAC_E_LIMITS;
    if (p->antiwindup < FRAC_FOPID_AW_NONE || p->antiwindup > FRAC_FOPID_AW_BACKCALC) return FRAC_E_PARAM;
    if (p->antiwindup == FRAC_FOPID_AW_BACKCALC && !(FRAC_ISFINITE(p->tt) && p->tt > FRAC_R(0.0))) return FRAC_E_GAIN;
    if (!FRAC_ISFINITE(p->ts) || p->ts <= FRAC_R(0.0)) return FRAC_E_TS;
    oi = op_params(p, order_i(p));
    od = op_params(p, order_d(p));
    ni = frac_fo_storage_len(&oi);
    nd = frac_fo_storage_len(&od);
    if (ni + nd > 0 && storage == NULL) return FRAC_E_NULL;
    if (len < ni + nd) return FRAC_E_STORAGE;
    st = frac_fo_init(&c->opi, &oi, ni > 0 ? storage : NULL, ni);
    if (st != FRAC_OK) return st;
    st = frac_fo_init(&c->opd, &od, nd > 0 ? storage + ni : NULL, nd);
    if (st != FRAC_OK) return st;
    c->p = *p;
    c->af = p->tf > FRAC_R(0.0) ? FRAC_R(1.0) - FRAC_EXP(-p->ts / p->tf) : FRAC_R(1.0);
    c->mode = FRAC_FOPID_AUTO;
    c->ready = 1;
    return frac_fopid_reset(c);
}

int frac_fopid_reset(frac_fopid *c)
{
    if (c == NULL) return FRAC_E_NULL;
    if (!c->ready) return FRAC_E_NOT_INIT;
    frac_fo_reset(&c->opi);
    frac_fo_reset(&c->opd);
    c->xi = FRAC_R(0.0);
    c->df = FRAC_R(0.0);
    c->uman = FRAC_R(0.0);
    c->last = FRAC_R(0.0);
    return FRAC_OK;
}

static frac_real clamp(frac_real v, frac_real lo, frac_real hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

int frac_fopid_step(frac_fopid *c, frac_real r, frac_real y, frac_real *u)
{
    const frac_fopid_params *p;
    frac_real e, q = FRAC_R(0.0), d = FRAC_R(0.0), pd, inc, v, us, xi;
    if (c == NULL || u == NULL) return FRAC_E_NULL;
    if (!c->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(r) || !FRAC_ISFINITE(y)) {
        *u = c->last;
        return FRAC_E_NONFINITE;
    }
    p = &c->p;
    e = r - y;
    if (p->ki != FRAC_R(0.0)) frac_fo_step(&c->opi, e, &q);
    if (p->kd != FRAC_R(0.0)) {
        frac_fo_step(&c->opd, p->c * r - y, &d);
        c->df += c->af * (d - c->df);
    }
    /* everything but the integral state: P + D + positive feedback */
    pd = p->kp * (p->b * r - y) + p->kd * c->df + p->delta * y;
    inc = p->ts * p->ki * q;
    xi = c->xi;
    if (c->mode == FRAC_FOPID_MANUAL) {
        us = clamp(c->uman, p->umin, p->umax);
        xi = us - pd; /* tracking: automatic mode resumes from us */
    } else {
        v = pd + xi + inc;
        us = clamp(v, p->umin, p->umax);
        if (p->antiwindup == FRAC_FOPID_AW_CLAMP) {
            /* drop an increment that drives the output further into saturation */
            if (!((v > p->umax && inc > FRAC_R(0.0)) || (v < p->umin && inc < FRAC_R(0.0)))) xi += inc;
            us = clamp(pd + xi, p->umin, p->umax);
        } else if (p->antiwindup == FRAC_FOPID_AW_BACKCALC) {
            xi += inc + p->ts / p->tt * (us - v);
        } else {
            xi += inc;
        }
    }
    c->xi = xi;
    c->last = us;
    *u = us;
    return (us == p->umin || us == p->umax) ? FRAC_W_SATURATED : FRAC_OK;
}

int frac_fopid_set_mode(frac_fopid *c, int mode)
{
    if (c == NULL) return FRAC_E_NULL;
    if (!c->ready) return FRAC_E_NOT_INIT;
    if (mode != FRAC_FOPID_AUTO && mode != FRAC_FOPID_MANUAL) return FRAC_E_PARAM;
    if (mode == FRAC_FOPID_MANUAL && c->mode == FRAC_FOPID_AUTO) c->uman = c->last;
    c->mode = mode;
    return FRAC_OK;
}

int frac_fopid_set_manual(frac_fopid *c, frac_real u_man)
{
    if (c == NULL) return FRAC_E_NULL;
    if (!c->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(u_man)) return FRAC_E_NONFINITE;
    c->uman = u_man;
    return FRAC_OK;
}
