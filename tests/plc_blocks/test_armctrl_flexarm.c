/* ArmCtrl (Cyclic #1, 1.2 ms) with ImuRead (Cyclic #2, 0.6 ms) in the task
 * runtime, closing the loop in lockstep against the full-order flexible arm
 * of design_tools, on the parameter tables `fracdesign armctrl` makes for
 * seed 004 Exp. A-D (Table 8.5 move, Table 8.6 PD and friction, Tables
 * 8.7/8.8 LQG), loaded through armctrl_program_table as on the PLC.
 *
 * Plant: `fracdesign model arm --N 12 --full --r_t 0.5 --h 1e-4
 * --save-plant` (tests/plc_blocks/fracdesign_fixtures.cmake): the
 * pseudo-spectral beam (3.103) on the drive, exact ZOH at the 100 us tick,
 * x <- Ad x + Bd tau_net per tick with outputs theta_M, dtheta_M, psi_L,
 * dpsi_L. The design (fracdesign armctrl) works on N = 9 points and the
 * Krylov-reduced beam, so the plant is not the controller's model. The
 * net torque is the drive torque minus the motor friction (5.2) with the
 * Table 8.6 values (b_1 = 3.04, b_0 = 7.684, k = 60), which Exp. A/B
 * compensate and Exp. C/D estimate.
 *
 * Delays: Exp. A, B and C each on the plant without delays (the drive
 * applies the setpoint at the next tick, the IMU frame of Cyclic #2 is
 * fresh) and on the delayed plant of Sec. 8.6 (torque path d_i T = 4.8 ms,
 * IMU path d_o T = 3.6 ms including the 0.6 ms of Cyclic #2); Exp. D on the
 * delayed plant. A, B and C have no delay model in the controller, D has
 * (7.18)-(7.27) and the feedforward shifts. */
#include "frac_test.h"
#include "frac_test_file.h"
#include "ArmCtrl.h"
#include "ImuRead.h"
#include "plc_rt.h"
#include "frac/ptable.h"
#include "frac/traj.h"

#include <stdio.h>
#include <string.h>

#if !defined(FLEXARM_FIXTURE_DIR) || !defined(FLEXARM_TABLE_DIR)
#error "FLEXARM_FIXTURE_DIR and FLEXARM_TABLE_DIR are set by tests/plc_blocks/fracdesign_fixtures.cmake"
#endif

#define NX_MAX 64
#define TICK 1e-4
#define T_CYCLE 1.2e-3
#define FRIC_B1 3.04 /* Table 8.6 */
#define FRIC_B0 7.684
#define KTANH 60.0
#define TAU_PEAK 251.0 /* drive peak torque, driven side (notes 8.2: 1.571 Nm x 160) */
#define RING 64

typedef struct arm_plant {
    unsigned n;
    double Ad[NX_MAX * NX_MAX], Bd[NX_MAX], C[4 * NX_MAX];
    double x[NX_MAX], y[4];
} arm_plant;

/* A table fracdesign made at build time in `dir`, read whole (caller frees). */
static unsigned char *read_fixture(const char *dir, const char *name, unsigned long *size)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return frac_test_slurp(path, size);
}

static void plant_outputs(arm_plant *p)
{
    unsigned i, j;
    for (i = 0; i < 4; i++) {
        double s = 0.0;
        for (j = 0; j < p->n; j++) {
            s += p->C[i * p->n + j] * p->x[j];
        }
        p->y[i] = s;
    }
}

static void load_plant(arm_plant *p)
{
    frac_ptable t;
    frac_real dims[2], h, *buf;
    static frac_real tmp[NX_MAX * NX_MAX];
    unsigned long size, i;
    unsigned char *data = read_fixture(FLEXARM_FIXTURE_DIR, "arm_plant.bin", &size);
    unsigned n;
    assert_int_equal(frac_ptable_open(&t, data, size), FRAC_OK);
    assert_int_equal(frac_ptable_get(&t, "plant_dims", 1, 2, dims), FRAC_OK);
    assert_int_equal(frac_ptable_get(&t, "h", 1, 1, &h), FRAC_OK);
    n = (unsigned)dims[0];
    /* 4 + 4 N states of the full arm, N = 12 */
    assert_int_equal(n, 4 + 4 * 12);
    assert_true(n <= NX_MAX);
    /* one exact ZOH step per system tick */
    assert_close(h, TICK, 1e-12);
    memset(p, 0, sizeof *p);
    p->n = n;
    buf = tmp;
    assert_int_equal(frac_ptable_get(&t, "Ad", n, n, buf), FRAC_OK);
    for (i = 0; i < (unsigned long)n * n; i++) {
        p->Ad[i] = (double)buf[i];
    }
    assert_int_equal(frac_ptable_get(&t, "Bd", n, 1, buf), FRAC_OK);
    for (i = 0; i < n; i++) {
        p->Bd[i] = (double)buf[i];
    }
    assert_int_equal(frac_ptable_get(&t, "C", 4, n, buf), FRAC_OK);
    for (i = 0; i < 4ul * n; i++) {
        p->C[i] = (double)buf[i];
    }
    free(data);
}

