/* ArmCtrl + ImuRead in the plc_rt task runtime as the controller node's law
 * (hil/plc/plc_law.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "frac/ptable.h"
#include "hil/can.h"
#include "plc_law.h"

/* Table 2.3 task classes with the programs of Fig. 2.12 (system tick 100 us:
 * 400 us interface cycle x 0.25) and the cycle times of the law: ArmCtrl in
 * Cyclic #1 = T, ImuRead in Cyclic #2 = T/2 (the thesis: 1.2 and 0.6 ms);
 * simulated CPU time per cycle: ArmCtrl 300 us, ImuRead 50 us. T must be a
 * whole multiple of 2 ticks (HIL_PLC_T_MIN .. HIL_PLC_T_MAX). */
#define PLC_TICK_US 100u
static int task_config(char *cfg, size_t n, double T, unsigned *ticks)
{
    const double us = T * 1e6, k = floor(us / (2.0 * PLC_TICK_US) + 0.5);
    if (!(T >= HIL_PLC_T_MIN && T <= HIL_PLC_T_MAX) || fabs(k * 2.0 * PLC_TICK_US - us) > 1e-6)
        return HIL_E_ARG;
    *ticks = (unsigned)(2.0 * k);
    snprintf(cfg, n,
             "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = continue\n"
             "[cyclic1]\nduration_us = %u\nsim_cost_us = 300\nprograms = ArmCtrl\n"
             "[cyclic2]\nduration_us = %u\nsim_cost_us = 50\nprograms = ImuRead\n",
             *ticks * PLC_TICK_US, *ticks * PLC_TICK_US / 2u);
    return HIL_OK;
}

/* Tip reference of the logs: psi_ref[i] = int_0^{t_i} dpsi_L* (trapezoid),
 * looked up over table time by psi_lut. */
static int integrate_ref(struct hil_plc_law *L)
{
    const TrajLUTParType *f = &L->P->Ff;
    UDINT i, n = f->N < ARMCTRL_FF_MAX ? f->N : ARMCTRL_FF_MAX;
    L->psi_ref[0] = 0;
    for (i = 1; i < n; i++)
        L->psi_ref[i] = L->psi_ref[i - 1] +
                        (frac_real)0.5 * (frac_real)f->Dt * (f->pData[ARMCTRL_FF_DPSI][i - 1] + f->pData[ARMCTRL_FF_DPSI][i]);
    return frac_lut1_init_uniform(&L->psi_lut, (frac_real)f->T0, (frac_real)f->Dt, L->psi_ref, n, FRAC_LUT_LINEAR,
                                  FRAC_LUT_CLAMP, NULL);
}

/* Registers ArmCtrl (filled by the caller) and ImuRead, starts the runtime
 * (_INIT). HIL_OK, or HIL_E_STATE when the runtime or ArmCtrl's _INIT refused
 * (message in err; L stays started in the second case). */
static int start(struct hil_plc_law *L, double T, char *err, size_t errlen)
{
    plc_rt_config cfg;
    const plc_program *reg[2];
    char text[512];
    if (task_config(text, sizeof text, T, &L->ticks_per_cycle) != HIL_OK)
        return HIL_E_ARG;
    imuread_program(&L->m, &L->pm, 1.0f, &L->can_img, &L->imu_img);
    reg[0] = &L->pa;
    reg[1] = &L->pm;
    if (plc_rt_config_parse(&cfg, text, "table_2_3", err, errlen) != PLC_RT_OK ||
        plc_rt_init(&L->rt, &cfg, reg, 2, err, errlen) != PLC_RT_OK || plc_rt_start(&L->rt) != PLC_RT_OK)
        return HIL_E_STATE;
    L->started = 1;
    if (L->a.fault) {
        if (err && errlen)
            snprintf(err, errlen, "ArmCtrl _INIT refused its parameters (StatusID %u)",
                     (unsigned)L->a.out.StatusID);
        return HIL_E_STATE;
    }
    if (integrate_ref(L) != FRAC_OK) {
        if (err && errlen)
            snprintf(err, errlen, "the feedforward grid (T0, dt, N) gives no tip reference");
        return HIL_E_STATE;
    }
    return HIL_OK;
}

