/* CANopen-style frames of the rig (CiA 301 communication, CiA 402 drive).
 *
 * Nodes: the drive (node 1), the IMU (node 2), the controller (node 3, the
 * NMT master and SYNC producer). Pre-defined connection set COB-IDs:
 *
 *   frame              COB-ID       DLC  content (little endian)
 *   NMT                0x000         2   command specifier u8, node id u8 (0 = all)
 *   SYNC               0x080         1   counter u8 (1..240, CiA 301 sync counter)
 *   EMCY               0x080+node    8   error code u16, error register u8, info u8[5]
 *   drive RPDO1        0x200+1       6   controlword u16, target torque i32 [mNm]
 *   drive TPDO1        0x180+1       6   statusword u16, position actual i32 [increments]
 *   drive TPDO2        0x280+1       8   velocity actual i32 [urad/s], torque actual i32 [mNm]
 *   IMU TPDO1          0x180+2       8   angular rate x,y,z i16 [mrad/s], seq u8, status u8
 *   IMU TPDO2          0x280+2       8   acceleration x,y,z i16 [mm/s^2], seq u8, status u8
 *   heartbeat          0x700+node    1   NMT state u8
 *
 * The target torque is INTEGER32 in mNm on the driven side, not the INTEGER16
 * per-mille of rated torque of CiA 402 object 0x6071: with a rated torque of
 * 95.7 Nm the per-mille unit (0.0957 Nm) would quantize the command far more
 * than the real set-up does (the B&R PLC writes a REAL, ACOPOS ParID 586).
 * Positions are encoder increments of a 2^20 counts/rev absolute encoder
 * (seed 004 Table G.1: AksIM class), driven side.
 *
 * Rig-internal frames (0x6F0..0x6F3) stand for the physical wiring between the
 * emulated drive, arm and IMU (shaft torque, shaft angle, tip motion); no
 * controller reads them. Payload float32 pairs:
 *   RIG_TORQUE 0x6F0  drive -> plant   torque at the start and end of the cycle [Nm]
 *   RIG_MOTOR  0x6F1  plant -> drive   motor-side angle [rad], velocity [rad/s]
 *   RIG_TIP    0x6F2  plant -> IMU     tip angular rate [rad/s], tangential acc [m/s^2]
 *   RIG_TIPPOS 0x6F3  plant -> IMU/log tip angle [rad], radial (centripetal) acc [m/s^2]
 * and RIG_IMU_DONE 0x6F4 (DLC 2, acquisition counter u16): the IMU's answer
 * to RIG_MOTOR, sent after the TPDOs of that step's acquisitions. It is the
 * co-simulation "step complete" handshake a controller pacing in lockstep over
 * a multi-process bus waits for, so no IMU reading slips into the next cycle.
 *
 * The codec functions validate: decoders return HIL_E_UNKNOWN_ID for a
 * different identifier and HIL_E_DLC for a wrong length, encoders HIL_E_RANGE
 * for non-finite values (finite out-of-range values saturate and say so). */
#ifndef HIL_CANOPEN_H
#define HIL_CANOPEN_H
#include <stdint.h>
#include "hil/can.h"

#define HIL_NODE_DRIVE 1u
#define HIL_NODE_IMU 2u
#define HIL_NODE_CTRL 3u

#define HIL_COB_NMT 0x000u
#define HIL_COB_SYNC 0x080u
#define HIL_COB_EMCY(n) (0x080u + (n))
#define HIL_COB_TPDO1(n) (0x180u + (n))
#define HIL_COB_RPDO1(n) (0x200u + (n))
#define HIL_COB_TPDO2(n) (0x280u + (n))
#define HIL_COB_HEARTBEAT(n) (0x700u + (n))
#define HIL_COB_RIG_TORQUE 0x6F0u
#define HIL_COB_RIG_MOTOR 0x6F1u
#define HIL_COB_RIG_TIP 0x6F2u
#define HIL_COB_RIG_TIPPOS 0x6F3u
#define HIL_COB_RIG_IMU_DONE 0x6F4u

/* NMT command specifiers and states (CiA 301). */
#define HIL_NMT_START 0x01u
#define HIL_NMT_STOP 0x02u
#define HIL_NMT_PREOP 0x80u
#define HIL_NMT_RESET_NODE 0x81u
#define HIL_NMT_RESET_COMM 0x82u
#define HIL_NMT_STATE_BOOTUP 0x00u
#define HIL_NMT_STATE_STOPPED 0x04u
#define HIL_NMT_STATE_OPERATIONAL 0x05u
#define HIL_NMT_STATE_PREOP 0x7Fu

