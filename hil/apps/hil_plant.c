/* hil_plant: the emulated arm (hil/plant.h: the "rigid" test plant, "twomass" or the flexible "arm") as a bus node. */
#include "app_common.h"
#include "hil/canopen.h"
#include "hil/plant.h"

static FILE *csv;

/* With --csv, one row per step: the truth at the start of the step (t_k) and
 * the drive's shaft torque at the end of it, as the lockstep bench logs them. */
static int handle(void *node, const struct hil_can_frame *f, struct hil_out *out)
{
    struct hil_plant *pl = (struct hil_plant *)node;
    double t = pl->t, psi = pl->psi, psi_d = pl->psi_d, tau0, tau1;
    int st = hil_plant_on_frame(pl, f, out);
    if (csv && st == HIL_OK && f->id == HIL_COB_RIG_TORQUE &&
        hil_co_rig_decode(f, HIL_COB_RIG_TORQUE, &tau0, &tau1) == HIL_OK)
        fprintf(csv, "%.6f,%.9g,%.9g,%.9g\n", t, psi, psi_d, tau1);
    return st;
}

int main(int argc, char **argv)
{
    struct app_opts o;
    struct hil_transport t;
    static struct hil_plant node;
    struct hil_out boot;
    int st;
    app_parse(argc, argv, &o,
              "usage: hil_plant [options]\n"
              "the emulated arm: plant = rigid (a TEST plant), twomass (seed 004 rbFFC model) or arm (the\n"
              "flexible arm's table, plant.table), from the scenario.\n"
              "Runs until the bus has been idle for --idle-exit seconds, then prints HIL_STATS.\n"
              "  --csv FILE          truth per step: t, tip_angle, tip_velocity, torque_actual\n");
    boot.n = 0;
    st = hil_plant_init(&node, &o.cfg.plant_p);
    if (st != HIL_OK) {
        fprintf(stderr, "hil_plant: invalid parameters (%s)%s%s\n", hil_status_str(st), node.err[0] ? ": " : "",
                node.err);
        return 2;
    }
    if (o.csv) {
        csv = fopen(o.csv, "w");
        if (!csv) {
            perror(o.csv);
            return 1;
        }
        fprintf(csv, "t,tip_angle,tip_velocity,torque_actual\n");
    }
    app_open_bus(&t, o.bus);
    st = app_run_reactive(&t, handle, &node, &boot, o.idle_exit, "plant", &node.rx);
    hil_transport_close(&t);
    if (csv)
        fclose(csv);
    return st;
}