/* One tick: x <- Ad x + Bd (tau - friction(dtheta_M)), (5.2) held over the tick. */
static void plant_step(arm_plant *p, double tau)
{
    static double xn[NX_MAX];
    double v = p->y[1], u = tau - (FRIC_B1 * v + FRIC_B0 * tanh(KTANH * v));
    unsigned i, j;
    for (i = 0; i < p->n; i++) {
        double s = p->Bd[i] * u;
        const double *a = &p->Ad[i * p->n];
        for (j = 0; j < p->n; j++) {
            s += a[j] * p->x[j];
        }
        xn[i] = s;
    }
    memcpy(p->x, xn, p->n * sizeof(double));
    plant_outputs(p);
}

/* The bench: process image, plant, "hardware" side of the I/O, figures. */
typedef struct flexbench {
    arm_plant pl;
    armctrl_inputs drive_img;
    armctrl_outputs ctrl_img;
    imuread_inputs can_img;
    imuread_outputs imu_img;
    uint64_t ticks;
    unsigned torque_delay, imu_delay; /* ticks added to the torque and IMU paths */
    double tau_hist[RING], rate_hist[RING];
    frac_traj traj;
    int started;
    uint64_t t0_ns;           /* release of the first cycle with the counter running: table time 0 */
    double max_track_err;     /* max |psi_L - q| while the counter runs */
    double max_abs_tau;
    double max_settle_dev;    /* max |psi_L - pi/2| from 1 s after the motion's end */
    int torque_seen;
} flexbench;

static void flex_tick(void *ctx, uint64_t t_ns)
{
    flexbench *b = (flexbench *)ctx;
    double tau = b->ctrl_img.TorqueEnable ? (double)b->ctrl_img.TorqueSetpoint : 0.0;
    b->tau_hist[b->ticks % RING] = tau;
    tau = b->ticks >= b->torque_delay ? b->tau_hist[(b->ticks - b->torque_delay) % RING] : 0.0;
    b->torque_seen |= b->ctrl_img.TorqueEnable;
    if (fabs(tau) > b->max_abs_tau) {
        b->max_abs_tau = fabs(tau);
    }
    plant_step(&b->pl, tau);
    b->ticks++;
    /* drive values every POWERLINK cycle (400 us, Table 2.3) */
    if (b->ticks % 4 == 0) {
        b->drive_img.MotorAngle = (REAL)b->pl.y[0];
        b->drive_img.MotorVelocity = (REAL)b->pl.y[1];
        b->drive_img.DriveCounter++;
    }
    /* an IMU frame (tip rate) every 600 us */
    b->rate_hist[b->ticks % RING] = b->pl.y[3];
    if (b->ticks % 6 == 0) {
        b->can_img.RawRate = (REAL)(b->ticks >= b->imu_delay ? b->rate_hist[(b->ticks - b->imu_delay) % RING] : 0.0);
        b->can_img.FrameCounter++;
    }
    b->drive_img.Start = b->ticks >= 24;
    /* table time 0 = release of the cycle that first counted (published at
     * its end, seen here at the next tick at the latest) */
    if (!b->started && b->ctrl_img.Counter > 0) {
        b->started = 1;
        b->t0_ns = (t_ns - 1) / 1200000u * 1200000u;
    }
    if (b->started) {
        frac_real d[5];
        double t = (double)(t_ns - b->t0_ns) * 1e-9 + TICK; /* the plant is now at t_ns + tick */
        (void)frac_traj_eval(&b->traj, (frac_real)t, d);
        if (fabs(b->pl.y[2] - (double)d[0]) > b->max_track_err) {
            b->max_track_err = fabs(b->pl.y[2] - (double)d[0]);
        }
        if (t > 3.0 && fabs(b->pl.y[2] - FRAC_PI / 2) > b->max_settle_dev) {
            b->max_settle_dev = fabs(b->pl.y[2] - FRAC_PI / 2);
        }
    }
}

