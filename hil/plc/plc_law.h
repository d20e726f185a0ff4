/* The controller node's law from plc_blocks: the ArmCtrl program (Cyclic #1,
 * 1.2 ms) and ImuRead (Cyclic #2, 0.6 ms) run by the plc_rt task runtime with
 * the Table 2.3 task classes, on a simulated clock that advances 12 system
 * ticks (1.2 ms) per controller cycle of the bus.
 *
 * Per cycle (hil_ctrl_law contract, hil/ctrl.h): the values the node decoded
 * from the bus go into the I/O images (drive: angle, velocity and a counter
 * advanced only when both drive TPDOs arrived; CAN: the IMU rate and a frame
 * counter advanced per reading received), the runtime runs 12 ticks (Cyclic
 * #1 latches the image at its release, publishes after its simulated CPU time
 * of 300 us; Cyclic #2 runs twice), and the published TorqueSetpoint is the
 * command (0 while TorqueEnable is FALSE). The cyclic tasks start to run in
 * the first cycle in which the drive reports "operation enabled" and an IMU
 * reading has arrived (the application starts when its I/O is up; before,
 * the command is 0 Nm): the watchdogs would count the boot of the bus as
 * stale sensors. Start goes TRUE one cycle later (an edge for ArmCtrl).
 * Recovery: a stale drive or IMU latches ArmCtrl's Watchdog fault (torque
 * ramps to 0, EMCY); the node plays the operator who acknowledges it once
 * the data are fresh again: while the program reports Error, the drive
 * values came this cycle and an IMU reading within the last 2 cycles, it
 * pulses ArmCtrl's Acknowledge (rising edge every other cycle), and the
 * Watchdog clears on the first edge that finds both sensors fresh (a fault
 * of the parameters at _INIT is never acknowledged).
 *
 * Variant Exp. A (Table 8.1): rbFFC feedforward (4.14)-(4.17) of the Table
 * 8.5 point-to-point move (frac/traj.h: 0 -> pi/2, dq_max pi/2, ddq_max 2 pi,
 * motion 0.5 .. 2.0 s after Start) on the drive + rigid link + gear spring
 * design model (I_M, I_L, c_s given), PD gains Kp 320 Nm/rad, Kd 200 Nm s/rad
 * and linear friction compensation b1 3.04, b0 7.684, k 60 (Table 8.6).
 * Drive watchdog: 2 stale cycles; its fault ramp 25000 Nm/s takes the 250 Nm
 * limit to 0 in 10 ms. The law reports a fault (negative return: minus the
 * program's StatusID) while the program's published Error is set (a block or
 * a watchdog in fault).
 *
 * Any variant from a table (ctrl.law = armctrl, ctrl.table = FILE): ArmCtrl's
 * parameter table (plc_blocks ArmCtrl.h, armctrl_program_table: the layout
 * above armctrl_params_from_table; `fracdesign armctrl --exp A|B|C|D` writes
 * it), validated by ParTable and loaded at _INIT. A table that fails leaves
 * the program in fault: the torque is never enabled and every cycle reports
 * the StatusID.
 *
 * The reference *ref (for the logs only) is the tip angle of the feedforward,
 * the running trapezoidal integral of the table's dpsi_L* row, at the table
 * time of the run-time counter. */
#ifndef HIL_PLC_LAW_H
#define HIL_PLC_LAW_H
#include "ArmCtrl.h"
#include "ImuRead.h"
#include "frac/lut.h"
#include "hil/ctrl.h"
#include "plc_rt.h"

#define HIL_PLC_FF_SAMPLES 2668 /* 0 .. 3.2 s at 1.2 ms */

struct hil_plc_law {
    armctrl a;
    imuread m;
    plc_program pa, pm;
    plc_rt rt;
    armctrl_params par;
    armctrl_inputs drive_img;
    armctrl_outputs ctrl_img;
    imuread_inputs can_img;
    imuread_outputs imu_img;
    frac_real ff[ARMCTRL_FF_N][HIL_PLC_FF_SAMPLES];
    armctrl_table_storage store;   /* table variant: the values ArmCtrl's _INIT copies */
    const armctrl_params *P;       /* the parameters in use (par or store.par) */
    frac_real psi_ref[ARMCTRL_FF_MAX]; /* integral of the dpsi_L* row, per table sample */
    frac_lut1 psi_lut;             /* psi_ref over table time (linear, clamped): the logs' reference */
    int started;
    int io_up;                     /* the drive is enabled and an IMU reading came: the tasks run */
    uint64_t cycles_run;           /* controller cycles the task runtime has run */
    uint64_t imu_seen_at;          /* imu_readings when the last new reading came */
    uint64_t imu_new_cycle;        /* cycles_run at that reading */
    unsigned ticks_per_cycle;      /* system ticks (100 us) per controller cycle T */
};

/* Cycle times the task configuration accepts: a whole multiple of 200 us
 * (Cyclic #2 = T/2 on the 100 us tick). */
#define HIL_PLC_T_MIN 4e-4
#define HIL_PLC_T_MAX 0.1

/* Builds Exp. A for cycle T = 1.2 ms on the design model (I_M, I_L, c_s),
 * starts the runtime (_INIT). Returns HIL_OK, HIL_E_ARG (T not 1.2 ms, a
 * model value not positive) or HIL_E_STATE (the runtime or a block refused
 * its configuration; message in err). */
int hil_plc_law_init_exp_a(struct hil_plc_law *L, double T, double I_M, double I_L, double c_s, char *err,
                           size_t errlen);

/* Any variant from ArmCtrl's parameter table (size bytes at table, which must
 * outlive the law) for cycle T (Cyclic #1 = T, Cyclic #2 = T/2; T a multiple
 * of 200 us in [HIL_PLC_T_MIN, HIL_PLC_T_MAX]); starts the runtime. Returns HIL_OK;
 * HIL_E_ARG (T not such a cycle, NULL, or the table's "ts" is not T); HIL_E_STATE
 * with the message in err: either the runtime refused its configuration
 * (L not started), or ArmCtrl's _INIT refused the table (err names the
 * failing field or entry and the StatusID) - then L is started
 * and usable as a law that never enables the torque and returns minus the
 * StatusID every cycle. */
int hil_plc_law_init_table(struct hil_plc_law *L, double T, const void *table, unsigned long size, char *err,
                           size_t errlen);

/* ArmCtrl's StatusID (0: no error). */
unsigned hil_plc_law_status(const struct hil_plc_law *L);

/* The hil_ctrl_law callback; ctx is the struct hil_plc_law. 0 while the
 * cyclic tasks wait for the I/O (drive enabled, an IMU reading), 1 once they
 * ran this cycle, minus the StatusID in ArmCtrl's fault reaction. */
int hil_plc_law_step(void *ctx, const struct hil_ctrl_law_in *in, double *torque, double *ref);

/* Runs the _EXIT programs. */
void hil_plc_law_stop(struct hil_plc_law *L);

#endif
