/*
 * trajlut.h - time-indexed multi-channel trajectory playback with
 * per-channel lead/lag, for the lookup-table feedforward of seed 004.
 *
 * The offline feedforward (rbFFC/ibFFC, thesis Ch. 4) produces reference
 * signals sampled in time: theta_M*, dtheta_M*, dpsi_L*, tau_M* (notes
 * 004b section 4.5: "stored in advance and interpolated in real time").
 * This object plays them back at the controller period Ts: at cycle k,
 * channel c returns its table value at time
 *        t = k Ts + lead_c Ts,
 * interpolated (frac/lut.h, linear or monotone cubic) on the table grid
 * t0 + i dt. Thesis Sec. 8.6 / notes 004b section 7.7 and check 21:
 *  - torque sent d_i samples early: lead = +d_i gives u_bar*[k] = u*[k + d_i];
 *  - IMU reference delayed by d_o: lead = -d_o gives y_bar_3*[k] = y_3*[k - d_o];
 *  - the encoder references theta_M*, dtheta_M* are not shifted (lead 0).
 * Segments (reported per cycle from the unshifted time k Ts): before the
 * table (rest at the first sample), pre-actuation (table time before the
 * nominal motion start, where stable inversion already moves the hub,
 * thesis Fig. 8.6), motion, post-actuation (after the nominal end, inside
 * the table), after the table (rest at the last sample). Outside the
 * table every channel holds its end value and the step reports
 * FRAC_W_CLAMPED.
 * Storage: the channel arrays (n values each) are held by pointer; cubic
 * interpolation needs channels * n frac_real of slope storage.
 * Cost per cycle: channels O(1) uniform lookups.
 */
#ifndef FRAC_TRAJLUT_H
#define FRAC_TRAJLUT_H

#include "frac/lut.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FRAC_TRAJLUT_MAX_CH 8

typedef enum frac_trajlut_segment {
    FRAC_TRAJLUT_BEFORE = 0, /* before the first table sample */
    FRAC_TRAJLUT_PRE = 1,    /* pre-actuation: in the table, before t_motion_start */
    FRAC_TRAJLUT_MOTION = 2, /* t_motion_start <= t <= t_motion_end */
    FRAC_TRAJLUT_POST = 3,   /* post-actuation: in the table, after t_motion_end */
    FRAC_TRAJLUT_AFTER = 4   /* after the last table sample */
} frac_trajlut_segment;

typedef struct frac_trajlut_params {
    size_t channels;              /* 1..FRAC_TRAJLUT_MAX_CH */
    size_t n;                     /* samples per channel, >= 2 */
    const frac_real *const *data; /* channels pointers to n samples each */
    frac_real t0, dt;             /* table time of sample 0 and table sample time (s), dt > 0 */
    frac_real Ts;                 /* controller period (s) > 0; cycle k is at time k Ts */
    const long *lead;             /* per channel lead in controller samples (+ early, - late); NULL: 0 */
    frac_real t_motion_start;     /* nominal motion interval, t0 <= start <= end */
    frac_real t_motion_end;
    int interp;                   /* FRAC_LUT_LINEAR or FRAC_LUT_CUBIC */
} frac_trajlut_params;

typedef struct frac_trajlut {
    frac_lut1 lut[FRAC_TRAJLUT_MAX_CH];
    long lead[FRAC_TRAJLUT_MAX_CH];
    size_t channels;
    frac_real Ts, t_lo, t_hi, t_ms, t_me;
    unsigned long k; /* next cycle of frac_trajlut_step */
    int ready;
} frac_trajlut;

/*
 * Validates and builds one table per channel. `slopes`: channels * n
 * entries for FRAC_LUT_CUBIC, NULL allowed for linear.
 * Returns FRAC_OK, FRAC_E_NULL, FRAC_E_DIM (channels or n out of range),
 * FRAC_E_TS (dt or Ts not finite and positive), FRAC_E_PARAM (t0 or the
 * motion interval invalid, unknown interp), FRAC_E_NONFINITE (a sample),
 * FRAC_E_STORAGE (cubic without slopes).
 */
int frac_trajlut_init(frac_trajlut *tl, const frac_trajlut_params *p, frac_real *slopes);

/*
 * Values of cycle k (stateless apart from the lookup caches): out[c] for
 * every channel, *segment (may be NULL). Returns FRAC_OK, FRAC_W_CLAMPED
 * (some channel read outside its table), FRAC_E_NULL, FRAC_E_NOT_INIT.
 */
int frac_trajlut_eval(frac_trajlut *tl, unsigned long k, frac_real *out, int *segment);

/* frac_trajlut_eval at the internal cycle counter, then counter + 1. */
int frac_trajlut_step(frac_trajlut *tl, frac_real *out, int *segment);

/* Restarts playback at cycle k. Returns FRAC_OK, FRAC_E_NULL, FRAC_E_NOT_INIT. */
int frac_trajlut_seek(frac_trajlut *tl, unsigned long k);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_TRAJLUT_H */
