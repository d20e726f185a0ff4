/* plant = arm: the flexible arm of seed 004 (3.103), full order, from the
 * plant table `fracdesign model arm --N 9 --full --save-plant` writes at
 * build time (HIL_ARM_TABLE, beam damping r_t = 0.5 as the bench's tables;
 * HIL_ARM_TABLE_UNDAMPED without). Proves: the table loads (dimensions, step);
 * bad tables (missing file, truncated, NaN value, wrong dimensions, missing
 * entry, h not dividing T/2) and twomass-only effects are refused with the
 * field named; the free response is the table's own discrete model; a
 * constant torque accelerates the rigid-body mode by 1 / (I_M + I_h +
 * I_beam) within 1 %; every friction model brakes the motor as on the
 * rigid arm; the arm closes the loop on the lockstep bench. */
#include <stdlib.h>
#include <string.h>
#include "frac_test.h"
#include "frac_test_file.h"
#include "../../plc_blocks/ptable_writer.h"
#include "hil/canopen.h"
#include "hil/rig.h"

static struct hil_plant pl;
static struct hil_rig rig;

static void spit(const char *path, const unsigned char *b, unsigned long n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(b, 1, n, f), n);
    fclose(f);
}

/* Arm plant parameters on the fixture table, friction off (b1 = b0 = 0). */
static void arm_params(struct hil_plant_params *p, const char *table)
{
    hil_plant_params_default(p);
    p->model = HIL_PLANT_ARM;
    p->friction.b1 = 0;
    p->friction.b0 = 0;
    p->L = 1.225;
    snprintf(p->table, sizeof p->table, "%s", table);
}

/* Advances the plant one cycle at constant torque. */
static void cycle(struct hil_plant *q, double tau)
{
    struct hil_can_frame f;
    struct hil_out out;
    out.n = 0;
    assert_int_equal(hil_co_rig_encode(&f, HIL_COB_RIG_TORQUE, tau, tau), HIL_OK);
    assert_int_equal(hil_plant_on_frame(q, &f, &out), HIL_OK);
    assert_int_equal(out.n, 5);
}

static void test_table_loads_with_its_dimensions_and_step(void **state)
{
    struct hil_plant_params p;
    (void)state;
    arm_params(&p, HIL_ARM_TABLE);
    assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
    assert_string_equal(pl.err, "");
    assert_int_equal(pl.aN, 9);
    assert_int_equal(pl.an, 40);
    assert_close(pl.ah, 1.2e-3 / 8, 1e-18);
    assert_int_equal(pl.asub, 4);
    /* C row 1: theta_M; row 2: theta_M' = p_M / I_M (drive state 2) */
    assert_close(pl.C[0], 1.0, 0.0);
    assert_rel(pl.C[pl.an + 2], 1.0 / (160.0 * 160.0 * 2.29e-4), 1e-12);
}

/* Writes a copy of the fixture with `mutate` applied and expects init to
 * fail naming `field`. */
static void expect_refused(const char *path, const char *field)
{
    struct hil_plant_params p;
    arm_params(&p, path);
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
    print_message("refused: %s\n", pl.err);
    assert_non_null(strstr(pl.err, field));
}

