/* The emulated nodes one by one: CiA 402 drive (state machine, 4-sample
 * torque delay, current-loop lag, torque limits, RPDO timeout), IMU (reading
 * latency, seeded noise, quantization, saturation), rigid test plant (against
 * the closed-form solution) and controller (IMU watchdog fault reaction and
 * recovery); malformed frames counted and ignored with the state untouched;
 * the drive's torque effects for the gap bench (dead zone and gain act on
 * the shaft torque only; their scenario keys and run metadata). */
#include <string.h>
#include "frac_test.h"
#include "hil/canopen.h"
#include "hil/ctrl.h"
#include "hil/drive.h"
#include "hil/imu.h"
#include "hil/node.h"
#include "hil/plant.h"
#include "hil/rig.h"

static struct hil_can_frame nmt_start(void)
{
    struct hil_can_frame f;
    hil_co_nmt_encode(&f, HIL_NMT_START, 0);
    return f;
}

static struct hil_can_frame sync_frame(void)
{
    struct hil_can_frame f;
    hil_co_sync_encode(&f, 1);
    return f;
}

static struct hil_can_frame rpdo(uint16_t cw, double torque)
{
    struct hil_can_frame f;
    struct hil_drive_rpdo r;
    r.controlword = cw;
    r.torque_mnm = (int32_t)(torque * 1000.0);
    hil_co_drive_rpdo_encode(&f, &r);
    return f;
}

static const struct hil_can_frame *find(const struct hil_out *o, uint32_t id)
{
    int i;
    for (i = 0; i < o->n; i++)
        if (o->f[i].id == id)
            return &o->f[i];
    return NULL;
}

/* Torque the drive applies over the cycle started by one SYNC (end value). */
static double sync_torque(struct hil_drive *d, struct hil_out *o)
{
    struct hil_can_frame s = sync_frame();
    const struct hil_can_frame *t;
    double a, b;
    o->n = 0;
    assert_int_equal(hil_drive_on_frame(d, &s, o), HIL_OK);
    t = find(o, HIL_COB_RIG_TORQUE);
    assert_non_null(t);
    assert_int_equal(hil_co_rig_decode(t, HIL_COB_RIG_TORQUE, &a, &b), HIL_OK);
    return b;
}

static void enable_drive(struct hil_drive *d, struct hil_out *o)
{
    static const uint16_t cws[] = {HIL_CW_SHUTDOWN, HIL_CW_SWITCH_ON, HIL_CW_ENABLE_OP};
    struct hil_can_frame f = nmt_start();
    int i;
    o->n = 0;
    assert_int_equal(hil_drive_on_frame(d, &f, o), HIL_OK);
    for (i = 0; i < 3; i++) {
        f = rpdo(cws[i], 0.0);
        assert_int_equal(hil_drive_on_frame(d, &f, o), HIL_OK);
    }
    assert_int_equal(d->state, HIL_CIA402_OPERATION_ENABLED);
    assert_int_equal(hil_drive_statusword(d) & 0x6F, 0x27);
}

static void test_drive_follows_cia402_state_machine_and_boots_with_heartbeat(void **state)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    (void)state;
    hil_drive_params_default(&p);
    o.n = 0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_OK);
    assert_int_equal(o.n, 1);
    assert_int_equal(o.f[0].id, 0x701);
    assert_int_equal(o.f[0].data[0], HIL_NMT_STATE_BOOTUP);
    /* PDOs are ignored before NMT start */
    f = rpdo(HIL_CW_SHUTDOWN, 0.0);
    assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_E_STATE);
    assert_int_equal(d.state, HIL_CIA402_SWITCH_ON_DISABLED);
    /* enable operation without the intermediate states is refused */
    f = nmt_start();
    hil_drive_on_frame(&d, &f, &o);
    f = rpdo(HIL_CW_ENABLE_OP, 0.0);
    hil_drive_on_frame(&d, &f, &o);
    assert_int_equal(d.state, HIL_CIA402_SWITCH_ON_DISABLED);
    enable_drive(&d, &o);
    f = rpdo(HIL_CW_QUICK_STOP, 0.0);
    hil_drive_on_frame(&d, &f, &o);
    assert_int_equal(d.state, HIL_CIA402_QUICK_STOP_ACTIVE);
    f = rpdo(HIL_CW_DISABLE_VOLTAGE, 0.0);
    hil_drive_on_frame(&d, &f, &o);
    assert_int_equal(d.state, HIL_CIA402_SWITCH_ON_DISABLED);
    p.delay = 0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_E_ARG);
}

static void test_drive_applies_command_after_four_samples(void **state)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    int k;
    (void)state;
    hil_drive_params_default(&p);
    p.tau_current = 0.0; /* ideal current loop: the delay alone is visible */
    o.n = 0;
    hil_drive_init(&d, &p, &o);
    enable_drive(&d, &o);
    /* cycle j: SYNC then the RPDO computed in that cycle (u_j = 10 (j + 1)) */
    for (k = 0; k < 10; k++) {
        double tau = sync_torque(&d, &o);
        double want = k >= 4 ? 10.0 * (k - 4 + 1) : 0.0;
        assert_close(tau, want, 1e-9);
        f = rpdo(HIL_CW_ENABLE_OP, 10.0 * (k + 1));
        assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_OK);
    }
}

