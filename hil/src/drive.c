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
    p->heartbeat_syncs = 84;
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
           isfinite(p->thermal_tau) && p->rpdo_timeout >= 1 && p->heartbeat_syncs >= 1 &&
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

static void emcy(struct hil_drive *d, uint16_t code, struct hil_out *out)
{
    struct hil_emcy e;
    struct hil_can_frame f;
    memset(&e, 0, sizeof e);
    e.code = code;
    e.error_register = code ? 0x01 : 0x00; /* bit 0: generic error */
    e.info[0] = (uint8_t)d->state;
    if (hil_co_emcy_encode(&f, HIL_NODE_DRIVE, &e) == HIL_OK && hil_out_push(out, &f) == HIL_OK)
        d->emcy_sent++;
}

static void reset(struct hil_drive *d)
{
    d->state = HIL_CIA402_SWITCH_ON_DISABLED;
    d->last_controlword = 0;
    d->cmd_latest = 0.0;
    memset(d->line, 0, sizeof d->line);
    d->since_rpdo = 0;
    d->limiting = 0;
}

int hil_drive_init(struct hil_drive *d, const struct hil_drive_params *p, struct hil_out *out)
{
    if (!d || !params_ok(p) || !out)
        return HIL_E_ARG;
    memset(d, 0, sizeof *d);
    d->p = *p;
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
        emcy(d, HIL_EMCY_BUS_OFF_RECOVERED, out);
    d->bus_off = off != 0;
    return HIL_OK;
}

uint16_t hil_drive_statusword(const struct hil_drive *d)
{
    static const uint16_t sw[] = {0x0040, 0x0021, 0x0023, 0x0027, 0x0007, 0x0008};
    uint16_t w = (uint16_t)(sw[d->state] | 0x0200u); /* bit 9: remote */
    if (d->state != HIL_CIA402_SWITCH_ON_DISABLED && d->state != HIL_CIA402_FAULT)
        w |= 0x0010u; /* bit 4: voltage enabled */
    if (d->limiting)
        w |= HIL_SW_INTERNAL_LIMIT;
    return w;
}

/* CiA 402 device control (state transitions 2..12, 15 of the standard's
 * state machine; 0x6040 command coding). */
static void controlword(struct hil_drive *d, uint16_t cw)
{
    enum hil_cia402_state s = d->state;
    int reset_edge = (cw & 0x80u) && !(d->last_controlword & 0x80u);
    d->last_controlword = cw;
    if (s == HIL_CIA402_FAULT) {
        if (reset_edge)
            d->state = HIL_CIA402_SWITCH_ON_DISABLED;
        return;
    }
    if ((cw & 0x02u) == 0) { /* disable voltage */
        d->state = HIL_CIA402_SWITCH_ON_DISABLED;
    } else if ((cw & 0x06u) == 0x02u) { /* quick stop */
        d->state = s == HIL_CIA402_OPERATION_ENABLED ? HIL_CIA402_QUICK_STOP_ACTIVE
                                                     : HIL_CIA402_SWITCH_ON_DISABLED;
    } else if ((cw & 0x87u) == 0x06u) { /* shutdown */
        if (s != HIL_CIA402_QUICK_STOP_ACTIVE)
            d->state = HIL_CIA402_READY_TO_SWITCH_ON;
    } else if ((cw & 0x8Fu) == 0x07u) { /* switch on / disable operation */
        if (s == HIL_CIA402_READY_TO_SWITCH_ON || s == HIL_CIA402_OPERATION_ENABLED)
            d->state = HIL_CIA402_SWITCHED_ON;
    } else if ((cw & 0x8Fu) == 0x0Fu) { /* enable operation */
        if (s == HIL_CIA402_SWITCHED_ON || s == HIL_CIA402_QUICK_STOP_ACTIVE)
            d->state = HIL_CIA402_OPERATION_ENABLED;
    }
    if (d->state == HIL_CIA402_OPERATION_ENABLED && s != HIL_CIA402_OPERATION_ENABLED)
        d->since_rpdo = 0;
}

/* The torque the shaft receives for the drive torque tau (hil/drive.h, 5.). */
static double shaft_torque(const struct hil_drive *d, double tau)
{
    double a = fabs(tau) <= d->p.deadzone ? 0.0 : tau - copysign(d->p.deadzone, tau);
    return d->p.gain * a;
}