static void test_bad_tables_are_refused_with_the_field_named(void **state)
{
    unsigned long n, ad_off = 0, i;
    unsigned char *b = frac_test_slurp(HIL_ARM_TABLE, &n), *c = malloc(n);
    char path[512];
    static unsigned char w[4096];
    const double small[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, dims[2] = {40, 9}, dims_bad[2] = {41, 9}, h = 1.5e-4,
                 h_bad = 1.7e-4, h_fine = 1.5e-5;
    ptw_entry e[3];
    (void)state;
    assert_non_null(c);
    /* missing file */
    expect_refused(HIL_ARM_TMP "/no_such_table.bin", "cannot read");
    /* truncated: the header's total size exceeds the file */
    snprintf(path, sizeof path, "%s/truncated.bin", HIL_ARM_TMP);
    spit(path, b, n / 2);
    expect_refused(path, "total_size");
    /* a NaN in Ad (CRC resealed, so finiteness is what fails) */
    for (i = 0; i < 7; i++) {
        const unsigned char *d = b + FRAC_PTABLE_HEADER_SIZE + i * FRAC_PTABLE_ENTRY_SIZE;
        if (strcmp((const char *)d, "Ad") == 0)
            ad_off = d[28] | (unsigned long)d[29] << 8 | (unsigned long)d[30] << 16 | (unsigned long)d[31] << 24;
    }
    assert_true(ad_off > 0);
    memcpy(c, b, n);
    memset(c + ad_off + 8 * 5, 0xFF, 8); /* all-ones: a quiet NaN */
    ptw_seal(c, n);
    snprintf(path, sizeof path, "%s/nan.bin", HIL_ARM_TMP);
    spit(path, c, n);
    expect_refused(path, "entry.values of entry 2 'Ad'");
    /* a corrupted byte without resealing: the CRC */
    memcpy(c, b, n);
    c[ad_off] ^= 1;
    snprintf(path, sizeof path, "%s/crc.bin", HIL_ARM_TMP);
    spit(path, c, n);
    expect_refused(path, "crc32");
    /* wrong dimensions: Ad 3 x 3 where plant_dims says 40 states */
    e[0].name = "plant_dims"; e[0].rows = 1; e[0].cols = 2; e[0].values = dims;
    e[1].name = "h"; e[1].rows = 1; e[1].cols = 1; e[1].values = &h;
    e[2].name = "Ad"; e[2].rows = 3; e[2].cols = 3; e[2].values = small;
    snprintf(path, sizeof path, "%s/dims.bin", HIL_ARM_TMP);
    spit(path, w, ptw_write(w, sizeof w, "arm_plant", e, 3));
    expect_refused(path, "entry 'Ad' is 3 x 3, expected 40 x 40");
    /* plant_dims not n = 4 + 4 N */
    e[0].values = dims_bad;
    spit(path, w, ptw_write(w, sizeof w, "arm_plant", e, 3));
    expect_refused(path, "plant_dims");
    /* plant_dims (n, N, P) with payload states P not 0, 2 or 4, and with n != 4 + 4 N + P */
    {
        static const double dims3_odd[3] = {43.0, 9.0, 3.0}, dims3_sum[3] = {44.0, 9.0, 2.0};
        e[0].cols = 3;
        e[0].values = dims3_odd;
        spit(path, w, ptw_write(w, sizeof w, "arm_plant", e, 3));
        expect_refused(path, "P in {0, 2, 4}");
        e[0].values = dims3_sum;
        spit(path, w, ptw_write(w, sizeof w, "arm_plant", e, 3));
        expect_refused(path, "plant_dims (44, 9, 2)");
        e[0].cols = 2;
    }
    /* step not dividing T/2 */
    e[0].values = dims;
    e[1].values = &h_bad;
    spit(path, w, ptw_write(w, sizeof w, "arm_plant", e, 3));
    expect_refused(path, "does not divide");
    /* a step too fine for the composed half cycle (40 steps > 32) */
    e[1].values = &h_fine;
    spit(path, w, ptw_write(w, sizeof w, "arm_plant", e, 3));
    expect_refused(path, "more than 32 steps");
    /* entry missing */
    spit(path, w, ptw_write(w, sizeof w, "arm_plant", e, 1));
    expect_refused(path, "entry 'h' missing");
    free(b);
    free(c);
}

static void test_twomass_effects_and_missing_table_are_refused(void **state)
{
    struct hil_plant_params p;
    (void)state;
    arm_params(&p, HIL_ARM_TABLE);
    p.backlash = 1e-3;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
    assert_non_null(strstr(pl.err, "plant.backlash"));
    arm_params(&p, HIL_ARM_TABLE);
    p.extra_inertia = 0.1;
    p.extra_hz = 20;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
    assert_non_null(strstr(pl.err, "plant.extra_inertia"));
    arm_params(&p, HIL_ARM_TABLE);
    p.kv_damping = 1.0;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
    assert_non_null(strstr(pl.err, "plant.kv_damping"));
    arm_params(&p, "");
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
    assert_non_null(strstr(pl.err, "needs plant.table"));
    arm_params(&p, HIL_ARM_TABLE);
    p.friction.k = -1;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
    assert_non_null(strstr(pl.err, "friction"));
}

/* x[k] = Ad^k x[0] with the table's own Ad, step by step, against the
 * plant's state after the same number of steps at zero torque (the plant
 * composes the steps of a half cycle: equal to rounding, 1e-12 relative). */
static void test_free_response_is_the_tables_discrete_model(void **state)
{
    struct hil_plant_params p;
    unsigned n, i, j, k, cyc;
    double x[HIL_PLANT_ARM_NMAX], y[HIL_PLANT_ARM_NMAX], err = 0.0, mag = 0.0;
    (void)state;
    arm_params(&p, HIL_ARM_TABLE);
    assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
    n = pl.an;
    /* a deterministic state with every mode excited: momentum on the motor
     * and along the beam, strain on the beam */
    for (i = 0; i < n; i++)
        x[i] = pl.ax[i] = 1e-3 * (double)((i * 37u) % 11u) - 5e-3;
    for (cyc = 0; cyc < 200; cyc++) {
        cycle(&pl, 0.0);
        for (k = 0; k < 2 * pl.asub; k++) {
            for (i = 0; i < n; i++) {
                y[i] = 0.0;
                for (j = 0; j < n; j++)
                    y[i] += pl.Ad[j * n + i] * x[j]; /* column-major */
            }
            memcpy(x, y, sizeof x);
        }
    }
    for (i = 0; i < n; i++) {
        double d = fabs(pl.ax[i] - x[i]);
        err = d > err ? d : err;
        mag = fabs(x[i]) > mag ? fabs(x[i]) : mag;
    }
    print_message("free response after 200 cycles: max |x - Ad^k x0| = %.3g (max |x| %.3g)\n", err, mag);
    assert_true(mag > 1e-3);
    assert_true(err <= 1e-12 * mag);
    /* the reported outputs are C x */
    {
        double th = 0.0, tip = 0.0;
        for (j = 0; j < n; j++) {
            th += pl.C[j] * x[j];
            tip += pl.C[2 * n + j] * x[j];
        }
        assert_close(pl.theta, th, 1e-12);
        assert_close(pl.psi, tip, 1e-12);
    }
}

/* Seed 004 Tables 8.2/8.3: the rigid arm's inertia about the motor axis. */
static double rigid_inertia(void)
{
    const double I_M = 160.0 * 160.0 * 2.29e-4, I_h = 1.69e-4, r_h = 0.025, L = 1.2;
    const double rho = 7856.0 * 0.03 * 0.005, I_rho = 7856.0 * 0.03 * 0.005 * 0.005 * 0.005 / 12.0;
    return I_M + I_h + rho * ((r_h + L) * (r_h + L) * (r_h + L) - r_h * r_h * r_h) / 3.0 + I_rho * L;
}

static void test_constant_torque_accelerates_the_rigid_body_mode(void **state)
{
    struct hil_plant_params p;
    const double tau = 10.0, I = rigid_inertia();
    double s[5] = {0, 0, 0, 0, 0}, r[3] = {0, 0, 0}, a, t;
    unsigned k, K = 1667; /* 2.0 s */
    (void)state;
    /* the undamped beam: the bench tables' r_t damps the rigid-body motion
     * too (it is a damping against the inertial frame) */
    arm_params(&p, HIL_ARM_TABLE_UNDAMPED);
    assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
    /* least-squares fit theta_M(t) = c0 + c1 t + c2 t^2: acceleration 2 c2 */
    for (k = 1; k <= K; k++) {
        cycle(&pl, tau);
        t = k * p.T;
        s[0] += 1; s[1] += t; s[2] += t * t; s[3] += t * t * t; s[4] += t * t * t * t;
        r[0] += pl.theta; r[1] += t * pl.theta; r[2] += t * t * pl.theta;
    }
    {
        /* normal equations by Cramer's rule */
        double m[3][3], det, m2[3][3];
        int i, j;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++)
                m[i][j] = s[i + j];
        det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
              m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        memcpy(m2, m, sizeof m);
        for (i = 0; i < 3; i++)
            m2[i][2] = r[i];
        a = 2.0 * (m2[0][0] * (m2[1][1] * m2[2][2] - m2[1][2] * m2[2][1]) -
                   m2[0][1] * (m2[1][0] * m2[2][2] - m2[1][2] * m2[2][0]) +
                   m2[0][2] * (m2[1][0] * m2[2][1] - m2[1][1] * m2[2][0])) / det;
    }
    print_message("constant %.0f Nm: acceleration %.6f rad/s^2, tau / I = %.6f (I = %.5f kg m^2)\n", tau, a, tau / I, I);
    assert_rel(a, tau / I, 0.01);
    /* the tip follows the hub: same mean acceleration, angle close to the motor's */
    assert_close(pl.psi, pl.theta, 0.02 * pl.theta);
}

