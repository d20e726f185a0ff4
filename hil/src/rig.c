/* In-process lockstep bench; behaviour in hil/rig.h. */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "hil/candump.h"
#include "hil/canopen.h"
#include "hil/rig.h"

#ifndef HIL_VERSION
#define HIL_VERSION "unknown"
#endif

enum { K_DBL, K_UNS, K_U64, K_INT, K_REAL };
struct key { const char *name; int type; size_t off; };
#define D(n, f) {n, K_DBL, offsetof(struct hil_rig_config, f)}
#define U(n, f) {n, K_UNS, offsetof(struct hil_rig_config, f)}
#define Q(n, f) {n, K_U64, offsetof(struct hil_rig_config, f)}
#define I(n, f) {n, K_INT, offsetof(struct hil_rig_config, f)}
#define R(n, f) {n, K_REAL, offsetof(struct hil_rig_config, f)}
static const struct key keys[] = {
    D("duration", duration), D("frame_loss", frame_loss), Q("bus_seed", bus_seed),
    U("inject_every", inject_every), D("imu_dropout_start", imu_dropout_start),
    D("imu_dropout_end", imu_dropout_end), D("drive_dropout_start", drive_dropout_start),
    D("drive_dropout_end", drive_dropout_end), D("drive_busoff_start", drive_busoff_start),
    D("drive_busoff_end", drive_busoff_end),
    U("drive.delay", drive.delay), D("drive.tau_current", drive.tau_current),
    D("drive.torque_rated", drive.torque_rated), D("drive.torque_peak", drive.torque_peak),
    D("drive.thermal_tau", drive.thermal_tau), U("drive.rpdo_timeout", drive.rpdo_timeout),
    U("drive.encoder_bits", drive.encoder_bits),
    U("drive.velocity_from_encoder", drive.velocity_from_encoder), D("drive.deadzone", drive.deadzone),
    D("drive.gain", drive.gain),
    U("imu.reading_cycles", imu.reading_cycles), D("imu.jitter_prob", imu.jitter_prob),
    D("imu.gyro_bias", imu.gyro_bias), D("imu.gyro_noise", imu.gyro_noise),
    D("imu.gyro_quant", imu.gyro_quant), D("imu.acc_bias", imu.acc_bias),
    D("imu.acc_noise", imu.acc_noise), D("imu.acc_quant", imu.acc_quant),
    Q("imu.seed", imu.seed),
    D("plant.J", plant_p.J), D("plant.b", plant_p.b), D("plant.L", plant_p.L),
    D("plant.I_M", plant_p.I_M), D("plant.I_L", plant_p.I_L), D("plant.c_s", plant_p.c_s),
    I("plant.friction", plant_p.friction.model), R("plant.fric_k", plant_p.friction.k),
    R("plant.fric_b1", plant_p.friction.b1), R("plant.fric_b0", plant_p.friction.b0),
    R("plant.fric_b1s", plant_p.friction.b1s), R("plant.fric_b2s", plant_p.friction.b2s),
    R("plant.fric_b3s", plant_p.friction.b3s), R("plant.fric_v_s", plant_p.friction.v_s),
    R("plant.fric_delta", plant_p.friction.delta), R("plant.fric_b1n", plant_p.friction.b1n),
    R("plant.fric_b1p", plant_p.friction.b1p), R("plant.fric_b0n", plant_p.friction.b0n),
    R("plant.fric_b0p", plant_p.friction.b0p), D("plant.backlash", plant_p.backlash),
    D("plant.extra_inertia", plant_p.extra_inertia), D("plant.extra_hz", plant_p.extra_hz),
    D("plant.extra_zeta", plant_p.extra_zeta), D("plant.kv_damping", plant_p.kv_damping),
    D("plant.kv_order", plant_p.kv_order), U("plant.kv_memory", plant_p.kv_memory),
    U("plant.substeps", plant_p.substeps),
    D("ctrl.kp", ctrl.kp), D("ctrl.kd", ctrl.kd), D("ctrl.k_tip", ctrl.k_tip),
    D("ctrl.move", ctrl.move), D("ctrl.move_start", ctrl.move_start),
    D("ctrl.move_time", ctrl.move_time), U("ctrl.imu_timeout", ctrl.imu_timeout),
    D("ctrl.ramp_time", ctrl.ramp_time), D("ctrl.torque_max", ctrl.torque_max),
};
#define NKEYS (sizeof keys / sizeof keys[0])