int hil_plc_law_init_exp_a(struct hil_plc_law *L, double T, double I_M, double I_L, double c_s, char *err,
                           size_t errlen)
{
    frac_traj_params tp;
    frac_traj traj;
    int i, ch;
    if (!L || fabs(T - 1.2e-3) > 1e-12 || !(I_M > 0.0) || !(I_L > 0.0) || !(c_s > 0.0) || !isfinite(I_M) ||
        !isfinite(I_L) || !isfinite(c_s))
        return HIL_E_ARG;
    memset(L, 0, sizeof *L);
    /* Table 8.5 point-to-point move */
    armctrl_table_8_5_move(&tp);
    if (frac_traj_init(&traj, &tp) != FRAC_OK)
        return HIL_E_ARG;
    /* rbFFC (4.14)-(4.17): link at the trajectory, motor ahead by the spring
     * twist I_L q'' / c_s, torque I_M theta_M'' + c_s (theta_M - q). */
    for (i = 0; i < HIL_PLC_FF_SAMPLES; i++) {
        frac_real d[5], th, ddth;
        frac_traj_eval(&traj, (frac_real)(i * T), d);
        th = (frac_real)(I_L / c_s) * d[2] + d[0];
        ddth = (frac_real)(I_L / c_s) * d[4] + d[2];
        L->ff[ARMCTRL_FF_THETA][i] = th;
        L->ff[ARMCTRL_FF_DTHETA][i] = (frac_real)(I_L / c_s) * d[3] + d[1];
        L->ff[ARMCTRL_FF_DPSI][i] = d[1];
        L->ff[ARMCTRL_FF_TAU][i] = (frac_real)I_M * ddth + (frac_real)c_s * (th - d[0]);
    }
    L->par.Variant = ARMCTRL_EXP_A;
    L->par.CycleTime = (REAL)T;
    L->par.Ff.Channels = ARMCTRL_FF_N;
    L->par.Ff.N = HIL_PLC_FF_SAMPLES;
    for (ch = 0; ch < ARMCTRL_FF_N; ch++)
        L->par.Ff.pData[ch] = L->ff[ch];
    L->par.Ff.T0 = 0.0;
    L->par.Ff.Dt = (REAL)T;
    L->par.Ff.Ts = (REAL)T;
    L->par.Ff.TMotionStart = 0.5f;
    L->par.Ff.TMotionEnd = 2.0f;
    L->par.Ff.Interpolation = fracINTERP_LINEAR;
    L->par.Kp = 320.0f;
    L->par.Kd = 200.0f;
    L->par.Friction.Model = fracFRICTION_LINEAR;
    L->par.Friction.K = 60.0f;
    L->par.Friction.B1 = 3.04f;
    L->par.Friction.B0 = 7.684f;
    L->par.WdDrive.MaxStaleCycles = 2;
    L->par.WdDrive.RampRate = 25000.0f;
    L->par.WdDrive.CycleTime = (REAL)T;
    L->par.WdImu = L->par.WdDrive;
    L->par.WdImu.MaxStaleCycles = 3;
    L->par.TorqueLimit = 250.0f;
    L->P = &L->par;
    armctrl_program(&L->a, &L->pa, &L->par, &L->drive_img, &L->imu_img, &L->ctrl_img);
    return start(L, T, err, errlen);
}

/* err for a table ArmCtrl's _INIT refused: the failing field of the FRPT
 * validation (frac_ptable_open: "crc32", "entry.values of entry 2 'A'", ...),
 * else the entry of ArmCtrl's layout that failed (armctrl_params_from_table:
 * missing, of the wrong size or out of range), else a value a block
 * refused; each with
 * ArmCtrl's StatusID. */
static void describe_refusal(struct hil_plc_law *L, const unsigned char *b, unsigned long size, char *err,
                             size_t errlen)
{
    frac_ptable t;
    unsigned sid = (unsigned)L->a.out.StatusID;
    int st = frac_ptable_open(&t, b, size);
    if (!err || !errlen)
        return;
    if (st != FRAC_OK) {
        char ename[FRAC_PTABLE_NAME_LEN + 1] = "";
        if (t.fail_entry >= 0 &&
            FRAC_PTABLE_HEADER_SIZE + (unsigned long)(t.fail_entry + 1) * FRAC_PTABLE_ENTRY_SIZE <= size)
            memcpy(ename, b + FRAC_PTABLE_HEADER_SIZE + (unsigned long)t.fail_entry * FRAC_PTABLE_ENTRY_SIZE,
                   FRAC_PTABLE_NAME_LEN);
        if (t.fail_entry >= 0)
            snprintf(err, errlen, "%s (field %s of entry %ld '%s'; ArmCtrl StatusID %u)", frac_status_str(st),
                     t.fail_field, t.fail_entry, ename, sid);
        else
            snprintf(err, errlen, "%s (field %s; ArmCtrl StatusID %u)", frac_status_str(st), t.fail_field, sid);
        return;
    }
    st = armctrl_params_from_table(&L->store, &t);
    if (st != FRAC_OK)
        snprintf(err, errlen, "%s (entry '%s': missing, of the wrong size or out of range for ArmCtrl's layout, "
                 "plc_blocks/programs/ArmCtrl.h; ArmCtrl StatusID %u)", frac_status_str(st), L->store.fail_entry, sid);
    else
        snprintf(err, errlen, "a block refused a value at ArmCtrl's _INIT (ArmCtrl StatusID %u; FracCtrl.var "
                 "names the codes)", sid);
}

