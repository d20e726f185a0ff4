/* hil_imu: the emulated tip IMU (0.6 ms acquisition, ~2.4 ms per reading) as a bus node. */
#include "app_common.h"
#include "hil/imu.h"

static int handle(void *node, const struct hil_can_frame *f, struct hil_out *out)
{
    return hil_imu_on_frame((struct hil_imu *)node, f, out);
}

int main(int argc, char **argv)
{
    struct app_opts o;
    struct hil_transport t;
    struct hil_imu node;
    struct hil_out boot;
    int st;
    app_parse(argc, argv, &o,
              "usage: hil_imu [options]\n"
              "the emulated tip IMU (0.6 ms acquisition, ~2.4 ms per reading).\n"
              "Runs until the bus has been idle for --idle-exit seconds, then prints HIL_STATS.\n");
    boot.n = 0;
    st = hil_imu_init(&node, &o.cfg.imu, &boot);
    if (st != HIL_OK) {
        fprintf(stderr, "hil_imu: invalid parameters (%s)\n", hil_status_str(st));
        return 2;
    }
    app_open_bus(&t, o.bus);
    st = app_run_reactive(&t, handle, &node, &boot, o.idle_exit, "imu", &node.rx);
    hil_transport_close(&t);
    return st;
}
