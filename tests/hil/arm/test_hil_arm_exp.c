/* Seed 004 Exp. A-D on the bench (hil/scenarios/exp_{a,b,c,d}.txt):
 * ArmCtrl from the tables `fracdesign armctrl --exp X` writes, in the task
 * runtime of the controller node, against the full-order flexible arm
 * (N = 12) with the thesis delays (torque path 4 samples, IMU reading every
 * 2.4 ms, ~3 samples old), in lockstep. Checks against the thesis (Ch. 8):
 *  - torque range: Exp. A about -40 .. 60 Nm, Exp. B about -20 .. 50 Nm.
 *    Tolerance: each extreme within 25 % of the thesis figure. The figures
 *    are read off the thesis's plots ("about"), and the peak is set by the
 *    feedforward I ddq_max = 6.58 kg m^2 * 2 pi rad/s^2 = 41 Nm plus the
 *    friction (Coulomb 7.7 Nm, 15-20 % of the peak) the real drive has and
 *    the bench models only as Table 8.6 says;
 *  - tracking of the Table 8.5 move: final tip angle within 2e-3 rad of
 *    pi/2 for B-D; 1e-2 rad for A, whose rigid-body feedforward leaves the
 *    first beam mode ringing (the thesis's motivation for Exp. B);
 *  - tip lag (the time shift that best fits the tip angle to its reference
 *    over the motion, least squares on a 0.1 ms grid): Exp. D's below
 *    Exp. C's (thesis: 15 ms -> 6 ms); both printed;
 *  - bad table: ArmCtrl never enables the torque and the node reports the
 *    StatusID (EMCY, law_status).
 * And with Stribeck stiction in the plant (static 11.5 Nm > Coulomb 7.684
 * Nm, v_s 0.05 rad/s; the controllers compensate linear friction (A/B) or
 * estimate it as a disturbance (C/D), neither models stiction) the residual
 * oscillation after the move is measured (amplitude, frequency) and
 * reported; it must ring down (no limit cycle with the tanh-smoothed
 * stiction). */
#include <stdlib.h>
#include <string.h>
#include "frac_test.h"
#include "frac_test_file.h"
#include "hil/canopen.h"
#include "hil/rig.h"
#include "plc_law.h"

#define NMAX 6000

static struct hil_rig rig;
static struct hil_plc_law law;
static double sig_t[NMAX], sig_ref[NMAX], sig_u[NMAX], sig_tip[NMAX];
static int sig_fault[NMAX];
static unsigned n_sig;

struct exp_result {
    double umin, umax, final_tip, lag;
};

/* The scenario file with its tables taken from the build's table directory. */
static void load_scenario(struct hil_rig_config *c, char which)
{
    char path[512], tab[512];
    int line = 0;
    hil_rig_config_default(c);
    snprintf(path, sizeof path, "%s/hil/scenarios/exp_%c.txt", FRAC_SOURCE_DIR, which);
    assert_int_equal(hil_rig_config_load(c, path, &line), HIL_OK);
    assert_int_equal(c->plant_p.model, HIL_PLANT_ARM);
    assert_string_equal(c->law, "armctrl");
    snprintf(tab, sizeof tab, "%s/%s", HIL_TABLE_DIR, c->plant_p.table);
    assert_int_equal(hil_rig_config_set(c, "plant.table", tab), HIL_OK);
    snprintf(tab, sizeof tab, "%s/%s", HIL_TABLE_DIR, c->ctrl_table);
    assert_int_equal(hil_rig_config_set(c, "ctrl.table", tab), HIL_OK);
}