/* Runs ArmCtrl on the table of experiment `exp` for 4 s of table time
 * (the motion of Table 8.5 from 0.5 s to 2 s). */
static void run_flexarm(flexbench *b, char exp, int delayed)
{
    static armctrl a;
    static imuread m;
    static armctrl_table_storage storage;
    static plc_rt rt;
    plc_program pa, pm;
    const plc_program *reg[2];
    plc_rt_config cfg;
    frac_traj_params tp;
    char err[256], name[32], table_2_3[400];
    unsigned long size;
    unsigned char *table;
    int lqg = exp == 'C' || exp == 'D';
    memset(b, 0, sizeof *b);
    load_plant(&b->pl);
    plant_outputs(&b->pl);
    armctrl_table_8_5_move(&tp);
    assert_int_equal(frac_traj_init(&b->traj, &tp), FRAC_OK);
    if (delayed) {
        b->torque_delay = 48; /* d_i T = 4.8 ms */
        b->imu_delay = 30;    /* + the 0.6 ms Cyclic #2 path = d_o T = 3.6 ms */
    }
    snprintf(name, sizeof name, "armctrl_%c.bin", exp);
    table = read_fixture(FLEXARM_TABLE_DIR, name, &size);
    armctrl_program_table(&a, &pa, table, (UDINT)size, &storage, &b->drive_img, &b->imu_img, &b->ctrl_img);
    imuread_program(&m, &pm, 1.0f, &b->can_img, &b->imu_img);
    reg[0] = &pa;
    reg[1] = &pm;
    /* Table 2.3 classes; the LQG variants run without simulated CPU time
     * (an exact ZOH sampled loop, as their design assumes), A/B take 300 us */
    snprintf(table_2_3, sizeof table_2_3,
             "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = service\n"
             "[cyclic1]\nduration_us = 1200\nsim_cost_us = %d\nprograms = ArmCtrl\n"
             "[cyclic2]\nduration_us = 600\nsim_cost_us = %d\nprograms = ImuRead\n", lqg ? 0 : 300, lqg ? 0 : 50);
    assert_int_equal(plc_rt_config_parse(&cfg, table_2_3, "table_2_3", err, sizeof err), PLC_RT_OK);
    assert_int_equal(plc_rt_init(&rt, &cfg, reg, 2, err, sizeof err), PLC_RT_OK);
    rt.tick_hook = flex_tick;
    rt.tick_ctx = b;
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_sim(&rt, 40024), PLC_RT_OK);
    assert_int_equal(rt.stats[0].violations + rt.stats[1].violations, 0);
    assert_int_equal(storage.par.Variant, (armctrl_variant)(exp - 'A'));
    /* the delay model is Exp. D's alone: d_i = 4, d_o = 3 on the IMU
     * (Table 8.8), torque table 4 cycles early, IMU reference 3 late */
    assert_int_equal(storage.par.Lqg.Di, exp == 'D' ? 4 : 0);
    assert_int_equal(storage.par.Lqg.Do[0] + storage.par.Lqg.Do[1], 0);
    assert_int_equal(storage.par.Lqg.Do[2], exp == 'D' ? 3 : 0);
    assert_int_equal(storage.par.Ff.Lead[ARMCTRL_FF_TAU], exp == 'D' ? 4 : 0);
    assert_int_equal(storage.par.Ff.Lead[ARMCTRL_FF_DPSI], exp == 'D' ? -3 : 0);
    assert_int_equal(storage.par.Ff.Lead[ARMCTRL_FF_THETA] + storage.par.Ff.Lead[ARMCTRL_FF_DTHETA], 0);
    plc_rt_stop(&rt);
    free(table);
    print_message("Exp. %c (%s plant): max |psi_L - q| = %.3g rad, final psi_L = %.6f rad (pi/2 %+.2e), "
                  "max |psi_L - pi/2| after 3 s = %.3g rad, max |tau| = %.1f Nm, StatusID %u\n",
                  exp, delayed ? "delayed" : "undelayed", b->max_track_err, b->pl.y[2], b->pl.y[2] - FRAC_PI / 2,
                  b->max_settle_dev, b->max_abs_tau, (unsigned)b->ctrl_img.StatusID);
}