void hil_rig_config_default(struct hil_rig_config *c)
{
    memset(c, 0, sizeof *c);
    strcpy(c->scenario, "default");
    strcpy(c->plant, "rigid");
    strcpy(c->law, "pd");
    c->duration = 1.0;
    c->bus_seed = 1;
    hil_drive_params_default(&c->drive);
    hil_imu_params_default(&c->imu);
    hil_plant_params_default(&c->plant_p);
    hil_ctrl_params_default(&c->ctrl);
}

/* Sets c->err to "KEY = 'VALUE': WHY" and returns status. */
static int bad_value(struct hil_rig_config *c, int status, const char *key, const char *value, const char *why)
{
    snprintf(c->err, sizeof c->err, "%s = '%.60s': %s", key, value, why);
    return status;
}

/* What a key of type t accepts, for the messages. */
static const char *type_wants(int t)
{
    switch (t) {
    case K_DBL:
    case K_REAL: return "wants a finite number";
    case K_INT: return "wants an integer";
    case K_UNS: return "wants an integer 0..4294967295";
    default: return "wants an integer 0..18446744073709551615";
    }
}

/* c->err for an unknown key: the keys of its group ("drive.", ...) when the
 * group exists, else the top-level keys and the groups. */
static int unknown_key(struct hil_rig_config *c, const char *key)
{
    const char *dot = strchr(key, '.');
    size_t i, n, group = dot ? (size_t)(dot - key) + 1 : 0, hits = 0;
    n = (size_t)snprintf(c->err, sizeof c->err, "unknown key '%.40s'", key);
    for (i = 0; i < NKEYS && group; i++)
        if (strncmp(keys[i].name, key, group) == 0 && n < sizeof c->err)
            n += (size_t)snprintf(c->err + n, sizeof c->err - n, "%s%s", hits++ ? ", " : "; the keys of this group are ",
                                  keys[i].name);
    if (!hits && n < sizeof c->err)
        snprintf(c->err + n, sizeof c->err - n,
                 "; the keys are T, duration, plant, frame_loss, bus_seed, inject_every, "
                 "imu_dropout_start/end, drive_dropout_start/end, drive_busoff_start/end, ctrl.law, plant.table, "
                 "ctrl.table and the groups drive.*, imu.*, plant.*, ctrl.* (docs/hil.md)");
    return HIL_E_UNKNOWN_ID;
}

