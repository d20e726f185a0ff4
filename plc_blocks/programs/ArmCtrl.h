/*
 * ArmCtrl.h - the arm controller program of Cyclic #1 (1.2 ms), seed 004
 * part 2 (notes 8.5, Fig. 2.12): per cycle, in the thesis order,
 *   1. read drive values   (MC_BR_CyclicRead: ParID 91 angle, 92 speed;
 *                           here the latched I/O image) and the IMU tip rate
 *                           published by ImuRead (Cyclic #2);
 *   2. counter             (counts run time once the motion is activated);
 *   3. controller          (exp_obc: feedforward playback (TrajLUT) + feedback law);
 *   4. torque setpoint     (MC_BR_CyclicWrite ParID 586 + MC_BR_TorqueControl;
 *                           here the output image, published at task end).
 * Variants (Table 8.1):
 *   Exp. A  rbFFC tables + PD (5.1) + static friction compensation (5.2);
 *   Exp. B  ibFFC tables + PD (5.1) + static friction compensation;
 *   Exp. C  ibFFC tables + state-difference LQG with friction state (6.45);
 *   Exp. D  as C with the delay model (7.21), feedforward torque sent d_i
 *           cycles early and the IMU reference delayed d_o cycles (Sec. 8.6).
 * The feedforward tables themselves (rbFFC (4.14)-(4.16) or the stable
 * inversion of Sec. 4.3) and the LQG gains come from the design tools.
 *
 * Parameters are checked at _INIT by enabling every block the variant
 * uses; if any block reports Error, the program latches the fault
 * (StatusID of the first failing block) and never enables the torque.
 * At run time a stale drive or IMU value (Watchdog) ramps the torque to
 * zero. No allocation anywhere; cost per cycle is the blocks' cost.
 */
#ifndef ARMCTRL_H
#define ARMCTRL_H

#include "FracCtrl.h"
#include "ImuRead.h"
#include "plc_rt.h"
#include "frac/mat.h"
#include "frac/ptable.h"
#include "frac/traj.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum armctrl_variant {
    ARMCTRL_EXP_A = 0,
    ARMCTRL_EXP_B = 1,
    ARMCTRL_EXP_C = 2,
    ARMCTRL_EXP_D = 3
} armctrl_variant;

/* Feedforward channels (notes 4.5: only y* and u* are stored on the PLC). */
enum {
    ARMCTRL_FF_THETA = 0,  /* theta_M* [rad] */
    ARMCTRL_FF_DTHETA = 1, /* dtheta_M* [rad/s] */
    ARMCTRL_FF_DPSI = 2,   /* dpsi_L* tip rate [rad/s] (LQG variants) */
    ARMCTRL_FF_TAU = 3,    /* tau_M* = u* [Nm] */
    ARMCTRL_FF_N = 4
};

/* Inputs of the I/O image. */
typedef struct armctrl_inputs {
    REAL MotorAngle;    /* theta_M, driven side [rad] (ParID 91) */
    REAL MotorVelocity; /* dtheta_M [rad/s] (ParID 92) */
    UDINT DriveCounter; /* incremented by the drive interface for every new value */
    REAL TipRate;       /* dpsi_L [rad/s], from ImuRead */
    UDINT ImuCounter;   /* incremented by ImuRead for every new IMU sample */
    BOOL Start;         /* rising edge: start the motion (the counter runs) */
    BOOL Acknowledge;   /* rising edge: clear a latched watchdog fault once its sensor is fresh
                           again (operator reset; no automatic restart, PLCopen) */
} armctrl_inputs;

/* Outputs of the I/O image. */
typedef struct armctrl_outputs {
    REAL TorqueSetpoint; /* tau_M set [Nm] (ParID 586) */
    BOOL TorqueEnable;   /* MC_BR_TorqueControl Enable */
    UDINT Counter;       /* cycles since the motion started */
    BOOL Error;          /* a block reports Error */
    UINT StatusID;       /* StatusID of the first block in Error, else fracSTAT_OK */
} armctrl_outputs;

typedef struct armctrl_params {
    armctrl_variant Variant;
    REAL CycleTime;                    /* task class duration [s] (1.2e-3) */
    TrajLUTParType Ff;                 /* feedforward tables, channels ARMCTRL_FF_*, with per-channel
                                          lead/lag (Exp. D: tau +d_i, dpsi -d_o, Sec. 8.6) */
    REAL Kp, Kd;                       /* PD gains, Table 8.6: 320 Nm/rad, 200 Nm s/rad */
    FrictionCompParType Friction;      /* Table 8.6: linear, 3.04, 7.684, k = 60 */
    LQGDelayParType Lqg;               /* Exp. C/D */
    WatchdogParType WdDrive, WdImu;    /* stale limits and ramp */
    REAL TorqueLimit;                  /* |tau| limit [Nm] (thesis [GAP]; drive peak ~251 Nm) */
} armctrl_params;

