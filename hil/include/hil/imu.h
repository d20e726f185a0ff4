/* Emulated tip IMU (LPMS-CU2 read by a 0.6 ms PLC task, seed 004 sec. 8.5).
 *
 * The IMU is clocked by its own acquisition task: every RIG_TIP frame from
 * the plant is one acquisition instant (period acq_period = T/2 = 0.6 ms).
 * A reading starts every reading_cycles acquisitions (4: the CANopen library
 * "needs about four times 0.6 ms to read, write and save the data") and is
 * transmitted reading_cycles acquisitions later, i.e. ~2.4 ms after the tip
 * was sampled; with jitter_prob > 0 a reading is late by one more acquisition
 * with that probability (asynchronous CAN transmission). Each reading is
 * TPDO1 (angular rate x,y,z) + TPDO2 (acceleration x,y,z) with the same
 * sequence number. Axes: the arm turns about z; x is radial (outward), y
 * tangential, z up, so a horizontal arm at rest reads acc = (0, 0, +g).
 * Effects per channel: bias, white Gaussian noise (std per sample) and
 * quantization to a multiple of quant (0: the wire resolution). Values beyond
 * the int16 wire range saturate and set status bit 0. Each RIG_MOTOR (end of
 * a plant step) is answered with RIG_IMU_DONE (hil/canopen.h).
 *
 * CANopen device (CiA 301): the object dictionary hil_imu_od (imu_od.c,
 * hil/imu.eds) holds the readings (0x2000 rate, 0x2001 acceleration, 0x2002
 * sequence, 0x2003 status) and the communication parameters; SDO server on
 * 0x602/0x582 (hil/sdo.h); its TPDOs are the dictionary's 0x18xx/0x1Axx
 * values compiled at NMT start, event-driven (transmission type 254/255:
 * each valid TPDO once per reading; other types are refused with abort
 * 0x06090030), by default the frames of hil/canopen.h. Heartbeat every
 * 0x1017 ms of acquisition-counted time (acq_period per acquisition). */
#ifndef HIL_IMU_H
#define HIL_IMU_H
#include "hil/node.h"
#include "hil/od.h"
#include "hil/pdo.h"
#include "hil/rng.h"
#include "hil/sdo.h"

#define HIL_IMU_MAX_PENDING 16

struct hil_imu_params {
    unsigned reading_cycles;  /* acquisitions per reading and of latency, 1..8 */
    double jitter_prob;       /* probability of one extra acquisition of latency, [0, 1] */
    double gyro_bias, gyro_noise, gyro_quant;  /* [rad/s] */
    double acc_bias, acc_noise, acc_quant;     /* [m/s^2] */
    uint64_t seed;
    double acq_period;        /* acquisition period [s] > 0 (the plant's half cycle, T/2) */
};

struct hil_imu_sample { double rate, acc_r, acc_t; unsigned due; };

extern const struct hil_od hil_imu_od;

struct hil_imu {
    struct hil_imu_params p;
    uint32_t od[HIL_OD_MAX];  /* values of hil_imu_od's entries */
    int16_t ix_rate, ix_acc, ix_seq, ix_status, ix_heartbeat; /* positions in the dictionary */
    struct hil_sdo_server sdo;
    struct hil_pdo_set pdo;   /* TPDOs in effect since NMT start */
    struct hil_rx_stats rx;
    struct hil_rng rng;
    uint8_t nmt;
    double acc_r;             /* radial acceleration from the last RIG_TIPPOS */
    unsigned acq;             /* acquisitions so far */
    struct hil_imu_sample pending[HIL_IMU_MAX_PENDING];
    int npending;
    uint8_t seq;
    unsigned since_heartbeat;
    uint64_t readings_sent;
};

/* Thesis defaults: 4 acquisitions per reading, no jitter, no noise/bias,
 * wire quantization, seed 1, acquisitions every 0.6 ms. */
void hil_imu_params_default(struct hil_imu_params *p);
/* Validates p, seeds the generator, appends the boot-up heartbeat.
 * Returns HIL_OK or HIL_E_ARG (node untouched). */
int hil_imu_init(struct hil_imu *m, const struct hil_imu_params *p, struct hil_out *out);
/* Consumes one bus frame; same contract as hil_drive_on_frame. */
int hil_imu_on_frame(struct hil_imu *m, const struct hil_can_frame *f, struct hil_out *out);

/* The IMU's dictionary as the SDO server and PDOs see it. */
struct hil_od_dev hil_imu_od_dev(struct hil_imu *m);

#endif
