/* Shared command-line handling and real-time loops of the rig executables. */
#ifndef HIL_APP_COMMON_H
#define HIL_APP_COMMON_H
#include <stdio.h>
#include "hil/node.h"
#include "hil/rig.h"
#include "hil/transport.h"

/* Options every node executable takes. */
struct app_opts {
    const char *bus;       /* --bus SPEC, default socketcan:vcan0 */
    int bus_given;         /* --bus was on the command line */
    double idle_exit;      /* --idle-exit S: stop after S seconds without a frame */
    const char *csv;       /* --csv FILE */
    const char *out;       /* --out FILE or DIR */
    long cycles;           /* --cycles N (controller) */
    int rt_priority;       /* --rt-priority N: SCHED_FIFO priority (0: normal scheduling) */
    struct hil_rig_config cfg; /* --scenario FILE and --set KEY=VALUE applied */
};

/* Parses argv; prints usage (text) on --help and exits 0; on a bad option
 * prints the reason and exits 2. */
void app_parse(int argc, char **argv, struct app_opts *o, const char *usage);

/* Monotonic seconds. */
double app_now(void);

/* Opens the bus or exits 1 with the reason. */
void app_open_bus(struct hil_transport *t, const char *spec);

/* Sends every frame of out; returns the number of send failures. */
int app_send_all(struct hil_transport *t, const struct hil_out *out);

/* Reactive node loop: every received frame goes to handler(node, frame, out)
 * and what it returns is sent. Ends after idle_exit seconds without a frame.
 * Prints one "HIL_STATS ..." line with the transport and receive counters. */
typedef int (*app_handler)(void *node, const struct hil_can_frame *f, struct hil_out *out);
int app_run_reactive(struct hil_transport *t, app_handler h, void *node, const struct hil_out *boot,
                     double idle_exit, const char *name, const struct hil_rx_stats *rx);

/* Installs the scenario's controller law (ctrl.law) in c: "pd" keeps the
 * test law; "armctrl_a" runs plc_blocks' ArmCtrl Exp. A in the task runtime
 * (hil/plc/plc_law.h) with the scenario's plant.I_M/I_L/c_s as its design
 * model; "armctrl" runs ArmCtrl with the parameter table ctrl.table.
 * Returns 0, or 2 after printing why on stderr when the law cannot be set up:
 * the table is missing or ArmCtrl refuses it (the message names the failing
 * field or entry and the StatusID; such a run would never enable the
 * torque), or plc_blocks is not built. Relative table paths were resolved by
 * app_parse (--tables). Calling it again replaces the law. */
int app_setup_law(struct hil_ctrl *c, const struct hil_rig_config *cfg);

void app_print_stats(FILE *f, const char *name, const struct hil_transport *t,
                     const struct hil_rx_stats *rx);

#endif