static void test_drive_current_loop_is_first_order_lag(void **state)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    double tau = 0.0;
    int k;
    (void)state;
    hil_drive_params_default(&p);
    p.delay = 1;
    o.n = 0;
    hil_drive_init(&d, &p, &o);
    enable_drive(&d, &o);
    f = rpdo(HIL_CW_ENABLE_OP, 50.0);
    hil_drive_on_frame(&d, &f, &o);
    for (k = 1; k <= 3; k++) {
        tau = sync_torque(&d, &o);
        assert_close(tau, 50.0 * (1.0 - exp(-k * p.T / p.tau_current)), 1e-5); /* float32 frame */
        hil_drive_on_frame(&d, &f, &o);
    }
    (void)tau;
}

static void test_drive_limits_to_peak_then_rated_torque(void **state)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    const struct hil_can_frame *t1;
    struct hil_drive_tpdo1 tp;
    double tau = 0.0;
    int k;
    (void)state;
    hil_drive_params_default(&p);
    p.delay = 1;
    p.tau_current = 0.0;
    o.n = 0;
    hil_drive_init(&d, &p, &o);
    enable_drive(&d, &o);
    f = rpdo(HIL_CW_ENABLE_OP, 400.0);
    hil_drive_on_frame(&d, &f, &o);
    tau = sync_torque(&d, &o);
    assert_close(tau, 251.0, 1e-9);
    /* i^2 t: after the thermal estimate passes rated^2 the limit drops */
    for (k = 0; k < 2000; k++) {
        hil_drive_on_frame(&d, &f, &o);
        tau = sync_torque(&d, &o);
    }
    assert_close(tau, 95.7, 1e-5);
    hil_drive_on_frame(&d, &f, &o);
    sync_torque(&d, &o);
    o.n = 0;
    f = sync_frame();
    hil_drive_on_frame(&d, &f, &o);
    t1 = find(&o, HIL_COB_TPDO1(HIL_NODE_DRIVE));
    assert_non_null(t1);
    hil_co_drive_tpdo1_decode(t1, &tp);
    assert_true(tp.statusword & HIL_SW_INTERNAL_LIMIT);
}

static void test_drive_faults_and_sends_emcy_when_rpdos_stop(void **state)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    struct hil_emcy e;
    const struct hil_can_frame *em = NULL;
    int k;
    (void)state;
    hil_drive_params_default(&p);
    o.n = 0;
    hil_drive_init(&d, &p, &o);
    enable_drive(&d, &o);
    for (k = 0; k < 5 && !em; k++) {
        sync_torque(&d, &o);
        em = find(&o, HIL_COB_EMCY(HIL_NODE_DRIVE));
    }
    assert_non_null(em);
    assert_int_equal(k, 4); /* rpdo_timeout = 3 SYNCs tolerated */
    hil_co_emcy_decode(em, NULL, &e);
    assert_int_equal(e.code, HIL_EMCY_RPDO_TIMEOUT);
    assert_int_equal(d.state, HIL_CIA402_FAULT);
    assert_int_equal(hil_drive_statusword(&d) & HIL_SW_FAULT, HIL_SW_FAULT);
    assert_close(sync_torque(&d, &o), 0.0, 1e-6);
    f = rpdo(HIL_CW_FAULT_RESET, 0.0);
    hil_drive_on_frame(&d, &f, &o);
    assert_int_equal(d.state, HIL_CIA402_SWITCH_ON_DISABLED);
}

static void test_drive_counts_and_ignores_malformed_frames(void **state)
{
    struct hil_drive d, before;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    (void)state;
    hil_drive_params_default(&p);
    o.n = 0;
    hil_drive_init(&d, &p, &o);
    enable_drive(&d, &o);
    before = d;
    f = rpdo(HIL_CW_DISABLE_VOLTAGE, 200.0);
    f.dlc = 5;
    o.n = 0;
    assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_E_DLC);
    f.id = 0x555;
    f.dlc = 8;
    assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_E_UNKNOWN_ID);
    hil_co_rig_encode(&f, HIL_COB_RIG_MOTOR, 1.0, 2.0);
    hil_put_f32(f.data, (float)NAN);
    assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_E_RANGE);
    f = sync_frame();
    f.data[0] = 0;
    assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_E_FORMAT);
    assert_int_equal(o.n, 0);
    assert_int_equal(d.rx.bad_dlc, 1);
    assert_int_equal(d.rx.unknown_id, 1);
    assert_int_equal(d.rx.bad_value, 2);
    assert_int_equal(d.state, before.state);
    assert_true(d.cmd_latest == before.cmd_latest && d.theta == before.theta && d.syncs == before.syncs);
}

