/* ArmCtrl: the Cyclic #1 arm controller program (ArmCtrl.h). */
#include "ArmCtrl.h"
#include "plcprog.h"
#include "frac/frac_types.h"

#include <string.h>

static int uses_lqg(const armctrl_params *p)
{
    return p->Variant == ARMCTRL_EXP_C || p->Variant == ARMCTRL_EXP_D;
}

/* First Error among the blocks the variant runs (0 if none). */
static UINT first_error(const armctrl *a)
{
    if (a->ff.Error) {
        return a->ff.StatusID;
    }
    if (uses_lqg(a->par)) {
        if (a->lqg.Error) {
            return a->lqg.StatusID;
        }
        if (a->wd_imu.Error) {
            return a->wd_imu.StatusID;
        }
    } else if (a->friction.Error) {
        return a->friction.StatusID;
    }
    return a->wd_drive.Error ? a->wd_drive.StatusID : fracSTAT_OK;
}

static void run_blocks(armctrl *a)
{
    const armctrl_params *p = a->par;
    const REAL *ff = a->ff.Y;
    REAL tau;

    /* 3. controller: feedforward of cycle k at (k + lead) T per channel; it
     * advances while the motion runs (the thesis's run-time counter) */
    a->ff.Run = a->running;
    TrajLUT(&a->ff);
    if (uses_lqg(p)) {
        /* (6.45)/(7.21): u = u* + K e_x - e_z, outputs [theta_M, dtheta_M, dpsi_L] */
        a->lqg.UStar = ff[ARMCTRL_FF_TAU];
        a->lqg.YRef[0] = ff[ARMCTRL_FF_THETA];
        a->lqg.YRef[1] = ff[ARMCTRL_FF_DTHETA];
        a->lqg.YRef[2] = ff[ARMCTRL_FF_DPSI];
        a->lqg.Y[0] = a->in.MotorAngle;
        a->lqg.Y[1] = a->in.MotorVelocity;
        a->lqg.Y[2] = a->in.TipRate;
        LQGDelay(&a->lqg);
        tau = a->lqg.U;
    } else {
        /* (5.1): tau = tau* + Kp (theta* - theta) + Kd (dtheta* - dtheta) + tau_f(dtheta), measured velocity */
        a->friction.Velocity = a->in.MotorVelocity;
        FrictionComp(&a->friction);
        tau = ff[ARMCTRL_FF_TAU] + p->Kp * (ff[ARMCTRL_FF_THETA] - a->in.MotorAngle)
              + p->Kd * (ff[ARMCTRL_FF_DTHETA] - a->in.MotorVelocity) + a->friction.Torque;
    }
    if (tau > p->TorqueLimit) {
        tau = p->TorqueLimit;
    } else if (tau < -p->TorqueLimit) {
        tau = -p->TorqueLimit;
    }
    /* fault reaction: stale sensors (or a non-finite torque) ramp the torque to zero */
    a->wd_drive.SampleCounter = a->in.DriveCounter;
    a->wd_drive.Acknowledge = a->in.Acknowledge;
    a->wd_drive.TorqueIn = tau;
    Watchdog(&a->wd_drive);
    tau = a->wd_drive.TorqueOut;
    if (uses_lqg(p)) {
        a->wd_imu.SampleCounter = a->in.ImuCounter;
        a->wd_imu.Acknowledge = a->in.Acknowledge;
        a->wd_imu.TorqueIn = tau;
        Watchdog(&a->wd_imu);
        tau = a->wd_imu.TorqueOut;
    }
    a->out.TorqueSetpoint = tau;
}

/* Records the entry `name` that failed in s->fail_entry; returns st. */
static int failed(armctrl_table_storage *s, const char *name, int st)
{
    s->fail_entry = name;
    return st;
}

/* Entry `name` of exactly rows x cols into dst. */
static int get(armctrl_table_storage *s, const frac_ptable *t, const char *name, unsigned rows, unsigned cols,
               frac_real *dst)
{
    int st = frac_ptable_get(t, name, rows, cols, dst);
    return st == FRAC_OK ? st : failed(s, name, st);
}

