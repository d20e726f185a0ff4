/* hil_bench: the whole bench from one scenario file.
 *
 * Default: lockstep in one process (hil/rig.h), deterministic, as fast as the
 * host runs. --processes: every node as its own process (hil_ctrl, hil_drive,
 * hil_imu, hil_plant and the hil_candump logger, found next to this
 * executable) on one bus: --bus socketcan:IFACE, or by default a UDP loopback
 * bus; the controller paces in lockstep over the bus, or with --realtime by
 * the wall clock. Output in DIR: frames.log (candump format), signals.csv,
 * meta.json, and with --processes each node's report (NODE.txt), the
 * effective scenario (scenario.txt) the nodes were started with, and the
 * controller's and the plant's own CSVs (controller.csv, truth.csv) that
 * signals.csv joins. The run writes into a temporary directory beside DIR
 * that is renamed into DIR only when the run succeeded, so a refused or
 * failed run leaves DIR (an earlier run) as it was; why it stopped goes to
 * stderr (with --processes, the failing node's report too). Exit 0, 1 (the
 * run failed) or 2 (the scenario or a table was refused). */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "app_common.h"

static FILE *open_in(const char *dir, const char *name, const char *mode)
{
    char path[PATH_MAX + 128];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    f = fopen(path, mode);
    if (!f)
        perror(path);
    return f;
}

static int close_ok(FILE *f, const char *dir, const char *name)
{
    int bad = !f || ferror(f);
    if (f && fclose(f) != 0)
        bad = 1;
    if (bad)
        fprintf(stderr, "hil_bench: cannot write %s/%s: %s\n", dir, name, strerror(errno));
    return !bad;
}

/* The run into dir (the temporary directory); 0, 1 (the run failed) or 2
 * (the scenario was refused). */
static int run_lockstep(const struct app_opts *o, const char *dir)
{
    static struct hil_rig rig;
    FILE *log = open_in(dir, "frames.log", "w"), *csv = open_in(dir, "signals.csv", "w"),
         *meta = open_in(dir, "meta.json", "w");
    double t0, wall, boot_wall;
    int st, ok;
    if (!log || !csv || !meta) {
        if (log)
            fclose(log);
        if (csv)
            fclose(csv);
        if (meta)
            fclose(meta);
        return 1;
    }
    t0 = app_now();
    st = hil_rig_init(&rig, &o->cfg, log, csv);
    boot_wall = app_now() - t0;
    if (st != HIL_OK || app_setup_law(&rig.ctrl, &o->cfg) != 0) {
        if (st == HIL_E_STATE)
            fprintf(stderr, "hil_bench: %s\n", rig.err);
        else if (st != HIL_OK)
            fprintf(stderr, "hil_bench: the scenario is refused: %s\n", rig.err);
        fclose(log);
        fclose(csv);
        fclose(meta);
        if (st == HIL_E_STATE)
            return 1;
        return 2;
    }
    t0 = app_now();
    st = hil_rig_run(&rig);
    wall = app_now() - t0;
    hil_rig_write_meta(&rig, meta, wall);
    ok = close_ok(log, dir, "frames.log");
    ok = close_ok(csv, dir, "signals.csv") && ok;
    ok = close_ok(meta, dir, "meta.json") && ok;
    if (st != HIL_OK) {
        fprintf(stderr, "hil_bench: run failed at t = %.6f s (%s): %s\n", rig.st.cycles * o->cfg.ctrl.T,
                hil_status_str(st), rig.err);
        return 1;
    }
    if (!ok)
        return 1;
    printf("hil_bench: lockstep, %llu cycles (%.3f s simulated) in %.3f s wall (%.1fx real time); "
           "frames sent %llu, lost %llu, logged %llu; final tip angle %.4f rad (reference %.4f)%s\n",
           (unsigned long long)rig.st.cycles, rig.st.cycles * o->cfg.ctrl.T, wall,
           wall > 0 ? rig.st.cycles * o->cfg.ctrl.T / wall : 0.0, (unsigned long long)rig.st.frames_sent,
           (unsigned long long)rig.st.frames_lost, (unsigned long long)rig.st.frames_logged,
           rig.plant.psi, rig.ctrl.sig.ref, rig.ctrl.law_status ? "; the law reported a fault" : "");
    printf("hil_bench: boot by SDO before cycle 0: %llu frames, %llu SDO requests, %.3f ms wall\n",
           (unsigned long long)rig.st.boot_frames, (unsigned long long)rig.ctrl.sdo_requests, 1e3 * boot_wall);
    if (rig.ctrl.law_status)
        printf("hil_bench: law status %u (ArmCtrl StatusID), faults %llu\n", rig.ctrl.law_status,
               (unsigned long long)rig.ctrl.faults);
    return 0;
}