static void test_drive_encoder_counts_with_its_resolution_and_differences_velocity(void **state)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    struct hil_drive_tpdo1 t1;
    struct hil_drive_tpdo2 t2;
    static const double angle[] = {0.001, 0.002, 0.0045, -0.001};
    static const int32_t want[] = {0, 256, 512, -256}; /* floor(angle 4096 / 2 pi) * 2^8 */
    int k;
    (void)state;
    hil_drive_params_default(&p);
    p.encoder_bits = 12;
    p.velocity_from_encoder = 1;
    o.n = 0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_OK);
    f = nmt_start();
    hil_drive_on_frame(&d, &f, &o);
    for (k = 0; k < 4; k++) {
        hil_co_rig_encode(&f, HIL_COB_RIG_MOTOR, angle[k], 123.0);
        assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_OK);
        o.n = 0;
        f = sync_frame();
        hil_drive_on_frame(&d, &f, &o);
        hil_co_drive_tpdo1_decode(find(&o, HIL_COB_TPDO1(HIL_NODE_DRIVE)), &t1);
        hil_co_drive_tpdo2_decode(find(&o, HIL_COB_TPDO2(HIL_NODE_DRIVE)), &t2);
        assert_int_equal(t1.position_inc, want[k]);
        if (k > 0) /* one count = 2 pi / 4096 rad in one cycle */
            assert_close(t2.velocity_urads * 1e-6, (want[k] - want[k - 1]) / 256.0 * (2.0 * M_PI / 4096) / p.T, 1e-6);
    }
    p.encoder_bits = 21;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_E_ARG);
}

/* ---- the drive's torque effects for the gap bench (drive.deadzone, drive.gain) ---- */

/* Enabled drive with delay 1, an ideal current loop and the torque effects
 * (deadzone, gain); after one SYNC with command `cmd` pending: *shaft = end
 * torque sent to the plant, *reported = the torque actual of the next TPDO2
 * (the drive reports the commanded torque, hil/drive.h). */
static void shaft_and_reported(double deadzone, double gain, double cmd, double *shaft, double *reported)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    struct hil_drive_tpdo2 t2;
    const struct hil_can_frame *t;
    hil_drive_params_default(&p);
    p.delay = 1;
    p.tau_current = 0.0;
    p.deadzone = deadzone;
    p.gain = gain;
    o.n = 0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_OK);
    enable_drive(&d, &o);
    f = rpdo(HIL_CW_ENABLE_OP, cmd);
    assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_OK);
    *shaft = sync_torque(&d, &o);
    f = rpdo(HIL_CW_ENABLE_OP, cmd);
    assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_OK);
    (void)sync_torque(&d, &o); /* o: this SYNC's frames, TPDO2 among them */
    t = find(&o, HIL_COB_TPDO2(HIL_NODE_DRIVE));
    assert_non_null(t);
    assert_int_equal(hil_co_drive_tpdo2_decode(t, &t2), HIL_OK);
    *reported = t2.torque_mnm * HIL_TORQUE_LSB;
}

static void test_drive_dead_zone_and_gain_act_on_the_shaft_torque_only(void **state)
{
    double shaft, rep;
    (void)state;
    shaft_and_reported(0.0, 1.0, 20.0, &shaft, &rep);
    assert_close(shaft, 20.0, 1e-9);
    shaft_and_reported(5.0, 1.0, 20.0, &shaft, &rep);
    assert_close(shaft, 15.0, 1e-9);
    assert_close(rep, 20.0, 1e-9);
    shaft_and_reported(5.0, 1.0, -20.0, &shaft, &rep);
    assert_close(shaft, -15.0, 1e-9);
    shaft_and_reported(5.0, 1.0, 4.0, &shaft, &rep);
    assert_close(shaft, 0.0, 1e-12);
    assert_close(rep, 4.0, 1e-9);
    shaft_and_reported(0.0, 1.25, 20.0, &shaft, &rep);
    assert_close(shaft, 25.0, 1e-9);
    assert_close(rep, 20.0, 1e-9);
    shaft_and_reported(2.0, 0.5, -20.0, &shaft, &rep);
    assert_close(shaft, -9.0, 1e-9);
}

static void test_drive_rejects_negative_dead_zone_and_non_positive_gain(void **state)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    (void)state;
    o.n = 0;
    hil_drive_params_default(&p);
    assert_close(p.gain, 1.0, 0.0);
    assert_close(p.deadzone, 0.0, 0.0);
    p.deadzone = -1.0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_E_ARG);
    hil_drive_params_default(&p);
    p.gain = 0.0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_E_ARG);
    p.gain = -1.0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_E_ARG);
}

