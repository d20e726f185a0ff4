/* hil_ctrl: the controller node over a bus: NMT master, SYNC producer, the
 * scenario's law (PD test law, hil/ctrl.h, or ArmCtrl, hil/plc/plc_law.h).
 * Real time (default): SYNC every T by the wall clock; the law runs when the
 * drive's TPDOs are in or at 0.8 T; reports the cycle jitter (SYNC send time
 * minus its schedule) as p50/p99/max and the deadline misses (jitter > T).
 * --lockstep: simulated time paced by the bus: SYNC, wait for the drive's
 * TPDOs (law), wait for the end of the physics step (RIG_IMU_DONE), next
 * SYNC; each wait is
 * bounded (--step-timeout, default 0.1 s; a timeout counts as a missed
 * input). For slow hosts such as a TCG-emulated guest. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "app_common.h"
#include "hil/canopen.h"
#include "hil/ctrl.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Receives and handles frames until the monotonic time `until`, or, with
 * want != 0, until that condition holds: 1 = both drive TPDOs of this cycle
 * in, 2 = the end of the physics step (RIG_IMU_DONE, sent by the IMU after
 * the plant's RIG_MOTOR and after its own TPDOs of that step) seen. */
static int step_done;
static uint64_t boot_seen; /* want = 3: a frame was accepted (an SDO answer during the boot) */

static int serve(struct hil_transport *t, struct hil_ctrl *c, double until, int want)
{
    for (;;) {
        struct hil_can_frame f;
        struct hil_out out;
        double left;
        int st;
        if (want == 1 && c->have_tpdo1 && c->have_tpdo2)
            return 1;
        if (want == 2 && step_done)
            return 1;
        if (want == 3 && (c->boot_status != 0 || c->rx.accepted + c->rx.bad_value != boot_seen)) {
            boot_seen = c->rx.accepted + c->rx.bad_value;
            return 1;
        }
        left = until - app_now();
        if (left <= 0.0)
            return 0;
        st = hil_transport_recv(t, &f, (long)(left * 1e6));
        if (st == HIL_E_TIMEOUT || st == HIL_E_IO)
            return 0;
        if (st != HIL_OK)
            continue;
        if (f.id == HIL_COB_RIG_IMU_DONE)
            step_done = 1;
        out.n = 0;
        hil_ctrl_on_frame(c, &f, &out);
        app_send_all(t, &out);
    }
}

static void inject(struct hil_transport *t)
{
    struct hil_can_frame f;
    memset(&f, 0, sizeof f);
    f.id = HIL_COB_RPDO1(HIL_NODE_DRIVE);
    f.dlc = 5; /* RPDO1 needs 6 */
    hil_transport_send(t, &f);
    f.id = 0x555; /* not in the dictionary */
    f.dlc = 8;
    hil_transport_send(t, &f);
}

