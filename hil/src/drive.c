/* Emulated CiA 402 servo drive; behaviour in hil/drive.h. */
#include <math.h>
#include <string.h>
#include "hil/canopen.h"
#include "hil/drive.h"

void hil_drive_params_default(struct hil_drive_params *p)
{
    p->T = 1.2e-3;
    p->delay = 4;
    p->tau_current = 0.25e-3;
    p->torque_rated = 95.7;
    p->torque_peak = 251.0;
    p->thermal_tau = 1.0;
    p->rpdo_timeout = 3;
    p->encoder_bits = 20;
    p->velocity_from_encoder = 0;
    p->deadzone = 0.0;
    p->gain = 1.0;
}

static int params_ok(const struct hil_drive_params *p)
{
    return p && p->T > 0.0 && isfinite(p->T) && p->delay >= 1 && p->delay <= HIL_DRIVE_MAX_DELAY &&
           p->tau_current >= 0.0 && isfinite(p->tau_current) && p->torque_rated > 0.0 &&
           p->torque_peak >= p->torque_rated && isfinite(p->torque_peak) && p->thermal_tau > 0.0 &&
           isfinite(p->thermal_tau) && p->rpdo_timeout >= 1 && p->torque_rated * 1e3 < 4294967295.0 &&
           p->torque_peak / p->torque_rated * 1e3 < 65535.5 &&
           p->encoder_bits >= 1 && p->encoder_bits <= 20 && p->velocity_from_encoder <= 1 &&
           p->deadzone >= 0.0 && isfinite(p->deadzone) && p->gain > 0.0 && isfinite(p->gain);
}

static void heartbeat(struct hil_drive *d, struct hil_out *out)
{
    struct hil_can_frame f;
    if (hil_co_heartbeat_encode(&f, HIL_NODE_DRIVE, d->nmt) == HIL_OK)
        hil_out_push(out, &f);
    d->since_heartbeat = 0;
}

/* (index, sub) of enum hil_drive_obj. */
static const uint16_t obj_index[HIL_DRV_NOBJ] = {
    0x1001, 0x1017, 0x2071, 0x2077, 0x2100, 0x2101, 0x603F, 0x6040, 0x6041, 0x605A,
    0x6060, 0x6061, 0x6064, 0x606C, 0x6071, 0x6072, 0x6076, 0x6077};

#define VAL(d, k) ((d)->od[(d)->ix[k]])

/* Error register 0x1001 bits (CiA 301 table 48). */
#define ER_GENERIC 0x01u
#define ER_TEMPERATURE 0x08u
#define ER_COMMUNICATION 0x10u

static void emcy(struct hil_drive *d, uint16_t code, struct hil_out *out)
{
    struct hil_emcy e;
    struct hil_can_frame f;
    memset(&e, 0, sizeof e);
    e.code = code;
    e.error_register = (uint8_t)VAL(d, HIL_DRV_ERROR_REGISTER);
    e.info[0] = (uint8_t)d->state;
    if (hil_co_emcy_encode(&f, HIL_NODE_DRIVE, &e) == HIL_OK && hil_out_push(out, &f) == HIL_OK)
        d->emcy_sent++;
}

/* Latches an error: 0x603F = code, 0x1001 |= bits, EMCY. */
static void error(struct hil_drive *d, uint16_t code, uint32_t bits, struct hil_out *out)
{
    VAL(d, HIL_DRV_ERROR_CODE) = code;
    VAL(d, HIL_DRV_ERROR_REGISTER) |= ER_GENERIC | bits;
    emcy(d, code, out);
}

static void fault(struct hil_drive *d, uint16_t code, uint32_t bits, struct hil_out *out)
{
    d->state = HIL_CIA402_FAULT; /* fault reaction: torque command 0 (the line below is fed 0) */
    error(d, code, bits, out);
}

/* Power-on values that come from the parameters, not from the table. */
static void od_from_params(struct hil_drive *d)
{
    VAL(d, HIL_DRV_RATED_TORQUE) = (uint32_t)floor(d->p.torque_rated * 1e3 + 0.5);
    VAL(d, HIL_DRV_MAX_TORQUE) = (uint32_t)floor(d->p.torque_peak / d->p.torque_rated * 1e3 + 0.5);
}

static void reset(struct hil_drive *d)
{
    d->state = HIL_CIA402_SWITCH_ON_DISABLED;
    d->last_controlword = 0;
    d->cmd_latest = 0.0;
    memset(d->line, 0, sizeof d->line);
    d->since_rpdo = 0;
    d->limiting = 0;
    VAL(d, HIL_DRV_ERROR_CODE) = 0;
    VAL(d, HIL_DRV_ERROR_REGISTER) = 0;
    hil_sdo_server_init(&d->sdo, HIL_NODE_DRIVE);
    memset(&d->pdo, 0, sizeof d->pdo);
}