/* Runs the scenario with ArmCtrl from bytes (size); records the signals. */
static int run(const struct hil_rig_config *c, const unsigned char *bytes, unsigned long size)
{
    char err[256] = "";
    unsigned k, n = (unsigned)(c->duration / c->ctrl.T + 0.5);
    int st;
    assert_true(n <= NMAX);
    assert_int_equal(hil_rig_init(&rig, c, NULL, NULL), HIL_OK);
    st = hil_plc_law_init_table(&law, c->ctrl.T, bytes, size, err, sizeof err);
    if (st != HIL_OK)
        print_message("law: %s\n", err);
    assert_true(law.started);
    hil_ctrl_set_law(&rig.ctrl, hil_plc_law_step, &law);
    for (k = 0; k < n; k++) {
        double tip = rig.plant.psi;
        assert_int_equal(hil_rig_cycle(&rig), HIL_OK);
        sig_t[k] = rig.ctrl.sig.t;
        sig_ref[k] = rig.ctrl.sig.ref;
        sig_u[k] = rig.ctrl.sig.torque_cmd;
        sig_tip[k] = tip;
        sig_fault[k] = rig.ctrl.sig.fault;
    }
    n_sig = n;
    hil_plc_law_stop(&law);
    return st;
}

static double ref_at(double t)
{
    double s = t / sig_t[1];
    unsigned i;
    if (s <= 0.0)
        return sig_ref[0];
    if (s >= (double)(n_sig - 1))
        return sig_ref[n_sig - 1];
    i = (unsigned)s;
    return sig_ref[i] + (s - (double)i) * (sig_ref[i + 1] - sig_ref[i]);
}

static void analyse(struct exp_result *r)
{
    unsigned k, i0 = 0, i1 = 0;
    double best = -1.0;
    int j;
    r->umin = r->umax = 0.0;
    for (k = 0; k < n_sig; k++) {
        r->umin = sig_u[k] < r->umin ? sig_u[k] : r->umin;
        r->umax = sig_u[k] > r->umax ? sig_u[k] : r->umax;
        if (!i0 && sig_ref[k] > 1e-6)
            i0 = k;
        if (!i1 && sig_ref[k] > FRAC_PI / 2 - 1e-6)
            i1 = k;
    }
    assert_true(i0 > 0 && i1 > i0);
    r->final_tip = sig_tip[n_sig - 1];
    for (j = -300; j <= 300; j++) {
        double lag = 1e-4 * j, e = 0.0;
        for (k = i0; k < i1; k++) {
            double d = sig_tip[k] - ref_at(sig_t[k] - lag);
            e += d * d;
        }
        if (best < 0.0 || e < best) {
            best = e;
            r->lag = lag;
        }
    }
}

static void exp_run(char which, struct exp_result *r)
{
    struct hil_rig_config c;
    unsigned long size;
    unsigned char *b;
    load_scenario(&c, which);
    b = frac_test_slurp(c.ctrl_table, &size);
    assert_int_equal(run(&c, b, size), HIL_OK);
    free(b);
    analyse(r);
    print_message("Exp. %c: torque %.1f .. %.1f Nm, final tip %.5f rad (pi/2 %+.1e), tip lag %.1f ms\n",
                  which - 'a' + 'A', r->umin, r->umax, r->final_tip, r->final_tip - FRAC_PI / 2, 1e3 * r->lag);
    assert_int_equal(rig.ctrl.faults, 0);
    assert_int_equal(rig.ctrl.law_status, 0);
    assert_int_equal(rig.ctrl.missed_inputs, 0);
}

static void within(double got, double thesis, double rel)
{
    print_message("  %.1f Nm vs thesis about %.0f Nm (tolerance %.0f %%)\n", got, thesis, 100 * rel);
    assert_true(fabs(got - thesis) <= rel * fabs(thesis));
}

static void test_exp_a_and_b_torque_ranges_and_tracking(void **state)
{
    struct exp_result a, b;
    (void)state;
    exp_run('a', &a);
    within(a.umin, -40.0, 0.25);
    within(a.umax, 60.0, 0.25);
    assert_close(a.final_tip, FRAC_PI / 2, 1e-2);
    exp_run('b', &b);
    within(b.umin, -20.0, 0.25);
    within(b.umax, 50.0, 0.25);
    assert_close(b.final_tip, FRAC_PI / 2, 2e-3);
}

