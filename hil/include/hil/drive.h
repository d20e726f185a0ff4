/* Emulated servo drive (ACOPOS in torque mode, seed 004 sec. 8.2) as a CiA 402
 * node in cyclic synchronous torque mode.
 *
 * Per SYNC k the drive
 *   1. sends TPDO1 (statusword, position actual) and TPDO2 (velocity actual,
 *      torque actual) from the shaft state at t_k (last RIG_MOTOR frame);
 *   2. latches the latest RPDO target torque into its delay line; the command
 *      the controller sent during cycle j acts on the shaft over
 *      [t_{j+delay}, t_{j+delay+1}) (seed 004: 4 samples at T = 1.2 ms);
 *   3. limits it: peak torque while the thermal estimate (first-order filter
 *      of tau^2, time constant thermal_tau) is below rated^2, rated torque
 *      otherwise (i^2 t protection; statusword bit 11 while limiting);
 *   4. runs the current loop, a first-order lag
 *      tau(t) = c + (tau0 - c) exp(-t / tau_current), over the cycle and sends
 *      RIG_TORQUE(tau(t_k), tau(t_{k+1})) to the plant (ZOH on the command);
 *   5. the shaft receives gain * dz(tau), dz the torque dead zone of half
 *      width `deadzone` (dz(x) = 0 for |x| <= deadzone, else x - deadzone
 *      sgn(x)), applied to both ends of the RIG_TORQUE ramp. Both are effects
 *      (default gain 1, deadzone 0): a motor torque constant that differs from
 *      the drive's value and a power-stage dead zone, so the drive's reported
 *      torque actual (TPDO2) stays tau, without them.
 * Torque is applied only in "operation enabled" with mode of operation 10
 * (cyclic synchronous torque); any other state commands 0.
 *
 * CANopen device (CiA 301 / CiA 402): the object dictionary hil_drive_od
 * (drive_od.c, hil/drive.eds) holds every parameter and process value; an
 * SDO server (hil/sdo.h) on 0x601/0x581 serves it in pre-operational and
 * operational; the PDOs are those of the dictionary's 0x14xx/0x16xx/0x18xx/
 * 0x1Axx values compiled at NMT start (hil/pdo.h; TPDOs synchronous only,
 * transmission type 1..240), by default RPDO1 = controlword + 0x2071 target
 * torque [mNm], TPDO1 = statusword + position, TPDO2 = velocity + 0x2077
 * torque actual [mNm] (the frames of hil/canopen.h). A received frame on an
 * RPDO identifier of another length than its mapping is counted bad_dlc and
 * ignored. Heartbeat every 0x1017 ms of SYNC-counted time (0: none).
 * Torque limit: the i^2t limit (3.) and 0x6072 (per mille of 0x6076).
 * Power state machine (CiA 402 fig. 13) on 0x6040: shutdown, switch on,
 * enable operation, disable operation, disable voltage, quick stop (0x605A =
 * 6: stay in quick stop active, torque 0, enable operation resumes; 2: torque
 * 0, then switch on disabled at the next SYNC), fault reset (rising edge of
 * bit 7: clears 0x603F / 0x1001, EMCY 0x0000; a fault whose cause persists
 * stays). Statusword per CiA 402 table 30, bit 4 voltage enabled, 9 remote,
 * 11 internal limit (torque limited), 12 (CST) the drive follows the target.
 * Faults (fault reaction: torque command 0, within the cycle; then FAULT),
 * each an EMCY with the CiA 402 code, 0x603F = that code and 0x1001 bits:
 *   no RPDO for rpdo_timeout SYNCs while enabled: 0x8250, communication;
 *   i^2t estimate above 0x2101 (per mille of rated^2): 0x4310 excess
 *   temperature drive, temperature (reset refused while above);
 *   bus-off recovered: EMCY 0x8140, communication (no fault by itself: while
 *   bus-off an enabled drive has no RPDO and faults with 0x8250).
 * NMT start/stop/pre-op/reset node/reset communication are obeyed (reset
 * communication restores 0x1000-0x1FFF, reset node the whole dictionary). A
 * following error (CiA 402 0x8611) does not exist in torque mode: there is no
 * position demand to follow.
 * Encoder effects: the position is counted (floor) with 2^encoder_bits counts
 * per revolution and sent in the 2^20 wire unit; with velocity_from_encoder
 * the velocity actual is the difference of two counted positions over T
 * instead of the shaft's velocity. */
#ifndef HIL_DRIVE_H
#define HIL_DRIVE_H
#include "hil/node.h"
#include "hil/od.h"
#include "hil/pdo.h"
#include "hil/sdo.h"

#define HIL_DRIVE_MAX_DELAY 32

enum hil_cia402_state {
    HIL_CIA402_SWITCH_ON_DISABLED = 0,
    HIL_CIA402_READY_TO_SWITCH_ON,
    HIL_CIA402_SWITCHED_ON,
    HIL_CIA402_OPERATION_ENABLED,
    HIL_CIA402_QUICK_STOP_ACTIVE,
    HIL_CIA402_FAULT
};

