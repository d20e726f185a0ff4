/*
 * ImuRead.h - the IMU acquisition program of Cyclic #2 (0.6 ms), seed 004
 * part 2 (notes 8.5): the LPMS-CU2 tip IMU is read over CAN through the
 * X20IF2772 module with LibAsCanOpen2_ST. The program takes the gyro rate
 * of the latest frame from the input image, scales it to rad/s and
 * publishes it with a sample counter that ArmCtrl's Watchdog monitors; a
 * frame with a non-finite value is dropped (the counter does not advance,
 * so a persistent fault shows up as a stale sensor).
 * The thesis's acquisition latency (~4 x 0.6 ms, d_o = 3 cycles of 1.2 ms)
 * belongs to the CAN path and is emulated by the HIL rig, not here.
 */
#ifndef IMUREAD_H
#define IMUREAD_H

#include "FracCtrl.h"
#include "plc_rt.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct imuread_inputs {
    REAL RawRate;       /* gyro rate of the latest CAN frame, sensor units */
    UDINT FrameCounter; /* incremented by the CAN interface for every frame */
} imuread_inputs;

typedef struct imuread_outputs {
    REAL TipRate;     /* dpsi_L [rad/s] */
    UDINT ImuCounter; /* incremented for every accepted sample */
    UDINT Dropped;    /* frames rejected (non-finite) */
} imuread_outputs;

typedef struct imuread {
    REAL scale;       /* rad/s per sensor unit */
    imuread_inputs in;
    imuread_outputs out;
    UDINT frame_old;
    plc_io io_in, io_out;
} imuread;

/* Fills `prog` (name "ImuRead"); scale converts sensor units to rad/s. */
void imuread_program(imuread *m, plc_program *prog, REAL scale, imuread_inputs *image_in,
                     imuread_outputs *image_out);

void imuread_init(void *ctx);
void imuread_cyclic(void *ctx);

#ifdef __cplusplus
}
#endif

#endif /* IMUREAD_H */
