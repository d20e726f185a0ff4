/* The rig's plants, "rigid" and "twomass" (hil/plant.h). */
#include <math.h>
#include <string.h>
#include "hil/canopen.h"
#include "hil/plant.h"

void hil_plant_params_default(struct hil_plant_params *p)
{
    memset(p, 0, sizeof *p);
    p->model = HIL_PLANT_RIGID;
    p->T = 1.2e-3;
    p->J = 2.0;
    p->b = 1.0;
    p->I_M = 160.0 * 160.0 * 2.29e-4;
    p->I_L = 1.69e-4 + 0.7221;
    p->c_s = 5.0e4;
    p->friction.model = FRAC_FRICTION_LINEAR;
    p->friction.k = 60.0;
    p->friction.b1 = 3.04;
    p->friction.b0 = 7.684;
    p->friction.v_s = 0.1;
    p->friction.delta = 2.0;
    p->L = 1.0;
    p->substeps = 4;
    p->kv_order = 0.5;
    p->kv_memory = 200;
}

static int pos(double x) { return isfinite(x) && x > 0.0; }

int hil_plant_init(struct hil_plant *pl, const struct hil_plant_params *p)
{
    frac_friction fr;
    if (!pl || !p || !pos(p->T) || !pos(p->L) || p->substeps < 1 || p->substeps > 1000)
        return HIL_E_ARG;
    if (p->model == HIL_PLANT_RIGID) {
        if (!pos(p->J) || !(p->b >= 0.0) || !isfinite(p->b))
            return HIL_E_ARG;
    } else if (p->model == HIL_PLANT_TWOMASS) {
        if (!pos(p->I_M) || !pos(p->I_L) || !pos(p->c_s) || frac_friction_init(&fr, &p->friction) != FRAC_OK ||
            !(p->backlash >= 0.0) || !isfinite(p->backlash) || !(p->extra_inertia >= 0.0) ||
            !isfinite(p->extra_inertia) || (p->extra_inertia > 0.0 && (!pos(p->extra_hz) || !(p->extra_zeta >= 0.0) ||
                                                                         !isfinite(p->extra_zeta))))
            return HIL_E_ARG;
    } else {
        return HIL_E_ARG;
    }
    if (p->model == HIL_PLANT_TWOMASS && p->kv_damping != 0.0 &&
        (!(p->kv_damping > 0.0) || !isfinite(p->kv_damping) || !(p->kv_order > 0.0 && p->kv_order <= 1.0) ||
         p->kv_memory < 1 || p->kv_memory > HIL_PLANT_KV_MAX))
        return HIL_E_ARG;
    memset(pl, 0, sizeof *pl);
    pl->p = *p;
    if (p->model == HIL_PLANT_TWOMASS) {
        pl->fric = fr;
        if (p->kv_damping > 0.0 &&
            frac_gl_init(&pl->kv, (frac_real)p->kv_order, (frac_real)(0.5 * p->T / p->substeps), p->kv_memory,
                         pl->kv_store, FRAC_GL_STORAGE(HIL_PLANT_KV_MAX)) != FRAC_OK)
            return HIL_E_ARG;
    }
    return HIL_OK;
}

/* State x = [theta, omega, psi, psi', q_e, q_e'] (rigid: psi == theta,
 * q_e == 0); dx = f(x, tau). */
static void deriv(struct hil_plant *pl, const double *x, double tau, double *dx)
{
    if (pl->p.model == HIL_PLANT_RIGID) {
        double a = (tau - pl->p.b * x[1]) / pl->p.J;
        dx[0] = x[1];
        dx[1] = a;
        dx[2] = x[1];
        dx[3] = a;
        dx[4] = dx[5] = 0.0;
    } else {
        frac_real tf = 0;
        double delta = x[0] - x[2], h = 0.5 * pl->p.backlash, spring, extra = 0.0, k_e, d_e;
        double dz = delta > h ? delta - h : (delta < -h ? delta + h : 0.0);
        spring = pl->p.c_s * dz + pl->kv_torque;
        frac_friction_eval(&pl->fric, (frac_real)x[1], &tf);
        if (pl->p.extra_inertia > 0.0) {
            double w = 2.0 * M_PI * pl->p.extra_hz;
            k_e = pl->p.extra_inertia * w * w;
            d_e = 2.0 * pl->p.extra_zeta * sqrt(k_e * pl->p.extra_inertia);
            extra = k_e * x[4] + d_e * x[5];
        }
        dx[0] = x[1];
        dx[1] = (tau - spring - (double)tf) / pl->p.I_M;
        dx[2] = x[3];
        dx[3] = (spring + extra) / pl->p.I_L;
        dx[4] = x[5];
        dx[5] = pl->p.extra_inertia > 0.0 ? -extra / pl->p.extra_inertia - dx[3] : 0.0;
    }
}