static void test_exp_c_and_d_track_and_d_lags_less(void **state)
{
    struct exp_result c, d;
    (void)state;
    exp_run('c', &c);
    assert_close(c.final_tip, FRAC_PI / 2, 2e-3);
    exp_run('d', &d);
    assert_close(d.final_tip, FRAC_PI / 2, 2e-3);
    print_message("tip lag Exp. C %.1f ms -> Exp. D %.1f ms (thesis 15 ms -> 6 ms)\n", 1e3 * c.lag, 1e3 * d.lag);
    assert_true(d.lag < c.lag);
}

static void test_bad_table_never_enables_torque_and_reports_status(void **state)
{
    struct hil_rig_config c;
    unsigned long size, k;
    unsigned char *b;
    (void)state;
    load_scenario(&c, 'd');
    c.duration = 0.1;
    b = frac_test_slurp(c.ctrl_table, &size);
    b[size / 2] ^= 0x40; /* CRC no longer matches */
    assert_int_equal(run(&c, b, size), HIL_E_STATE);
    free(b);
    for (k = 0; k < n_sig; k++)
        assert_true(sig_u[k] == 0.0);
    print_message("refused table: law_status %u, EMCY sent %llu\n", rig.ctrl.law_status,
                  (unsigned long long)rig.ctrl.emcy_sent);
    assert_true(rig.ctrl.law_status >= 50000); /* a FracCtrl error StatusID */
    assert_int_equal(rig.ctrl.faults, 1);
    assert_true(rig.ctrl.emcy_sent >= 1);
    assert_true(rig.drive.tau_act == 0.0);
}

/* IMU frames stop for 100 ms mid-move (Exp. D, whose LQG needs the tip
 * rate): ArmCtrl's IMU Watchdog trips within 3 cycles of the first missing
 * reading (readings come every 2.4 ms; + 1 cycle for ImuRead's task to
 * publish), EMCY, the torque reaches 0 within 10 ms; once readings are
 * fresh again the node acknowledges (hil/plc/plc_law.h), EMCY "no error",
 * and the move still ends at pi/2. */
static void test_imu_dropout_trips_watchdog_and_recovers_on_fresh_data(void **state)
{
    struct hil_rig_config c;
    unsigned long size, k;
    unsigned char *b;
    double t_fault = -1.0, t_zero = -1.0, t_clear = -1.0, T;
    int episodes = 0;
    (void)state;
    load_scenario(&c, 'd');
    T = c.ctrl.T;
    c.imu_dropout_start = 1.0;
    c.imu_dropout_end = 1.1;
    b = frac_test_slurp(c.ctrl_table, &size);
    assert_int_equal(run(&c, b, size), HIL_OK);
    free(b);
    for (k = 1; k < n_sig; k++) {
        if (sig_fault[k] && !sig_fault[k - 1]) {
            episodes++;
            t_fault = sig_t[k];
        }
        if (t_fault > 0.0 && t_zero < 0.0 && sig_u[k] == 0.0)
            t_zero = sig_t[k];
        if (!sig_fault[k] && sig_fault[k - 1])
            t_clear = sig_t[k];
    }
    print_message("IMU dropout 1.0-1.1 s: fault at %.1f ms, torque 0 %.1f ms later, cleared at %.1f ms; "
                  "final tip %.5f rad (pi/2 %+.1e); EMCY %llu\n", 1e3 * t_fault, 1e3 * (t_zero - t_fault),
                  1e3 * t_clear, sig_tip[n_sig - 1], sig_tip[n_sig - 1] - FRAC_PI / 2,
                  (unsigned long long)rig.ctrl.emcy_sent);
    assert_int_equal(episodes, 1);
    assert_int_equal(rig.ctrl.faults, 1);
    assert_true(t_fault > 1.0 && t_fault <= 1.0 + 2.4e-3 + 4 * T + 1e-9);
    assert_true(t_zero >= t_fault && t_zero - t_fault <= 10e-3 + 1e-9);
    assert_true(t_clear > 1.1 && t_clear <= 1.1 + 2.4e-3 + 3 * T + 1e-9);
    assert_true(rig.ctrl.emcy_sent >= 2); /* the fault and "no error" */
    assert_close(sig_tip[n_sig - 1], FRAC_PI / 2, 5e-3);
}