int hil_plc_law_init_table(struct hil_plc_law *L, double T, const void *table, unsigned long size, char *err,
                           size_t errlen)
{
    int st;
    unsigned ticks;
    char text[512];
    if (!L || !table || task_config(text, sizeof text, T, &ticks) != HIL_OK || size > 0xFFFFFFFFul)
        return HIL_E_ARG;
    memset(L, 0, sizeof *L);
    L->P = &L->store.par;
    armctrl_program_table(&L->a, &L->pa, table, (UDINT)size, &L->store, &L->drive_img, &L->imu_img, &L->ctrl_img);
    st = start(L, T, err, errlen);
    if (st == HIL_E_STATE && L->started && L->a.fault)
        describe_refusal(L, (const unsigned char *)table, size, err, errlen);
    if (st == HIL_OK && fabs((double)L->P->CycleTime - T) > 1e-9) {
        hil_plc_law_stop(L);
        if (err && errlen)
            snprintf(err, errlen, "the table's ts = %g s is not the bus cycle T = %g s", (double)L->P->CycleTime, T);
        return HIL_E_ARG;
    }
    return st;
}

unsigned hil_plc_law_status(const struct hil_plc_law *L) { return L ? (unsigned)L->a.out.StatusID : 0u; }

int hil_plc_law_step(void *ctx, const struct hil_ctrl_law_in *in, double *torque, double *ref)
{
    struct hil_plc_law *L = (struct hil_plc_law *)ctx;
    if (!L || !in || !torque || !ref || !L->started)
        return HIL_E_ARG;
    L->drive_img.MotorAngle = (REAL)in->theta;
    L->drive_img.MotorVelocity = (REAL)in->omega;
    if (in->drive_fresh)
        L->drive_img.DriveCounter++;
    /* the cyclic tasks start once the I/O is up (drive enabled, an IMU
     * reading in): the watchdogs would otherwise count the boot of the bus
     * as stale sensors; a program in fault runs (and reports) at once */
    if (!L->io_up && !L->a.fault && !(in->enabled && in->imu_readings > 0)) {
        *torque = 0.0;
        *ref = 0.0;
        return HIL_OK;
    }
    L->io_up = 1;
    /* Start rises in the second cycle run (a Start already TRUE at the first
     * is not an edge for ArmCtrl) */
    L->drive_img.Start = (L->cycles_run > 0 && in->enabled) || L->drive_img.Start;
    L->can_img.RawRate = (REAL)in->imu_rate;
    L->can_img.FrameCounter = (UDINT)in->imu_readings;
    if (in->imu_readings != L->imu_seen_at) {
        L->imu_seen_at = in->imu_readings;
        L->imu_new_cycle = L->cycles_run;
    }
    /* the operator's acknowledge of a run-time fault once the data are fresh */
    L->drive_img.Acknowledge = !L->a.fault && L->ctrl_img.Error && in->drive_fresh &&
                               L->cycles_run - L->imu_new_cycle <= 2 && !L->drive_img.Acknowledge;
    plc_rt_run_sim(&L->rt, L->ticks_per_cycle);
    L->cycles_run++;
    *torque = L->ctrl_img.TorqueEnable ? (double)L->ctrl_img.TorqueSetpoint : 0.0;
    *ref = 0.0;
    if (!L->a.fault) {
        frac_real r = 0;
        (void)frac_lut1_eval(&L->psi_lut, (frac_real)((double)L->ctrl_img.Counter * (double)L->P->CycleTime), &r);
        *ref = (double)r;
    }
    if (L->ctrl_img.Error)
        return L->ctrl_img.StatusID ? -(int)L->ctrl_img.StatusID : -1;
    return 1; /* the tasks ran this cycle (hil_ctrl_law) */
}

void hil_plc_law_stop(struct hil_plc_law *L)
{
    if (L && L->started) {
        plc_rt_stop(&L->rt);
        L->started = 0;
    }
}