static void on_sync(struct hil_drive *d, struct hil_out *out)
{
    struct hil_can_frame f;
    struct hil_drive_tpdo1 t1;
    struct hil_drive_tpdo2 t2;
    int64_t q, counts, scale = (int64_t)1 << (20 - d->p.encoder_bits);
    double c, lim, a, tau_end, vel, cpr = (double)((int64_t)1 << d->p.encoder_bits);
    unsigned i;
    int op = d->nmt == HIL_NMT_STATE_OPERATIONAL;
    int enabled = d->state == HIL_CIA402_OPERATION_ENABLED;

    d->syncs++;
    if (op) {
        t1.statusword = hil_drive_statusword(d);
        /* encoder count (floor), in 2^20 wire units */
        hil_co_quantize(floor(d->theta * cpr / (2.0 * M_PI)), 1.0, INT32_MIN / scale, INT32_MAX / scale, &counts);
        t1.position_inc = (int32_t)(counts * scale);
        vel = d->p.velocity_from_encoder ? (double)(counts - d->last_counts) * (2.0 * M_PI / cpr) / d->p.T
                                         : d->omega;
        d->last_counts = counts;
        hil_co_quantize(vel, HIL_VEL_LSB, INT32_MIN, INT32_MAX, &q);
        t2.velocity_urads = (int32_t)q;
        hil_co_quantize(d->tau_act, HIL_TORQUE_LSB, INT32_MIN, INT32_MAX, &q);
        t2.torque_mnm = (int32_t)q;
        if (hil_co_drive_tpdo1_encode(&f, &t1) == HIL_OK)
            hil_out_push(out, &f);
        if (hil_co_drive_tpdo2_encode(&f, &t2) == HIL_OK)
            hil_out_push(out, &f);
    }
    if (enabled && op && ++d->since_rpdo > d->p.rpdo_timeout) {
        d->state = HIL_CIA402_FAULT;
        emcy(d, HIL_EMCY_RPDO_TIMEOUT, out);
        enabled = 0;
    }
    for (i = d->p.delay - 1; i > 0; i--)
        d->line[i] = d->line[i - 1];
    d->line[0] = (enabled && op) ? d->cmd_latest : 0.0;
    c = enabled ? d->line[d->p.delay - 1] : 0.0;
    lim = d->thermal > d->p.torque_rated * d->p.torque_rated ? d->p.torque_rated : d->p.torque_peak;
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
    if (++d->since_heartbeat >= d->p.heartbeat_syncs)
        heartbeat(d, out);
}

int hil_drive_on_frame(struct hil_drive *d, const struct hil_can_frame *f, struct hil_out *out)
{
    int st;
    if (!d || !f || !out)
        return HIL_E_ARG;
    st = hil_rx_screen(&d->rx, f);
    if (st != HIL_OK)
        return st;
    switch (f->id) {
    case HIL_COB_NMT: {
        int reset_cmd;
        st = hil_nmt_on_frame(&d->rx, f, HIL_NODE_DRIVE, &d->nmt, &reset_cmd);
        if (st != HIL_OK)
            return st;
        if (reset_cmd) {
            reset(d);
            d->nmt = HIL_NMT_STATE_BOOTUP;
            heartbeat(d, out);
            d->nmt = HIL_NMT_STATE_PREOP;
            return HIL_OK;
        }
        heartbeat(d, out);
        return HIL_OK;
    }
    case HIL_COB_SYNC:
        if (hil_co_sync_decode(f, NULL) != HIL_OK) {
            d->rx.bad_value++;
            return HIL_E_FORMAT;
        }
        d->rx.accepted++;
        on_sync(d, out);
        return HIL_OK;
    case HIL_COB_RPDO1(HIL_NODE_DRIVE): {
        struct hil_drive_rpdo r;
        hil_co_drive_rpdo_decode(f, &r);
        d->rx.accepted++;
        if (d->nmt != HIL_NMT_STATE_OPERATIONAL)
            return HIL_E_STATE; /* PDOs are ignored outside "operational" (CiA 301) */
        controlword(d, r.controlword);
        d->cmd_latest = r.torque_mnm * HIL_TORQUE_LSB;
        d->since_rpdo = 0;
        return HIL_OK;
    }
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
        d->rx.other++;
        return HIL_E_UNKNOWN_ID;
    }
}
