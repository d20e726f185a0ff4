/* The emulated arm as a bus node.
 *
 * Each RIG_TORQUE(tau0, tau1) frame from the drive advances the plant by one
 * controller cycle T, with the shaft torque interpolated linearly from tau0
 * to tau1, in two halves of T/2 (the IMU acquisition period, 0.6 ms). After
 * each half the plant sends RIG_TIPPOS(tip angle, radial acc) and
 * RIG_TIP(tip rate, tangential acc); after the second also RIG_MOTOR(shaft
 * angle, shaft velocity), the state at t_{k+1} the drive reports at the next
 * SYNC. Integration: rigid and twomass classical RK4, `substeps` steps per
 * half cycle; arm the table's exact ZOH steps (below).
 *
 * Three named plants:
 *  - "rigid" (TEST plant): one rigid inertia J with viscous friction b,
 *        J theta'' = tau - b theta',  tip angle psi = theta;
 *  - "twomass": the rbFFC design model of seed 004 (4.8)-(4.12): motor side
 *    inertia I_M (driven side, n^2 I_m) joined by the gear spring c_s to the
 *    rigid link I_L, motor friction tau_f(theta_M') by frac/friction.h
 *    ((5.2) linear or (5.4) Stribeck, tanh-smoothed):
 *        I_M theta_M'' = tau - c_s (theta_M - psi) - tau_f(theta_M'),
 *        I_L psi''     = c_s (theta_M - psi).
 * The tip is at radius L on the link: tangential acc L psi'', radial
 * -L psi'^2.
 * Effects of "twomass" (each off at 0):
 *  - backlash: total play b of the gear, the spring acts on the dead-zone
 *    twist dz(theta_M - psi) = delta - clamp(delta, -b/2, b/2);
 *  - extra (unmodelled) mode: an inertia I_e on the link through a spring of
 *    natural frequency f_e (k_e = I_e (2 pi f_e)^2) with damping ratio zeta_e:
 *        I_e (q_e'' + psi'') = -k_e q_e - d_e q_e',  d_e = 2 zeta_e sqrt(k_e I_e),
 *    acting back on the link (I_L psi'' = spring + k_e q_e + d_e q_e'); the
 *    tip (IMU) then sees psi + q_e;
 *  - fractional Kelvin-Voigt damping of the gear spring: torque
 *    kv_damping * D^kv_order (theta_M - psi) added to the spring torque, the
 *    operator by Grunwald-Letnikov (frac/fo_gl.h) at the RK4 substep with
 *    kv_memory terms, evaluated once per substep and held over it (an
 *    explicit coupling, first order in the substep). The flexible beam of the
 *    issue carries this damping along its length; here the only compliance
 *    is the gear's.
 *  - "arm": the flexible arm of the design models, seed 004 (3.103) (drive +
 *    pseudo-spectral Timoshenko beam, full order n = 4 + 4 N), read from the
 *    plant table `table` that `fracdesign model arm --full --save-plant`
 *    writes (docs/hil.md): x <- Ad x + Bd (tau - tau_f(theta_M')) + Bd1 s
 *    per step h of the table (Ad, Bd: exact ZOH of the continuous arm at h;
 *    Bd1 = int_0^h e^{A (h - r)} B (r - h/2) dr, the exact response to the
 *    torque's ramp of slope s about its mid-step value), h dividing T/2 in
 *    at most HIL_PLANT_ARM_SUBMAX steps; tau is the shaft torque at the
 *    middle of the step (linear over the cycle as above), so the drive's
 *    torque is integrated exactly for any h (a table without Bd1, written
 *    before it existed, holds the mid-step value: error O(h^2) in the
 *    slope's part); tau_f the motor friction by frac/friction.h, held over
 *    the step at the mean of the step's start and end velocities (the
 *    trapezoidal rule, second order in h: the end velocity is
 *    v_free - C_2 Bd tau_f, solved by two fixed-point corrections of the
 *    explicit value, each contracting by C_2 Bd |tau_f'| / 2 = 0.006 at
 *    Table 8.6's friction and h = T/8; the explicit value where the second
 *    does not halve the first). The
 *    friction's time constant I_M / (b0 k) = 13 ms at Table 8.6 is ~85 h;
 *    the explicit rule (first order) left a motor-velocity error of ~3 x
 *    the wire's step at h = T/8 on seed 004's arm. The steps of a half
 *    cycle are composed (Ad^k precomputed at init): one n x n product per
 *    half cycle, the velocities from the rows C_2 Ad^k.
 *    Outputs C x: theta_M, theta_M', tip angle psi_L, tip rate psi_L'; tip
 *    tangential acceleration L psi_L'' with psi_L'' = C_4 (Ac x + Bc u).
 *    backlash, the extra mode and Kelvin-Voigt damping are twomass effects:
 *    the arm plant refuses them (init fails, message in err). */
#ifndef HIL_PLANT_H
#define HIL_PLANT_H
#include "frac/fo_gl.h"
#include "frac/friction.h"
#include "hil/node.h"

enum hil_plant_model { HIL_PLANT_RIGID = 0, HIL_PLANT_TWOMASS = 1, HIL_PLANT_ARM = 2 };

#define HIL_PLANT_KV_MAX 1000 /* most Grunwald-Letnikov terms of the Kelvin-Voigt effect */
#define HIL_PLANT_ARM_NMAX 128 /* most states of the arm plant (N <= 31) */
#define HIL_PLANT_ARM_SUBMAX 32 /* most ZOH steps per half cycle (h >= T/64) */
#define HIL_PLANT_TABLE_MAX (8u << 20) /* largest plant table file [bytes] */
#define HIL_PLANT_PATH_MAX 256