/* Starts exe with args, stdout and stderr to DIR/name.txt. */
static pid_t spawn(const char *dir, const char *name, char *const argv[])
{
    char path[PATH_MAX];
    pid_t pid;
    snprintf(path, sizeof path, "%s/%s.txt", dir, name);
    pid = fork();
    if (pid == 0) {
        int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0666);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
            close(fd);
        }
        execv(argv[0], argv);
        _exit(127);
    }
    return pid;
}

static void pause_s(double s)
{
    struct timespec ts;
    ts.tv_sec = (time_t)s;
    ts.tv_nsec = (long)((s - (double)ts.tv_sec) * 1e9);
    nanosleep(&ts, NULL);
}

/* Appends every "HIL_xxx k=v ..." line of DIR/name.txt as a JSON object. */
static void report_json(FILE *meta, const char *dir, const char *name, int last)
{
    char line[512];
    FILE *f = open_in(dir, name, "r");
    int first = 1;
    fprintf(meta, "    \"%s\": [", name);
    while (f && fgets(line, sizeof line, f)) {
        char *tok, *save = NULL;
        int n = 0;
        if (strncmp(line, "HIL_", 4) != 0)
            continue;
        fprintf(meta, "%s{", first ? "" : ", ");
        first = 0;
        for (tok = strtok_r(line, " \n", &save); tok; tok = strtok_r(NULL, " \n", &save)) {
            char *eq = strchr(tok, '=');
            if (n++ == 0) {
                fprintf(meta, "\"line\": \"%s\"", tok);
                continue;
            }
            if (!eq)
                continue;
            *eq = '\0';
            fprintf(meta, ", \"%s\": \"%s\"", tok, eq + 1);
        }
        fputc('}', meta);
    }
    fprintf(meta, "]%s\n", last ? "" : ",");
    if (f)
        fclose(f);
}

/* signals.csv with the lockstep bench's columns: row k of controller.csv
 * (t, ref, torque_cmd, motor_angle, motor_velocity, imu_rate, fault, run) joined
 * with row k of the plant's truth.csv (t, tip_angle, tip_velocity,
 * torque_actual): the plant steps once per SYNC, so row k of both is cycle k.
 * Returns 0, or -1 when the row counts or times differ. */
static int merge_signals(const char *dir)
{
    FILE *c = open_in(dir, "controller.csv", "r"), *p = open_in(dir, "truth.csv", "r"),
         *o = open_in(dir, "signals.csv", "w");
    char lc[512], lp[512];
    int rc = 0;
    if (!c || !p || !o)
        rc = -1;
    if (!rc && (!fgets(lc, sizeof lc, c) || !fgets(lp, sizeof lp, p)))
        rc = -1;
    if (!rc)
        fprintf(o, "t,ref,torque_cmd,motor_angle,motor_velocity,imu_rate,tip_angle,tip_velocity,"
                   "torque_actual,fault,run\n");
    while (!rc && fgets(lc, sizeof lc, c)) {
        char *fault = lc, *tp;
        double t;
        int i;
        /* the controller's columns after imu_rate (fault, run) go last: split at its 6th comma */
        for (i = 0; i < 6 && fault; i++)
            fault = strchr(i ? fault + 1 : fault, ',');
        if (!fgets(lp, sizeof lp, p) || !fault) {
            rc = -1;
            break;
        }
        *fault++ = '\0';
        lp[strcspn(lp, "\n")] = '\0';
        tp = strchr(lp, ',');
        t = strtod(lc, NULL);
        if (!tp || fabs(t - strtod(lp, NULL)) > 1e-6) {
            rc = -1;
            break;
        }
        fprintf(o, "%s%s,%s", lc, tp, fault);
    }
    if (!rc && p && fgets(lp, sizeof lp, p))
        rc = -1;
    if (c)
        fclose(c);
    if (p)
        fclose(p);
    if (o)
        fclose(o);
    return rc;
}