static uint32_t write_hook(void *ctx, int i, uint32_t v);

struct hil_od_dev hil_drive_od_dev(struct hil_drive *d)
{
    struct hil_od_dev v;
    v.od = &hil_drive_od;
    v.val = d->od;
    v.write = write_hook;
    v.ctx = d;
    v.nmt = &d->nmt;
    return v;
}

/* NMT reset node (whole dictionary) or reset communication (0x1000-0x1FFF). */
static void od_reset(struct hil_drive *d, int comm_only)
{
    struct hil_od_dev v = hil_drive_od_dev(d);
    hil_od_reset(&v, comm_only);
    if (!comm_only)
        od_from_params(d);
}

int hil_drive_init(struct hil_drive *d, const struct hil_drive_params *p, struct hil_out *out)
{
    int k;
    if (!d || !params_ok(p) || !out)
        return HIL_E_ARG;
    memset(d, 0, sizeof *d);
    d->p = *p;
    for (k = 0; k < HIL_DRV_NOBJ; k++)
        d->ix[k] = (int16_t)hil_od_find(&hil_drive_od, obj_index[k], 0, NULL);
    for (k = 0; k < hil_drive_od.n; k++)
        d->od[k] = (uint32_t)hil_drive_od.e[k].dflt;
    od_reset(d, 0);
    reset(d);
    d->nmt = HIL_NMT_STATE_BOOTUP;
    heartbeat(d, out);
    d->nmt = HIL_NMT_STATE_PREOP;
    return HIL_OK;
}

int hil_drive_set_bus_off(struct hil_drive *d, int off, struct hil_out *out)
{
    if (!d || !out)
        return HIL_E_ARG;
    if (d->bus_off && !off)
        error(d, HIL_EMCY_BUS_OFF_RECOVERED, ER_COMMUNICATION, out);
    d->bus_off = off != 0;
    return HIL_OK;
}

/* The i^2t estimate is above the over-temperature trip 0x2101. */
static int hot(const struct hil_drive *d)
{
    return d->thermal * 1e3 > (double)VAL(d, HIL_DRV_I2T_TRIP) * d->p.torque_rated * d->p.torque_rated;
}

static int cst(const struct hil_drive *d) { return (int8_t)VAL(d, HIL_DRV_MODE) == 10; }

uint16_t hil_drive_statusword(const struct hil_drive *d)
{
    static const uint16_t sw[] = {0x0040, 0x0021, 0x0023, 0x0027, 0x0007, 0x0008};
    uint16_t w = (uint16_t)(sw[d->state] | 0x0200u); /* bit 9: remote */
    if (d->state != HIL_CIA402_SWITCH_ON_DISABLED && d->state != HIL_CIA402_FAULT)
        w |= 0x0010u; /* bit 4: voltage enabled */
    if (d->limiting)
        w |= HIL_SW_INTERNAL_LIMIT;
    if (d->state == HIL_CIA402_OPERATION_ENABLED && cst(d) && d->nmt == HIL_NMT_STATE_OPERATIONAL)
        w |= 0x1000u; /* bit 12 in CST: the drive follows the target torque */
    return w;
}

/* Clears the latched errors (fault reset): EMCY "error reset" when any was set. */
static void clear_errors(struct hil_drive *d, struct hil_out *out)
{
    if (VAL(d, HIL_DRV_ERROR_REGISTER) == 0 && VAL(d, HIL_DRV_ERROR_CODE) == 0)
        return;
    VAL(d, HIL_DRV_ERROR_CODE) = 0;
    VAL(d, HIL_DRV_ERROR_REGISTER) = 0;
    emcy(d, HIL_EMCY_NO_ERROR, out);
}

/* CiA 402 device control (state transitions 2..12, 15, 16 of the standard's
 * state machine; 0x6040 command coding, table 27). */