int hil_rig_config_set(struct hil_rig_config *c, const char *key, const char *value)
{
    size_t i;
    char *end;
    if (!c || !key || !value)
        return HIL_E_ARG;
    c->err[0] = '\0';
    if (strcmp(key, "plant") == 0) {
        if (strcmp(value, "rigid") == 0)
            c->plant_p.model = HIL_PLANT_RIGID;
        else if (strcmp(value, "twomass") == 0)
            c->plant_p.model = HIL_PLANT_TWOMASS;
        else if (strcmp(value, "arm") == 0)
            c->plant_p.model = HIL_PLANT_ARM;
        else
            return bad_value(c, HIL_E_FORMAT, key, value, "wants rigid, twomass or arm");
        strcpy(c->plant, value);
        return HIL_OK;
    }
    if (strcmp(key, "ctrl.law") == 0) {
        if (strcmp(value, "pd") != 0 && strcmp(value, "armctrl_a") != 0 && strcmp(value, "armctrl") != 0)
            return bad_value(c, HIL_E_FORMAT, key, value, "wants pd, armctrl_a or armctrl");
        strcpy(c->law, value);
        return HIL_OK;
    }
    if (strcmp(key, "plant.table") == 0 || strcmp(key, "ctrl.table") == 0) {
        /* a file path: not empty, no '#' (comment) and fits the field */
        char *dst = key[0] == 'p' ? c->plant_p.table : c->ctrl_table;
        if (!*value || strchr(value, '#') || strlen(value) >= HIL_PLANT_PATH_MAX)
            return bad_value(c, HIL_E_FORMAT, key, value, "wants a file path, not empty, without '#', shorter than 256 bytes");
        strcpy(dst, value);
        return HIL_OK;
    }
    if (strcmp(key, "T") == 0) {
        double v;
        errno = 0;
        v = strtod(value, &end);
        if (errno || end == value || *end || !(v > 0.0) || !isfinite(v))
            return bad_value(c, HIL_E_FORMAT, key, value, "wants the cycle time in seconds, a finite number > 0");
        c->drive.T = c->plant_p.T = c->ctrl.T = v;
        c->imu.acq_period = v / 2.0; /* the plant's half cycle (hil/plant.h) */
        return HIL_OK;
    }
    for (i = 0; i < NKEYS; i++) {
        void *p;
        if (strcmp(key, keys[i].name) != 0)
            continue;
        p = (char *)c + keys[i].off;
        errno = 0;
        if (keys[i].type == K_DBL || keys[i].type == K_REAL) {
            double v = strtod(value, &end);
            if (errno || end == value || *end || !isfinite(v))
                return bad_value(c, HIL_E_FORMAT, key, value, type_wants(keys[i].type));
            if (p == &c->duration && !(v > 0.0 && v <= HIL_RIG_DURATION_MAX)) {
                char why[160];
                snprintf(why, sizeof why, "wants simulated seconds in (0, %g] (the bound keeps frames.log "
                         "below ~%.0f MB; docs/hil.md)", HIL_RIG_DURATION_MAX, HIL_RIG_DURATION_MAX * 0.45);
                return bad_value(c, HIL_E_RANGE, key, value, why);
            }
            if (p == &c->frame_loss && !(v >= 0.0 && v < 1.0))
                return bad_value(c, HIL_E_RANGE, key, value, "wants a probability in [0, 1)");
            if (keys[i].type == K_DBL)
                *(double *)p = v;
            else
                *(frac_real *)p = (frac_real)v;
        } else if (keys[i].type == K_INT) {
            long v = strtol(value, &end, 10);
            if (errno || end == value || *end || v < INT_MIN || v > INT_MAX)
                return bad_value(c, HIL_E_FORMAT, key, value, type_wants(keys[i].type));
            *(int *)p = (int)v;
        } else {
            unsigned long long v;
            if (!isdigit((unsigned char)value[0]))
                return bad_value(c, HIL_E_FORMAT, key, value, type_wants(keys[i].type));
            v = strtoull(value, &end, 10);
            if (errno || *end || (keys[i].type == K_UNS && v > 0xFFFFFFFFull))
                return bad_value(c, HIL_E_FORMAT, key, value, type_wants(keys[i].type));
            if (keys[i].type == K_UNS)
                *(unsigned *)p = (unsigned)v;
            else
                *(uint64_t *)p = (uint64_t)v;
        }
        return HIL_OK;
    }
    return unknown_key(c, key);
}

static char *trim(char *s)
{
    char *e;
    while (isspace((unsigned char)*s))
        s++;
    e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = '\0';
    return s;
}