static void test_rig_keys_set_dead_zone_and_gain_and_the_metadata_records_them(void **state)
{
    struct hil_rig_config c;
    char buf[16384];
    FILE *f;
    size_t n;
    (void)state;
    hil_rig_config_default(&c);
    assert_int_equal(hil_rig_config_set(&c, "drive.deadzone", "3.5"), HIL_OK);
    assert_int_equal(hil_rig_config_set(&c, "drive.gain", "0.8"), HIL_OK);
    assert_int_equal(hil_rig_config_set(&c, "drive.gain", "x"), HIL_E_FORMAT);
    assert_close(c.drive.deadzone, 3.5, 0.0);
    assert_close(c.drive.gain, 0.8, 0.0);
    f = tmpfile();
    assert_non_null(f);
    assert_int_equal(hil_rig_meta_begin(&c, "lockstep", f), HIL_OK);
    rewind(f);
    n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    assert_non_null(strstr(buf, "\"drive.deadzone\": 3.5,"));
    assert_non_null(strstr(buf, "\"drive.gain\": 0.80000000000000004,"));
    assert_non_null(strstr(buf, "\"torque_deadzone\": 3.5, \"torque_gain\": 0.80000000000000004}"));
}

/* Feeds the IMU one plant half-step (RIG_TIPPOS + RIG_TIP). */
static void acquire(struct hil_imu *m, double rate, struct hil_out *o)
{
    struct hil_can_frame f;
    hil_co_rig_encode(&f, HIL_COB_RIG_TIPPOS, 0.0, 0.0);
    assert_int_equal(hil_imu_on_frame(m, &f, o), HIL_OK);
    hil_co_rig_encode(&f, HIL_COB_RIG_TIP, rate, 0.0);
    assert_int_equal(hil_imu_on_frame(m, &f, o), HIL_OK);
}

static void test_imu_reading_leaves_four_acquisitions_after_sampling(void **state)
{
    struct hil_imu m;
    struct hil_imu_params p;
    struct hil_out o;
    struct hil_can_frame f = nmt_start();
    struct hil_imu_tpdo t;
    const struct hil_can_frame *r;
    int j;
    (void)state;
    hil_imu_params_default(&p);
    o.n = 0;
    hil_imu_init(&m, &p, &o);
    hil_imu_on_frame(&m, &f, &o);
    /* acquisition j sees rate 0.01 j; readings start at j = 4, 8, ... */
    for (j = 1; j <= 12; j++) {
        o.n = 0;
        acquire(&m, 0.01 * j, &o);
        r = find(&o, HIL_COB_TPDO1(HIL_NODE_IMU));
        if (j == 8 || j == 12) {
            assert_non_null(r);
            hil_co_imu_decode(r, 1, &t);
            assert_int_equal(t.xyz[2], (int)(10 * (j - 4)));
            assert_int_equal(t.seq, j / 4 - 1);
            assert_non_null(find(&o, HIL_COB_TPDO2(HIL_NODE_IMU)));
        } else {
            assert_null(r);
        }
    }
}

/* Acquisition index at which each of the first readings leaves the IMU. */
static int reading_departures(double jitter_prob, uint64_t seed, int *dep, int n)
{
    struct hil_imu m;
    struct hil_imu_params p;
    struct hil_out o;
    struct hil_can_frame f = nmt_start();
    int j, got = 0;
    hil_imu_params_default(&p);
    p.jitter_prob = jitter_prob;
    p.seed = seed;
    o.n = 0;
    hil_imu_init(&m, &p, &o);
    hil_imu_on_frame(&m, &f, &o);
    for (j = 1; j <= 400 && got < n; j++) {
        int i;
        o.n = 0;
        acquire(&m, 0.0, &o);
        for (i = 0; i < o.n && got < n; i++)
            if (o.f[i].id == HIL_COB_TPDO1(HIL_NODE_IMU))
                dep[got++] = j;
    }
    return got;
}

static void test_imu_jitter_delays_readings_by_one_acquisition(void **state)
{
    int a[40], b[40], c[40], k, late = 0;
    (void)state;
    assert_int_equal(reading_departures(0.0, 1, a, 40), 40);
    assert_int_equal(reading_departures(1.0, 1, b, 40), 40);
    assert_int_equal(reading_departures(0.5, 3, c, 40), 40);
    for (k = 0; k < 40; k++) {
        assert_int_equal(a[k], 4 * (k + 2));     /* sampled at 4 (k + 1), sent 4 later */
        assert_int_equal(b[k], 4 * (k + 2) + 1); /* always one acquisition late */
        assert_true(c[k] == a[k] || c[k] == b[k]);
        late += c[k] == b[k];
    }
    assert_true(late > 5 && late < 35); /* seeded coin, both outcomes */
}