/* Residual oscillation of the tip after the move with stiction: amplitude
 * (half peak-to-peak about the mean) and frequency (zero crossings) per
 * window of one second. */
static void residual(double t0, double t1, double *amp, double *hz)
{
    unsigned k, n = 0, zc = 0;
    double mean = 0.0, lo = 1e9, hi = -1e9, prev = 0.0, tz0 = 0.0, tz1 = 0.0;
    for (k = 0; k < n_sig; k++)
        if (sig_t[k] > t0 && sig_t[k] <= t1) {
            mean += sig_tip[k];
            n++;
        }
    mean /= n;
    for (k = 0; k < n_sig; k++) {
        double s;
        if (!(sig_t[k] > t0 && sig_t[k] <= t1))
            continue;
        s = sig_tip[k] - mean;
        lo = s < lo ? s : lo;
        hi = s > hi ? s : hi;
        if (prev != 0.0 && (s > 0.0) != (prev > 0.0)) {
            if (!zc)
                tz0 = sig_t[k];
            tz1 = sig_t[k];
            zc++;
        }
        prev = s;
    }
    *amp = 0.5 * (hi - lo);
    *hz = zc > 2 ? 0.5 * (double)(zc - 1) / (tz1 - tz0) : 0.0;
}

static void test_stiction_residual_oscillation_is_measured(void **state)
{
    const char which[2] = {'b', 'd'};
    int i;
    (void)state;
    for (i = 0; i < 2; i++) {
        struct hil_rig_config c;
        unsigned long size;
        unsigned char *b;
        double a1, f1, a3, f3;
        load_scenario(&c, which[i]);
        assert_int_equal(hil_rig_config_set(&c, "plant.friction", "2"), HIL_OK);
        c.plant_p.friction.b1s = 7.684;
        c.plant_p.friction.b2s = 11.5;
        c.plant_p.friction.b3s = 3.04;
        c.plant_p.friction.v_s = 0.05;
        c.plant_p.friction.delta = 2.0;
        c.duration = 6.0;
        b = frac_test_slurp(c.ctrl_table, &size);
        assert_int_equal(run(&c, b, size), HIL_OK);
        free(b);
        residual(2.2, 3.2, &a1, &f1);
        residual(5.0, 6.0, &a3, &f3);
        print_message("stiction, Exp. %c: residual tip oscillation %.2e rad at %.2f Hz (2.2-3.2 s), %.2e rad at "
                      "%.2f Hz (5-6 s); final tip %.5f rad\n",
                      which[i] - 'a' + 'A', a1, f1, a3, f3, sig_tip[n_sig - 1]);
        /* the tanh-smoothed stiction (k = 60) holds the motor like a stiff
         * damper below |v| ~ 1/k: no limit cycle, the beam's modes ring down */
        assert_true(a1 > 0.0);
        assert_true(a3 < 0.5 * a1);
        assert_close(sig_tip[n_sig - 1], FRAC_PI / 2, 2e-3);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exp_a_and_b_torque_ranges_and_tracking),
        cmocka_unit_test(test_exp_c_and_d_track_and_d_lags_less),
        cmocka_unit_test(test_bad_table_never_enables_torque_and_reports_status),
        cmocka_unit_test(test_imu_dropout_trips_watchdog_and_recovers_on_fresh_data),
        cmocka_unit_test(test_stiction_residual_oscillation_is_measured),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