/*
 * ArmCtrl's parameter table (the data object of `fracdesign table`,
 * validated by the ParTable block, frac/ptable.h). Entries, row-major:
 *   "variant"      1 x 1  0..3 = Exp. A..D
 *   "ts"           1 x 1  cycle time T [s] (1.2e-3)
 *   "ff"           4 x N  feedforward rows theta_M*, dtheta_M*, dpsi_L*, tau_M*, N <= ARMCTRL_FF_MAX
 *   "ff_grid"      1 x 4  table time of sample 0, sample time, nominal motion start and end [s]
 *   "ff_lead"      1 x 4  lead (+) / lag (-) per row [cycles] (Exp. D: 0, 0, -3, 4)
 *   "torque_limit" 1 x 1  [Nm]
 *   "watchdog"     1 x 2  max stale cycles, ramp rate [Nm/s] (drive; also the IMU's
 *                         unless "watchdog_imu" is given)
 * Exp. A/B:
 *   "pd"           1 x 2  K_P [Nm/rad], K_D [Nm s/rad] (Table 8.6)
 *   "friction"     1 x 3  b_1 [Nm s/rad], b_0 [Nm], k (linear model (5.2), Table 8.6)
 * Exp. C/D:
 *   "lqg_dims"     1 x 5  n, d_i, d_o of theta_M, dtheta_M, dpsi_L
 *   "A" n x n, "B" n x 1, "C" 3 x n, "K" 1 x n_bar, "L" (n_bar + 1) x 3
 *                         (n_bar = n + d_i + sum d_o, frac/lqg.h)
 *   "watchdog_imu" 1 x 2  optional: the IMU watchdog's max stale cycles and ramp rate
 *                         (the IMU delivers one reading per 2.4 ms = 2 cycles, so its
 *                         limit may need to differ from the drive's)
 */
#define ARMCTRL_FF_MAX 4096
#define ARMCTRL_LQG_NMAX 32

/* Caller-owned storage the table's values are copied into at _INIT. */
typedef struct armctrl_table_storage {
    frac_real ff[ARMCTRL_FF_N * ARMCTRL_FF_MAX];
    frac_real A[ARMCTRL_LQG_NMAX * ARMCTRL_LQG_NMAX];
    frac_real B[ARMCTRL_LQG_NMAX];
    frac_real C[3 * ARMCTRL_LQG_NMAX];
    frac_real K[FRAC_MAT_MAX];
    frac_real L[FRAC_MAT_MAX * 3];
    armctrl_params par;
    const char *fail_entry; /* entry armctrl_params_from_table refused ("" when none) */
} armctrl_table_storage;

/*
 * Fills s->par (and the arrays it points to) from a validated table.
 * Returns FRAC_OK or the first failure: FRAC_E_NOT_FOUND (entry missing),
 * FRAC_E_DIM (entry size not as listed above or above the capacities),
 * FRAC_E_PARAM (variant or a dimension out of range), FRAC_E_NULL; the
 * entry that failed is left in s->fail_entry.
 * Values themselves are validated by the blocks at _INIT.
 */
int armctrl_params_from_table(armctrl_table_storage *s, const frac_ptable *t);

typedef struct armctrl {
    const armctrl_params *par;
    const void *table;              /* data object, or NULL when par is given directly */
    UDINT table_size;
    armctrl_table_storage *storage; /* where the table's values go */
    struct ParTable partable;
    armctrl_inputs in;   /* program-local copy of the inputs (latched) */
    armctrl_outputs out; /* program-local copy of the outputs (published at task end) */
    struct TrajLUT ff;
    struct FrictionComp friction;
    struct LQGDelay lqg;
    struct Watchdog wd_drive, wd_imu;
    BOOL start_old, running, fault;
    UDINT counter;
    plc_io io_in[3], io_out;
} armctrl;

/*
 * Fills `prog` (name "ArmCtrl") for the task runtime: _INIT/_CYCLIC/_EXIT
 * on `a`, inputs latched from *image_in, except TipRate and ImuCounter,
 * which come from ImuRead's output image *imu_image when it is not NULL
 * (the I/O mapping between the two task classes); outputs published to
 * *image_out. `par` must stay valid while the program runs.
 */
void armctrl_program(armctrl *a, plc_program *prog, const armctrl_params *par, armctrl_inputs *image_in,
                     imuread_outputs *imu_image, armctrl_outputs *image_out);

/*
 * As armctrl_program, but the parameters come from the data object
 * `table` (size bytes) at _INIT: ParTable validates it, then
 * armctrl_params_from_table copies it into *storage. A table that fails
 * leaves the program in fault with the failing StatusID: the torque is
 * never enabled.
 */
void armctrl_program_table(armctrl *a, plc_program *prog, const void *table, UDINT size,
                           armctrl_table_storage *storage, armctrl_inputs *image_in, imuread_outputs *imu_image,
                           armctrl_outputs *image_out);

/*
 * The point-to-point move of Table 8.5 (seed 004, notes 004b 2.2) that the
 * feedforward tables play: q 0 -> pi/2 rad, dq_max pi/2 rad/s, ddq_max
 * 2 pi rad/s^2, start t_s = 0.5 s, duration 1.5 s (t_e = 2 s), for
 * frac_traj_init (frac/traj.h).
 */
void armctrl_table_8_5_move(frac_traj_params *tp);

void armctrl_init(void *ctx);   /* _INIT */
void armctrl_cyclic(void *ctx); /* _CYCLIC */
void armctrl_exit(void *ctx);   /* _EXIT */

#ifdef __cplusplus
}
#endif

#endif /* ARMCTRL_H */