static void test_imu_noise_is_seeded_and_quantized(void **state)
{
    struct hil_imu a, b;
    struct hil_imu_params p;
    struct hil_out oa, ob;
    struct hil_can_frame f = nmt_start();
    int j, differs = 0;
    (void)state;
    hil_imu_params_default(&p);
    p.reading_cycles = 1;
    p.gyro_noise = 0.05;
    p.gyro_quant = 0.004;
    p.seed = 42;
    oa.n = ob.n = 0;
    hil_imu_init(&a, &p, &oa);
    hil_imu_init(&b, &p, &ob);
    hil_imu_on_frame(&a, &f, &oa);
    hil_imu_on_frame(&b, &f, &ob);
    for (j = 0; j < 50; j++) {
        const struct hil_can_frame *ra, *rb;
        struct hil_imu_tpdo ta;
        oa.n = ob.n = 0;
        acquire(&a, 0.5, &oa);
        acquire(&b, 0.5, &ob);
        ra = find(&oa, HIL_COB_TPDO1(HIL_NODE_IMU));
        rb = find(&ob, HIL_COB_TPDO1(HIL_NODE_IMU));
        if (!ra)
            continue;
        assert_non_null(rb);
        assert_memory_equal(ra->data, rb->data, 8);
        hil_co_imu_decode(ra, 1, &ta);
        assert_int_equal(ta.xyz[2] % 4, 0); /* 4 mrad/s steps */
        differs |= ta.xyz[2] != 500;
    }
    assert_true(differs);
    p.gyro_noise = -1.0;
    assert_int_equal(hil_imu_init(&a, &p, &oa), HIL_E_ARG);
}

static void test_imu_saturates_and_flags_out_of_range_rates(void **state)
{
    struct hil_imu m;
    struct hil_imu_params p;
    struct hil_out o;
    struct hil_can_frame f = nmt_start();
    struct hil_imu_tpdo t;
    int j;
    (void)state;
    hil_imu_params_default(&p);
    p.reading_cycles = 1;
    o.n = 0;
    hil_imu_init(&m, &p, &o);
    hil_imu_on_frame(&m, &f, &o);
    for (j = 0; j < 2; j++) {
        o.n = 0;
        acquire(&m, 100.0, &o);
    }
    hil_co_imu_decode(find(&o, HIL_COB_TPDO1(HIL_NODE_IMU)), 1, &t);
    assert_int_equal(t.xyz[2], 32767);
    assert_int_equal(t.status & HIL_IMU_ST_SATURATED, HIL_IMU_ST_SATURATED);
}

static void test_rigid_plant_matches_closed_form_under_constant_torque(void **state)
{
    struct hil_plant pl;
    struct hil_plant_params p;
    struct hil_out o;
    struct hil_can_frame f;
    double a, b, tau = 10.0, t, w_exact, th_exact;
    int k;
    (void)state;
    hil_plant_params_default(&p);
    assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
    hil_co_rig_encode(&f, HIL_COB_RIG_TORQUE, tau, tau);
    for (k = 0; k < 100; k++) {
        o.n = 0;
        assert_int_equal(hil_plant_on_frame(&pl, &f, &o), HIL_OK);
    }
    assert_int_equal(o.n, 5);
    assert_int_equal(o.f[4].id, HIL_COB_RIG_MOTOR);
    hil_co_rig_decode(&o.f[4], HIL_COB_RIG_MOTOR, &a, &b);
    /* J w' = tau - b w: w = tau/b (1 - e^{-b t / J}) */
    t = 100 * p.T;
    w_exact = tau / p.b * (1.0 - exp(-p.b * t / p.J));
    th_exact = tau / p.b * (t - p.J / p.b * (1.0 - exp(-p.b * t / p.J)));
    assert_rel(b, w_exact, 1e-6);
    assert_rel(a, th_exact, 1e-6);
    assert_rel(pl.omega, w_exact, 1e-10);
    p.J = 0.0;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
}

static void test_twomass_plant_conserves_momentum_and_oscillates_at_gear_mode(void **state)
{
    struct hil_plant pl;
    struct hil_plant_params p;
    struct hil_out o;
    struct hil_can_frame f;
    double tau = 20.0, t, wn, peak = 0.0;
    int k;
    (void)state;
    hil_plant_params_default(&p);
    p.model = HIL_PLANT_TWOMASS;
    p.friction.b1 = 0.0;
    p.friction.b0 = 0.0;
    p.substeps = 8;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
    hil_co_rig_encode(&f, HIL_COB_RIG_TORQUE, tau, tau);
    for (k = 0; k < 200; k++) {
        o.n = 0;
        assert_int_equal(hil_plant_on_frame(&pl, &f, &o), HIL_OK);
        if (fabs(pl.theta - pl.psi) > peak)
            peak = fabs(pl.theta - pl.psi);
    }
    /* the spring is internal: I_M theta' + I_L psi' = tau t (RK4 keeps linear invariants) */
    t = 200 * p.T;
    assert_rel(p.I_M * pl.omega + p.I_L * pl.psi_d, tau * t, 1e-9);
    /* a step torque excites the gear mode: twist peaks at twice its static value
     * tau I_L / ((I_M + I_L) c_s) (undamped second-order step response) */
    wn = sqrt(p.c_s * (1.0 / p.I_M + 1.0 / p.I_L));
    assert_true(wn > 200.0);
    assert_rel(peak, 2.0 * tau * p.I_L / ((p.I_M + p.I_L) * p.c_s), 2e-3);
    p.friction.k = 0.0; /* frac_friction_init refuses it */
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
    p.model = 7;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
}