/* Number of columns of a 4-row or 1-row entry (0 if missing). */
static int cols_of(armctrl_table_storage *s, const frac_ptable *t, const char *name, unsigned rows, unsigned *cols)
{
    frac_ptable_entry e;
    int st = frac_ptable_find(t, name, &e);
    if (st != FRAC_OK) {
        return failed(s, name, st);
    }
    if (e.rows != rows) {
        return failed(s, name, FRAC_E_DIM);
    }
    *cols = e.cols;
    return FRAC_OK;
}

/* Watchdog entry `name`, 1 x 2: max stale cycles (1..1e6), ramp rate [Nm/s]
 * (the ramp rate is validated by the Watchdog block at _INIT). */
static int read_watchdog(armctrl_table_storage *s, const frac_ptable *t, const char *name, WatchdogParType *wd)
{
    frac_real v[2];
    int st = get(s, t, name, 1, 2, v);
    if (st != FRAC_OK) {
        return st;
    }
    if (!(v[0] >= 1 && v[0] <= 1e6)) {
        return failed(s, name, FRAC_E_PARAM);
    }
    wd->MaxStaleCycles = (UDINT)v[0];
    wd->RampRate = (REAL)v[1];
    return FRAC_OK;
}

int armctrl_params_from_table(armctrl_table_storage *s, const frac_ptable *t)
{
    armctrl_params *p;
    frac_ptable_entry e;
    frac_real v[5];
    unsigned n_ff, c, n, nb;
    int st;
    if (!s || !t) {
        return FRAC_E_NULL;
    }
    s->fail_entry = "";
    p = &s->par;
    memset(p, 0, sizeof *p);
    if ((st = get(s, t, "variant", 1, 1, v)) != FRAC_OK) {
        return st;
    }
    if (!(v[0] >= 0 && v[0] <= ARMCTRL_EXP_D) || v[0] != FRAC_FLOOR(v[0])) {
        return failed(s, "variant", FRAC_E_PARAM);
    }
    p->Variant = (armctrl_variant)(int)v[0];
    if ((st = get(s, t, "ts", 1, 1, v)) != FRAC_OK) {
        return st;
    }
    p->CycleTime = (REAL)v[0];
    /* feedforward: 4 rows of N samples, played by TrajLUT */
    if ((st = cols_of(s, t, "ff", ARMCTRL_FF_N, &n_ff)) != FRAC_OK) {
        return st;
    }
    if (n_ff > ARMCTRL_FF_MAX) {
        return failed(s, "ff", FRAC_E_DIM);
    }
    if ((st = get(s, t, "ff", ARMCTRL_FF_N, n_ff, s->ff)) != FRAC_OK) {
        return st;
    }
    p->Ff.Channels = ARMCTRL_FF_N;
    p->Ff.N = n_ff;
    for (c = 0; c < ARMCTRL_FF_N; c++) {
        p->Ff.pData[c] = s->ff + c * n_ff;
    }
    if ((st = get(s, t, "ff_grid", 1, 4, v)) != FRAC_OK) {
        return st;
    }
    p->Ff.T0 = v[0];
    p->Ff.Dt = v[1];
    p->Ff.TMotionStart = v[2];
    p->Ff.TMotionEnd = v[3];
    p->Ff.Ts = p->CycleTime;
    p->Ff.Interpolation = fracINTERP_LINEAR;
    if ((st = get(s, t, "ff_lead", 1, 4, v)) != FRAC_OK) {
        return st;
    }
    for (c = 0; c < ARMCTRL_FF_N; c++) {
        if (v[c] != FRAC_FLOOR(v[c]) || v[c] > 1000 || v[c] < -1000) {
            return failed(s, "ff_lead", FRAC_E_PARAM);
        }
        p->Ff.Lead[c] = (DINT)v[c];
    }
    if ((st = get(s, t, "torque_limit", 1, 1, v)) != FRAC_OK) {
        return st;
    }
    p->TorqueLimit = (REAL)v[0];
    if ((st = read_watchdog(s, t, "watchdog", &p->WdDrive)) != FRAC_OK) {
        return st;
    }
    p->WdDrive.CycleTime = p->CycleTime;
    p->WdImu = p->WdDrive;
    if (frac_ptable_find(t, "watchdog_imu", &e) != FRAC_E_NOT_FOUND
        && (st = read_watchdog(s, t, "watchdog_imu", &p->WdImu)) != FRAC_OK) {
        return st;
    }
    if (!uses_lqg(p)) {
        if ((st = get(s, t, "pd", 1, 2, v)) != FRAC_OK) {
            return st;
        }
        p->Kp = (REAL)v[0];
        p->Kd = (REAL)v[1];
        if ((st = get(s, t, "friction", 1, 3, v)) != FRAC_OK) {
            return st;
        }
        p->Friction.Model = fracFRICTION_LINEAR;
        p->Friction.B1 = (REAL)v[0];
        p->Friction.B0 = (REAL)v[1];
        p->Friction.K = (REAL)v[2];
        return FRAC_OK;
    }
    if ((st = get(s, t, "lqg_dims", 1, 5, v)) != FRAC_OK) {
        return st;
    }
    for (c = 0; c < 5; c++) {
        if (!(v[c] >= 0 && v[c] <= FRAC_MAT_MAX) || v[c] != FRAC_FLOOR(v[c])) {
            return failed(s, "lqg_dims", FRAC_E_PARAM);
        }
    }
    n = (unsigned)v[0];
    nb = n + (unsigned)v[1] + (unsigned)v[2] + (unsigned)v[3] + (unsigned)v[4];
    if (n < 1 || n > ARMCTRL_LQG_NMAX || nb + 1 > FRAC_MAT_MAX) {
        return failed(s, "lqg_dims", FRAC_E_DIM);
    }
    p->Lqg.N = n;
    p->Lqg.Di = (UDINT)v[1];
    p->Lqg.P = 3;
    p->Lqg.Do[0] = (UDINT)v[2];
    p->Lqg.Do[1] = (UDINT)v[3];
    p->Lqg.Do[2] = (UDINT)v[4];
    if ((st = get(s, t, "A", n, n, s->A)) != FRAC_OK || (st = get(s, t, "B", n, 1, s->B)) != FRAC_OK
        || (st = get(s, t, "C", 3, n, s->C)) != FRAC_OK || (st = get(s, t, "K", 1, nb, s->K)) != FRAC_OK
        || (st = get(s, t, "L", nb + 1, 3, s->L)) != FRAC_OK) {
        return st;
    }
    p->Lqg.pA = s->A;
    p->Lqg.pB = s->B;
    p->Lqg.pC = s->C;
    p->Lqg.pK = s->K;
    p->Lqg.pL = s->L;
    return FRAC_OK;
}