/* Advances the plant one cycle with the torque ramped from tau0 to tau1. */
static void ramp_cycle(struct hil_plant *q, double tau0, double tau1)
{
    struct hil_can_frame f;
    struct hil_out out;
    out.n = 0;
    assert_int_equal(hil_co_rig_encode(&f, HIL_COB_RIG_TORQUE, tau0, tau1), HIL_OK);
    assert_int_equal(hil_plant_on_frame(q, &f, &out), HIL_OK);
}

/* The drive's torque ramps over each cycle (first-order hold); with the
 * table's Bd1 the plant integrates it exactly, so the response does not
 * depend on the table's step: the undamped arm at h = T/8 (4 steps per half
 * cycle) and at h = T/64 (32) agree to rounding under a torque that jumps
 * every cycle (friction off). Without the ramp's column (the mid-step torque
 * held, as a table without Bd1) they differ by the O(h^2) error of the
 * coarse step, which the same comparison must see. */
static void test_ramped_torque_is_integrated_exactly_at_any_step(void **state)
{
    static struct hil_plant fine;
    struct hil_plant_params p, pf;
    double prev = 0.0, err = 0.0, mag = 0.0, err_mid = 0.0;
    unsigned k, pass;
    (void)state;
    arm_params(&p, HIL_ARM_TABLE_UNDAMPED);
    arm_params(&pf, HIL_ARM_TABLE_UNDAMPED_FINE);
    for (pass = 0; pass < 2; pass++) {
        double *e = pass == 0 ? &err : &err_mid;
        assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
        assert_int_equal(hil_plant_init(&fine, &pf), HIL_OK);
        assert_int_equal(pl.asub, 4);
        assert_int_equal(fine.asub, 32);
        if (pass == 1) { /* the coarse plant as a table without Bd1 */
            memset(pl.bramp, 0, sizeof pl.bramp);
            memset(pl.vb1, 0, sizeof pl.vb1);
        }
        prev = 0.0;
        for (k = 0; k < 400; k++) {
            /* a command full of jumps: a 40 Hz sine and a 7-cycle staircase */
            const double tau = 20.0 * sin(2.0 * M_PI * 40.0 * k * p.T) + 6.0 * (double)(k % 7) - 18.0;
            double d;
            ramp_cycle(&pl, prev, tau);
            ramp_cycle(&fine, prev, tau);
            prev = tau;
            d = fabs(pl.omega - fine.omega);
            *e = d > *e ? d : *e;
            if (pass == 0)
                mag = fabs(fine.omega) > mag ? fabs(fine.omega) : mag;
            d = fabs(pl.psi_d - fine.psi_d);
            *e = d > *e ? d : *e;
        }
    }
    print_message("ramped torque, h = T/8 against T/64: max |rate difference| %.3g rad/s with Bd1, %.3g with the "
                  "mid-step torque held (max |theta_M'| %.3g rad/s)\n", err, err_mid, mag);
    assert_true(mag > 0.01);
    assert_true(err <= 1e-9 * mag);
    assert_true(err_mid >= 1e3 * err);
}

