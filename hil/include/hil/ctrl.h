/* The controller node: NMT master, SYNC producer and the control law, seen
 * from the bus exactly as the PLC's Cyclic #1 task.
 *
 * Boot (hil_ctrl_boot, before cycle 0), as a CANopen manager boots its
 * slaves: NMT "reset communication" to all, then per device (drive and IMU
 * in parallel, one SDO request outstanding per device) the SDO steps
 * derived from the device's object dictionary table, i.e. from the values
 * of its EDS (hil/drive.eds, hil/imu.eds; test hil_eds_matches_table):
 * read 0x1000 (device type) and 0x1018:1/2 (vendor, product) and compare
 * them with the EDS; for every PDO of the EDS write its COB-ID with bit 31
 * set (not valid), its mapping (sub 0 = 0, the EDS's entries, sub 0 = n)
 * and transmission type, then its COB-ID (valid as in the EDS); write
 * 0x1017 (heartbeat) and, for the drive, 0x6060 (mode of operation, 10
 * CST). A mismatch, an abort or no answer fails the boot (boot_status < 0,
 * boot_error says which step and why) and the node never starts the bus.
 * The PDO layouts the controller decodes (hil/canopen.h codec) are the ones
 * it writes here; test_hil_sdo checks they are the EDS's.
 *
 * Cycle k: hil_ctrl_tick() sends SYNC(k) (preceded at k = 0 by NMT "start
 * all"); the drive answers with TPDO1/TPDO2 (shaft at t_k); as soon as both
 * are in, the law runs and the RPDO (controlword + target torque) goes out.
 * If the cycle ends without them, hil_ctrl_deadline() runs the law on the last
 * values received (counted in missed_inputs), as a PLC task does when its
 * inputs are not refreshed.
 *
 * Law "pd" (a TEST law until the plc_blocks controllers are wired in):
 *     tau = kp (r - theta) + kd (r' - theta') - k_tip * psi'_imu
 * with r(t) the cos^2 point-to-point move of amplitude `move` [rad] over
 * `move_time` [s] starting at `move_start` [s].
 *
 * Drive enabling per CiA 402, driven by the reported statusword: 0x06 in
 * "switch on disabled", 0x07 in "ready to switch on", 0x0F afterwards, and a
 * fault reset (0x80) when the drive reports a fault, so the drive is
 * re-enabled after e.g. an RPDO timeout or a bus-off episode.
 * IMU watchdog: when no new IMU reading (sequence number) arrived for more
 * than imu_timeout cycles while enabled, the node enters its fault reaction:
 * EMCY 0x7300 once, and the torque command ramps linearly from its last value
 * to 0 over ramp_time (default 8.4 ms: 7 cycles, inside the 10 ms bound). A
 * fresh reading ends the reaction (EMCY 0x0000, error reset) and the law
 * resumes. */
#ifndef HIL_CTRL_H
#define HIL_CTRL_H
#include "hil/node.h"

struct hil_ctrl_params {
    double T;             /* cycle [s] > 0 */
    double kp, kd, k_tip; /* gains [Nm/rad], [Nm s/rad], [Nm s/rad] */
    double move, move_start, move_time; /* reference move [rad], [s], [s] (> 0) */
    unsigned imu_timeout; /* cycles, >= 1 */
    double ramp_time;     /* fault ramp to zero torque [s] > 0 */
    double torque_max;    /* command clamp [Nm] > 0 */
};

/* An external control law in place of the PD test law (e.g. the plc_blocks
 * ArmCtrl program, hil/plc_law.h). Called once per cycle with what the node
 * decoded from the bus; returns the torque command in *torque and the
 * reference in *ref (for the logs), and a negative value when the law is in
 * its fault reaction, else 0 before the law's cyclic tasks run and 1 once
 * they do (ArmCtrl: from the cycle the drive is enabled and an IMU reading
 * came; logged as the records' column `run`): -st is the law's status code (ArmCtrl: its StatusID;
 * 1 when the law has none), kept in law_status; the node then sends EMCY
 * 0x7300 once per episode with the status code as u16 in bytes 3-4 (the
 * first two manufacturer-specific bytes).
 * With an external law the node's own IMU watchdog is off: the law has its
 * own fault reaction. */