/* RK4 over [0, h] with torque tau(s) = tau0 + slope * s. */
static void rk4(struct hil_plant *pl, double h, double tau0, double slope, unsigned n)
{
    double *x = pl->x, y[6], k1[6], k2[6], k3[6], k4[6];
    double dt = h / n, s = 0.0;
    unsigned i;
    int j;
    for (i = 0; i < n; i++, s += dt) {
        if (pl->p.model == HIL_PLANT_TWOMASS && pl->p.kv_damping > 0.0) {
            frac_real y = 0;
            if (frac_gl_step(&pl->kv, (frac_real)(x[0] - x[2]), &y) == FRAC_OK)
                pl->kv_torque = pl->p.kv_damping * (double)y;
        }
        deriv(pl, x, tau0 + slope * s, k1);
        for (j = 0; j < 6; j++)
            y[j] = x[j] + 0.5 * dt * k1[j];
        deriv(pl, y, tau0 + slope * (s + 0.5 * dt), k2);
        for (j = 0; j < 6; j++)
            y[j] = x[j] + 0.5 * dt * k2[j];
        deriv(pl, y, tau0 + slope * (s + 0.5 * dt), k3);
        for (j = 0; j < 6; j++)
            y[j] = x[j] + dt * k3[j];
        deriv(pl, y, tau0 + slope * (s + dt), k4);
        for (j = 0; j < 6; j++)
            x[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
    }
    deriv(pl, x, tau0 + slope * h, k1);
    pl->theta = x[0];
    pl->omega = x[1];
    pl->psi = x[2] + x[4];
    pl->psi_d = x[3] + x[5];
    pl->psi_dd = k1[3] + k1[5];
}

static void emit(uint32_t cob, double a, double b, struct hil_out *out)
{
    struct hil_can_frame f;
    if (hil_co_rig_encode(&f, cob, a, b) == HIL_OK)
        hil_out_push(out, &f);
}

int hil_plant_on_frame(struct hil_plant *pl, const struct hil_can_frame *f, struct hil_out *out)
{
    int st, half;
    double tau0, tau1, h, slope;
    if (!pl || !f || !out)
        return HIL_E_ARG;
    st = hil_rx_screen(&pl->rx, f);
    if (st != HIL_OK)
        return st;
    if (f->id != HIL_COB_RIG_TORQUE) {
        pl->rx.other++;
        return HIL_E_UNKNOWN_ID;
    }
    if (hil_co_rig_decode(f, HIL_COB_RIG_TORQUE, &tau0, &tau1) != HIL_OK) {
        pl->rx.bad_value++;
        return HIL_E_RANGE;
    }
    pl->rx.accepted++;
    h = 0.5 * pl->p.T;
    slope = (tau1 - tau0) / pl->p.T;
    for (half = 0; half < 2; half++) {
        rk4(pl, h, tau0 + slope * h * half, slope, pl->p.substeps);
        pl->t += h;
        emit(HIL_COB_RIG_TIPPOS, pl->psi, -pl->p.L * pl->psi_d * pl->psi_d, out);
        emit(HIL_COB_RIG_TIP, pl->psi_d, pl->p.L * pl->psi_dd, out);
    }
    emit(HIL_COB_RIG_MOTOR, pl->theta, pl->omega, out);
    pl->steps++;
    return HIL_OK;
}