/* Copies DIR/NAME.txt (a node's report) to stderr: the temporary directory
 * it is in goes away with a failed run. */
static void echo_report(const char *dir, const char *name)
{
    char line[512], file[80];
    FILE *f;
    snprintf(file, sizeof file, "%s.txt", name);
    f = open_in(dir, file, "r");
    while (f && fgets(line, sizeof line, f))
        fprintf(stderr, "  %s: %s", name, line);
    if (f)
        fclose(f);
}

static int run_processes(const struct app_opts *o, const char *out, int realtime)
{
    char prio[16];
    static const char *nodes[] = {"hil_ctrl", "hil_plant", "hil_drive", "hil_imu", "hil_candump"};
    char exe[PATH_MAX], dir[PATH_MAX], bin[5][PATH_MAX + 16], bus[5][64], scen[PATH_MAX + 16], logp[PATH_MAX + 16],
         csvp[PATH_MAX + 16], truthp[PATH_MAX + 16];
    pid_t pid[5];
    ssize_t n;
    FILE *f, *meta;
    int i, status, rc = 0;
    unsigned port = 41000u + (unsigned)(getpid() % 1000) * 8u;
    double t0;
    if (o->cfg.frame_loss > 0.0 || o->cfg.imu_dropout_end > o->cfg.imu_dropout_start ||
        o->cfg.drive_dropout_end > o->cfg.drive_dropout_start ||
        o->cfg.drive_busoff_end > o->cfg.drive_busoff_start) {
        fprintf(stderr, "hil_bench: frame_loss, the dropouts and bus-off are effects of the in-process bus; "
                        "they are not available with --processes\n");
        return 2;
    }
    n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return 1;
    exe[n] = '\0';
    snprintf(dir, sizeof dir, "%s", exe);
    *strrchr(dir, '/') = '\0';
    for (i = 0; i < 5; i++) {
        snprintf(bin[i], sizeof bin[i], "%s/%s", dir, nodes[i]);
        if (o->bus_given) {
            size_t len = strlen(o->bus);
            if (len >= sizeof bus[i]) {
                fprintf(stderr, "hil_bench: bus spec too long\n");
                return 2;
            }
            memcpy(bus[i], o->bus, len + 1);
        } else
            snprintf(bus[i], sizeof bus[i], "udp:%u:%d:5", port, i);
    }
    snprintf(scen, sizeof scen, "%s/scenario.txt", out);
    snprintf(logp, sizeof logp, "%s/frames.log", out);
    snprintf(csvp, sizeof csvp, "%s/controller.csv", out);
    snprintf(truthp, sizeof truthp, "%s/truth.csv", out);
    snprintf(prio, sizeof prio, "%d", o->rt_priority);
    f = fopen(scen, "w");
    if (!f || hil_rig_config_write(&o->cfg, f) != HIL_OK) {
        perror(scen);
        return 1;
    }
    fclose(f);
    {
        char *a[] = {bin[4], "--bus", bus[4], "--out", logp, "--idle-exit", "1", NULL, NULL, NULL};
        if (o->rt_priority) {
            a[7] = "--rt-priority";
            a[8] = prio;
        }
        unlink(logp); /* its appearance below means the new logger is up */
        pid[4] = spawn(out, "hil_candump", a);
    }
    /* the logger listens before anyone sends (the nodes' boot-up heartbeats
     * are their first frames): it opens its log once its socket is bound */
    {
        int exited = 0;
        for (i = 0; i < 1000 && !exited && access(logp, F_OK) != 0; i++) {
            pause_s(0.01);
            exited = waitpid(pid[4], &status, WNOHANG) == pid[4];
        }
        if (access(logp, F_OK) != 0) {
            fprintf(stderr, "hil_bench: hil_candump %s; its report:\n",
                    exited ? "exited before its log was open" : "did not start within 10 s");
            if (!exited) {
                kill(pid[4], SIGTERM);
                waitpid(pid[4], &status, 0);
            }
            echo_report(out, nodes[4]);
            return 1;
        }
    }
    for (i = 1; i < 4; i++) {
        char *a[] = {bin[i], "--bus", bus[i], "--scenario", scen, "--idle-exit", "1", NULL, NULL, NULL, NULL, NULL};
        int k = 7;
        if (o->rt_priority) {
            a[k++] = "--rt-priority";
            a[k++] = prio;
        }
        if (i == 1) {
            a[k++] = "--csv";
            a[k++] = truthp;
        }
        pid[i] = spawn(out, nodes[i], a);
    }
    pause_s(0.2);
    t0 = app_now();
    {
        char *a[12];
        int n = 0;
        a[n++] = bin[0];
        if (!realtime)
            a[n++] = "--lockstep";
        a[n++] = "--bus";
        a[n++] = bus[0];
        a[n++] = "--scenario";
        a[n++] = scen;
        a[n++] = "--csv";
        a[n++] = csvp;
        if (o->rt_priority) {
            a[n++] = "--rt-priority";
            a[n++] = prio;
        }
        a[n] = NULL;
        pid[0] = spawn(out, "hil_ctrl", a);
    }
    for (i = 0; i < 5; i++) {
        if (pid[i] < 0 || waitpid(pid[i], &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            fprintf(stderr, "hil_bench: %s failed; its report:\n", nodes[i]);
            echo_report(out, nodes[i]);
            rc = 1;
        }
    }
    if (merge_signals(out) != 0) {
        fprintf(stderr, "hil_bench: controller.csv and truth.csv do not line up\n");
        rc = 1;
    }
    if (rc)
        return rc;
    meta = open_in(out, "meta.json", "w");
    if (!meta)
        return 1;
    hil_rig_meta_begin(&o->cfg, realtime ? "realtime" : "lockstep-processes", meta);
    fprintf(meta, "  \"bus\": \"%s\",\n  \"rt_priority\": %d,\n  \"wall_s\": %.6f,\n  \"reports\": {\n",
            o->bus_given ? o->bus : "udp loopback", o->rt_priority, app_now() - t0);
    for (i = 0; i < 5; i++) {
        char name[64];
        snprintf(name, sizeof name, "%s.txt", nodes[i]);
        report_json(meta, out, name, i == 4);
    }
    fprintf(meta, "  }\n}\n");
    if (!close_ok(meta, out, "meta.json"))
        rc = 1;
    f = open_in(out, "hil_ctrl.txt", "r");
    while (f && fgets(exe, sizeof exe, f))
        if (strncmp(exe, "HIL_JITTER", 10) == 0 || strncmp(exe, "HIL_CTRL", 8) == 0)
            fputs(exe, stdout);
    if (f)
        fclose(f);
    return rc;
}

/* Every file a run writes into DIR (lockstep: the first three). */
static const char *const outputs[] = {"frames.log", "signals.csv", "meta.json", "scenario.txt", "controller.csv",
                                      "truth.csv", "hil_ctrl.txt", "hil_plant.txt", "hil_drive.txt", "hil_imu.txt",
                                      "hil_candump.txt"};
#define NOUTPUTS (sizeof outputs / sizeof outputs[0])

/* The run goes into a temporary directory beside DIR (DIR's parent,
 * ".NAME.hil-tmp-XXXXXX"), made here; DIR itself is not touched until the
 * run succeeded (out_commit). 0, or -1 with the reason printed. */
static int out_begin(const char *out, char *tmp, size_t cap)
{
    char parent[PATH_MAX], *slash, *p;
    const char *base;
    size_t len = strlen(out);
    while (len > 1 && out[len - 1] == '/')
        len--;
    if (len == 0 || len >= sizeof parent || (len == 1 && out[0] == '/')) {
        fprintf(stderr, "hil_bench: --out '%s': wants a directory path (not /) shorter than %d bytes\n", out, PATH_MAX);
        return -1;
    }
    memcpy(parent, out, len);
    parent[len] = '\0';
    slash = strrchr(parent, '/');
    if (slash) {
        *slash = '\0';
        base = out + (slash - parent) + 1;
        if (slash == parent)
            strcpy(parent, "/");
    } else {
        base = out;
        strcpy(parent, ".");
    }
    /* the parent's own parents, as mkdir -p */
    for (p = parent + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(parent, 0777) != 0 && errno != EEXIST) {
                perror(parent);
                return -1;
            }
            *p = '/';
        }
    if (mkdir(parent, 0777) != 0 && errno != EEXIST) {
        perror(parent);
        return -1;
    }
    if ((size_t)snprintf(tmp, cap, "%s/.%.*s.hil-tmp-XXXXXX", parent, (int)(len - (size_t)(base - out)), base) >= cap) {
        fprintf(stderr, "hil_bench: --out '%s': path too long\n", out);
        return -1;
    }
    if (!mkdtemp(tmp)) {
        fprintf(stderr, "hil_bench: cannot create a temporary directory in %s: %s\n", parent, strerror(errno));
        return -1;
    }
    return 0;
}

