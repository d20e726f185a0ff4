/* The emulated arm as a bus node.
 *
 * Each RIG_TORQUE(tau0, tau1) frame from the drive advances the plant by one
 * controller cycle T, with the shaft torque interpolated linearly from tau0
 * to tau1, in two halves of T/2 (the IMU acquisition period, 0.6 ms). After
 * each half the plant sends RIG_TIPPOS(tip angle, radial acc) and
 * RIG_TIP(tip rate, tangential acc); after the second also RIG_MOTOR(shaft
 * angle, shaft velocity), the state at t_{k+1} the drive reports at the next
 * SYNC.
 *
 * Plant "rigid" (the only one so far, a named TEST plant, not the flexible
 * arm): one rigid inertia J on the driven side with viscous friction b,
 *     J theta'' = tau - b theta',   tip angle = theta, tip radius L,
 * integrated by classical RK4 with `substeps` steps per half cycle. */
#ifndef HIL_PLANT_H
#define HIL_PLANT_H
#include "hil/node.h"

struct hil_plant_params {
    double T;          /* controller cycle [s] > 0 */
    double J;          /* inertia on the driven side [kg m^2] > 0 */
    double b;          /* viscous friction [Nm s/rad] >= 0 */
    double L;          /* tip radius [m] > 0 */
    unsigned substeps; /* RK4 steps per half cycle, 1..1000 */
};

struct hil_plant {
    struct hil_plant_params p;
    struct hil_rx_stats rx;
    double t, theta, omega, alpha; /* time [s], angle, rate, acceleration */
    uint64_t steps;
};

/* Test-plant defaults: J = 2.0 kg m^2, b = 1.0 Nm s/rad, L = 1.0 m,
 * 4 substeps, T = 1.2 ms (assumed round figures, not the thesis arm). */
void hil_plant_params_default(struct hil_plant_params *p);
/* Validates p and starts at rest at angle 0. HIL_OK or HIL_E_ARG. */
int hil_plant_init(struct hil_plant *pl, const struct hil_plant_params *p);
/* Consumes one bus frame; same contract as hil_drive_on_frame. */
int hil_plant_on_frame(struct hil_plant *pl, const struct hil_can_frame *f, struct hil_out *out);

#endif
