/*
 * traj.h - sin^2 point-to-point trajectory with derivatives up to the 4th.
 *
 * Seed 004 (M. Wang, TUM 2022), Sec. 4.1, (4.1)-(4.7): a joint-space PTP
 * motion from q_s to q_e in three phases (accelerate, cruise, brake) with
 * the acceleration profile ddq = ddq_m sin^2(pi tau / t_a), tau = t - t_s
 * the local time. Corrections applied (notes 004b section 2.1, erratum 6):
 *  - (4.5): velocity and position of the acceleration phase carry ddq_m,
 *    not dq_m: dq = ddq_m (tau/2 - t_a/(4 pi) sin(2 pi tau/t_a)),
 *    q = ddq_m (tau^2/4 + t_a^2/(8 pi^2)(cos(2 pi tau/t_a) - 1));
 *  - (4.7): the braking acceleration is -ddq_m sin^2(pi (tau - t_b)/t_a).
 * Timing: t_a = 2 dq_m / ddq_m (4.1), t_e_min = s_e/dq_m + t_a (4.3),
 * t_b = t_e - t_a. A requested duration t_e > t_e_min keeps ddq_m and
 * lowers dq_m by (4.4), then recomputes t_a by (4.1). A distance too short
 * to reach dq_m (s_e < dq_m t_a, no cruise phase; not treated in the
 * thesis) lowers dq_m to sqrt(s_e ddq_m / 2), so that t_b = t_a.
 * Derivatives: jerk = ddq_m (pi/t_a) sin(2 pi tau/t_a) (continuous),
 * snap = ddq_m (2 pi^2/t_a^2) cos(2 pi tau/t_a) (jumps at the phase
 * borders by 2 pi^2 ddq_m / t_a^2).
 * q_e < q_s runs the same profile mirrored. Before t_s the output is q_s
 * at rest, after t_s + t_e it is q_e at rest.
 */
#ifndef FRAC_TRAJ_H
#define FRAC_TRAJ_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct frac_traj_params {
    frac_real q_s;      /* start position */
    frac_real q_e;      /* end position */
    frac_real dq_max;   /* maximum velocity dq_m > 0 */
    frac_real ddq_max;  /* maximum acceleration ddq_m > 0 */
    frac_real t_start;  /* absolute start time t_s */
    frac_real duration; /* requested t_e; <= 0 selects the minimum t_e_min */
} frac_traj_params;

typedef struct frac_traj {
    frac_real q_s, s_e, sign; /* start, |q_e - q_s|, direction +-1 */
    frac_real dq_m, ddq_m;    /* effective peak velocity and acceleration */
    frac_real t_s, t_a, t_b, t_e; /* start (absolute), then local phase times */
    int ready;
} frac_traj;

/*
 * Plans the motion. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_PARAM (non-finite
 * value, dq_max or ddq_max <= 0, or 0 < duration < the minimum duration).
 */
int frac_traj_init(frac_traj *tr, const frac_traj_params *p);

/*
 * Evaluates at absolute time t: d[0] = q, d[1] = dq, d[2] = ddq,
 * d[3] = jerk, d[4] = snap (4th derivative). At a phase border the value
 * of the later phase is returned (right limit).
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT, FRAC_E_NONFINITE (t not
 * finite; d untouched).
 */
int frac_traj_eval(const frac_traj *tr, frac_real t, frac_real d[5]);

/* Local phase times: t_a (end of acceleration), t_b (start of braking), t_e (end). */
int frac_traj_times(const frac_traj *tr, frac_real *t_a, frac_real *t_b, frac_real *t_e);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_TRAJ_H */