/* Tracking of the Table 8.5 move: max |psi_L - q| while the counter runs
 * below track_tol, psi_L within settle_tol of pi/2 from 1 s after the
 * motion's end to the last tick, torque within the drive's peak, no Error. */
static void expect_tracking(const flexbench *b, double track_tol, double settle_tol)
{
    assert_true(b->torque_seen);
    assert_false(b->ctrl_img.Error);
    assert_int_equal(b->ctrl_img.StatusID, fracSTAT_OK);
    assert_true(b->ctrl_img.Counter > 3300); /* 4 s of table time at 1.2 ms */
    assert_true(b->max_track_err < track_tol);
    assert_true(b->max_settle_dev < settle_tol);
    assert_close(b->pl.y[2], FRAC_PI / 2, settle_tol);
    assert_true(b->max_abs_tau < TAU_PEAK);
}

/* Bounds: the thesis reports no tracking error (notes 9.7), only torque
 * ranges and lags, so the tracking bounds are the project's: well above
 * the figures measured here (docs/plc_blocks.md) so that a retuned design
 * still passes, well below what a loop blind to the beam gives (Exp. A's
 * rbFFC, about 5e-2 rad, fails every other bound); B's 1e-3 rad also
 * catches a table shifted by one cycle (q'max T = 1.9e-3 rad). */
static void test_exp_a_and_b_track_table_8_5_on_the_flexible_arm(void **state)
{
    static flexbench a, b;
    double a_err;
    (void)state;
    /* rbFFC ignores the beam: the tip lags and rings (about 5e-2 rad),
     * and keeps ringing after the move (about 6e-3 rad at 3 s) */
    run_flexarm(&a, 'A', 0);
    expect_tracking(&a, 6e-2, 1e-2);
    /* notes 9.3: torque range about -40..60 Nm in Exp. A; peak within 25 % */
    assert_true(a.max_abs_tau > 45.0 && a.max_abs_tau < 75.0);
    a_err = a.max_track_err;
    run_flexarm(&a, 'A', 1);
    expect_tracking(&a, 6e-2, 1e-2);
    /* ibFFC, the stable inversion of the (N = 9, reduced) beam model:
     * about 1e-4 rad on the N = 12 plant; the 4.8 ms torque delay, which
     * Exp. B does not compensate, costs about 1e-3 rad */
    run_flexarm(&b, 'B', 0);
    expect_tracking(&b, 1e-3, 2e-4);
    /* notes 9.4: about -20..50 Nm in Exp. B; peak within 25 % */
    assert_true(b.max_abs_tau > 37.5 && b.max_abs_tau < 62.5);
    assert_true(b.max_track_err < a_err / 10.0);
    run_flexarm(&b, 'B', 1);
    expect_tracking(&b, 5e-3, 1e-3);
}

static void test_exp_c_tracks_table_8_5_on_the_flexible_arm(void **state)
{
    static flexbench b;
    (void)state;
    run_flexarm(&b, 'C', 0);
    expect_tracking(&b, 1e-2, 2e-3);
    run_flexarm(&b, 'C', 1);
    expect_tracking(&b, 1e-2, 2e-3);
}

static void test_exp_d_tracks_table_8_5_on_the_delayed_flexible_arm(void **state)
{
    static flexbench c, d;
    (void)state;
    run_flexarm(&d, 'D', 1);
    expect_tracking(&d, 5e-3, 1e-3);
    /* Ch. 7 / Sec. 8.6: on the delayed plant the delay model (and the
     * feedforward time shifts) track better than Exp. C without them */
    run_flexarm(&c, 'C', 1);
    assert_true(d.max_track_err < c.max_track_err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exp_a_and_b_track_table_8_5_on_the_flexible_arm),
        cmocka_unit_test(test_exp_c_tracks_table_8_5_on_the_flexible_arm),
        cmocka_unit_test(test_exp_d_tracks_table_8_5_on_the_delayed_flexible_arm),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
