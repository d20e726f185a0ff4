/* hil_drive: the emulated CiA 402 servo drive (cyclic synchronous torque) as a bus node. */
#include "app_common.h"
#include "hil/drive.h"

static int handle(void *node, const struct hil_can_frame *f, struct hil_out *out)
{
    return hil_drive_on_frame((struct hil_drive *)node, f, out);
}

int main(int argc, char **argv)
{
    struct app_opts o;
    struct hil_transport t;
    struct hil_drive node;
    struct hil_out boot;
    int st;
    app_parse(argc, argv, &o,
              "usage: hil_drive [options]\n"
              "the emulated CiA 402 servo drive (cyclic synchronous torque).\n"
              "Runs until the bus has been idle for --idle-exit seconds, then prints HIL_STATS.\n");
    boot.n = 0;
    st = hil_drive_init(&node, &o.cfg.drive, &boot);
    if (st != HIL_OK) {
        fprintf(stderr, "hil_drive: invalid parameters (%s)\n", hil_status_str(st));
        return 2;
    }
    app_open_bus(&t, o.bus);
    st = app_run_reactive(&t, handle, &node, &boot, o.idle_exit, "drive", &node.rx);
    hil_transport_close(&t);
    return st;
}
