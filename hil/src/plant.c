/* The rig's plants, "rigid", "twomass" and "arm" (hil/plant.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "frac/ptable.h"
#include "hil/canopen.h"
#include "hil/file.h"
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

static int refuse(struct hil_plant *pl, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(pl->err, sizeof pl->err, fmt, ap);
    va_end(ap);
    return HIL_E_ARG;
}

/* Entry `name` of exactly rows x cols into dst (double); the message names
 * the entry and its dimensions when they differ. */
static int table_get(struct hil_plant *pl, const frac_ptable *t, const char *name, unsigned rows, unsigned cols,
                     frac_real *tmp, double *dst)
{
    frac_ptable_entry e;
    unsigned long i;
    if (frac_ptable_find(t, name, &e) != FRAC_OK)
        return refuse(pl, "plant.table %s: entry '%s' missing", pl->p.table, name);
    if (e.rows != rows || e.cols != cols)
        return refuse(pl, "plant.table %s: entry '%s' is %u x %u, expected %u x %u", pl->p.table, name, e.rows,
                      e.cols, rows, cols);
    if (frac_ptable_get(t, name, rows, cols, tmp) != FRAC_OK)
        return refuse(pl, "plant.table %s: entry '%s' unreadable", pl->p.table, name);
    for (i = 0; i < (unsigned long)rows * cols; i++)
        dst[i] = (double)tmp[i];
    return HIL_OK;
}

/* The asub steps of a half cycle composed (hil/plant.h): from Ad (column-
 * major), Bd and Bd1, the rows C_2 Ad^k (k <= asub: the last gives the end
 * velocity of the last step), the columns Ad^k Bd and scalars C_2 Ad^k Bd
 * (k < asub), Am = Ad^asub, the ramp's column sum_k Ad^k Bd1 and its
 * velocity terms sum_{i<k} C_2 Ad^i Bd1 (k <= asub). P, Q: n x n scratch. */
static void compose(struct hil_plant *pl, double *P, double *Q)
{
    const unsigned n = pl->an, m = pl->asub;
    unsigned i, j, l, k;
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++)
            P[j * n + i] = i == j ? 1.0 : 0.0;
    for (i = 0; i < n; i++)
        pl->bramp[i] = 0.0;
    for (k = 0; k <= m; k++) {
        double *r = pl->vrow + (size_t)k * n, *b = pl->bcol + (size_t)k * n, c1 = 0.0;
        for (j = 0; j < n; j++) {
            double a = 0.0;
            for (i = 0; i < n; i++)
                a += pl->C[n + i] * P[j * n + i];
            r[j] = a;
        }
        if (k == m)
            break;
        for (i = 0; i < n; i++)
            b[i] = 0.0;
        for (j = 0; j < n; j++)
            for (i = 0; i < n; i++) {
                b[i] += P[j * n + i] * pl->Bd[j];
                pl->bramp[i] += P[j * n + i] * pl->Bd1[j];
            }
        pl->vb[k] = 0.0;
        for (j = 0; j < n; j++) {
            pl->vb[k] += r[j] * pl->Bd[j];
            c1 += r[j] * pl->Bd1[j];
        }
        pl->vb1[k + 1] = pl->vb1[k] + c1;
        for (j = 0; j < n; j++) /* Q = Ad P */
            for (i = 0; i < n; i++) {
                double a = 0.0;
                for (l = 0; l < n; l++)
                    a += pl->Ad[l * n + i] * P[j * n + l];
                Q[j * n + i] = a;
            }
        memcpy(P, Q, (size_t)n * n * sizeof *P);
    }
    memcpy(pl->Am, P, (size_t)n * n * sizeof *P);
}