/* EMCY error codes used by the rig (CiA 301 / CiA 402 tables). */
#define HIL_EMCY_NO_ERROR 0x0000u
#define HIL_EMCY_SENSOR 0x7300u       /* controller: IMU data stale (watchdog) */
#define HIL_EMCY_HEARTBEAT 0x8130u    /* life guard / heartbeat error */
#define HIL_EMCY_RPDO_TIMEOUT 0x8250u /* drive: no setpoint within the timeout */
#define HIL_EMCY_BUS_OFF_RECOVERED 0x8140u /* recovered from bus off */
#define HIL_EMCY_OVERTEMP 0x4310u      /* drive: excess temperature drive (CiA 402), i^2t above its trip */

/* CiA 402 controlword bits and commands, statusword masks. */
#define HIL_CW_SHUTDOWN 0x0006u
#define HIL_CW_SWITCH_ON 0x0007u
#define HIL_CW_ENABLE_OP 0x000Fu
#define HIL_CW_DISABLE_VOLTAGE 0x0000u
#define HIL_CW_QUICK_STOP 0x0002u
#define HIL_CW_FAULT_RESET 0x0080u
#define HIL_SW_INTERNAL_LIMIT 0x0800u /* bit 11: torque limit active */
#define HIL_SW_FAULT 0x0008u

/* Units on the wire. */
#define HIL_ENC_COUNTS_PER_REV 1048576.0 /* 2^20 */
#define HIL_TORQUE_LSB 1e-3              /* Nm per count */
#define HIL_VEL_LSB 1e-6                 /* rad/s per count */
#define HIL_GYRO_LSB 1e-3                /* rad/s per count */
#define HIL_ACC_LSB 1e-3                 /* m/s^2 per count */

/* IMU status bits. */
#define HIL_IMU_ST_SATURATED 0x01u

struct hil_drive_rpdo { uint16_t controlword; int32_t torque_mnm; };
struct hil_drive_tpdo1 { uint16_t statusword; int32_t position_inc; };
struct hil_drive_tpdo2 { int32_t velocity_urads; int32_t torque_mnm; };
struct hil_imu_tpdo { int16_t xyz[3]; uint8_t seq; uint8_t status; };
struct hil_emcy { uint16_t code; uint8_t error_register; uint8_t info[5]; };

int hil_co_sync_encode(struct hil_can_frame *f, uint8_t counter);
int hil_co_sync_decode(const struct hil_can_frame *f, uint8_t *counter);
int hil_co_nmt_encode(struct hil_can_frame *f, uint8_t command, uint8_t node);
int hil_co_nmt_decode(const struct hil_can_frame *f, uint8_t *command, uint8_t *node);
int hil_co_heartbeat_encode(struct hil_can_frame *f, uint8_t node, uint8_t state);
/* Decodes any heartbeat 0x701..0x77F; *node receives the producer. */
int hil_co_heartbeat_decode(const struct hil_can_frame *f, uint8_t *node, uint8_t *state);
int hil_co_emcy_encode(struct hil_can_frame *f, uint8_t node, const struct hil_emcy *e);
/* Decodes any EMCY 0x081..0x0FF; *node receives the producer. */
int hil_co_emcy_decode(const struct hil_can_frame *f, uint8_t *node, struct hil_emcy *e);

int hil_co_drive_rpdo_encode(struct hil_can_frame *f, const struct hil_drive_rpdo *p);
int hil_co_drive_rpdo_decode(const struct hil_can_frame *f, struct hil_drive_rpdo *p);
int hil_co_drive_tpdo1_encode(struct hil_can_frame *f, const struct hil_drive_tpdo1 *p);
int hil_co_drive_tpdo1_decode(const struct hil_can_frame *f, struct hil_drive_tpdo1 *p);
int hil_co_drive_tpdo2_encode(struct hil_can_frame *f, const struct hil_drive_tpdo2 *p);
int hil_co_drive_tpdo2_decode(const struct hil_can_frame *f, struct hil_drive_tpdo2 *p);
/* which = 1 (angular rate, TPDO1) or 2 (acceleration, TPDO2). */
int hil_co_imu_encode(struct hil_can_frame *f, int which, const struct hil_imu_tpdo *p);
int hil_co_imu_decode(const struct hil_can_frame *f, int which, struct hil_imu_tpdo *p);

/* Rig-internal float32 pair frames (cob = HIL_COB_RIG_*). */
int hil_co_rig_encode(struct hil_can_frame *f, uint32_t cob, double a, double b);
int hil_co_rig_decode(const struct hil_can_frame *f, uint32_t cob, double *a, double *b);

/* RIG_IMU_DONE with the IMU's acquisition counter (mod 2^16). */
int hil_co_imu_done_encode(struct hil_can_frame *f, uint16_t acquisitions);
int hil_co_imu_done_decode(const struct hil_can_frame *f, uint16_t *acquisitions);

/* Physical value -> saturated integer count: round(x / lsb) clamped to
 * [lo, hi]. Returns HIL_OK, 1 when clamped, HIL_E_RANGE when x is not finite
 * (then *out = 0). */
int hil_co_quantize(double x, double lsb, int64_t lo, int64_t hi, int64_t *out);

#endif