/* Removes the run's files and the temporary directory. */
static void out_abort(const char *tmp)
{
    char path[PATH_MAX + 32];
    size_t i;
    for (i = 0; i < NOUTPUTS; i++) {
        snprintf(path, sizeof path, "%s/%s", tmp, outputs[i]);
        unlink(path);
    }
    if (rmdir(tmp) != 0)
        fprintf(stderr, "hil_bench: cannot remove %s: %s\n", tmp, strerror(errno));
}

/* Moves the run's files from tmp into out (made if missing): the outputs of
 * an earlier run this run does not write are removed first, so DIR holds one
 * run; other files in DIR are left alone. 0, or -1 with the reason printed. */
static int out_commit(const char *tmp, const char *out)
{
    char from[PATH_MAX + 32], to[PATH_MAX + 32];
    size_t i;
    if (mkdir(out, 0777) != 0 && errno != EEXIST) {
        perror(out);
        return -1;
    }
    for (i = 0; i < NOUTPUTS; i++) {
        snprintf(from, sizeof from, "%s/%s", tmp, outputs[i]);
        snprintf(to, sizeof to, "%s/%s", out, outputs[i]);
        if (access(from, F_OK) != 0)
            unlink(to);
        else if (rename(from, to) != 0) {
            fprintf(stderr, "hil_bench: cannot move %s to %s: %s\n", from, to, strerror(errno));
            return -1;
        }
    }
    return rmdir(tmp) == 0 ? 0 : -1;
}