/* Loads the arm plant table (hil/plant.h, docs/hil.md) into pl. */
static int load_arm(struct hil_plant *pl)
{
    unsigned long size = 0;
    unsigned char *bytes;
    frac_ptable t;
    frac_real *tmp;
    double v[3] = {0.0, 0.0, 0.0}, *Ac, *Bc;
    unsigned n, i, j;
    double half = 0.5 * pl->p.T, m;
    int st;
    if (!pl->p.table[0])
        return refuse(pl, "plant = arm needs plant.table (fracdesign model arm --full --save-plant FILE)");
    bytes = hil_read_file(pl->p.table, HIL_PLANT_TABLE_MAX, &size);
    if (!bytes)
        return refuse(pl, "plant.table %s: cannot read the file (missing, unreadable or larger than %u bytes)",
                      pl->p.table, HIL_PLANT_TABLE_MAX);
    st = frac_ptable_open(&t, bytes, size);
    if (st != FRAC_OK) {
        char ename[FRAC_PTABLE_NAME_LEN + 1] = "";
        if (t.fail_entry >= 0 &&
            FRAC_PTABLE_HEADER_SIZE + (unsigned long)(t.fail_entry + 1) * FRAC_PTABLE_ENTRY_SIZE <= size)
            memcpy(ename, bytes + FRAC_PTABLE_HEADER_SIZE + (unsigned long)t.fail_entry * FRAC_PTABLE_ENTRY_SIZE,
                   FRAC_PTABLE_NAME_LEN);
        ename[FRAC_PTABLE_NAME_LEN] = '\0';
        free(bytes);
        if (t.fail_entry >= 0)
            return refuse(pl, "plant.table %s: %s (field %s of entry %ld '%s')", pl->p.table, frac_status_str(st),
                          t.fail_field, t.fail_entry, ename);
        return refuse(pl, "plant.table %s: %s (field %s)", pl->p.table, frac_status_str(st), t.fail_field);
    }
    /* frac_real scratch, also the double scratch of compose (sizeof(double) >= sizeof(frac_real)) */
    tmp = (frac_real *)malloc(sizeof(double) * HIL_PLANT_ARM_NMAX * HIL_PLANT_ARM_NMAX);
    /* Ac (n x n) followed by Bc (n) */
    Ac = (double *)malloc(sizeof(double) * (HIL_PLANT_ARM_NMAX * HIL_PLANT_ARM_NMAX + HIL_PLANT_ARM_NMAX));
    Bc = Ac ? Ac + HIL_PLANT_ARM_NMAX * HIL_PLANT_ARM_NMAX : NULL;
    st = !tmp || !Ac ? refuse(pl, "plant.table %s: out of memory", pl->p.table) : HIL_OK;
    /* plant_dims (n, N) of the seed arm, or (n, N, P) with P = 0, 2 or 4 payload states after the
     * beam's (fracdesign model --arm: the tip payload on its mount) */
    if (st == HIL_OK) {
        frac_ptable_entry e;
        v[2] = 0.0;
        if (frac_ptable_find(&t, "plant_dims", &e) == FRAC_OK && e.rows == 1 && e.cols == 3)
            st = table_get(pl, &t, "plant_dims", 1, 3, tmp, v);
        else
            st = table_get(pl, &t, "plant_dims", 1, 2, tmp, v);
    }
    if (st == HIL_OK && (v[0] != floor(v[0]) || v[1] != floor(v[1]) || v[1] < 2 ||
                         !(v[2] == 0.0 || v[2] == 2.0 || v[2] == 4.0) || v[0] != 4.0 + 4.0 * v[1] + v[2] ||
                         v[0] > HIL_PLANT_ARM_NMAX))
        st = refuse(pl, "plant.table %s: plant_dims (%g, %g, %g): want n = 4 + 4 N + P, N >= 2, P in {0, 2, 4}, n <= %d",
                    pl->p.table, v[0], v[1], v[2], HIL_PLANT_ARM_NMAX);
    n = st == HIL_OK ? (unsigned)v[0] : 0;
    if (st == HIL_OK && (st = table_get(pl, &t, "h", 1, 1, tmp, v)) == HIL_OK) {
        m = floor(half / v[0] + 0.5);
        if (!(v[0] > 0.0) || m < 1.0 || fabs(m * v[0] - half) > 1e-9 * half)
            st = refuse(pl, "plant.table %s: h = %g s does not divide the half cycle T/2 = %g s", pl->p.table, v[0],
                        half);
        else if (m > HIL_PLANT_ARM_SUBMAX)
            st = refuse(pl, "plant.table %s: h = %g s: more than %d steps per half cycle T/2 = %g s", pl->p.table,
                        v[0], HIL_PLANT_ARM_SUBMAX, half);
        pl->ah = v[0];
        pl->asub = (unsigned)m;
    }
    if (st == HIL_OK && (st = table_get(pl, &t, "Ad", n, n, tmp, Ac)) == HIL_OK)
        for (i = 0; i < n; i++) /* column-major: the step is a sum of columns */
            for (j = 0; j < n; j++)
                pl->Ad[j * n + i] = Ac[i * n + j];
    if (st == HIL_OK)
        st = table_get(pl, &t, "Bd", n, 1, tmp, pl->Bd);
    /* Bd1 (the ramp's column) is optional: tables written before it hold the
     * torque at its mid-step value (hil/plant.h) */
    memset(pl->Bd1, 0, sizeof pl->Bd1);
    memset(pl->vb1, 0, sizeof pl->vb1);
    if (st == HIL_OK) {
        frac_ptable_entry e;
        if (frac_ptable_find(&t, "Bd1", &e) == FRAC_OK)
            st = table_get(pl, &t, "Bd1", n, 1, tmp, pl->Bd1);
    }
    if (st == HIL_OK)
        st = table_get(pl, &t, "C", 4, n, tmp, pl->C);
    if (st == HIL_OK)
        st = table_get(pl, &t, "Ac", n, n, tmp, Ac);
    if (st == HIL_OK)
        st = table_get(pl, &t, "Bc", n, 1, tmp, Bc);
    if (st == HIL_OK) {
        pl->an = n;
        pl->aN = (unsigned)v[1];
        pl->acc_b = 0.0;
        for (j = 0; j < n; j++) {
            double a = 0.0;
            for (i = 0; i < n; i++)
                a += pl->C[3 * n + i] * Ac[i * n + j];
            pl->acc_row[j] = a;
            pl->acc_b += pl->C[3 * n + j] * Bc[j];
        }
        compose(pl, Ac, (double *)tmp);
    }
    free(tmp);
    free(Ac);
    free(bytes);
    return st;
}