struct hil_plant_params {
    int model;         /* enum hil_plant_model */
    double T;          /* controller cycle [s] > 0 */
    double J;          /* rigid: inertia on the driven side [kg m^2] > 0 */
    double b;          /* rigid: viscous friction [Nm s/rad] >= 0 */
    double I_M, I_L;   /* twomass: motor (driven side) and link inertia [kg m^2] > 0 */
    double c_s;        /* twomass: gear stiffness [Nm/rad] > 0 */
    frac_friction_params friction; /* twomass: motor friction (frac/friction.h) */
    double backlash;   /* twomass: total gear play [rad] >= 0 */
    double extra_inertia, extra_hz, extra_zeta; /* twomass: extra mode (I_e = 0: off) */
    double kv_damping;   /* twomass: fractional damping [Nm s^a/rad] >= 0 (0: off) */
    double kv_order;     /* its order a, (0, 1] */
    unsigned kv_memory;  /* GL terms, 1..HIL_PLANT_KV_MAX */
    double L;          /* tip radius [m] > 0 */
    unsigned substeps; /* RK4 steps per half cycle, 1..1000 */
    char table[HIL_PLANT_PATH_MAX]; /* arm: the plant table file (FRPT) */
};

struct hil_plant {
    struct hil_plant_params p;
    struct hil_rx_stats rx;
    frac_friction fric;
    double t;                  /* simulated time [s] */
    double theta, omega;       /* shaft (motor, driven side): angle, rate */
    double psi, psi_d, psi_dd; /* tip: angle, rate, acceleration (link + extra mode) */
    double x[6];               /* theta_M, theta_M', psi_link, psi_link', q_e, q_e' */
    frac_gl kv;                /* D^a of the gear twist (uses kv_store) */
    frac_real kv_store[FRAC_GL_STORAGE(HIL_PLANT_KV_MAX)];
    double kv_torque;          /* fractional damping torque of the current substep */
    uint64_t steps;
    /* arm: the table's model; Ad column-major (Ad[j n + i] = Ad(i, j)), C row-major */
    unsigned an, aN, asub;     /* states, collocation points, ZOH steps per half cycle */
    double ah;                 /* ZOH step [s] */
    double Ad[HIL_PLANT_ARM_NMAX * HIL_PLANT_ARM_NMAX], Bd[HIL_PLANT_ARM_NMAX];
    double Am[HIL_PLANT_ARM_NMAX * HIL_PLANT_ARM_NMAX]; /* Ad^asub, column-major */
    double vrow[(HIL_PLANT_ARM_SUBMAX + 1) * HIL_PLANT_ARM_NMAX]; /* rows C_2 Ad^k, k <= asub */
    double bcol[HIL_PLANT_ARM_SUBMAX * HIL_PLANT_ARM_NMAX]; /* columns Ad^k Bd, k < asub */
    double vb[HIL_PLANT_ARM_SUBMAX];                      /* C_2 Ad^k Bd */
    double Bd1[HIL_PLANT_ARM_NMAX];  /* response over h to the torque's ramp about its mid-step value, per unit slope */
    double bramp[HIL_PLANT_ARM_NMAX]; /* sum_{k < asub} Ad^k Bd1: the ramp's part of a half cycle */
    double vb1[HIL_PLANT_ARM_SUBMAX + 1]; /* sum_{i < k} C_2 Ad^i Bd1 (k <= asub): its part of the velocity at step k */
    double C[4 * HIL_PLANT_ARM_NMAX];
    double acc_row[HIL_PLANT_ARM_NMAX], acc_b; /* psi_L'' = acc_row x + acc_b u (C_4 Ac, C_4 Bc) */
    double ax[HIL_PLANT_ARM_NMAX], ay[HIL_PLANT_ARM_NMAX]; /* state, scratch */
    char err[256];             /* why init failed ("" when it did not) */
};

/* Defaults: model rigid with J = 2.0 kg m^2, b = 1.0 Nm s/rad, L = 1.0 m,
 * 4 substeps, T = 1.2 ms (assumed round figures, not the thesis arm); the
 * twomass fields hold seed 004's values: I_M = 160^2 * 2.29e-4 = 5.8624,
 * I_L = 1.69e-4 + 0.7221 kg m^2, c_s = 5e4 Nm/rad (Table 8.2, notes 004b),
 * linear friction b1 = 3.04, b0 = 7.684, k = 60 (Table 8.6). */
void hil_plant_params_default(struct hil_plant_params *p);
/* Validates p (friction by frac_friction_init for twomass and arm; for arm
 * also reads and validates the table) and starts at rest at angle 0. HIL_OK
 * or HIL_E_ARG with the reason in pl->err (for a bad table: the file, the
 * failing field, e.g. "entry.values of entry 'Ad'", or the entry whose
 * dimensions are wrong). The struct holds pointers into itself (the GL
 * history): initialise it where it lives, do not copy it. */
int hil_plant_init(struct hil_plant *pl, const struct hil_plant_params *p);
/* Consumes one bus frame; same contract as hil_drive_on_frame. */
int hil_plant_on_frame(struct hil_plant *pl, const struct hil_can_frame *f, struct hil_out *out);

#endif
