/* ramp.c - bounded-rate ramp towards a target (see ramp.h). */
#include "frac/ramp.h"

int frac_ramp_step(frac_real x, frac_real target, frac_real rate, frac_real ts, frac_real *y)
{
    frac_real step, diff;
    if (y == NULL) {
        return FRAC_E_NULL;
    }
    if (!FRAC_ISFINITE(rate) || !(rate > FRAC_R(0.0)) || !FRAC_ISFINITE(ts) || !(ts > FRAC_R(0.0))) {
        return FRAC_E_PARAM;
    }
    if (!FRAC_ISFINITE(x) || !FRAC_ISFINITE(target)) {
        return FRAC_E_NONFINITE;
    }
    step = rate * ts;
    diff = target - x;
    if (diff > step) {
        *y = x + step;
    } else if (diff < -step) {
        *y = x - step;
    } else {
        *y = target;
    }
    return FRAC_OK;
}