/* The friction is held over each step at the mean of its start and end
 * velocities (trapezoidal, hil/plant.h): second order in the table's step.
 * The motor velocity under a ramped torque with Table 8.6's friction, at
 * h = T/8 and T/16 against T/64: halving the step divides the error by
 * (1/64 - 1/4096) / (1/256 - 1/4096) = 4.27 for a second-order rule and by
 * 2.33 for a first-order one (the explicit rule it replaced). */
static void test_friction_coupling_is_second_order_in_the_step(void **state)
{
    static struct hil_plant q[3];
    const char *tables[3] = {HIL_ARM_TABLE_UNDAMPED, HIL_ARM_TABLE_UNDAMPED_HALF, HIL_ARM_TABLE_UNDAMPED_FINE};
    double prev = 0.0, e8 = 0.0, e16 = 0.0, mag = 0.0, ratio;
    unsigned k, i;
    (void)state;
    for (i = 0; i < 3; i++) {
        struct hil_plant_params p;
        arm_params(&p, tables[i]);
        p.friction.b1 = 3.04; /* Table 8.6, model (5.2) */
        p.friction.b0 = 7.684;
        p.friction.k = 60.0;
        assert_int_equal(hil_plant_init(&q[i], &p), HIL_OK);
    }
    assert_int_equal(q[1].asub, 8);
    for (k = 0; k < 800; k++) {
        /* slow reversals through rest (where tanh(60 v) is stiffest) and jumps */
        const double tau = 30.0 * sin(2.0 * M_PI * 2.0 * k * 1.2e-3) + 4.0 * (double)(k % 5) - 8.0;
        double d;
        for (i = 0; i < 3; i++)
            ramp_cycle(&q[i], prev, tau);
        prev = tau;
        d = fabs(q[0].omega - q[2].omega);
        e8 = d > e8 ? d : e8;
        d = fabs(q[1].omega - q[2].omega);
        e16 = d > e16 ? d : e16;
        mag = fabs(q[2].omega) > mag ? fabs(q[2].omega) : mag;
    }
    ratio = e8 / e16;
    print_message("friction, max |theta_M' - theta_M'(T/64)|: %.3g rad/s at h = T/8, %.3g at T/16 (ratio %.2f; "
                  "max |theta_M'| %.3g rad/s)\n", e8, e16, ratio, mag);
    assert_true(mag > 0.05);
    assert_true(e16 > 0.0);
    assert_true(ratio > 3.5 && ratio < 5.0);
}