/* Parameters at _INIT from the data object: ParTable validates it, then it
 * is copied into the storage. Returns the StatusID of the first failure. */
static UINT load_table(armctrl *a)
{
    UINT st = plcprog_open_table(&a->partable, a->table, a->table_size);
    if (st == fracSTAT_OK) {
        st = plcprog_status_id(armctrl_params_from_table(a->storage, FracPtableObj_C(a->partable.Handle)));
    }
    if (st == fracSTAT_OK) {
        a->par = &a->storage->par;
    }
    return st;
}

void armctrl_init(void *ctx)
{
    armctrl *a = (armctrl *)ctx;
    const armctrl_params *p;
    UINT st = fracSTAT_OK;

    memset(&a->out, 0, sizeof a->out);
    a->fault = 0;
    if (a->table) {
        st = load_table(a);
        if (st != fracSTAT_OK) {
            a->fault = 1;
            a->out.Error = 1;
            a->out.StatusID = st;
            return;
        }
    }
    p = a->par;

    memset(&a->ff, 0, sizeof a->ff);
    memset(&a->friction, 0, sizeof a->friction);
    memset(&a->lqg, 0, sizeof a->lqg);
    memset(&a->wd_drive, 0, sizeof a->wd_drive);
    memset(&a->wd_imu, 0, sizeof a->wd_imu);
    a->counter = 0;
    a->running = 0;
    a->start_old = 1; /* a Start already TRUE at power-on is not an edge */
    a->ff.Parameters = p->Ff;
    a->ff.Enable = 1;
    a->wd_drive.Parameters = p->WdDrive;
    a->wd_drive.Enable = 1;
    if (uses_lqg(p)) {
        a->lqg.Parameters = p->Lqg;
        a->lqg.Enable = 1;
        a->wd_imu.Parameters = p->WdImu;
        a->wd_imu.Enable = 1;
    } else {
        a->friction.Parameters = p->Friction;
        a->friction.Enable = 1;
    }
    /* program-level parameters (not owned by a block) */
    if (!(p->CycleTime > 0.0f) || !(p->TorqueLimit > 0.0f) || (unsigned)p->Variant > ARMCTRL_EXP_D
        || p->Ff.Channels != ARMCTRL_FF_N
        || (!uses_lqg(p) && !(FRAC_ISFINITE(p->Kp) && FRAC_ISFINITE(p->Kd)))) {
        st = fracERR_PARAM;
    }
    /* one evaluation at rest validates every parameter set (Enable edge) */
    run_blocks(a);
    if (st == fracSTAT_OK) {
        st = first_error(a);
    }
    if (st != fracSTAT_OK) {
        a->fault = 1;
    }
    a->out.Error = a->fault;
    a->out.StatusID = st;
    a->out.TorqueEnable = 0;
    a->out.TorqueSetpoint = 0.0f;
}