int hil_rig_config_load(struct hil_rig_config *c, const char *path, int *line_no)
{
    FILE *f;
    char line[256];
    int n = 0, st = HIL_OK;
    if (!c || !path)
        return HIL_E_ARG;
    if (line_no)
        *line_no = 0;
    c->err[0] = '\0';
    f = fopen(path, "r");
    if (!f) {
        snprintf(c->err, sizeof c->err, "cannot open the scenario file: %s", strerror(errno));
        return HIL_E_IO;
    }
    while (fgets(line, sizeof line, f)) {
        char *hash, *eq, *k, *v;
        n++;
        if (!strchr(line, '\n') && !feof(f)) {
            snprintf(c->err, sizeof c->err, "line longer than %d bytes", (int)sizeof line - 2);
            st = HIL_E_FORMAT;
            break;
        }
        if ((hash = strchr(line, '#')) != NULL)
            *hash = '\0';
        k = trim(line);
        if (!*k)
            continue;
        eq = strchr(k, '=');
        if (!eq) {
            snprintf(c->err, sizeof c->err, "'%.60s' is not a 'key = value' line", k);
            st = HIL_E_FORMAT;
            break;
        }
        *eq = '\0';
        v = trim(eq + 1);
        k = trim(k);
        if (hil_rig_config_set(c, k, v) != HIL_OK) {
            st = HIL_E_FORMAT;
            break;
        }
    }
    fclose(f);
    if (st != HIL_OK && line_no)
        *line_no = n;
    if (st == HIL_OK)
        snprintf(c->scenario, sizeof c->scenario, "%s", path);
    return st;
}

enum { FROM_DRIVE, FROM_IMU, FROM_PLANT, FROM_CTRL, FROM_FOREIGN, NODES = 4 };

static int is_pdo(uint32_t id) { return id >= 0x180u && id < 0x580u; }

/* The rig-internal frames model wiring, not CAN traffic: no bus effect. */
static int is_rig(uint32_t id) { return id >= HIL_COB_RIG_TORQUE && id <= HIL_COB_RIG_IMU_DONE; }

static int drive_bus_off(const struct hil_rig *r, double now)
{
    return now >= r->cfg.drive_busoff_start && now < r->cfg.drive_busoff_end;
}

/* Sets r->err to msg and returns status. */
static int rig_fail(struct hil_rig *r, int status, const char *msg)
{
    snprintf(r->err, sizeof r->err, "%s", msg);
    return status;
}

static int enqueue(struct hil_rig *r, const struct hil_out *out, int from)
{
    double now = (double)(r->ctrl.cycle ? r->ctrl.cycle - 1 : 0) * r->cfg.ctrl.T;
    int i;
    for (i = 0; i < out->n; i++) {
        int at;
        r->st.frames_sent++;
        if ((from == FROM_DRIVE && !is_rig(out->f[i].id) && drive_bus_off(r, now)) ||
            (is_pdo(out->f[i].id) &&
            ((from == FROM_IMU && now >= r->cfg.imu_dropout_start && now < r->cfg.imu_dropout_end) ||
             (from == FROM_DRIVE && now >= r->cfg.drive_dropout_start && now < r->cfg.drive_dropout_end)))) {
            r->st.frames_lost++;
            continue;
        }
        if (r->cfg.frame_loss > 0.0 && is_pdo(out->f[i].id) &&
            hil_rng_uniform(&r->bus_rng) < r->cfg.frame_loss) {
            r->st.frames_lost++;
            continue;
        }
        if (r->q_len >= HIL_RIG_QUEUE)
            return rig_fail(r, HIL_E_FULL, "the bus queue (HIL_RIG_QUEUE frames) overflowed");
        at = (r->q_head + r->q_len) % HIL_RIG_QUEUE;
        r->q[at] = out->f[i];
        r->q_from[at] = from;
        r->q_len++;
    }
    return HIL_OK;
}

static int drain(struct hil_rig *r);