int main(int argc, char **argv)
{
    struct app_opts o;
    char tmp[PATH_MAX];
    int processes = 0, realtime = 0, i, rc;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--processes") == 0)
            processes = 1;
        else if (strcmp(argv[i], "--realtime") == 0)
            processes = realtime = 1;
        else
            continue;
        memmove(&argv[i], &argv[i + 1], (size_t)(argc - i - 1) * sizeof *argv);
        argc--;
        i--;
    }
    app_parse(argc, argv, &o,
              "usage: hil_bench --scenario FILE [--out DIR] [--processes | --realtime] [options]\n"
              "Runs the whole bench (controller, drive, IMU, plant, logger) from one scenario and\n"
              "writes DIR/frames.log (candump format), DIR/signals.csv and DIR/meta.json\n"
              "(DIR defaults to hil-run).\n"
              "  (default)           lockstep in one process: simulated time, deterministic\n"
              "  --processes         one process per node on --bus (default: UDP loopback),\n"
              "                      the controller pacing in lockstep over the bus\n"
              "  --realtime          as --processes, the controller on the wall clock; reports\n"
              "                      the cycle jitter p50/p99/max and the deadline misses\n");
    if (!o.out)
        o.out = "hil-run";
    if (processes) {
        /* the nodes validate the scenario each in its own process; refusing
         * it here says why once, before any process or file exists */
        static struct hil_rig check;
        if (hil_rig_init(&check, &o.cfg, NULL, NULL) != HIL_OK) {
            fprintf(stderr, "hil_bench: the scenario is refused: %s\n", check.err);
            return 2;
        }
        if (app_setup_law(&check.ctrl, &o.cfg) != 0)
            return 2;
    }
    if (out_begin(o.out, tmp, sizeof tmp) != 0)
        return 1;
    signal(SIGPIPE, SIG_IGN);
    rc = processes ? run_processes(&o, tmp, realtime) : run_lockstep(&o, tmp);
    if (rc == 0 && out_commit(tmp, o.out) == 0)
        return 0;
    out_abort(tmp);
    if (rc == 0)
        rc = 1;
    fprintf(stderr, "hil_bench: nothing written; %s is as it was\n", o.out);
    return rc;
}