static void controlword(struct hil_drive *d, uint16_t cw, struct hil_out *out)
{
    enum hil_cia402_state s = d->state;
    int reset_edge = (cw & 0x80u) && !(d->last_controlword & 0x80u);
    d->last_controlword = cw;
    if (reset_edge) {
        if (s == HIL_CIA402_FAULT && hot(d))
            return; /* the cause persists: stay in fault */
        clear_errors(d, out);
        if (s == HIL_CIA402_FAULT)
            d->state = HIL_CIA402_SWITCH_ON_DISABLED;
        return;
    }
    if (s == HIL_CIA402_FAULT)
        return;
    if ((cw & 0x02u) == 0) { /* disable voltage */
        d->state = HIL_CIA402_SWITCH_ON_DISABLED;
    } else if ((cw & 0x06u) == 0x02u) { /* quick stop */
        d->state = s == HIL_CIA402_OPERATION_ENABLED || s == HIL_CIA402_QUICK_STOP_ACTIVE
                       ? HIL_CIA402_QUICK_STOP_ACTIVE : HIL_CIA402_SWITCH_ON_DISABLED;
    } else if ((cw & 0x87u) == 0x06u) { /* shutdown */
        if (s != HIL_CIA402_QUICK_STOP_ACTIVE)
            d->state = HIL_CIA402_READY_TO_SWITCH_ON;
    } else if ((cw & 0x8Fu) == 0x07u) { /* switch on / disable operation */
        if (s == HIL_CIA402_READY_TO_SWITCH_ON || s == HIL_CIA402_OPERATION_ENABLED)
            d->state = HIL_CIA402_SWITCHED_ON;
    } else if ((cw & 0x8Fu) == 0x0Fu) { /* enable operation */
        if (s == HIL_CIA402_SWITCHED_ON || (s == HIL_CIA402_QUICK_STOP_ACTIVE &&
                                           (int16_t)VAL(d, HIL_DRV_QUICK_STOP_OPTION) >= 5))
            d->state = HIL_CIA402_OPERATION_ENABLED;
    }
    if (d->state == HIL_CIA402_OPERATION_ENABLED && s != HIL_CIA402_OPERATION_ENABLED)
        d->since_rpdo = 0;
}

/* Device rules and actions of a write (hil/od.h hook): the supported modes
 * (0 none, 10 CST), quick stop options 2 and 6, synchronous TPDOs only, the
 * two views of the target torque (0x6071 per mille, 0x2071 mNm), the
 * controlword into the state machine. */
static uint32_t write_hook(void *ctx, int i, uint32_t v)
{
    struct hil_drive *d = ctx;
    const struct hil_od_entry *e = &hil_drive_od.e[i];
    double rated_mnm = (double)VAL(d, HIL_DRV_RATED_TORQUE);
    int64_t q;
    if (e->index >= 0x1800u && e->index < 0x1800u + HIL_PDO_MAX && e->sub == 2 && (v < 1u || v > 240u))
        return HIL_SDO_ABORT_RANGE;
    if (i == d->ix[HIL_DRV_MODE] && (int8_t)v != 0 && (int8_t)v != 10)
        return HIL_SDO_ABORT_RANGE;
    if (i == d->ix[HIL_DRV_QUICK_STOP_OPTION] && (int16_t)v != 2 && (int16_t)v != 6)
        return HIL_SDO_ABORT_RANGE;
    if (i == d->ix[HIL_DRV_CONTROLWORD]) {
        struct hil_out scratch;
        scratch.n = 0;
        controlword(d, (uint16_t)v, d->out_now ? d->out_now : &scratch);
    } else if (i == d->ix[HIL_DRV_TARGET_TORQUE]) {
        hil_co_quantize((int16_t)v * rated_mnm / 1e3, 1.0, INT32_MIN, INT32_MAX, &q);
        VAL(d, HIL_DRV_TARGET_MNM) = (uint32_t)(int32_t)q;
        d->cmd_latest = (double)q * HIL_TORQUE_LSB;
    } else if (i == d->ix[HIL_DRV_TARGET_MNM]) {
        hil_co_quantize((int32_t)v * 1e3 / rated_mnm, 1.0, INT16_MIN, INT16_MAX, &q);
        VAL(d, HIL_DRV_TARGET_TORQUE) = (uint32_t)(uint16_t)(int16_t)q;
        d->cmd_latest = (int32_t)v * HIL_TORQUE_LSB;
    }
    return 0;
}

/* The torque the shaft receives for the drive torque tau (hil/drive.h, 5.). */
static double shaft_torque(const struct hil_drive *d, double tau)
{
    double a = fabs(tau) <= d->p.deadzone ? 0.0 : tau - copysign(d->p.deadzone, tau);
    return d->p.gain * a;
}

/* Process values of the dictionary from the drive's state. */
static void refresh(struct hil_drive *d)
{
    int64_t q;
    hil_co_quantize(d->thermal / (d->p.torque_rated * d->p.torque_rated) * 1e3, 1.0, 0, 65535, &q);
    VAL(d, HIL_DRV_I2T) = (uint32_t)q;
    VAL(d, HIL_DRV_STATUSWORD) = hil_drive_statusword(d);
    VAL(d, HIL_DRV_MODE_DISPLAY) = VAL(d, HIL_DRV_MODE);
}