int hil_rig_init(struct hil_rig *r, const struct hil_rig_config *c, FILE *log, FILE *csv)
{
    struct hil_out out, out2;
    if (!r || !c)
        return HIL_E_ARG;
    memset(r, 0, sizeof *r);
    if (!(c->duration > 0.0 && c->duration <= HIL_RIG_DURATION_MAX)) {
        snprintf(r->err, sizeof r->err, "duration = %g: wants simulated seconds in (0, %g]", c->duration,
                 HIL_RIG_DURATION_MAX);
        return HIL_E_ARG;
    }
    if (!(c->frame_loss >= 0.0 && c->frame_loss < 1.0))
        return rig_fail(r, HIL_E_ARG, "frame_loss: wants a probability in [0, 1)");
    if (c->drive.T != c->ctrl.T || c->plant_p.T != c->ctrl.T)
        return rig_fail(r, HIL_E_ARG, "the drive's, the plant's and the controller's T differ (set T)");
    r->cfg = *c;
    out.n = 0;
    out2.n = 0;
    if (hil_drive_init(&r->drive, &c->drive, &out) != HIL_OK)
        return rig_fail(r, HIL_E_ARG, "the drive.* parameters are out of range (docs/hil.md, Drive)");
    if (hil_imu_init(&r->imu, &c->imu, &out2) != HIL_OK)
        return rig_fail(r, HIL_E_ARG, "the imu.* parameters are out of range (docs/hil.md, IMU)");
    if (hil_plant_init(&r->plant, &c->plant_p) != HIL_OK)
        return rig_fail(r, HIL_E_ARG,
                        r->plant.err[0] ? r->plant.err : "the plant.* parameters are out of range (docs/hil.md, Plant)");
    if (hil_ctrl_init(&r->ctrl, &c->ctrl) != HIL_OK)
        return rig_fail(r, HIL_E_ARG, "the ctrl.* parameters are out of range (docs/hil.md, Controller)");
    hil_rng_seed(&r->bus_rng, c->bus_seed);
    r->log = log;
    r->csv = csv;
    r->log_max = HIL_RIG_LOG_MAX;
    enqueue(r, &out, FROM_DRIVE);
    enqueue(r, &out2, FROM_IMU);
    /* the controller boots the devices by SDO before cycle 0 (hil/ctrl.h);
     * these frames are logged at t = 0 + 1 us per frame, cycle 0 continues
     * the numbering */
    out.n = 0;
    hil_ctrl_boot(&r->ctrl, &out);
    if (enqueue(r, &out, FROM_CTRL) != HIL_OK || drain(r) != HIL_OK || r->ctrl.boot_status != 1) {
        char msg[sizeof r->err];
        snprintf(msg, sizeof msg, "the controller could not boot the devices by SDO: %s",
                 r->ctrl.boot_error[0] ? r->ctrl.boot_error : "the boot's frames did not all reach the bus");
        return rig_fail(r, HIL_E_STATE, msg);
    }
    r->booted_slots = r->slot;
    r->st.boot_frames = r->st.frames_delivered;
    if (csv)
        fprintf(csv, "t,ref,torque_cmd,motor_angle,motor_velocity,imu_rate,tip_angle,tip_velocity,"
                     "torque_actual,fault,run\n");
    return HIL_OK;
}

/* Logs f; HIL_E_FULL once the log would pass HIL_RIG_LOG_MAX. */
static int log_frame(struct hil_rig *r, const struct hil_can_frame *f)
{
    char line[HIL_CANDUMP_LINE_MAX];
    double t = (double)(r->ctrl.cycle ? r->ctrl.cycle - 1 : 0) * r->cfg.ctrl.T + r->slot * 1e-6;
    int len;
    r->slot++;
    if (r->log && (len = hil_candump_format(line, sizeof line, t, "vcan0", f)) > 0) {
        if (r->log_bytes + (unsigned long)len > r->log_max) {
            snprintf(r->err, sizeof r->err, "frames.log reached its bound of %lu bytes at t = %.6f s; "
                     "shorten duration (docs/hil.md, Bounds of a run)", r->log_max, t);
            return HIL_E_FULL;
        }
        fputs(line, r->log);
        r->log_bytes += (unsigned long)len;
        r->st.frames_logged++;
    }
    return HIL_OK;
}

