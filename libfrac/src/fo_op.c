/* fo_op.c - common front of the s^r realizations (see frac/fo_op.h). */
#include "frac/fo_op.h"

size_t frac_fo_storage_len(const frac_fo_params *p)
{
    if (p == NULL || p->order == FRAC_R(0.0)) return 0;
    switch (p->method) {
    case FRAC_FO_GL: return FRAC_GL_STORAGE(p->memory);
    case FRAC_FO_OUSTALOUP: return FRAC_OUSTALOUP_STORAGE(p->n, 0);
    case FRAC_FO_OUSTALOUP_REFINED: return FRAC_OUSTALOUP_STORAGE(p->n, 1);
    case FRAC_FO_CFE_TUSTIN:
    case FRAC_FO_CFE_ALALAOUI: return FRAC_CFE_STORAGE(p->n);
    default: return 0;
    }
}

int frac_fo_init(frac_fo *op, const frac_fo_params *p, frac_real *storage, size_t len)
{
    frac_oustaloup ou;
    frac_oustaloup_params op_;
    frac_cfe cfe;
    frac_cfe_params cp;
    int st, kind;
    if (op == NULL || p == NULL) return FRAC_E_NULL;
    op->ready = 0;
    op->kind = 0;
    if (p->method < FRAC_FO_GL || p->method > FRAC_FO_CFE_ALALAOUI) return FRAC_E_PARAM;
    if (!FRAC_ISFINITE(p->order)) return FRAC_E_ORDER;
    if (!FRAC_ISFINITE(p->ts) || p->ts <= FRAC_R(0.0)) return FRAC_E_TS;
    op->p = *p;
    op->last = FRAC_R(0.0);
    if (p->order == FRAC_R(0.0)) {
        op->ready = 1;
        return FRAC_OK;
    }
    switch (p->method) { /* each init validates its parameters, then the storage */
    case FRAC_FO_GL:
        st = frac_gl_init(&op->gl, p->order, p->ts, p->memory, storage, len);
        kind = 1;
        break;
    case FRAC_FO_OUSTALOUP:
    case FRAC_FO_OUSTALOUP_REFINED:
        op_.order = p->order;
        op_.wb = p->wb;
        op_.wh = p->wh;
        op_.ts = p->ts;
        op_.n = p->n;
        op_.refined = p->method == FRAC_FO_OUSTALOUP_REFINED;
        st = frac_oustaloup_init(&ou, &op_, storage, len);
        op->sos = ou.sos;
        kind = 2;
        break;
    default:
        cp.order = p->order;
        cp.ts = p->ts;
        cp.n = p->n;
        cp.rule = p->method == FRAC_FO_CFE_TUSTIN ? FRAC_CFE_TUSTIN : FRAC_CFE_ALALAOUI;
        st = frac_cfe_init(&cfe, &cp, storage, len);
        op->sos = cfe.sos;
        kind = 2;
        break;
    }
    if (st != FRAC_OK) return st;
    op->kind = kind;
    op->ready = 1;
    return FRAC_OK;
}

int frac_fo_step(frac_fo *op, frac_real x, frac_real *y)
{
    if (op == NULL) return FRAC_E_NULL;
    /* kind is nonzero only after a successful init; the realization checks y and x */
    if (op->kind == 2) return frac_sos_step(&op->sos, x, y);
    if (op->kind == 1) return frac_gl_step(&op->gl, x, y);
    if (y == NULL) return FRAC_E_NULL;
    if (!op->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(x)) {
        *y = op->last;
        return FRAC_E_NONFINITE;
    }
    op->last = x;
    *y = x;
    return FRAC_OK;
}

int frac_fo_reset(frac_fo *op)
{
    if (op == NULL) return FRAC_E_NULL;
    if (!op->ready) return FRAC_E_NOT_INIT;
    op->last = FRAC_R(0.0);
    if (op->kind == 1) return frac_gl_set_history(&op->gl, FRAC_R(0.0));
    if (op->kind == 2) return frac_sos_reset(&op->sos);
    return FRAC_OK;
}

int frac_fo_set_steady(frac_fo *op, frac_real x)
{
    int st = FRAC_OK;
    if (op == NULL) return FRAC_E_NULL;
    if (!op->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(x)) return FRAC_E_NONFINITE;
    if (op->kind == 1) {
        st = frac_gl_set_history(&op->gl, x);
    } else if (op->kind == 2) {
        st = frac_sos_set_steady(&op->sos, x);
    } else {
        op->last = x;
    }
    return st;
}

int frac_fo_free_response(const frac_fo *op, frac_real *y0)
{
    if (op == NULL || y0 == NULL) return FRAC_E_NULL;
    if (!op->ready) return FRAC_E_NOT_INIT;
    if (op->kind == 1) return frac_gl_free_response(&op->gl, y0);
    if (op->kind == 2) return frac_sos_free_response(&op->sos, y0);
    *y0 = FRAC_R(0.0);
    return FRAC_OK;
}

frac_real frac_fo_feedthrough(const frac_fo *op)
{
    if (op == NULL || !op->ready) return FRAC_R(0.0);
    if (op->kind == 1) return frac_gl_feedthrough(&op->gl);
    if (op->kind == 2) return frac_sos_feedthrough(&op->sos);
    return FRAC_R(1.0);
}

frac_real frac_fo_output(const frac_fo *op)
{
    if (op == NULL || !op->ready) return FRAC_R(0.0);
    if (op->kind == 1) return op->gl.last;
    if (op->kind == 2) return op->sos.last;
    return op->last;
}

int frac_fo_freqresp(const frac_fo *op, frac_real w, frac_real *re, frac_real *im)
{
    if (op == NULL || re == NULL || im == NULL) return FRAC_E_NULL;
    if (!op->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(w) || w < FRAC_R(0.0)) return FRAC_E_PARAM;
    if (op->kind == 1) return frac_gl_freqresp(&op->gl, w, re, im);
    if (op->kind == 2) return frac_sos_freqresp(op->sos.coeffs, op->sos.nsec, w * op->p.ts, re, im);
    *re = FRAC_R(1.0);
    *im = FRAC_R(0.0);
    return FRAC_OK;
}