struct hil_drive_params {
    double T;              /* controller cycle [s], > 0 */
    unsigned delay;        /* torque path delay in cycles, 1..HIL_DRIVE_MAX_DELAY */
    double tau_current;    /* current-loop time constant [s], >= 0 (0: ideal) */
    double torque_rated;   /* [Nm] driven side, > 0 */
    double torque_peak;    /* [Nm] driven side, >= torque_rated */
    double thermal_tau;    /* [s] > 0 */
    unsigned rpdo_timeout; /* SYNCs without RPDO before FAULT while enabled, >= 1 */
    unsigned encoder_bits; /* encoder resolution 2^bits counts/rev, 1..20 (effect; wire is 2^20) */
    unsigned velocity_from_encoder; /* 1: velocity actual = encoder difference / T (effect) */
    double deadzone;       /* shaft torque dead zone half width [Nm], >= 0 (effect; 0: off) */
    double gain;           /* shaft torque / drive torque, > 0 (effect; 1: off) */
};

/* Positions of the objects the drive code reads and refreshes (resolved at init). */
enum hil_drive_obj {
    HIL_DRV_ERROR_REGISTER, HIL_DRV_HEARTBEAT, HIL_DRV_TARGET_MNM, HIL_DRV_TORQUE_MNM, HIL_DRV_I2T,
    HIL_DRV_I2T_TRIP, HIL_DRV_ERROR_CODE, HIL_DRV_CONTROLWORD, HIL_DRV_STATUSWORD, HIL_DRV_QUICK_STOP_OPTION,
    HIL_DRV_MODE, HIL_DRV_MODE_DISPLAY, HIL_DRV_POSITION, HIL_DRV_VELOCITY, HIL_DRV_TARGET_TORQUE,
    HIL_DRV_MAX_TORQUE, HIL_DRV_RATED_TORQUE, HIL_DRV_TORQUE_ACTUAL, HIL_DRV_NOBJ
};

extern const struct hil_od hil_drive_od;

struct hil_drive {
    struct hil_drive_params p;
    uint32_t od[HIL_OD_MAX];              /* values of hil_drive_od's entries */
    int16_t ix[HIL_DRV_NOBJ];             /* positions of enum hil_drive_obj */
    struct hil_sdo_server sdo;
    struct hil_pdo_set pdo;               /* PDOs in effect since NMT start */
    struct hil_rx_stats rx;
    uint8_t nmt;
    enum hil_cia402_state state;
    uint16_t last_controlword;
    double cmd_latest;                    /* last target torque received [Nm] */
    double line[HIL_DRIVE_MAX_DELAY];     /* latched commands, newest first */
    double tau_act;                       /* current-loop output at t_k [Nm] */
    double thermal;                       /* filtered tau^2 [Nm^2] */
    int limiting;
    double theta, omega;                  /* shaft state from the plant */
    unsigned since_rpdo, since_heartbeat;
    struct hil_out *out_now;              /* where a write's actions send frames (during a call) */
    int64_t last_counts;                  /* encoder counts at the previous SYNC */
    uint64_t syncs, emcy_sent;
    uint64_t tx_syncs;                    /* SYNCs since NMT start (TPDO transmission types) */
    int bus_off;
};

/* Defaults of the thesis set-up: T 1.2 ms, delay 4, tau_current 0.25 ms
 * (5 current-controller cycles of 50 us), rated 95.7 Nm, peak 251 Nm,
 * thermal_tau 1 s, rpdo_timeout 3, 20-bit encoder, velocity from the
 * shaft, gain 1, no dead zone. */
void hil_drive_params_default(struct hil_drive_params *p);

/* Validates p and resets the node (NMT boot-up -> pre-operational, CiA 402
 * "switch on disabled", the dictionary at its power-on values with 0x6076 =
 * torque_rated and 0x6072 = torque_peak per mille); appends the boot-up
 * heartbeat to out.
 * Returns HIL_OK or HIL_E_ARG (node untouched). */
int hil_drive_init(struct hil_drive *d, const struct hil_drive_params *p, struct hil_out *out);

/* Consumes one bus frame. Returns HIL_OK when consumed, HIL_E_UNKNOWN_ID for
 * frames of other nodes (counted in rx.other when they are in the
 * dictionary), or the negative validation code (frame ignored). */
int hil_drive_on_frame(struct hil_drive *d, const struct hil_can_frame *f, struct hil_out *out);

/* Bus-off episode of the drive's CAN controller (the rig's bus-off effect):
 * off = 1 when it goes bus-off, 0 when it has recovered; on recovery the
 * drive sends EMCY 0x8140 (appended to out). The rig stops its transmissions
 * and receptions meanwhile; the drive keeps running on its own cycle.
 * Returns HIL_OK or HIL_E_ARG. */
int hil_drive_set_bus_off(struct hil_drive *d, int off, struct hil_out *out);

/* CiA 402 statusword of the current state. */
uint16_t hil_drive_statusword(const struct hil_drive *d);

/* The drive's dictionary as the SDO server and PDOs see it. */
struct hil_od_dev hil_drive_od_dev(struct hil_drive *d);

#endif