static int drain(struct hil_rig *r)
{
    int guard = 0;
    while (r->q_len > 0) {
        struct hil_can_frame f = r->q[r->q_head];
        int from = r->q_from[r->q_head], n, st;
        r->q_head = (r->q_head + 1) % HIL_RIG_QUEUE;
        r->q_len--;
        if (++guard > 10 * HIL_RIG_QUEUE)
            return rig_fail(r, HIL_E_FULL, "the bus did not go idle within a cycle (frames kept answering frames)");
        r->st.frames_delivered++;
        if ((st = log_frame(r, &f)) != HIL_OK)
            return st;
        for (n = 0; n < NODES; n++) {
            struct hil_out out;
            if (n == from)
                continue;
            out.n = 0;
            /* bus-off: the drive hears nothing; its own cycle (SYNC-locked
             * here) and the wiring (RIG_*) go on */
            if (n == FROM_DRIVE && r->drive.bus_off && f.id != HIL_COB_SYNC && !is_rig(f.id))
                continue;
            if (n == FROM_DRIVE)
                hil_drive_on_frame(&r->drive, &f, &out);
            else if (n == FROM_IMU)
                hil_imu_on_frame(&r->imu, &f, &out);
            else if (n == FROM_PLANT)
                hil_plant_on_frame(&r->plant, &f, &out);
            else
                hil_ctrl_on_frame(&r->ctrl, &f, &out);
            st = enqueue(r, &out, n);
            if (st != HIL_OK)
                return st;
        }
    }
    return HIL_OK;
}

static void inject(struct hil_rig *r)
{
    struct hil_out out;
    struct hil_can_frame *f = out.f;
    memset(&out, 0, sizeof out);
    f[0].id = HIL_COB_RPDO1(HIL_NODE_DRIVE);
    f[0].dlc = 5;
    f[1].id = 0x555;
    f[1].dlc = 8;
    out.n = 2;
    r->st.injected += 2;
    enqueue(r, &out, FROM_FOREIGN);
}

int hil_rig_cycle(struct hil_rig *r)
{
    struct hil_out out;
    double tip_angle, tip_rate;
    int st;
    if (!r)
        return HIL_E_ARG;
    r->slot = r->ctrl.cycle == 0 ? r->booted_slots : 0;
    tip_angle = r->plant.psi;
    tip_rate = r->plant.psi_d;
    out.n = 0;
    hil_ctrl_tick(&r->ctrl, &out);
    if ((st = enqueue(r, &out, FROM_CTRL)) != HIL_OK)
        return st;
    {
        /* bus-off starts or ends with this cycle (enqueue's time is now t_k) */
        int off = drive_bus_off(r, (double)(r->ctrl.cycle - 1) * r->cfg.ctrl.T);
        if (off != r->drive.bus_off) {
            out.n = 0;
            hil_drive_set_bus_off(&r->drive, off, &out);
            r->st.bus_off_episodes += (uint64_t)off;
            if ((st = enqueue(r, &out, FROM_DRIVE)) != HIL_OK)
                return st;
        }
    }
    if ((st = drain(r)) != HIL_OK)
        return st;
    if (r->cfg.inject_every && r->ctrl.cycle % r->cfg.inject_every == 0) {
        inject(r);
        if ((st = drain(r)) != HIL_OK)
            return st;
    }
    out.n = 0;
    hil_ctrl_deadline(&r->ctrl, &out);
    if ((st = enqueue(r, &out, FROM_CTRL)) != HIL_OK || (st = drain(r)) != HIL_OK)
        return st;
    r->st.cycles++;
    if (r->csv) {
        const struct hil_ctrl_signals *s = &r->ctrl.sig;
        fprintf(r->csv, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%d\n", s->t, s->ref,
                s->torque_cmd, s->theta, s->omega, s->imu_rate, tip_angle, tip_rate,
                r->drive.tau_act, s->fault, s->run);
    }
    return HIL_OK;
}

int hil_rig_run(struct hil_rig *r)
{
    uint64_t n, i;
    struct hil_out out;
    int st;
    if (!r)
        return HIL_E_ARG;
    n = (uint64_t)floor(r->cfg.duration / r->cfg.ctrl.T + 0.5);
    for (i = 0; i < n; i++)
        if ((st = hil_rig_cycle(r)) != HIL_OK)
            return st;
    out.n = 0;
    hil_ctrl_stop(&r->ctrl, &out);
    r->slot = 0;
    if ((st = enqueue(r, &out, FROM_CTRL)) != HIL_OK)
        return st;
    return drain(r);
}

