/* Command-line handling and the reactive loop of the rig executables. */
#include <limits.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>
#include "app_common.h"
#include "hil/file.h"
#ifdef HIL_HAVE_PLC
#include "plc_law.h"
#endif

double app_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char common_usage[] =
    "  --bus SPEC          socketcan:IFACE (default socketcan:vcan0) or udp:PORT:SLOT:NODES\n"
    "  --scenario FILE     key = value scenario file (see docs/hil.md)\n"
    "  --set KEY=VALUE     override one scenario key (repeatable)\n"
    "  --idle-exit S       exit after S seconds without a frame (default 2)\n"
    "  --tables DIR        where relative plant.table / ctrl.table paths not found from the\n"
    "                      current directory are looked up (default: tables/ next to this\n"
    "                      executable, where the build writes the scenarios' tables)\n"
    "  --rt-priority N     SCHED_FIFO priority 1..99 and locked memory (needs the privilege;\n"
    "                      without it a warning, normal scheduling)\n"
    "  --help              this text\n";

static void need(int i, int argc, const char *opt)
{
    if (i + 1 >= argc) {
        fprintf(stderr, "%s needs a value\n", opt);
        exit(2);
    }
}

/* A relative table path that does not exist from the current directory is
 * taken from dir (if it exists there); the path is rewritten in place. */
static void resolve_table(char *path, size_t cap, const char *dir)
{
    char alt[PATH_MAX + HIL_PLANT_PATH_MAX];
    if (!path[0] || path[0] == '/' || access(path, F_OK) == 0)
        return;
    snprintf(alt, sizeof alt, "%s/%s", dir, path);
    if (access(alt, F_OK) == 0 && strlen(alt) < cap)
        memcpy(path, alt, strlen(alt) + 1);
}

void app_parse(int argc, char **argv, struct app_opts *o, const char *usage)
{
    int i, line;
    char tables[PATH_MAX] = "";
    memset(o, 0, sizeof *o);
    o->bus = "socketcan:vcan0";
    o->idle_exit = 2.0;
    o->cycles = -1;
    hil_rig_config_default(&o->cfg);
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            printf("%s%s", usage, common_usage);
            exit(0);
        } else if (strcmp(a, "--bus") == 0) {
            need(i, argc, a);
            o->bus = argv[++i];
            o->bus_given = 1;
        } else if (strcmp(a, "--scenario") == 0) {
            int st;
            need(i, argc, a);
            st = hil_rig_config_load(&o->cfg, argv[++i], &line);
            if (st == HIL_E_IO) {
                fprintf(stderr, "--scenario %s: %s\n", argv[i], o->cfg.err);
                exit(2);
            }
            if (st != HIL_OK) {
                fprintf(stderr, "--scenario %s: line %d: %s\n", argv[i], line, o->cfg.err);
                exit(2);
            }
        } else if (strcmp(a, "--set") == 0) {
            char buf[256], *eq;
            need(i, argc, a);
            snprintf(buf, sizeof buf, "%s", argv[++i]);
            eq = strchr(buf, '=');
            if (!eq) {
                fprintf(stderr, "--set wants KEY=VALUE\n");
                exit(2);
            }
            *eq = '\0';
            if (hil_rig_config_set(&o->cfg, buf, eq + 1) != HIL_OK) {
                fprintf(stderr, "--set %s: %s\n", argv[i], o->cfg.err);
                exit(2);
            }
        } else if (strcmp(a, "--idle-exit") == 0) {
            char *end;
            need(i, argc, a);
            o->idle_exit = strtod(argv[++i], &end);
            if (*end || !(o->idle_exit > 0.0)) {
                fprintf(stderr, "--idle-exit wants seconds > 0\n");
                exit(2);
            }
        } else if (strcmp(a, "--rt-priority") == 0) {
            char *end;
            struct sched_param sp;
            need(i, argc, a);
            o->rt_priority = (int)strtol(argv[++i], &end, 10);
            if (*end || o->rt_priority < 1 || o->rt_priority > 99) {
                fprintf(stderr, "--rt-priority wants 1..99\n");
                exit(2);
            }
            memset(&sp, 0, sizeof sp);
            sp.sched_priority = o->rt_priority;
            if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0 || mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
                perror("--rt-priority (continuing with normal scheduling)");
                o->rt_priority = 0;
            }
        } else if (strcmp(a, "--tables") == 0) {
            need(i, argc, a);
            snprintf(tables, sizeof tables, "%s", argv[++i]);
        } else if (strcmp(a, "--csv") == 0) {
            need(i, argc, a);
            o->csv = argv[++i];
        } else if (strcmp(a, "--out") == 0) {
            need(i, argc, a);
            o->out = argv[++i];
        } else if (strcmp(a, "--cycles") == 0) {
            char *end;
            need(i, argc, a);
            o->cycles = strtol(argv[++i], &end, 10);
            if (*end || o->cycles < 1) {
                fprintf(stderr, "--cycles wants an integer >= 1\n");
                exit(2);
            }
        } else {
            fprintf(stderr, "unknown option %s (try --help)\n", a);
            exit(2);
        }
    }
    if (!tables[0]) {
        ssize_t n = readlink("/proc/self/exe", tables, sizeof tables - 8);
        char *slash;
        tables[n > 0 ? n : 0] = '\0';
        slash = strrchr(tables, '/');
        if (slash)
            strcpy(slash, "/tables");
        else
            strcpy(tables, "tables");
    }
    resolve_table(o->cfg.plant_p.table, sizeof o->cfg.plant_p.table, tables);
    resolve_table(o->cfg.ctrl_table, sizeof o->cfg.ctrl_table, tables);
}

