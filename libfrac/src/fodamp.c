/* fodamp.c - seed 002 collocated fractional damping law + prefilter (see frac/fodamp.h). */
#include "frac/fodamp.h"
#include "frac_zpk.h"

static int degree(frac_real q1, frac_real q2)
{
    return q2 != FRAC_R(0.0) ? 2 : (q1 != FRAC_R(0.0) ? 1 : 0);
}

/* integrators k and fractional order r of C = Kc s^(a-m) N/D */
static int split(const frac_fodamp_params *p, unsigned *k, frac_real *r)
{
    double e = (double)p->alpha - (double)p->m;
    int kk = e < 0.0 ? (int)floor(-e) : 0;
    while (degree(p->n1, p->n2) > kk + degree(p->d1, p->d2)) kk++;
    *k = (unsigned)kk;
    *r = (frac_real)(e + kk);
    return FRAC_OK;
}

static frac_fo_params op_params(const frac_fodamp_params *p, frac_real order)
{
    frac_fo_params o = p->op;
    o.order = order;
    o.ts = p->ts;
    return o;
}

static frac_real f_order(const frac_fodamp_params *p)
{
    return p->fa != FRAC_R(0.0) ? p->fbeta : FRAC_R(0.0);
}

size_t frac_fodamp_storage_len(const frac_fodamp_params *p)
{
    frac_fo_params oc, of;
    unsigned k;
    frac_real r;
    if (p == NULL || !(p->alpha > FRAC_R(0.0) && p->alpha < FRAC_R(2.0)) || p->m > 2) return 0;
    split(p, &k, &r);
    oc = op_params(p, r);
    of = op_params(p, f_order(p));
    return frac_fo_storage_len(&oc) + frac_fo_storage_len(&of);
}

/* roots of 1 + q1 s + q2 s^2 through the bilinear map; *lead = leading coefficient */
static int add_roots(frac_zpk_roots *z, frac_real q1_, frac_real q2_, double c, double *gain, double *lead)
{
    double q1 = (double)q1_, q2 = (double)q2_;
    int st = FRAC_OK;
    *lead = 1.0;
    if (q2 != 0.0) {
        double disc = q1 * q1 - 4.0 * q2;
        *lead = q2;
        if (disc >= 0.0) {
            double q = -0.5 * (q1 + (q1 >= 0.0 ? sqrt(disc) : -sqrt(disc)));
            st = frac_zpk_add_bilinear(z, q / q2, 0.0, c, gain);
            if (st == FRAC_OK) st = frac_zpk_add_bilinear(z, 1.0 / q, 0.0, c, gain);
        } else {
            st = frac_zpk_add_bilinear(z, -q1 / (2.0 * q2), sqrt(-disc) / (2.0 * fabs(q2)), c, gain);
        }
    } else if (q1 != 0.0) {
        *lead = q1;
        st = frac_zpk_add_bilinear(z, -1.0 / q1, 0.0, c, gain);
    }
    return st;
}

/*
 * R(s) = Kc N(s)/(s^k D(s)) by the bilinear map s = c (1 - x)/(1 + x):
 * a factor (s - s0) becomes (c - s0)(1 - z0 x)/(1 + x), the integrator
 * 1/s becomes (1/c)(1 + x)/(1 - x), and the (1 + x) left over by the
 * surplus of poles are zeros at z = -1.
 */
static int design_rational(frac_fodamp *f, const frac_fodamp_params *p)
{
    frac_zpk_roots zeros, poles;
    double c = 2.0 / (double)p->ts, gn = 1.0, gd = 1.0, ln, ld;
    int nz, np;
    unsigned i;
    size_t nsec;
    zeros.n = poles.n = 0;
    if (add_roots(&zeros, p->n1, p->n2, c, &gn, &ln) != FRAC_OK) return FRAC_E_NUMERIC;
    if (add_roots(&poles, p->d1, p->d2, c, &gd, &ld) != FRAC_OK) return FRAC_E_NUMERIC;
    for (i = 0; i < f->k; i++)
        if (frac_zpk_add_bilinear(&poles, 0.0, 0.0, c, &gd) != FRAC_OK) return FRAC_E_NUMERIC;
    nz = degree(p->n1, p->n2);
    np = degree(p->d1, p->d2) + (int)f->k;
    for (; nz < np; nz++) frac_zpk_add_real(&zeros, -1.0);
    if (zeros.n == 0 && poles.n == 0) frac_zpk_add_real(&zeros, 0.0); /* R = Kc: one constant section */
    nsec = frac_zpk_nsec(&zeros, &poles);
    if (nsec > FRAC_FODAMP_NSEC) return FRAC_E_NUMERIC;
    if (frac_zpk_to_sos(&zeros, &poles, (double)p->kc * ln * gn / (ld * gd), f->rcoef, nsec) != FRAC_OK)
        return FRAC_E_NUMERIC;
    return frac_sos_init(&f->rat, nsec, f->rcoef, f->rstate);
}