static void test_twomass_backlash_holds_link_until_play_is_crossed(void **state)
{
    struct hil_plant pl;
    struct hil_plant_params p;
    struct hil_out o;
    struct hil_can_frame f;
    double tau = 5.0, t_cross;
    int k, moved_early = 0;
    (void)state;
    hil_plant_params_default(&p);
    p.model = HIL_PLANT_TWOMASS;
    p.friction.b1 = 0.0;
    p.friction.b0 = 0.0;
    p.backlash = 0.02;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
    /* free motor: theta_M = tau t^2 / (2 I_M) reaches the half play 0.01 rad at t_cross */
    t_cross = sqrt(2.0 * 0.01 * p.I_M / tau);
    hil_co_rig_encode(&f, HIL_COB_RIG_TORQUE, tau, tau);
    for (k = 0; k < 300; k++) {
        o.n = 0;
        hil_plant_on_frame(&pl, &f, &o);
        if (pl.t < t_cross - 2 * p.T) {
            moved_early |= pl.psi != 0.0;
            assert_close(pl.theta, tau * pl.t * pl.t / (2.0 * p.I_M), 1e-9);
        }
    }
    assert_false(moved_early);
    assert_true(pl.psi > 0.0);
    p.backlash = -1.0;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
}

static void test_twomass_extra_mode_conserves_momentum_and_shows_at_the_tip(void **state)
{
    struct hil_plant pl;
    struct hil_plant_params p;
    struct hil_out o;
    struct hil_can_frame f;
    double tau = 20.0, dev = 0.0, t;
    int k;
    (void)state;
    hil_plant_params_default(&p);
    p.model = HIL_PLANT_TWOMASS;
    p.friction.b1 = 0.0;
    p.friction.b0 = 0.0;
    p.extra_inertia = 0.05;
    p.extra_hz = 20.0;
    p.extra_zeta = 0.0;
    p.substeps = 8;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
    hil_co_rig_encode(&f, HIL_COB_RIG_TORQUE, tau, tau);
    for (k = 0; k < 200; k++) {
        o.n = 0;
        hil_plant_on_frame(&pl, &f, &o);
        if (fabs(pl.x[4]) > dev)
            dev = fabs(pl.x[4]);
    }
    t = 200 * p.T;
    /* I_M theta' + I_L psi_link' + I_e (psi_link' + q_e') = tau t */
    assert_rel(p.I_M * pl.x[1] + p.I_L * pl.x[3] + p.extra_inertia * (pl.x[3] + pl.x[5]), tau * t, 1e-9);
    assert_true(dev > 1e-5);
    assert_close(pl.psi, pl.x[2] + pl.x[4], 0.0);
    p.extra_hz = 0.0;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
}

/* Twist ring-down amplitude over the last 100 ms of 0.4 s after a torque step. */
static double twist_ring(double kv_damping, double order)
{
    static struct hil_plant pl;
    struct hil_plant_params p;
    struct hil_out o;
    struct hil_can_frame f;
    double lo = 1e9, hi = -1e9;
    int k;
    hil_plant_params_default(&p);
    p.model = HIL_PLANT_TWOMASS;
    p.friction.b1 = 0.0;
    p.friction.b0 = 0.0;
    p.substeps = 8;
    p.kv_damping = kv_damping;
    p.kv_order = order;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_OK);
    hil_co_rig_encode(&f, HIL_COB_RIG_TORQUE, 20.0, 20.0);
    for (k = 0; k < 333; k++) {
        o.n = 0;
        hil_plant_on_frame(&pl, &f, &o);
        if (k >= 250) {
            double tw = pl.theta - pl.x[2];
            lo = tw < lo ? tw : lo;
            hi = tw > hi ? tw : hi;
        }
    }
    return hi - lo;
}

static void test_twomass_fractional_kelvin_voigt_damping_rings_down_the_gear_mode(void **state)
{
    struct hil_plant pl;
    struct hil_plant_params p;
    double free_ring = twist_ring(0.0, 0.5), damped = twist_ring(200.0, 0.5), damped_more = twist_ring(800.0, 0.5);
    (void)state;
    print_message("gear-mode twist ring p-p: free %.3g, kv 200 %.3g, kv 800 %.3g rad\n", free_ring, damped, damped_more);
    assert_true(free_ring > 5e-5); /* undamped: twice the static twist 4.4e-5 rad, peak to peak */
    assert_true(damped < 0.5 * free_ring);
    assert_true(damped_more < damped);
    hil_plant_params_default(&p);
    p.model = HIL_PLANT_TWOMASS;
    p.kv_damping = 1.0;
    p.kv_order = 1.5;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
    p.kv_order = 0.5;
    p.kv_memory = HIL_PLANT_KV_MAX + 1;
    assert_int_equal(hil_plant_init(&pl, &p), HIL_E_ARG);
}