/* Measured values at t_k (encoder count, velocity, torque actual, i^2t). */
static void measure(struct hil_drive *d)
{
    int64_t q, counts, scale = (int64_t)1 << (20 - d->p.encoder_bits);
    double vel, cpr = (double)((int64_t)1 << d->p.encoder_bits);
    /* encoder count (floor), in 2^20 wire units */
    hil_co_quantize(floor(d->theta * cpr / (2.0 * M_PI)), 1.0, INT32_MIN / scale, INT32_MAX / scale, &counts);
    VAL(d, HIL_DRV_POSITION) = (uint32_t)(int32_t)(counts * scale);
    vel = d->p.velocity_from_encoder ? (double)(counts - d->last_counts) * (2.0 * M_PI / cpr) / d->p.T : d->omega;
    d->last_counts = counts;
    hil_co_quantize(vel, HIL_VEL_LSB, INT32_MIN, INT32_MAX, &q);
    VAL(d, HIL_DRV_VELOCITY) = (uint32_t)(int32_t)q;
    hil_co_quantize(d->tau_act, HIL_TORQUE_LSB, INT32_MIN, INT32_MAX, &q);
    VAL(d, HIL_DRV_TORQUE_MNM) = (uint32_t)(int32_t)q;
    hil_co_quantize(d->tau_act / d->p.torque_rated * 1e3, 1.0, INT16_MIN, INT16_MAX, &q);
    VAL(d, HIL_DRV_TORQUE_ACTUAL) = (uint32_t)(uint16_t)(int16_t)q;
    refresh(d);
}

static void on_sync(struct hil_drive *d, struct hil_out *out)
{
    struct hil_can_frame f;
    struct hil_od_dev v = hil_drive_od_dev(d);
    double c, lim, a, tau_end, lim_max;
    unsigned i;
    int k, op = d->nmt == HIL_NMT_STATE_OPERATIONAL;
    int enabled;

    d->syncs++;
    d->tx_syncs++;
    if (op) {
        measure(d);
        for (k = 0; k < d->pdo.ntx; k++) {
            if (d->tx_syncs % d->pdo.tx[k].trans != 0)
                continue;
            hil_pdo_pack(&v, &d->pdo.tx[k], &f);
            hil_out_push(out, &f);
        }
    }
    if (d->state == HIL_CIA402_OPERATION_ENABLED && op && ++d->since_rpdo > d->p.rpdo_timeout)
        fault(d, HIL_EMCY_RPDO_TIMEOUT, ER_COMMUNICATION, out);
    if (d->state == HIL_CIA402_QUICK_STOP_ACTIVE && (int16_t)VAL(d, HIL_DRV_QUICK_STOP_OPTION) < 5)
        d->state = HIL_CIA402_SWITCH_ON_DISABLED; /* option 2: stopped (torque 0), then disabled */
    enabled = d->state == HIL_CIA402_OPERATION_ENABLED && cst(d);
    for (i = d->p.delay - 1; i > 0; i--)
        d->line[i] = d->line[i - 1];
    d->line[0] = (enabled && op) ? d->cmd_latest : 0.0;
    c = enabled ? d->line[d->p.delay - 1] : 0.0;
    lim = d->thermal > d->p.torque_rated * d->p.torque_rated ? d->p.torque_rated : d->p.torque_peak;
    lim_max = (double)VAL(d, HIL_DRV_MAX_TORQUE) * d->p.torque_rated * 1e-3;
    if (lim_max < lim)
        lim = lim_max;
    d->limiting = fabs(c) > lim;
    if (c > lim)
        c = lim;
    else if (c < -lim)
        c = -lim;
    a = d->p.tau_current > 0.0 ? exp(-d->p.T / d->p.tau_current) : 0.0;
    tau_end = c + (d->tau_act - c) * a;
    if (hil_co_rig_encode(&f, HIL_COB_RIG_TORQUE, shaft_torque(d, d->tau_act), shaft_torque(d, tau_end)) == HIL_OK)
        hil_out_push(out, &f);
    d->tau_act = tau_end;
    d->thermal += (d->p.T / d->p.thermal_tau) * (tau_end * tau_end - d->thermal);
    if (hot(d) && d->state != HIL_CIA402_FAULT)
        fault(d, HIL_EMCY_OVERTEMP, ER_TEMPERATURE, out);
    refresh(d);
    d->since_heartbeat++;
    if (VAL(d, HIL_DRV_HEARTBEAT) && (double)d->since_heartbeat * d->p.T * 1e3 >= (double)VAL(d, HIL_DRV_HEARTBEAT) - 1e-9)
        heartbeat(d, out);
}