int frac_fodamp_init(frac_fodamp *f, const frac_fodamp_params *p, frac_real *storage, size_t len)
{
    frac_fo_params oc, of;
    size_t nc, nf;
    int st;
    if (f == NULL || p == NULL) return FRAC_E_NULL;
    f->ready = 0;
    if (!FRAC_ISFINITE(p->kc) || p->kc <= FRAC_R(0.0) || !FRAC_ISFINITE(p->n1) || !FRAC_ISFINITE(p->n2)
        || !FRAC_ISFINITE(p->d1) || !FRAC_ISFINITE(p->d2) || !FRAC_ISFINITE(p->fa) || p->fa < FRAC_R(0.0)
        || !FRAC_ISFINITE(p->fb) || p->fb < FRAC_R(0.0))
        return FRAC_E_GAIN;
    if (!(p->alpha > FRAC_R(0.0) && p->alpha < FRAC_R(2.0))) return FRAC_E_ORDER;
    if (!(p->fbeta >= FRAC_R(0.0) && p->fbeta <= FRAC_R(2.0))) return FRAC_E_ORDER;
    if (p->m > 2) return FRAC_E_DIM;
    /* D Hurwitz: all coefficients of d2 s^2 + d1 s + 1 positive (or the lower-degree cases) */
    if (p->d2 < FRAC_R(0.0) || p->d1 < FRAC_R(0.0) || (p->d2 > FRAC_R(0.0) && p->d1 == FRAC_R(0.0))) return FRAC_E_UNSTABLE;
    if (!FRAC_ISFINITE(p->ts) || p->ts <= FRAC_R(0.0)) return FRAC_E_TS;
    split(p, &f->k, &f->r);
    oc = op_params(p, f->r);
    of = op_params(p, f_order(p));
    nc = frac_fo_storage_len(&oc);
    nf = frac_fo_storage_len(&of);
    if (nc + nf > 0 && storage == NULL) return FRAC_E_NULL;
    if (len < nc + nf) return FRAC_E_STORAGE;
    st = frac_fo_init(&f->opc, &oc, nc > 0 ? storage : NULL, nc);
    if (st != FRAC_OK) return st;
    st = frac_fo_init(&f->opf, &of, nf > 0 ? storage + nc : NULL, nf);
    if (st != FRAC_OK) return st;
    st = design_rational(f, p);
    if (st != FRAC_OK) return st;
    f->fa = p->fa;
    /* prefilter lag 1/(1 + fb s), bilinear: y = la y + lb (w + w_prev) */
    f->la = (FRAC_R(2.0) * p->fb - p->ts) / (FRAC_R(2.0) * p->fb + p->ts);
    f->lb = p->ts / (FRAC_R(2.0) * p->fb + p->ts);
    f->ts = p->ts;
    f->ready = 1;
    return frac_fodamp_reset(f);
}

int frac_fodamp_reset(frac_fodamp *f)
{
    if (f == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    frac_fo_reset(&f->opc);
    frac_fo_reset(&f->opf);
    frac_sos_reset(&f->rat);
    f->fy = f->fw = FRAC_R(0.0);
    f->last = FRAC_R(0.0);
    return FRAC_OK;
}

int frac_fodamp_step(frac_fodamp *f, frac_real ref, frac_real meas, frac_real *u)
{
    frac_real q, cu, d = FRAC_R(0.0), w;
    if (f == NULL || u == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(ref) || !FRAC_ISFINITE(meas)) {
        *u = f->last;
        return FRAC_E_NONFINITE;
    }
    /* C(s) meas = R(s) s^r meas */
    frac_fo_step(&f->opc, meas, &q);
    frac_sos_step(&f->rat, q, &cu);
    /* F(s) ref */
    if (f->fa != FRAC_R(0.0)) frac_fo_step(&f->opf, ref, &d);
    w = ref + f->fa * d;
    f->fy = f->la * f->fy + f->lb * (w + f->fw);
    f->fw = w;
    f->last = f->fy - cu;
    *u = f->last;
    return FRAC_OK;
}

int frac_fodamp_freqresp_c(const frac_fodamp *f, frac_real w, frac_real *re, frac_real *im)
{
    frac_real ar, ai, br, bi;
    int st;
    if (f == NULL || re == NULL || im == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(w) || w <= FRAC_R(0.0)) return FRAC_E_PARAM;
    st = frac_fo_freqresp(&f->opc, w, &ar, &ai);
    if (st == FRAC_OK) st = frac_sos_freqresp(f->rat.coeffs, f->rat.nsec, w * f->ts, &br, &bi);
    if (st != FRAC_OK) return st;
    *re = ar * br - ai * bi;
    *im = ar * bi + ai * br;
    return FRAC_OK;
}

int frac_fodamp_freqresp_f(const frac_fodamp *f, frac_real w, frac_real *re, frac_real *im)
{
    double dr, di, th, nr, ni, lr, li, den;
    frac_real ar = FRAC_R(0.0), ai = FRAC_R(0.0);
    int st = FRAC_OK;
    if (f == NULL || re == NULL || im == NULL) return FRAC_E_NULL;
    if (!f->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(w) || w <= FRAC_R(0.0)) return FRAC_E_PARAM;
    if (f->fa != FRAC_R(0.0)) st = frac_fo_freqresp(&f->opf, w, &ar, &ai);
    if (st != FRAC_OK) return st;
    nr = 1.0 + (double)f->fa * (double)ar;
    ni = (double)f->fa * (double)ai;
    /* lag lb (1 + x)/(1 - la x), x = e^{-j w Ts} */
    th = (double)w * (double)f->ts;
    lr = (double)f->lb * (1.0 + cos(th));
    li = -(double)f->lb * sin(th);
    dr = 1.0 - (double)f->la * cos(th);
    di = (double)f->la * sin(th);
    den = dr * dr + di * di;
    {
        double qr = (lr * dr + li * di) / den, qi = (li * dr - lr * di) / den;
        *re = (frac_real)(nr * qr - ni * qi);
        *im = (frac_real)(nr * qi + ni * qr);
    }
    return FRAC_OK;
}