void app_open_bus(struct hil_transport *t, const char *spec)
{
    int st = hil_transport_open(t, spec);
    if (st != HIL_OK) {
        fprintf(stderr, "cannot open bus %s: %s\n", spec, hil_status_str(st));
        exit(1);
    }
}

int app_send_all(struct hil_transport *t, const struct hil_out *out)
{
    int i, failed = 0;
    for (i = 0; i < out->n; i++)
        if (hil_transport_send(t, &out->f[i]) != HIL_OK)
            failed++;
    return failed;
}

void app_print_stats(FILE *f, const char *name, const struct hil_transport *t,
                     const struct hil_rx_stats *rx)
{
    fprintf(f, "HIL_STATS node=%s tx=%llu tx_errors=%llu rx=%llu rx_invalid=%llu rx_dropped=%llu", name,
            (unsigned long long)t->tx_frames, (unsigned long long)t->tx_errors,
            (unsigned long long)t->rx_frames, (unsigned long long)t->rx_invalid,
            (unsigned long long)t->rx_dropped);
    if (rx)
        fprintf(f, " accepted=%llu other=%llu unknown_id=%llu bad_dlc=%llu bad_value=%llu",
                (unsigned long long)rx->accepted, (unsigned long long)rx->other,
                (unsigned long long)rx->unknown_id, (unsigned long long)rx->bad_dlc,
                (unsigned long long)rx->bad_value);
    fputc('\n', f);
    fflush(f);
}

int app_run_reactive(struct hil_transport *t, app_handler h, void *node, const struct hil_out *boot,
                     double idle_exit, const char *name, const struct hil_rx_stats *rx)
{
    double last = app_now();
    int failed = app_send_all(t, boot);
    for (;;) {
        struct hil_can_frame f;
        struct hil_out out;
        int st = hil_transport_recv(t, &f, 100000);
        if (st == HIL_E_TIMEOUT) {
            if (app_now() - last > idle_exit)
                break;
            continue;
        }
        last = app_now();
        if (st != HIL_OK) {
            if (st == HIL_E_IO)
                break;
            continue;
        }
        out.n = 0;
        h(node, &f, &out);
        failed += app_send_all(t, &out);
    }
    app_print_stats(stdout, name, t, rx);
    return failed ? 1 : 0;
}

int app_setup_law(struct hil_ctrl *c, const struct hil_rig_config *cfg)
{
    if (strcmp(cfg->law, "pd") == 0)
        return 0;
#ifdef HIL_HAVE_PLC
    {
        /* static: the law (and the table it reads at _INIT) lives as long as
         * the process */
        static struct hil_plc_law law;
        static unsigned char *table;
        char err[512] = "";
        int st;
        if (strcmp(cfg->law, "armctrl") == 0) {
            unsigned long size = 0;
            if (!cfg->ctrl_table[0]) {
                fprintf(stderr, "ctrl.law = armctrl needs ctrl.table (ArmCtrl's parameter table)\n");
                return 2;
            }
            free(table);
            table = hil_read_file(cfg->ctrl_table, 64ul << 20, &size);
            if (!table) {
                fprintf(stderr, "ctrl.table %s: cannot read the file (missing, unreadable or larger than 64 MiB)\n",
                        cfg->ctrl_table);
                return 2;
            }
            st = hil_plc_law_init_table(&law, cfg->ctrl.T, table, size, err, sizeof err);
            if (st != HIL_OK) {
                /* a table ArmCtrl refuses would run with the torque never
                 * enabled: the bench does not start such a run */
                fprintf(stderr, "ctrl.table %s: ArmCtrl refuses the table: %s\n", cfg->ctrl_table, err);
                return 2;
            }
        } else {
            st = hil_plc_law_init_exp_a(&law, cfg->ctrl.T, cfg->plant_p.I_M, cfg->plant_p.I_L, cfg->plant_p.c_s, err,
                                        sizeof err);
            if (st != HIL_OK) {
                fprintf(stderr, "ctrl.law = %s: %s %s\n", cfg->law, hil_status_str(st), err);
                return 2;
            }
        }
        hil_ctrl_set_law(c, hil_plc_law_step, &law);
        return 0;
    }
#else
    (void)c;
    fprintf(stderr, "ctrl.law = %s needs plc_blocks, which this build lacks\n", cfg->law);
    return 2;
#endif
}