/* Writes s as a JSON string: quotes, backslashes and control bytes escaped. */
static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            fprintf(f, "\\%c", ch);
        else if (ch < 0x20)
            fprintf(f, "\\u%04x", ch);
        else
            fputc(ch, f);
    }
    fputc('"', f);
}

static void rx_json(FILE *f, const char *name, const struct hil_rx_stats *s, int last)
{
    fprintf(f, "    \"%s\": {\"accepted\": %llu, \"other\": %llu, \"unknown_id\": %llu, "
               "\"bad_dlc\": %llu, \"bad_value\": %llu}%s\n",
            name, (unsigned long long)s->accepted, (unsigned long long)s->other,
            (unsigned long long)s->unknown_id, (unsigned long long)s->bad_dlc,
            (unsigned long long)s->bad_value, last ? "" : ",");
}

int hil_rig_meta_begin(const struct hil_rig_config *c, const char *mode, FILE *f)
{
    size_t i;
    if (!c || !mode || !f)
        return HIL_E_ARG;
    fprintf(f, "{\n  \"schema\": \"fracarm.hil.run\",\n  \"version\": 1,\n");
    fprintf(f, "  \"software\": {\"fracarm\": \"%s\", \"hil_frames\": \"hil/fracarm.dbc\"},\n", HIL_VERSION);
    fprintf(f, "  \"mode\": ");
    json_str(f, mode);
    fprintf(f, ",\n  \"scenario\": ");
    json_str(f, c->scenario);
    fprintf(f, ",\n  \"plant\": \"%s\",\n", c->plant);
    fprintf(f, "  \"seeds\": {\"bus\": %llu, \"imu\": %llu},\n", (unsigned long long)c->bus_seed,
            (unsigned long long)c->imu.seed);
    fprintf(f, "  \"parameters\": {\n    \"T\": %.17g,\n    \"plant_name\": \"%s\",\n    \"ctrl.law\": \"%s\",\n",
            c->ctrl.T, c->plant, c->law);
    fprintf(f, "    \"plant.table\": ");
    json_str(f, c->plant_p.table);
    fprintf(f, ",\n    \"ctrl.table\": ");
    json_str(f, c->ctrl_table);
    fprintf(f, ",\n");
    for (i = 0; i < NKEYS; i++) {
        const char *p = (const char *)c + keys[i].off;
        fprintf(f, "    \"%s\": ", keys[i].name);
        if (keys[i].type == K_DBL)
            fprintf(f, "%.17g", *(const double *)p);
        else if (keys[i].type == K_REAL)
            fprintf(f, "%.17g", (double)*(const frac_real *)p);
        else if (keys[i].type == K_INT)
            fprintf(f, "%d", *(const int *)p);
        else if (keys[i].type == K_UNS)
            fprintf(f, "%u", *(const unsigned *)p);
        else
            fprintf(f, "%llu", (unsigned long long)*(const uint64_t *)p);
        fprintf(f, "%s\n", i + 1 < NKEYS ? "," : "");
    }
    fprintf(f, "  },\n  \"effects\": {\"drive_delay_cycles\": %u, \"imu_reading_cycles\": %u, "
               "\"imu_jitter_prob\": %.17g, \"imu_noise\": [%.17g, %.17g], \"imu_bias\": [%.17g, %.17g], "
               "\"imu_quant\": [%.17g, %.17g], \"torque_limits\": [%.17g, %.17g], \"frame_loss\": %.17g, "
               "\"imu_dropout\": [%.17g, %.17g], \"drive_dropout\": [%.17g, %.17g], "
               "\"torque_deadzone\": %.17g, \"torque_gain\": %.17g},\n",
            c->drive.delay, c->imu.reading_cycles, c->imu.jitter_prob, c->imu.gyro_noise,
            c->imu.acc_noise, c->imu.gyro_bias, c->imu.acc_bias, c->imu.gyro_quant, c->imu.acc_quant,
            c->drive.torque_rated, c->drive.torque_peak, c->frame_loss, c->imu_dropout_start,
            c->imu_dropout_end, c->drive_dropout_start, c->drive_dropout_end, c->drive.deadzone, c->drive.gain);
    return HIL_OK;
}

