/* The named test plant "rigid": J theta'' = tau - b theta' (hil/plant.h). */
#include <math.h>
#include <string.h>
#include "hil/canopen.h"
#include "hil/plant.h"

void hil_plant_params_default(struct hil_plant_params *p)
{
    p->T = 1.2e-3;
    p->J = 2.0;
    p->b = 1.0;
    p->L = 1.0;
    p->substeps = 4;
}

int hil_plant_init(struct hil_plant *pl, const struct hil_plant_params *p)
{
    if (!pl || !p || !(p->T > 0.0) || !isfinite(p->T) || !(p->J > 0.0) || !isfinite(p->J) ||
        !(p->b >= 0.0) || !isfinite(p->b) || !(p->L > 0.0) || !isfinite(p->L) ||
        p->substeps < 1 || p->substeps > 1000)
        return HIL_E_ARG;
    memset(pl, 0, sizeof *pl);
    pl->p = *p;
    return HIL_OK;
}

static double accel(const struct hil_plant *pl, double omega, double tau)
{
    return (tau - pl->p.b * omega) / pl->p.J;
}

/* RK4 over [t0, t0 + h] with torque tau(s) = tau0 + slope * s. */
static void rk4(struct hil_plant *pl, double h, double tau0, double slope, unsigned n)
{
    unsigned i;
    double dt = h / n, s = 0.0;
    for (i = 0; i < n; i++, s += dt) {
        double th = pl->theta, om = pl->omega;
        double k1t = om, k1o = accel(pl, om, tau0 + slope * s);
        double k2t = om + 0.5 * dt * k1o, k2o = accel(pl, k2t, tau0 + slope * (s + 0.5 * dt));
        double k3t = om + 0.5 * dt * k2o, k3o = accel(pl, k3t, tau0 + slope * (s + 0.5 * dt));
        double k4t = om + dt * k3o, k4o = accel(pl, k4t, tau0 + slope * (s + dt));
        pl->theta = th + dt / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t);
        pl->omega = om + dt / 6.0 * (k1o + 2.0 * k2o + 2.0 * k3o + k4o);
    }
    pl->alpha = accel(pl, pl->omega, tau0 + slope * h);
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
        emit(HIL_COB_RIG_TIPPOS, pl->theta, -pl->p.L * pl->omega * pl->omega, out);
        emit(HIL_COB_RIG_TIP, pl->omega, pl->p.L * pl->alpha, out);
    }
    emit(HIL_COB_RIG_MOTOR, pl->theta, pl->omega, out);
    pl->steps++;
    return HIL_OK;
}