int main(int argc, char **argv)
{
    struct app_opts o;
    struct hil_transport t;
    struct hil_ctrl c;
    struct hil_out out;
    FILE *csv = NULL;
    double *late, next, T, t0;
    long k, n, misses = 0, injected = 0, step_timeouts = 0;
    int lockstep = 0, i;
    double step_timeout = 0.1, sdo_boot_s = 0.0;
    /* hil_ctrl's own options, taken out before the common parser sees argv */
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--lockstep") == 0) {
            lockstep = 1;
        } else if (strcmp(argv[i], "--step-timeout") == 0 && i + 1 < argc) {
            char *end;
            step_timeout = strtod(argv[i + 1], &end);
            if (*end || !(step_timeout > 0.0)) {
                fprintf(stderr, "--step-timeout wants seconds > 0\n");
                return 2;
            }
            memmove(&argv[i], &argv[i + 1], (size_t)(argc - i - 1) * sizeof *argv);
            argc--;
        } else {
            continue;
        }
        memmove(&argv[i], &argv[i + 1], (size_t)(argc - i - 1) * sizeof *argv);
        argc--;
        i--;
    }
    app_parse(argc, argv, &o,
              "usage: hil_ctrl [options]\n"
              "The controller node: NMT master, SYNC every T (wall clock, or --lockstep), the\n"
              "scenario's ctrl.law (pd: test law with IMU watchdog; armctrl_a: plc_blocks ArmCtrl\n"
              "Exp. A in the task runtime; armctrl: ArmCtrl from the parameter table ctrl.table);\n"
              "prints HIL_STATS and HIL_JITTER (p50/p99/max in us).\n"
              "  --cycles N          cycles to run (default: duration / T from the scenario)\n"
              "  --csv FILE          signals as the controller saw them, one row per cycle\n"
              "  --lockstep          pace on the bus (wait for the drive, plant and IMU) instead\n"
              "                      of the wall clock\n"
              "  --step-timeout S    bound of each lockstep wait (default 0.1)\n");
    if (hil_ctrl_init(&c, &o.cfg.ctrl) != HIL_OK) {
        fprintf(stderr, "hil_ctrl: invalid parameters\n");
        return 2;
    }
    if (app_setup_law(&c, &o.cfg) != 0)
        return 2;
    T = o.cfg.ctrl.T;
    n = o.cycles > 0 ? o.cycles : (long)(o.cfg.duration / T + 0.5);
    if ((double)n > HIL_RIG_DURATION_MAX / T + 0.5) {
        fprintf(stderr, "hil_ctrl: --cycles %ld: wants at most %.0f cycles (%g s of simulated time at T = %g s)\n", n,
                floor(HIL_RIG_DURATION_MAX / T + 0.5), HIL_RIG_DURATION_MAX, T);
        return 2;
    }
    late = calloc((size_t)n, sizeof *late);
    if (!late)
        return 1;
    if (o.csv && !(csv = fopen(o.csv, "w"))) {
        perror(o.csv);
        return 1;
    }
    if (csv)
        fprintf(csv, "t,ref,torque_cmd,motor_angle,motor_velocity,imu_rate,fault,run\n");
    app_open_bus(&t, o.bus);
    t0 = app_now();
    serve(&t, &c, t0 + 0.05, 0);
    /* boot the devices by SDO (hil/ctrl.h), each answer awaited at most step_timeout */
    out.n = 0;
    hil_ctrl_boot(&c, &out);
    app_send_all(&t, &out);
    while (c.boot_status == 0) {
        uint64_t before = c.rx.accepted + c.rx.bad_value;
        serve(&t, &c, app_now() + step_timeout, 3);
        if (c.boot_status == 0 && c.rx.accepted + c.rx.bad_value == before) {
            snprintf(c.boot_error, sizeof c.boot_error, "no SDO answer within %g s (drive step %d/%d, IMU %d/%d)",
                     step_timeout, c.boot[0].at, c.boot[0].n, c.boot[1].at, c.boot[1].n);
            c.boot_status = -1;
        }
    }
    if (c.boot_status < 0) {
        fprintf(stderr, "hil_ctrl: the devices did not boot: %s\n", c.boot_error);
        return 1;
    }
    sdo_boot_s = app_now() - t0 - 0.05;
    t0 = next = app_now() + 0.01;
    serve(&t, &c, next, 0);
    for (k = 0; k < n; k++) {
        double now;
        out.n = 0;
        step_done = 0;
        hil_ctrl_tick(&c, &out);
        now = app_now();
        app_send_all(&t, &out);
        late[k] = lockstep ? 0.0 : now - next;
        if (late[k] > T)
            misses++;
        if (o.cfg.inject_every && (k + 1) % o.cfg.inject_every == 0) {
            inject(&t);
            injected += 2;
        }
        if (lockstep)
            serve(&t, &c, app_now() + step_timeout, 1);
        else
            serve(&t, &c, next + 0.8 * T, 1);
        out.n = 0;
        hil_ctrl_deadline(&c, &out);
        app_send_all(&t, &out);
        if (csv) {
            const struct hil_ctrl_signals *s = &c.sig;
            fprintf(csv, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%d\n", s->t, s->ref, s->torque_cmd, s->theta,
                    s->omega, s->imu_rate, s->fault, s->run);
        }
        if (lockstep) {
            if (!serve(&t, &c, app_now() + step_timeout, 2))
                step_timeouts++;
        } else {
            next += T;
            serve(&t, &c, next, 0);
        }
    }
    out.n = 0;
    hil_ctrl_stop(&c, &out);
    app_send_all(&t, &out);
    serve(&t, &c, app_now() + 0.05, 0);
    qsort(late, (size_t)n, sizeof *late, cmp_double);
    printf("HIL_JITTER mode=%s cycles=%ld p50_us=%.1f p99_us=%.1f max_us=%.1f deadline_misses=%ld "
           "step_timeouts=%ld wall_s=%.3f sdo_boot_ms=%.3f sdo_requests=%llu\n", lockstep ? "lockstep" : "realtime", n, 1e6 * late[n / 2],
           1e6 * late[(size_t)((n - 1) * 0.99)], 1e6 * late[n - 1], misses, step_timeouts, app_now() - t0, 1e3 * sdo_boot_s,
           (unsigned long long)c.sdo_requests);
    printf("HIL_CTRL cycles=%llu missed_inputs=%llu imu_readings=%llu faults=%llu emcy_received=%llu "
           "injected=%ld final_angle=%.6f\n",
           (unsigned long long)c.cycle, (unsigned long long)c.missed_inputs,
           (unsigned long long)c.imu_readings, (unsigned long long)c.faults,
           (unsigned long long)c.emcy_received, injected, c.theta);
    app_print_stats(stdout, "ctrl", &t, &c.rx);
    if (csv)
        fclose(csv);
    free(late);
    hil_transport_close(&t);
    return 0;
}
