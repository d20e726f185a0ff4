/* hil_ctrl: the controller node in real time (wall clock): NMT master, SYNC
 * every T, PD test law (hil/ctrl.h). Reports cycle jitter (SYNC send time
 * minus its schedule) as p50/p99/max and the deadline misses. */
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

/* Receives and handles frames until the monotonic time `until`. */
static void serve(struct hil_transport *t, struct hil_ctrl *c, double until)
{
    for (;;) {
        struct hil_can_frame f;
        struct hil_out out;
        double left = until - app_now();
        int st;
        if (left <= 0.0)
            return;
        st = hil_transport_recv(t, &f, (long)(left * 1e6));
        if (st == HIL_E_TIMEOUT || st == HIL_E_IO)
            return;
        if (st != HIL_OK)
            continue;
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
    long k, n, misses = 0, injected = 0;
    app_parse(argc, argv, &o,
              "usage: hil_ctrl [options]\n"
              "The controller node in real time: NMT start, SYNC every T, PD test law,\n"
              "IMU watchdog; prints HIL_STATS and HIL_JITTER (p50/p99/max in us).\n"
              "  --cycles N          cycles to run (default: duration / T from the scenario)\n"
              "  --csv FILE          signals as the controller saw them, one row per cycle\n");
    if (hil_ctrl_init(&c, &o.cfg.ctrl) != HIL_OK) {
        fprintf(stderr, "hil_ctrl: invalid parameters\n");
        return 2;
    }
    T = o.cfg.ctrl.T;
    n = o.cycles > 0 ? o.cycles : (long)(o.cfg.duration / T + 0.5);
    late = calloc((size_t)n, sizeof *late);
    if (!late)
        return 1;
    if (o.csv && !(csv = fopen(o.csv, "w"))) {
        perror(o.csv);
        return 1;
    }
    if (csv)
        fprintf(csv, "t,ref,torque_cmd,motor_angle,motor_velocity,imu_rate,fault\n");
    app_open_bus(&t, o.bus);
    t0 = next = app_now() + 0.05;
    serve(&t, &c, next);
    for (k = 0; k < n; k++) {
        double now;
        out.n = 0;
        hil_ctrl_tick(&c, &out);
        now = app_now();
        app_send_all(&t, &out);
        late[k] = now - next;
        if (late[k] > T)
            misses++;
        if (o.cfg.inject_every && (k + 1) % o.cfg.inject_every == 0) {
            inject(&t);
            injected += 2;
        }
        serve(&t, &c, next + 0.8 * T);
        out.n = 0;
        hil_ctrl_deadline(&c, &out);
        app_send_all(&t, &out);
        if (csv) {
            const struct hil_ctrl_signals *s = &c.sig;
            fprintf(csv, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n", s->t, s->ref, s->torque_cmd, s->theta,
                    s->omega, s->imu_rate, s->fault);
        }
        next += T;
        serve(&t, &c, next);
    }
    out.n = 0;
    hil_ctrl_stop(&c, &out);
    app_send_all(&t, &out);
    serve(&t, &c, app_now() + 0.05);
    qsort(late, (size_t)n, sizeof *late, cmp_double);
    printf("HIL_JITTER cycles=%ld p50_us=%.1f p99_us=%.1f max_us=%.1f deadline_misses=%ld wall_s=%.3f\n", n,
           1e6 * late[n / 2], 1e6 * late[(size_t)((n - 1) * 0.99)], 1e6 * late[n - 1], misses,
           app_now() - t0);
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