int hil_plant_init(struct hil_plant *pl, const struct hil_plant_params *p)
{
    frac_friction fr;
    int st;
    if (pl)
        pl->err[0] = '\0';
    if (!pl || !p || !pos(p->T) || !pos(p->L) || p->substeps < 1 || p->substeps > 1000)
        return HIL_E_ARG;
    if (p->model == HIL_PLANT_ARM) {
        const char *what = p->backlash != 0.0        ? "plant.backlash"
                           : p->extra_inertia != 0.0 ? "plant.extra_inertia (extra mode)"
                           : p->kv_damping != 0.0    ? "plant.kv_damping (Kelvin-Voigt)"
                                                     : NULL;
        if (what)
            return refuse(pl, "plant = arm does not model %s (a twomass effect); set it to 0 or use plant = twomass",
                          what);
        if (frac_friction_init(&fr, &p->friction) != FRAC_OK)
            return refuse(pl, "plant = arm: the friction parameters (plant.friction, plant.fric_*) are invalid");
        if (!memchr(p->table, '\0', sizeof p->table))
            return refuse(pl, "plant.table: path too long");
        memset(pl, 0, sizeof *pl);
        pl->p = *p;
        pl->fric = fr;
        st = load_arm(pl);
        if (st != HIL_OK) {
            char keep[sizeof pl->err];
            memcpy(keep, pl->err, sizeof keep);
            memset(pl, 0, sizeof *pl);
            memcpy(pl->err, keep, sizeof keep);
        }
        return st;
    }
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

/* The friction held over a step whose velocity goes from v0 to
 * vfree - g tau_f (hil/plant.h): tau_f = F((v0 + vfree - g tau_f) / 2), the
 * trapezoidal rule, by two fixed-point corrections of the explicit F(v0).
 * Each contracts the error by c = g |F'| / 2 (0.006 at Table 8.6 and
 * h = T/8), so two leave c^2 of the explicit value's O(h) error: the rule
 * stays second order (a velocity error ~1e-12 rad/s there). Where the second
 * correction does not halve the first (c > 1/2: a friction too stiff for the
 * step, where the explicit rule is at its own stability limit too) the
 * explicit value. */
static double step_friction(frac_friction *fr, double v0, double vfree, double g)
{
    frac_real t = 0;
    double f0, f1, f2;
    frac_friction_eval(fr, (frac_real)v0, &t);
    f0 = (double)t;
    frac_friction_eval(fr, (frac_real)(0.5 * (v0 + vfree - g * f0)), &t);
    f1 = (double)t;
    frac_friction_eval(fr, (frac_real)(0.5 * (v0 + vfree - g * f1)), &t);
    f2 = (double)t;
    return fabs(f2 - f1) <= 0.5 * fabs(f1 - f0) ? f2 : f0;
}

/* Arm: the table's m = asub steps over [0, T/2] with torque
 * tau(s) = tau0 + slope * s, each step its mid-step value less the friction
 * u_k (held over the step) through Bd and the ramp about it through Bd1
 * (exact), composed: the motor velocity at the end of step k
 *   v_(k+1) = C_2 Ad^(k+1) x_0 + sum_{j<=k} C_2 Ad^(k-j) Bd u_j + C_2 sum_{i<=k} Ad^i Bd1 slope
 * is linear in the step's friction (coefficient -C_2 Bd), which is held at
 * the mean of v_k and v_(k+1) (step_friction); then
 * x_m = Ad^m x_0 + sum_k Ad^(m-1-k) (Bd u_k + Bd1 slope) (one n x n product
 * per half cycle instead of m). */
static void arm_half(struct hil_plant *pl, double tau0, double slope)
{
    const unsigned n = pl->an, m = pl->asub;
    double *x = pl->ax, *y = pl->ay, u[HIL_PLANT_ARM_SUBMAX], h = pl->ah, w = 0.0;
    unsigned k, i, j;
    for (j = 0; j < n; j++)
        w += pl->vrow[j] * x[j];
    for (k = 0; k < m; k++) {
        const double *r = pl->vrow + (size_t)(k + 1) * n, mid = tau0 + slope * ((double)k + 0.5) * h;
        double wfree = slope * pl->vb1[k + 1] + pl->vb[0] * mid, tf;
        for (j = 0; j < n; j++)
            wfree += r[j] * x[j];
        for (j = 0; j < k; j++)
            wfree += pl->vb[k - j] * u[j];
        tf = step_friction(&pl->fric, w, wfree, pl->vb[0]);
        u[k] = mid - tf;
        w = wfree - pl->vb[0] * tf;
    }
    /* y = sum_j Am(:, j) x_j + sum_k Ad^(m-1-k) Bd u_k (inner loops over i
     * vectorize) */
    for (i = 0; i < n; i++)
        y[i] = slope * pl->bramp[i];
    for (j = 0; j < n; j++) {
        const double *a = pl->Am + (size_t)j * n, xj = x[j];
        for (i = 0; i < n; i++)
            y[i] += a[i] * xj;
    }
    for (k = 0; k < m; k++) {
        const double *b = pl->bcol + (size_t)(m - 1 - k) * n, uk = u[k];
        for (i = 0; i < n; i++)
            y[i] += b[i] * uk;
    }
    memcpy(x, y, n * sizeof *x);
    {
        /* psi_L'' at the end of the half cycle: the torque there, less the last step's friction */
        double o[4] = {0.0, 0.0, 0.0, 0.0}, acc = pl->acc_b * (u[m - 1] + 0.5 * slope * h);
        for (i = 0; i < 4; i++)
            for (j = 0; j < n; j++)
                o[i] += pl->C[i * n + j] * x[j];
        for (j = 0; j < n; j++)
            acc += pl->acc_row[j] * x[j];
        pl->theta = o[0];
        pl->omega = o[1];
        pl->psi = o[2];
        pl->psi_d = o[3];
        pl->psi_dd = acc;
    }
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
        if (pl->p.model == HIL_PLANT_ARM)
            arm_half(pl, tau0 + slope * h * half, slope);
        else
            rk4(pl, h, tau0 + slope * h * half, slope, pl->p.substeps);
        pl->t += h;
        emit(HIL_COB_RIG_TIPPOS, pl->psi, -pl->p.L * pl->psi_d * pl->psi_d, out);
        emit(HIL_COB_RIG_TIP, pl->psi_d, pl->p.L * pl->psi_dd, out);
    }
    emit(HIL_COB_RIG_MOTOR, pl->theta, pl->omega, out);
    pl->steps++;
    return HIL_OK;
}