/* Runs controller cycles against a drive reporting a resting shaft; IMU
 * readings arrive every second cycle while `imu_on`. Returns the RPDO torque. */
static double ctrl_cycle(struct hil_ctrl *c, int imu_on, uint8_t *seq, struct hil_out *o)
{
    struct hil_can_frame f;
    struct hil_drive_tpdo1 t1 = {0x0237, 0};
    struct hil_drive_tpdo2 t2 = {0, 0};
    struct hil_imu_tpdo im = {{0, 0, 0}, 0, 0};
    struct hil_drive_rpdo r;
    const struct hil_can_frame *rp;
    o->n = 0;
    hil_ctrl_tick(c, o);
    hil_co_drive_tpdo1_encode(&f, &t1);
    hil_ctrl_on_frame(c, &f, o);
    hil_co_drive_tpdo2_encode(&f, &t2);
    hil_ctrl_on_frame(c, &f, o);
    hil_ctrl_deadline(c, o);
    if (imu_on && c->cycle % 2 == 0) {
        im.seq = ++*seq;
        hil_co_imu_encode(&f, 1, &im);
        hil_ctrl_on_frame(c, &f, o);
    }
    rp = find(o, HIL_COB_RPDO1(HIL_NODE_DRIVE));
    assert_non_null(rp);
    hil_co_drive_rpdo_decode(rp, &r);
    return r.torque_mnm * 1e-3;
}

static void test_ctrl_watchdog_ramps_torque_to_zero_and_recovers(void **state)
{
    struct hil_ctrl c;
    struct hil_ctrl_params p;
    struct hil_out o;
    uint8_t seq = 0;
    int k, fault_at = -1, zero_at = -1, emcy_at = -1;
    double u = 0.0, u_before = 0.0;
    (void)state;
    hil_ctrl_params_default(&p);
    p.move_start = 0.0;
    assert_int_equal(hil_ctrl_init(&c, &p), HIL_OK);
    for (k = 0; k < 20; k++)
        u_before = ctrl_cycle(&c, 1, &seq, &o);
    assert_true(fabs(u_before) > 1.0);
    assert_int_equal(c.faults, 0);
    /* the last reading arrived at the end of cycle 19 (k = 19); none after */
    for (k = 20; k < 40; k++) {
        u = ctrl_cycle(&c, 0, &seq, &o);
        if (find(&o, HIL_COB_EMCY(HIL_NODE_CTRL)) && emcy_at < 0)
            emcy_at = k;
        if (c.fault && fault_at < 0)
            fault_at = k;
        if (fault_at >= 0 && zero_at < 0 && u == 0.0)
            zero_at = k;
    }
    assert_true(fault_at >= 0);
    assert_int_equal(emcy_at, fault_at);
    assert_true(fault_at - 19 <= 3 + 1); /* detected within 3 cycles of the first missing reading */
    assert_true((zero_at - fault_at + 1) * p.T <= 10e-3 + 1e-12);
    assert_int_equal(c.faults, 1);
    /* fresh data: EMCY "no error", the law resumes */
    for (k = 0; k < 6; k++)
        u = ctrl_cycle(&c, 1, &seq, &o);
    assert_int_equal(c.fault, 0);
    assert_true(fabs(u) > 1.0);
    assert_int_equal(c.emcy_sent, 2);
}

static void test_ctrl_counts_missed_inputs_and_ignores_malformed(void **state)
{
    struct hil_ctrl c;
    struct hil_ctrl_params p;
    struct hil_out o;
    struct hil_can_frame f;
    (void)state;
    hil_ctrl_params_default(&p);
    hil_ctrl_init(&c, &p);
    o.n = 0;
    assert_int_equal(hil_ctrl_deadline(&c, &o), HIL_E_ARG); /* no cycle yet */
    hil_ctrl_tick(&c, &o);
    assert_int_equal(o.n, 2); /* NMT start all + SYNC */
    assert_int_equal(o.f[0].id, HIL_COB_NMT);
    assert_int_equal(o.f[1].id, HIL_COB_SYNC);
    memset(&f, 0, sizeof f);
    f.id = HIL_COB_TPDO1(HIL_NODE_DRIVE);
    f.dlc = 7;
    assert_int_equal(hil_ctrl_on_frame(&c, &f, &o), HIL_E_DLC);
    assert_int_equal(c.have_tpdo1, 0);
    hil_co_heartbeat_encode(&f, HIL_NODE_DRIVE, HIL_NMT_STATE_OPERATIONAL);
    f.data[0] = 0x33; /* not an NMT state */
    assert_int_equal(hil_ctrl_on_frame(&c, &f, &o), HIL_E_FORMAT);
    assert_int_equal(c.rx.bad_value, 1);
    assert_int_equal(c.hb_state[HIL_NODE_DRIVE], 0xFF);
    o.n = 0;
    hil_ctrl_deadline(&c, &o);
    assert_int_equal(c.missed_inputs, 1);
    assert_non_null(find(&o, HIL_COB_RPDO1(HIL_NODE_DRIVE)));
    p.move_time = 0.0;
    assert_int_equal(hil_ctrl_init(&c, &p), HIL_E_ARG);
}