/* Each friction model of frac/friction.h acts on the motor: under a constant
 * torque (+-20 Nm, 1 s) the motor angle follows the rigid arm
 * I theta'' = tau - tau_f(theta') (integrated here with 10 us Euler steps)
 * within 1 % (the beam's modes ride on it). */
static void test_every_friction_model_brakes_the_motor(void **state)
{
    const double I = 6.58464; /* tau / a of the undamped arm, test above */
    int model;
    (void)state;
    for (model = 0; model < 3; model++) {
        int sign;
        for (sign = -1; sign <= 1; sign += 2) {
            struct hil_plant_params p;
            frac_friction f;
            double v = 0.0, th = 0.0, tau = 20.0 * sign;
            unsigned k;
            arm_params(&p, HIL_ARM_TABLE_UNDAMPED);
            p.friction.model = model;
            p.friction.b1 = 3.04;
            p.friction.b0 = 7.684;
            p.friction.b1n = 2.0;
            p.friction.b1p = 4.0;
            p.friction.b0n = 5.0;
            p.friction.b0p = 9.0;
            p.friction.b1s = 7.684;
            p.friction.b2s = 11.5;
            p.friction.b3s = 3.04;
            p.friction.v_s = 0.05;
            p.friction.delta = 2.0;
            assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
            assert_int_equal(frac_friction_init(&f, &p.friction), FRAC_OK);
            for (k = 0; k < 834; k++) /* 1.0008 s */
                cycle(&pl, tau);
            for (k = 0; k < 100080; k++) {
                frac_real tf = 0;
                frac_friction_eval(&f, (frac_real)v, &tf);
                th += 1e-5 * v;
                v += 1e-5 * (tau - (double)tf) / I;
            }
            print_message("friction model %d, %+.0f Nm: motor %.5f rad, rigid arm %.5f rad\n", model, tau, pl.theta, th);
            assert_rel(pl.theta, th, 0.01);
        }
    }
}

