/* The lockstep bench: deterministic, the candump log holds exactly the frames
 * delivered (sent minus lost), malformed frames counted and ignored by every
 * node, 1 % frame loss keeps the loop stable, IMU frames stopping trigger the
 * watchdog fault reaction with EMCY and recovery, scenario parsing. */
#include <stdlib.h>
#include <string.h>
#include "frac_test.h"
#include "hil/candump.h"
#include "hil/canopen.h"
#include "hil/rig.h"

static struct hil_rig rig;

static long count_lines(FILE *f, uint32_t id, long *total, long *bad)
{
    char line[256], iface[HIL_CANDUMP_IFACE_MAX];
    struct hil_can_frame fr;
    double t;
    long n = 0;
    *total = *bad = 0;
    rewind(f);
    while (fgets(line, sizeof line, f)) {
        (*total)++;
        if (hil_candump_parse(line, &t, iface, &fr) != HIL_OK) {
            (*bad)++;
            continue;
        }
        if (fr.id == id)
            n++;
    }
    return n;
}

static void run(const struct hil_rig_config *c, FILE *log, FILE *csv)
{
    assert_int_equal(hil_rig_init(&rig, c, log, csv), HIL_OK);
    assert_int_equal(hil_rig_run(&rig), HIL_OK);
}

static void test_log_holds_every_frame_sent_once(void **state)
{
    struct hil_rig_config c;
    FILE *log = tmpfile();
    long total, bad, syncs;
    (void)state;
    hil_rig_config_default(&c);
    c.duration = 0.3;
    run(&c, log, NULL);
    syncs = count_lines(log, 0x080, &total, &bad);
    assert_int_equal(bad, 0);
    assert_int_equal(rig.st.frames_lost, 0);
    assert_int_equal(total, (long)rig.st.frames_sent);
    assert_int_equal(total, (long)rig.st.frames_logged);
    assert_int_equal(syncs, 250);
    assert_int_equal(rig.st.cycles, 250);
    assert_int_equal(rig.ctrl.missed_inputs, 0);
    fclose(log);
}

static void test_lockstep_runs_are_bit_identical(void **state)
{
    struct hil_rig_config c;
    FILE *a = tmpfile(), *b = tmpfile();
    char la[256], lb[256];
    long n = 0;
    (void)state;
    hil_rig_config_default(&c);
    c.duration = 0.2;
    c.imu.gyro_noise = 0.01;
    c.frame_loss = 0.02;
    run(&c, a, NULL);
    run(&c, b, NULL);
    rewind(a);
    rewind(b);
    while (fgets(la, sizeof la, a)) {
        assert_non_null(fgets(lb, sizeof lb, b));
        assert_string_equal(la, lb);
        n++;
    }
    assert_null(fgets(lb, sizeof lb, b));
    assert_true(n > 1000);
    fclose(a);
    fclose(b);
}

static void test_malformed_frames_counted_and_ignored_by_every_node(void **state)
{
    struct hil_rig_config c;
    double clean_angle;
    (void)state;
    hil_rig_config_default(&c);
    c.duration = 0.6;
    run(&c, NULL, NULL);
    clean_angle = rig.plant.theta;
    c.inject_every = 10;
    run(&c, NULL, NULL);
    assert_int_equal(rig.st.injected, 2 * 50);
    assert_int_equal(rig.drive.rx.bad_dlc, 50);
    assert_int_equal(rig.drive.rx.unknown_id, 50);
    assert_int_equal(rig.imu.rx.bad_dlc, 50);
    assert_int_equal(rig.plant.rx.unknown_id, 50);
    assert_int_equal(rig.ctrl.rx.bad_dlc, 50);
    /* ignored means ignored: the trajectory is the same bit for bit */
    assert_true(rig.plant.theta == clean_angle);
}

static void test_one_percent_frame_loss_keeps_loop_stable(void **state)
{
    struct hil_rig_config c;
    FILE *log = tmpfile();
    long total, bad;
    (void)state;
    hil_rig_config_default(&c);
    c.duration = 1.5;
    c.frame_loss = 0.01;
    c.bus_seed = 7;
    run(&c, log, NULL);
    count_lines(log, 0x080, &total, &bad);
    assert_true(rig.st.frames_lost > 0);
    assert_int_equal(total, (long)(rig.st.frames_sent - rig.st.frames_lost));
    assert_true(rig.ctrl.missed_inputs > 0);
    assert_close(rig.plant.theta, c.ctrl.move, 0.01);
    assert_close(rig.plant.omega, 0.0, 0.01);
    fclose(log);
}