static int nmt(struct hil_drive *d, const struct hil_can_frame *f, struct hil_out *out)
{
    int reset_cmd;
    uint8_t before = d->nmt;
    int st = hil_nmt_on_frame(&d->rx, f, HIL_NODE_DRIVE, &d->nmt, &reset_cmd);
    if (st != HIL_OK)
        return st;
    if (reset_cmd) {
        od_reset(d, f->data[0] == HIL_NMT_RESET_COMM);
        reset(d);
        d->nmt = HIL_NMT_STATE_BOOTUP;
        heartbeat(d, out);
        d->nmt = HIL_NMT_STATE_PREOP;
        return HIL_OK;
    }
    if (d->nmt == HIL_NMT_STATE_OPERATIONAL && before != HIL_NMT_STATE_OPERATIONAL) {
        struct hil_od_dev v = hil_drive_od_dev(d);
        hil_pdo_compile(&v, &d->pdo); /* the PDO parameters written in pre-operational apply now */
        d->tx_syncs = 0;             /* transmission type n: every n-th SYNC from the start */
    }
    heartbeat(d, out);
    return HIL_OK;
}

static int rpdo(struct hil_drive *d, const struct hil_pdo *p, const struct hil_can_frame *f, struct hil_out *out)
{
    struct hil_od_dev v = hil_drive_od_dev(d);
    int st;
    if (hil_can_frame_check(f) != HIL_OK || f->dlc != p->dlc) {
        d->rx.bad_dlc++;
        return HIL_E_DLC;
    }
    d->rx.accepted++;
    if (d->nmt != HIL_NMT_STATE_OPERATIONAL)
        return HIL_E_STATE; /* PDOs are ignored outside "operational" (CiA 301) */
    d->out_now = out;
    st = hil_pdo_unpack(&v, p, f) ? HIL_E_RANGE : HIL_OK;
    d->out_now = NULL;
    d->since_rpdo = 0;
    return st;
}

static int sdo(struct hil_drive *d, const struct hil_can_frame *f, struct hil_out *out)
{
    struct hil_od_dev v = hil_drive_od_dev(d);
    struct hil_can_frame r;
    int st;
    if (d->nmt != HIL_NMT_STATE_PREOP && d->nmt != HIL_NMT_STATE_OPERATIONAL) {
        d->rx.accepted++;
        return HIL_E_STATE;
    }
    refresh(d);
    d->out_now = out;
    st = hil_sdo_server_on_frame(&d->sdo, &v, f, &r);
    d->out_now = NULL;
    if (st < 0)
        d->rx.bad_value++;
    else
        d->rx.accepted++;
    if (st != 0)
        hil_out_push(out, &r);
    refresh(d);
    return st < 0 ? HIL_E_FORMAT : HIL_OK;
}

int hil_drive_on_frame(struct hil_drive *d, const struct hil_can_frame *f, struct hil_out *out)
{
    const struct hil_pdo *p;
    int st;
    if (!d || !f || !out)
        return HIL_E_ARG;
    if ((p = hil_pdo_rx_find(&d->pdo, f->id)) != NULL && !(f->id & HIL_CAN_EFF_FLAG))
        return rpdo(d, p, f, out);
    st = hil_rx_screen(&d->rx, f);
    if (st != HIL_OK)
        return st;
    switch (f->id) {
    case HIL_COB_NMT:
        return nmt(d, f, out);
    case HIL_COB_SYNC:
        if (hil_co_sync_decode(f, NULL) != HIL_OK) {
            d->rx.bad_value++;
            return HIL_E_FORMAT;
        }
        d->rx.accepted++;
        on_sync(d, out);
        return HIL_OK;
    case HIL_COB_SDO_RX(HIL_NODE_DRIVE):
        return sdo(d, f, out);
    case HIL_COB_RIG_MOTOR: {
        double th, om;
        if (hil_co_rig_decode(f, HIL_COB_RIG_MOTOR, &th, &om) != HIL_OK) {
            d->rx.bad_value++;
            return HIL_E_RANGE;
        }
        d->rx.accepted++;
        d->theta = th;
        d->omega = om;
        return HIL_OK;
    }
    default:
        if (f->id == HIL_COB_RPDO1(HIL_NODE_DRIVE)) { /* the default RPDO before NMT start */
            d->rx.accepted++;
            return HIL_E_STATE;
        }
        d->rx.other++;
        return HIL_E_UNKNOWN_ID;
    }
}