static void test_arm_closes_the_loop_on_the_lockstep_bench(void **state)
{
    struct hil_rig_config c;
    (void)state;
    hil_rig_config_default(&c);
    assert_int_equal(hil_rig_config_set(&c, "plant", "arm"), HIL_OK);
    assert_int_equal(hil_rig_config_set(&c, "plant.table", HIL_ARM_TABLE), HIL_OK);
    assert_int_equal(hil_rig_config_set(&c, "plant.L", "1.225"), HIL_OK);
    c.duration = 2.0;
    assert_int_equal(hil_rig_init(&rig, &c, NULL, NULL), HIL_OK);
    assert_int_equal(hil_rig_run(&rig), HIL_OK);
    print_message("PD test law on the arm: motor %.5f rad, tip %.5f rad (reference %.3f)\n", rig.plant.theta,
                  rig.plant.psi, c.ctrl.move);
    /* the PD test law has no friction compensation: the Coulomb friction
     * b0 (Table 8.6) can hold the motor off by up to b0 / kp */
    assert_close(rig.plant.theta, c.ctrl.move, 1.05 * c.plant_p.friction.b0 / c.ctrl.kp);
    assert_close(rig.plant.psi, c.ctrl.move, 2e-2);
    assert_int_equal(rig.ctrl.missed_inputs, 0);
    assert_int_equal(rig.ctrl.faults, 0);
    assert_true(rig.plant.steps == rig.st.cycles);
    /* a table the plant refuses fails the rig's init, the reason kept */
    assert_int_equal(hil_rig_config_set(&c, "plant.table", HIL_ARM_TMP "/no_such_table.bin"), HIL_OK);
    assert_int_equal(hil_rig_init(&rig, &c, NULL, NULL), HIL_E_ARG);
    assert_non_null(strstr(rig.plant.err, "no_such_table.bin"));
    /* the key refuses '#' and empty paths */
    assert_int_equal(hil_rig_config_set(&c, "plant.table", "a#b"), HIL_E_FORMAT);
    assert_int_equal(hil_rig_config_set(&c, "plant.table", ""), HIL_E_FORMAT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_loads_with_its_dimensions_and_step),
        cmocka_unit_test(test_bad_tables_are_refused_with_the_field_named),
        cmocka_unit_test(test_twomass_effects_and_missing_table_are_refused),
        cmocka_unit_test(test_free_response_is_the_tables_discrete_model),
        cmocka_unit_test(test_constant_torque_accelerates_the_rigid_body_mode),
        cmocka_unit_test(test_ramped_torque_is_integrated_exactly_at_any_step),
        cmocka_unit_test(test_friction_coupling_is_second_order_in_the_step),
        cmocka_unit_test(test_every_friction_model_brakes_the_motor),
        cmocka_unit_test(test_arm_closes_the_loop_on_the_lockstep_bench),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