static void test_imu_dropout_trips_watchdog_emcy_and_recovers(void **state)
{
    struct hil_rig_config c;
    FILE *log = tmpfile(), *csv = tmpfile();
    char line[256];
    long emcy, total, bad, row = 0, fault_row = -1, zero_row = -1;
    (void)state;
    hil_rig_config_default(&c);
    c.duration = 1.2;
    c.imu_dropout_start = 0.3;
    c.imu_dropout_end = 0.4;
    run(&c, log, csv);
    emcy = count_lines(log, 0x083, &total, &bad);
    assert_int_equal(emcy, 2); /* sensor error, then error reset */
    assert_int_equal(rig.ctrl.faults, 1);
    assert_int_equal(rig.ctrl.fault, 0);
    rewind(csv);
    while (fgets(line, sizeof line, csv)) {
        double t, ref, u;
        int fault;
        char *p = line;
        if (row++ == 0)
            continue;
        t = strtod(p, &p);
        ref = strtod(p + 1, &p);
        u = strtod(p + 1, &p);
        *strrchr(line, ',') = '\0'; /* run, the last column */
        fault = atoi(strrchr(line, ',') + 1);
        (void)ref;
        if (fault && fault_row < 0) {
            fault_row = row;
            /* the last reading left the IMU before 0.3 s; detection within 3 cycles of
             * the next expected one (readings every 2 cycles) */
            assert_true(t > 0.3 && t < 0.3 + 6 * c.ctrl.T);
        }
        if (fault_row >= 0 && zero_row < 0 && u == 0.0)
            zero_row = row;
    }
    assert_true(fault_row > 0 && zero_row > 0);
    assert_true((zero_row - fault_row + 1) * c.ctrl.T <= 10e-3);
    assert_close(rig.plant.theta, c.ctrl.move, 0.01);
    fclose(log);
    fclose(csv);
}

static void test_drive_bus_off_faults_recovers_with_emcy_and_reenables(void **state)
{
    struct hil_rig_config c;
    FILE *log = tmpfile();
    char line[256], iface[HIL_CANDUMP_IFACE_MAX];
    struct hil_can_frame f;
    double t;
    long recovered = 0, timeouts = 0, tpdo_in_window = 0;
    (void)state;
    hil_rig_config_default(&c);
    c.duration = 1.2;
    c.drive_busoff_start = 0.3;
    c.drive_busoff_end = 0.35;
    run(&c, log, NULL);
    rewind(log);
    while (fgets(line, sizeof line, log)) {
        assert_int_equal(hil_candump_parse(line, &t, iface, &f), HIL_OK);
        if (f.id == 0x081 && hil_get_u16(f.data) == 0x8140)
            recovered++;
        if (f.id == 0x081 && hil_get_u16(f.data) == 0x8250)
            timeouts++;
        if (f.id == 0x181 && t >= 0.3 && t < 0.35 - 1e-9)
            tpdo_in_window++;
    }
    assert_int_equal(recovered, 1);
    assert_int_equal(timeouts, 0); /* raised while bus-off: never reached the bus */
    assert_int_equal(tpdo_in_window, 0);
    assert_int_equal(rig.st.bus_off_episodes, 1);
    assert_true(rig.ctrl.missed_inputs >= 40); /* 50 ms of cycles without TPDOs */
    assert_true(rig.st.frames_lost > 0);
    /* the controller reset the fault and re-enabled the drive */
    assert_int_equal(rig.drive.state, HIL_CIA402_OPERATION_ENABLED);
    assert_close(rig.plant.theta, c.ctrl.move, 0.01);
    fclose(log);
}

static void test_scenario_file_sets_keys_and_reports_bad_lines(void **state)
{
    struct hil_rig_config c;
    char path[] = "/tmp/hil_scenario_XXXXXX";
    int fd = mkstemp(path), line;
    FILE *f = fdopen(fd, "w");
    (void)state;
    fprintf(f, "# comment\nT = 0.001\nduration=2 # trailing\nimu.gyro_noise = 0.5\n\n"
               "drive.delay = 2\nbogus.key = 1\n");
    fclose(f);
    hil_rig_config_default(&c);
    assert_int_equal(hil_rig_config_load(&c, path, &line), HIL_E_FORMAT);
    assert_int_equal(line, 7);
    assert_close(c.ctrl.T, 0.001, 0);
    assert_close(c.drive.T, 0.001, 0);
    assert_close(c.duration, 2.0, 0);
    assert_close(c.imu.gyro_noise, 0.5, 0);
    assert_int_equal(c.drive.delay, 2);
    assert_int_equal(hil_rig_config_set(&c, "drive.delay", "-1"), HIL_E_FORMAT);
    assert_int_equal(hil_rig_config_set(&c, "ctrl.kp", "nan"), HIL_E_FORMAT);
    assert_int_equal(hil_rig_config_set(&c, "plant", "flexible"), HIL_E_FORMAT);
    assert_int_equal(hil_rig_config_set(&c, "nope", "1"), HIL_E_UNKNOWN_ID);
    assert_int_equal(hil_rig_config_load(&c, "/nonexistent/scenario", &line), HIL_E_IO);
    c.frame_loss = 1.0;
    assert_int_equal(hil_rig_init(&rig, &c, NULL, NULL), HIL_E_ARG);
    remove(path);
}

