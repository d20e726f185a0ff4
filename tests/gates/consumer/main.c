/* Installed-package consumer: a ramp step through the installed headers and library. */
#include <stdio.h>
#include "frac/ramp.h"

int main(void)
{
    frac_real y = FRAC_R(0.0);
    int st = frac_ramp_step(FRAC_R(1.0), FRAC_R(0.0), FRAC_R(10.0), FRAC_R(0.01), &y);
    printf("libfrac %s: ramp %s, y = %g\n", frac_version(), frac_status_str(st), (double)y);
    return (st == FRAC_OK && y > 0.89 && y < 0.91) ? 0 : 1;
}