struct hil_ctrl_law_in {
    double t;                 /* cycle time k T [s] */
    double theta, omega;      /* drive TPDO1/TPDO2 */
    int drive_fresh;          /* both drive TPDOs of this cycle arrived */
    double imu_rate;          /* latest IMU rate z [rad/s] */
    uint64_t imu_readings;    /* readings received so far */
    int enabled;              /* the drive reports "operation enabled" */
};
typedef int (*hil_ctrl_law)(void *ctx, const struct hil_ctrl_law_in *in, double *torque, double *ref);

struct hil_ctrl_signals {   /* what the controller saw and did in one cycle */
    double t, ref, torque_cmd, theta, omega, imu_rate;
    uint16_t statusword;
    int fault;
    int run;                /* the law's cyclic tasks run (from their first cycle on; the PD test law: drive enabled) */
};

#define HIL_CTRL_BOOT_MAX 64 /* SDO steps per device */

struct hil_ctrl_sdo_step {
    uint16_t index;
    uint8_t sub, bytes;  /* bytes: value size, 0 = an upload to compare with value */
    uint32_t value;
};

struct hil_ctrl_boot_dev {
    uint8_t node;
    struct hil_ctrl_sdo_step step[HIL_CTRL_BOOT_MAX];
    int n, at;             /* steps, the one outstanding */
};

struct hil_ctrl {
    struct hil_ctrl_params p;
    struct hil_ctrl_boot_dev boot[2]; /* drive, IMU */
    int boot_status;          /* 0 not started / running, 1 booted, < 0 failed */
    char boot_error[160];
    uint64_t sdo_requests;
    struct hil_rx_stats rx;
    uint64_t cycle;           /* cycles started (SYNCs sent) */
    uint8_t sync_counter;
    int have_tpdo1, have_tpdo2, commanded;
    uint16_t statusword;
    double theta, omega, imu_rate;
    int imu_seen;
    uint8_t imu_seq;
    uint64_t imu_last_cycle;
    uint64_t imu_readings;
    int fault;
    double ramp_from;
    uint64_t fault_cycle;
    struct hil_ctrl_signals sig;
    uint64_t missed_inputs, emcy_sent, emcy_received, faults;
    uint8_t hb_state[128];    /* last heartbeat state per node, 0xFF = none */
    unsigned law_status;      /* status code of the law's last fault (0: none yet) */
    hil_ctrl_law law;         /* NULL: the PD test law */
    void *law_ctx;
    int law_running;          /* the law returned 1 once: its tasks run */
};

/* Test-law defaults for the rigid test plant: kp 400, kd 60, k_tip 0,
 * move 0.5 rad from 0.1 s over 0.5 s, imu_timeout 3, ramp 8.4 ms,
 * torque_max 251 Nm, T 1.2 ms. */
void hil_ctrl_params_default(struct hil_ctrl_params *p);
int hil_ctrl_init(struct hil_ctrl *c, const struct hil_ctrl_params *p);
/* Starts the boot (above): appends NMT reset communication and the first
 * SDO request of each device. The boot then advances in hil_ctrl_on_frame
 * with each SDO response; boot_status becomes 1 or negative. */
int hil_ctrl_boot(struct hil_ctrl *c, struct hil_out *out);

/* Replaces the PD test law by `law` (NULL restores it). */
void hil_ctrl_set_law(struct hil_ctrl *c, hil_ctrl_law law, void *ctx);
/* Starts cycle k = c->cycle: NMT at k = 0, SYNC(k). */
int hil_ctrl_tick(struct hil_ctrl *c, struct hil_out *out);
/* Consumes one bus frame; same contract as hil_drive_on_frame. */
int hil_ctrl_on_frame(struct hil_ctrl *c, const struct hil_can_frame *f, struct hil_out *out);
/* Ends the cycle: runs the law on stale inputs if it has not run yet. */
int hil_ctrl_deadline(struct hil_ctrl *c, struct hil_out *out);
/* Sends NMT "stop all". */
int hil_ctrl_stop(struct hil_ctrl *c, struct hil_out *out);
/* Reference r(t) and r'(t) of the test law. */
void hil_ctrl_reference(const struct hil_ctrl_params *p, double t, double *r, double *rd);

#endif
