/*
 * traj.c - sin^2 PTP trajectory, seed 004 (4.1)-(4.7) with the notes 004b
 * section 2.1 corrections (see frac/traj.h).
 */
#include "frac/traj.h"

int frac_traj_init(frac_traj *tr, const frac_traj_params *p)
{
    frac_real s_e, dq_m, ddq_m, t_a, t_e;
    if (tr == NULL || p == NULL) return FRAC_E_NULL;
    tr->ready = 0;
    if (!FRAC_ISFINITE(p->q_s) || !FRAC_ISFINITE(p->q_e) || !FRAC_ISFINITE(p->dq_max) ||
        !FRAC_ISFINITE(p->ddq_max) || !FRAC_ISFINITE(p->t_start) || !FRAC_ISFINITE(p->duration))
        return FRAC_E_PARAM;
    if (!(p->dq_max > FRAC_R(0.0)) || !(p->ddq_max > FRAC_R(0.0))) return FRAC_E_PARAM;
    s_e = FRAC_FABS(p->q_e - p->q_s);
    dq_m = p->dq_max;
    ddq_m = p->ddq_max;
    t_a = FRAC_R(2.0) * dq_m / ddq_m; /* (4.1) */
    if (s_e < dq_m * t_a) {
        /* no cruise phase: the peak velocity is reached at half distance */
        dq_m = FRAC_SQRT(s_e * ddq_m / FRAC_R(2.0));
        t_a = FRAC_R(2.0) * dq_m / ddq_m;
    }
    t_e = (dq_m > FRAC_R(0.0) ? s_e / dq_m : FRAC_R(0.0)) + t_a; /* (4.3) */
    if (p->duration > FRAC_R(0.0)) {
        frac_real disc;
        if (p->duration < t_e * (FRAC_R(1.0) - FRAC_R(8.0) * FRAC_REAL_EPSILON)) return FRAC_E_PARAM;
        if (p->duration > t_e) {
            t_e = p->duration;
            /* (4.4): keep ddq_m, lower dq_m; disc >= 0 since t_e >= sqrt(8 s_e/ddq_m) */
            disc = ddq_m * ddq_m * t_e * t_e / FRAC_R(4.0) - FRAC_R(2.0) * ddq_m * s_e;
            if (disc < FRAC_R(0.0)) disc = FRAC_R(0.0);
            dq_m = FRAC_R(0.5) * (ddq_m * t_e / FRAC_R(2.0) - FRAC_SQRT(disc));
            t_a = FRAC_R(2.0) * dq_m / ddq_m; /* (4.1) again */
        }
    }
    tr->q_s = p->q_s;
    tr->s_e = s_e;
    tr->sign = p->q_e >= p->q_s ? FRAC_R(1.0) : FRAC_R(-1.0);
    tr->dq_m = dq_m;
    tr->ddq_m = ddq_m;
    tr->t_s = p->t_start;
    tr->t_a = t_a;
    tr->t_e = t_e;
    tr->t_b = t_e - t_a;
    tr->ready = 1;
    return FRAC_OK;
}

int frac_traj_eval(const frac_traj *tr, frac_real t, frac_real d[5])
{
    frac_real tau, w, a, q, dq, ddq, jerk, snap;
    int i;
    if (tr == NULL || d == NULL) return FRAC_E_NULL;
    if (!tr->ready) return FRAC_E_NOT_INIT;
    if (!FRAC_ISFINITE(t)) return FRAC_E_NONFINITE;
    tau = t - tr->t_s;
    a = tr->ddq_m;
    w = FRAC_R(2.0) * FRAC_PI / tr->t_a; /* 2 pi / t_a */
    if (tau < FRAC_R(0.0) || tr->t_a <= FRAC_R(0.0)) {
        q = tau < FRAC_R(0.0) ? FRAC_R(0.0) : tr->s_e;
        dq = ddq = jerk = snap = FRAC_R(0.0);
    } else if (tau < tr->t_a) {
        /* acceleration, corrected (4.5) */
        ddq = a * FRAC_R(0.5) * (FRAC_R(1.0) - FRAC_COS(w * tau)); /* = a sin^2(pi tau/t_a) */
        dq = a * (tau / FRAC_R(2.0) - FRAC_SIN(w * tau) / (FRAC_R(2.0) * w));
        q = a * (tau * tau / FRAC_R(4.0) + (FRAC_COS(w * tau) - FRAC_R(1.0)) / (FRAC_R(2.0) * w * w));
        jerk = a * FRAC_R(0.5) * w * FRAC_SIN(w * tau);
        snap = a * FRAC_R(0.5) * w * w * FRAC_COS(w * tau);
    } else if (tau < tr->t_b) {
        /* cruise (4.6) */
        q = tr->dq_m * (tau - tr->t_a / FRAC_R(2.0));
        dq = tr->dq_m;
        ddq = jerk = snap = FRAC_R(0.0);
    } else if (tau < tr->t_e) {
        /* braking, (4.7) with the corrected argument pi (tau - t_b)/t_a */
        frac_real tb = tau - tr->t_b, ta = tr->t_a, te = tr->t_e;
        ddq = -a * FRAC_R(0.5) * (FRAC_R(1.0) - FRAC_COS(w * tb));
        dq = tr->dq_m - a * (tb / FRAC_R(2.0) - FRAC_SIN(w * tb) / (FRAC_R(2.0) * w));
        q = FRAC_R(0.5) * a * (te * (tau + ta) - FRAC_R(0.5) * (tau * tau + te * te + FRAC_R(2.0) * ta * ta)
                               + (FRAC_R(1.0) - FRAC_COS(w * tb)) / (w * w));
        jerk = -a * FRAC_R(0.5) * w * FRAC_SIN(w * tb);
        snap = -a * FRAC_R(0.5) * w * w * FRAC_COS(w * tb);
    } else {
        q = tr->s_e;
        dq = ddq = jerk = snap = FRAC_R(0.0);
    }
    d[0] = q;
    d[1] = dq;
    d[2] = ddq;
    d[3] = jerk;
    d[4] = snap;
    for (i = 0; i < 5; i++) d[i] *= tr->sign;
    d[0] += tr->q_s;
    return FRAC_OK;
}

int frac_traj_times(const frac_traj *tr, frac_real *t_a, frac_real *t_b, frac_real *t_e)
{
    if (tr == NULL || t_a == NULL || t_b == NULL || t_e == NULL) return FRAC_E_NULL;
    if (!tr->ready) return FRAC_E_NOT_INIT;
    *t_a = tr->t_a;
    *t_b = tr->t_b;
    *t_e = tr->t_e;
    return FRAC_OK;
}
