/*
 * friction.c - linear, asymmetric and Stribeck friction, seed 004
 * (5.2)-(5.4) with sgn -> tanh(k v) (see frac/friction.h).
 */
#include "frac/friction.h"

#define FIN(x) FRAC_ISFINITE(x)

int frac_friction_init(frac_friction *f, const frac_friction_params *p)
{
    if (f == NULL || p == NULL) return FRAC_E_NULL;
    f->ready = 0;
    if (!FIN(p->k) || !(p->k > FRAC_R(0.0))) return FRAC_E_PARAM;
    switch (p->model) {
    case FRAC_FRICTION_LINEAR:
        if (!FIN(p->b1) || !FIN(p->b0)) return FRAC_E_PARAM;
        break;
    case FRAC_FRICTION_ASYMMETRIC:
        if (!FIN(p->b1n) || !FIN(p->b1p) || !FIN(p->b0n) || !FIN(p->b0p)) return FRAC_E_PARAM;
        break;
    case FRAC_FRICTION_STRIBECK:
        if (!FIN(p->b1s) || !FIN(p->b2s) || !FIN(p->b3s) || !FIN(p->v_s) || !FIN(p->delta))
            return FRAC_E_PARAM;
        if (!(p->v_s > FRAC_R(0.0)) || !(p->delta > FRAC_R(0.0))) return FRAC_E_PARAM;
        break;
    default:
        return FRAC_E_PARAM;
    }
    f->p = *p;
    f->last = FRAC_R(0.0);
    f->ready = 1;
    return FRAC_OK;
}

int frac_friction_eval(frac_friction *f, frac_real v, frac_real *tau)
{
    const frac_friction_params *p;
    frac_real sg, t;
    if (f == NULL || tau == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    if (!FIN(v)) {
        *tau = f->last;
        return FRAC_E_NONFINITE;
    }
    p = &f->p;
    sg = FRAC_TANH(p->k * v); /* smooth sgn(v) */
    if (p->model == FRAC_FRICTION_LINEAR) {
        t = p->b1 * v + p->b0 * sg; /* (5.2) */
    } else if (p->model == FRAC_FRICTION_ASYMMETRIC) {
        /* (5.3) with the side selectors smoothed as a partition of unity */
        frac_real gp = FRAC_R(0.5) * (FRAC_R(1.0) + sg), gn = FRAC_R(1.0) - gp;
        t = (p->b1n * gn + p->b1p * gp) * v + (p->b0n * gn + p->b0p * gp) * sg;
    } else {
        /* (5.4) */
        frac_real r = FRAC_POW(FRAC_FABS(v / p->v_s), p->delta);
        t = (p->b1s + (p->b2s - p->b1s) * FRAC_EXP(-r)) * sg + p->b3s * v;
    }
    f->last = t;
    *tau = t;
    return FRAC_OK;
}