static void test_metadata_records_scenario_seeds_and_counts(void **state)
{
    struct hil_rig_config c;
    FILE *m = tmpfile();
    char buf[8192];
    size_t n;
    (void)state;
    hil_rig_config_default(&c);
    c.duration = 0.05;
    c.imu.seed = 99;
    c.bus_seed = 5;
    run(&c, NULL, NULL);
    hil_rig_write_meta(&rig, m, 0.0);
    rewind(m);
    n = fread(buf, 1, sizeof buf - 1, m);
    buf[n] = '\0';
    assert_non_null(strstr(buf, "\"schema\": \"fracarm.hil.run\""));
    assert_non_null(strstr(buf, "\"seeds\": {\"bus\": 5, \"imu\": 99}"));
    assert_non_null(strstr(buf, "\"drive.delay\": 4"));
    assert_non_null(strstr(buf, "\"frames_sent\": "));
    assert_non_null(strstr(buf, "\"plant\": \"rigid\""));
    fclose(m);
}

/* A run whose log reaches its bound stops with HIL_E_FULL and says so; the
 * log holds only whole lines, never more than the bound; the duration bound
 * refuses a run before it starts. */
static void test_log_bound_stops_the_run_with_a_reason(void **state)
{
    struct hil_rig_config c;
    FILE *log = tmpfile();
    long size;
    int st = HIL_OK;
    (void)state;
    hil_rig_config_default(&c);
    c.duration = 1.0;
    assert_int_equal(hil_rig_init(&rig, &c, log, NULL), HIL_OK);
    rig.log_max = 20000; /* ~100 cycles of traffic */
    while (st == HIL_OK && rig.st.cycles < 833)
        st = hil_rig_cycle(&rig);
    assert_int_equal(st, HIL_E_FULL);
    assert_true(rig.st.cycles > 10 && rig.st.cycles < 833);
    assert_non_null(strstr(rig.err, "frames.log reached its bound of 20000 bytes"));
    fflush(log);
    size = ftell(log);
    assert_true(size <= 20000 && size > 19000);
    assert_int_equal((unsigned long)size, rig.log_bytes);
    fclose(log);
    c.duration = HIL_RIG_DURATION_MAX * 1.0001;
    assert_int_equal(hil_rig_init(&rig, &c, NULL, NULL), HIL_E_ARG);
    assert_non_null(strstr(rig.err, "wants simulated seconds in (0, 600]"));
    assert_int_equal(hil_rig_config_set(&c, "duration", "1e9"), HIL_E_RANGE);
    assert_non_null(strstr(c.err, "duration = '1e9': wants simulated seconds in (0, 600]"));
    assert_int_equal(hil_rig_config_set(&c, "duration", "600"), HIL_OK);
}

/* Found by fuzz_scenario: a bus-off over t = 0 loses the SDO boot's frames;
 * the rig refuses to start and says why (it returned without a reason). */
static void test_boot_lost_to_bus_off_is_refused_with_a_reason(void **state)
{
    struct hil_rig_config c;
    (void)state;
    hil_rig_config_default(&c);
    c.drive_busoff_start = 0.0;
    c.drive_busoff_end = 0.2;
    assert_int_equal(hil_rig_init(&rig, &c, NULL, NULL), HIL_E_STATE);
    assert_non_null(strstr(rig.err, "the controller could not boot the devices by SDO: "));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_log_holds_every_frame_sent_once),
        cmocka_unit_test(test_lockstep_runs_are_bit_identical),
        cmocka_unit_test(test_malformed_frames_counted_and_ignored_by_every_node),
        cmocka_unit_test(test_one_percent_frame_loss_keeps_loop_stable),
        cmocka_unit_test(test_imu_dropout_trips_watchdog_emcy_and_recovers),
        cmocka_unit_test(test_drive_bus_off_faults_recovers_with_emcy_and_reenables),
        cmocka_unit_test(test_scenario_file_sets_keys_and_reports_bad_lines),
        cmocka_unit_test(test_metadata_records_scenario_seeds_and_counts),
        cmocka_unit_test(test_log_bound_stops_the_run_with_a_reason),
        cmocka_unit_test(test_boot_lost_to_bus_off_is_refused_with_a_reason),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
