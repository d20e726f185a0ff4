/*
 * ramp.h - bounded-rate ramp of a value towards a target.
 *
 * y = x + clamp(target - x, -rate*Ts, +rate*Ts): one cycle of a rate
 * limiter, the fault reaction of seed 004 part 2 (9.2): after a sensor
 * fault the torque setpoint is ramped to zero instead of stepped, since a
 * torque step would excite the ~3 Hz first beam mode.
 *
 * Stateless: the caller keeps x (the last output). O(1), no storage.
 */
#ifndef FRAC_RAMP_H
#define FRAC_RAMP_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Moves x towards target by at most rate*ts and writes the result to *y;
 * reaching the target exactly when it is within one step.
 * Returns FRAC_OK, FRAC_E_NULL (y NULL), FRAC_E_PARAM (rate or ts not
 * finite and positive), FRAC_E_NONFINITE (x or target not finite); on an
 * error *y is left unchanged.
 */
int frac_ramp_step(frac_real x, frac_real target, frac_real rate, frac_real ts, frac_real *y);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_RAMP_H */