int hil_rig_config_write(const struct hil_rig_config *c, FILE *f)
{
    size_t i;
    if (!c || !f)
        return HIL_E_ARG;
    fprintf(f, "T = %.17g\nplant = %s\nctrl.law = %s\n", c->ctrl.T, c->plant, c->law);
    if (c->plant_p.table[0])
        fprintf(f, "plant.table = %s\n", c->plant_p.table);
    if (c->ctrl_table[0])
        fprintf(f, "ctrl.table = %s\n", c->ctrl_table);
    for (i = 0; i < NKEYS; i++) {
        const char *p = (const char *)c + keys[i].off;
        fprintf(f, "%s = ", keys[i].name);
        if (keys[i].type == K_DBL)
            fprintf(f, "%.17g\n", *(const double *)p);
        else if (keys[i].type == K_REAL)
            fprintf(f, "%.17g\n", (double)*(const frac_real *)p);
        else if (keys[i].type == K_INT)
            fprintf(f, "%d\n", *(const int *)p);
        else if (keys[i].type == K_UNS)
            fprintf(f, "%u\n", *(const unsigned *)p);
        else
            fprintf(f, "%llu\n", (unsigned long long)*(const uint64_t *)p);
    }
    return ferror(f) ? HIL_E_IO : HIL_OK;
}

int hil_rig_write_meta(const struct hil_rig *r, FILE *f, double wall_s)
{
    if (!r || !f)
        return HIL_E_ARG;
    hil_rig_meta_begin(&r->cfg, "lockstep", f);
    fprintf(f, "  \"plant_effects\": {\"backlash\": %.17g, \"extra_mode\": [%.17g, %.17g, %.17g], "
               "\"friction_model\": %d, \"kelvin_voigt\": [%.17g, %.17g, %u]},\n",
            r->cfg.plant_p.backlash, r->cfg.plant_p.extra_inertia, r->cfg.plant_p.extra_hz, r->cfg.plant_p.extra_zeta,
            r->cfg.plant_p.friction.model, r->cfg.plant_p.kv_damping, r->cfg.plant_p.kv_order,
            r->cfg.plant_p.kv_memory);
    fprintf(f, "  \"bus_off\": {\"drive\": [%.17g, %.17g], \"episodes\": %llu},\n",
            r->cfg.drive_busoff_start, r->cfg.drive_busoff_end, (unsigned long long)r->st.bus_off_episodes);
    fprintf(f, "  \"counts\": {\"cycles\": %llu, \"frames_sent\": %llu, \"frames_lost\": %llu, "
               "\"frames_delivered\": %llu, \"frames_logged\": %llu, \"injected\": %llu, "
               "\"missed_inputs\": %llu, \"imu_readings\": %llu, \"faults\": %llu, \"emcy\": %llu, "
               "\"law_status\": %u, \"boot_frames\": %llu, \"sdo_requests\": %llu},\n",
            (unsigned long long)r->st.cycles, (unsigned long long)r->st.frames_sent,
            (unsigned long long)r->st.frames_lost, (unsigned long long)r->st.frames_delivered,
            (unsigned long long)r->st.frames_logged, (unsigned long long)r->st.injected,
            (unsigned long long)r->ctrl.missed_inputs, (unsigned long long)r->ctrl.imu_readings,
            (unsigned long long)r->ctrl.faults,
            (unsigned long long)(r->ctrl.emcy_sent + r->drive.emcy_sent), r->ctrl.law_status,
            (unsigned long long)r->st.boot_frames, (unsigned long long)r->ctrl.sdo_requests);
    fprintf(f, "  \"rx\": {\n");
    rx_json(f, "drive", &r->drive.rx, 0);
    rx_json(f, "imu", &r->imu.rx, 0);
    rx_json(f, "plant", &r->plant.rx, 0);
    rx_json(f, "ctrl", &r->ctrl.rx, 1);
    fprintf(f, "  },\n  \"wall_s\": %.6f\n}\n", wall_s);
    return HIL_OK;
}