/* NMT node control shared by the drive and IMU (hil_nmt_on_frame): start,
 * stop, pre-operational, reset, another node's command, an invalid command. */
static void test_nmt_commands_change_state_count_and_request_reset(void **state)
{
    struct hil_rx_stats rx;
    struct hil_can_frame f;
    uint8_t st = HIL_NMT_STATE_PREOP;
    int reset = -1;
    (void)state;
    memset(&rx, 0, sizeof rx);
    hil_co_nmt_encode(&f, HIL_NMT_START, HIL_NODE_DRIVE);
    assert_int_equal(hil_nmt_on_frame(&rx, &f, HIL_NODE_DRIVE, &st, &reset), HIL_OK);
    assert_int_equal(st, HIL_NMT_STATE_OPERATIONAL);
    assert_int_equal(reset, 0);
    hil_co_nmt_encode(&f, HIL_NMT_STOP, 0);
    assert_int_equal(hil_nmt_on_frame(&rx, &f, HIL_NODE_DRIVE, &st, &reset), HIL_OK);
    assert_int_equal(st, HIL_NMT_STATE_STOPPED);
    hil_co_nmt_encode(&f, HIL_NMT_PREOP, 0);
    assert_int_equal(hil_nmt_on_frame(&rx, &f, HIL_NODE_DRIVE, &st, &reset), HIL_OK);
    assert_int_equal(st, HIL_NMT_STATE_PREOP);
    hil_co_nmt_encode(&f, HIL_NMT_RESET_NODE, 0);
    assert_int_equal(hil_nmt_on_frame(&rx, &f, HIL_NODE_DRIVE, &st, &reset), HIL_OK);
    assert_int_equal(reset, 1);
    assert_int_equal(st, HIL_NMT_STATE_PREOP); /* the node itself resets and boots up */
    assert_int_equal(rx.accepted, 4);
    hil_co_nmt_encode(&f, HIL_NMT_START, HIL_NODE_IMU);
    assert_int_equal(hil_nmt_on_frame(&rx, &f, HIL_NODE_DRIVE, &st, &reset), HIL_E_UNKNOWN_ID);
    assert_int_equal(rx.other, 1);
    assert_int_equal(st, HIL_NMT_STATE_PREOP);
    hil_co_nmt_encode(&f, HIL_NMT_START, 0);
    f.data[0] = 0x33; /* not an NMT command */
    assert_int_equal(hil_nmt_on_frame(&rx, &f, HIL_NODE_DRIVE, &st, &reset), HIL_E_FORMAT);
    assert_int_equal(rx.bad_value, 1);
    assert_int_equal(rx.accepted, 4);
    assert_int_equal(st, HIL_NMT_STATE_PREOP);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drive_follows_cia402_state_machine_and_boots_with_heartbeat),
        cmocka_unit_test(test_drive_applies_command_after_four_samples),
        cmocka_unit_test(test_drive_current_loop_is_first_order_lag),
        cmocka_unit_test(test_drive_limits_to_peak_then_rated_torque),
        cmocka_unit_test(test_drive_faults_and_sends_emcy_when_rpdos_stop),
        cmocka_unit_test(test_drive_counts_and_ignores_malformed_frames),
        cmocka_unit_test(test_drive_encoder_counts_with_its_resolution_and_differences_velocity),
        cmocka_unit_test(test_drive_dead_zone_and_gain_act_on_the_shaft_torque_only),
        cmocka_unit_test(test_drive_rejects_negative_dead_zone_and_non_positive_gain),
        cmocka_unit_test(test_rig_keys_set_dead_zone_and_gain_and_the_metadata_records_them),
        cmocka_unit_test(test_imu_reading_leaves_four_acquisitions_after_sampling),
        cmocka_unit_test(test_imu_jitter_delays_readings_by_one_acquisition),
        cmocka_unit_test(test_imu_noise_is_seeded_and_quantized),
        cmocka_unit_test(test_imu_saturates_and_flags_out_of_range_rates),
        cmocka_unit_test(test_rigid_plant_matches_closed_form_under_constant_torque),
        cmocka_unit_test(test_twomass_plant_conserves_momentum_and_oscillates_at_gear_mode),
        cmocka_unit_test(test_twomass_backlash_holds_link_until_play_is_crossed),
        cmocka_unit_test(test_twomass_extra_mode_conserves_momentum_and_shows_at_the_tip),
        cmocka_unit_test(test_twomass_fractional_kelvin_voigt_damping_rings_down_the_gear_mode),
        cmocka_unit_test(test_ctrl_watchdog_ramps_torque_to_zero_and_recovers),
        cmocka_unit_test(test_ctrl_counts_missed_inputs_and_ignores_malformed),
        cmocka_unit_test(test_nmt_commands_change_state_count_and_request_reset),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
