/* hil_plant: the emulated arm (plant \"rigid\": the named TEST plant, a rigid inertia with viscous friction) as a bus node. */
#include "app_common.h"
#include "hil/plant.h"

static int handle(void *node, const struct hil_can_frame *f, struct hil_out *out)
{
    return hil_plant_on_frame((struct hil_plant *)node, f, out);
}

int main(int argc, char **argv)
{
    struct app_opts o;
    struct hil_transport t;
    struct hil_plant node;
    struct hil_out boot;
    int st;
    app_parse(argc, argv, &o,
              "usage: hil_plant [options]\n"
              "the emulated arm (plant \"rigid\": the named TEST plant, a rigid inertia with viscous friction).\n"
              "Runs until the bus has been idle for --idle-exit seconds, then prints HIL_STATS.\n");
    boot.n = 0;
    st = hil_plant_init(&node, &o.cfg.plant_p);
    if (st != HIL_OK) {
        fprintf(stderr, "hil_plant: invalid parameters (%s)\n", hil_status_str(st));
        return 2;
    }
    app_open_bus(&t, o.bus);
    st = app_run_reactive(&t, handle, &node, &boot, o.idle_exit, "plant", &node.rx);
    hil_transport_close(&t);
    return st;
}
