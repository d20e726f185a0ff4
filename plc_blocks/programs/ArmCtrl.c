/* ArmCtrl: the Cyclic #1 arm controller program (ArmCtrl.h). */
#include "ArmCtrl.h"
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
    a->wd_drive.TorqueIn = tau;
    Watchdog(&a->wd_drive);
    tau = a->wd_drive.TorqueOut;
    if (uses_lqg(p)) {
        a->wd_imu.SampleCounter = a->in.ImuCounter;
        a->wd_imu.TorqueIn = tau;
        Watchdog(&a->wd_imu);
        tau = a->wd_imu.TorqueOut;
    }
    a->out.TorqueSetpoint = tau;
}

void armctrl_init(void *ctx)
{
    armctrl *a = (armctrl *)ctx;
    const armctrl_params *p = a->par;
    UINT st = fracSTAT_OK;

    memset(&a->ff, 0, sizeof a->ff);
    memset(&a->friction, 0, sizeof a->friction);
    memset(&a->lqg, 0, sizeof a->lqg);
    memset(&a->wd_drive, 0, sizeof a->wd_drive);
    memset(&a->wd_imu, 0, sizeof a->wd_imu);
    memset(&a->out, 0, sizeof a->out);
    a->counter = 0;
    a->running = 0;
    a->start_old = 1; /* a Start already TRUE at power-on is not an edge */
    a->fault = 0;
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

void armctrl_program(armctrl *a, plc_program *prog, const armctrl_params *par, armctrl_inputs *image_in,
                     imuread_outputs *imu_image, armctrl_outputs *image_out)
{
    memset(a, 0, sizeof *a);
    a->par = par;
    a->io_in[0].image = image_in;
    a->io_in[0].local = &a->in;
    a->io_in[0].size = sizeof a->in;
    if (imu_image) {
        a->io_in[1].image = &imu_image->TipRate;
        a->io_in[1].local = &a->in.TipRate;
        a->io_in[1].size = sizeof a->in.TipRate;
        a->io_in[2].image = &imu_image->ImuCounter;
        a->io_in[2].local = &a->in.ImuCounter;
        a->io_in[2].size = sizeof a->in.ImuCounter;
    }
    a->io_out.image = image_out;
    a->io_out.local = &a->out;
    a->io_out.size = sizeof a->out;
    memset(prog, 0, sizeof *prog);
    prog->name = "ArmCtrl";
    prog->init = armctrl_init;
    prog->cyclic = armctrl_cyclic;
    prog->exit = armctrl_exit;
    prog->ctx = a;
    prog->inputs = a->io_in;
    prog->n_inputs = imu_image ? 3 : 1;
    prog->outputs = &a->io_out;
    prog->n_outputs = 1;
}