void armctrl_cyclic(void *ctx)
{
    armctrl *a = (armctrl *)ctx;
    UINT st;
    /* 1. drive values: a->in was latched from the I/O image at task start */
    if (a->fault) {
        a->out.TorqueEnable = 0;
        a->out.TorqueSetpoint = 0.0f;
        return;
    }
    /* 2. counter: runs once the motion is activated */
    if (a->in.Start && !a->start_old) {
        a->running = 1;
    }
    a->start_old = a->in.Start;
    /* 3. controller; the LQG estimate starts from 0 at the first cycle
     * (Reset edge), not from the evaluation at rest in _INIT */
    a->lqg.Reset = 1;
    run_blocks(a);
    if (a->running) {
        a->counter++;
    }
    /* 4. torque setpoint (published at task end) */
    st = first_error(a);
    a->out.Counter = a->counter;
    a->out.Error = st != fracSTAT_OK;
    a->out.StatusID = st;
    a->out.TorqueEnable = 1;
}

void armctrl_exit(void *ctx)
{
    armctrl *a = (armctrl *)ctx;
    /* disable every block: outputs to zero, StatusID fracSTAT_DISABLED */
    a->partable.Enable = 0;
    ParTable(&a->partable);
    a->ff.Enable = 0;
    TrajLUT(&a->ff);
    a->friction.Enable = 0;
    FrictionComp(&a->friction);
    a->lqg.Enable = 0;
    LQGDelay(&a->lqg);
    a->wd_drive.Enable = 0;
    Watchdog(&a->wd_drive);
    a->wd_imu.Enable = 0;
    Watchdog(&a->wd_imu);
    a->out.TorqueEnable = 0;
    a->out.TorqueSetpoint = 0.0f;
}

void armctrl_table_8_5_move(frac_traj_params *tp)
{
    tp->q_s = 0.0;
    tp->q_e = FRAC_PI / 2;
    tp->dq_max = FRAC_PI / 2;
    tp->ddq_max = 2 * FRAC_PI;
    tp->t_start = 0.5;
    tp->duration = 1.5;
}

void armctrl_program(armctrl *a, plc_program *prog, const armctrl_params *par, armctrl_inputs *image_in,
                     imuread_outputs *imu_image, armctrl_outputs *image_out)
{
    memset(a, 0, sizeof *a);
    a->par = par;
    plcprog_io(&a->io_in[0], image_in, &a->in, sizeof a->in);
    if (imu_image) {
        plcprog_io(&a->io_in[1], &imu_image->TipRate, &a->in.TipRate, sizeof a->in.TipRate);
        plcprog_io(&a->io_in[2], &imu_image->ImuCounter, &a->in.ImuCounter, sizeof a->in.ImuCounter);
    }
    plcprog_io(&a->io_out, image_out, &a->out, sizeof a->out);
    plcprog_describe(prog, "ArmCtrl", armctrl_init, armctrl_cyclic, armctrl_exit, a, a->io_in, imu_image ? 3 : 1,
                     &a->io_out);
}

void armctrl_program_table(armctrl *a, plc_program *prog, const void *table, UDINT size,
                           armctrl_table_storage *storage, armctrl_inputs *image_in, imuread_outputs *imu_image,
                           armctrl_outputs *image_out)
{
    armctrl_program(a, prog, &storage->par, image_in, imu_image, image_out);
    a->table = table;
    a->table_size = size;
    a->storage = storage;
}
