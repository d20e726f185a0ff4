/* Controller node with the PD test law; behaviour in hil/ctrl.h. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "hil/canopen.h"
#include "hil/ctrl.h"
#include "hil/drive.h"
#include "hil/imu.h"
#include "hil/sdo.h"

void hil_ctrl_params_default(struct hil_ctrl_params *p)
{
    p->T = 1.2e-3;
    p->kp = 400.0;
    p->kd = 60.0;
    p->k_tip = 0.0;
    p->move = 0.5;
    p->move_start = 0.1;
    p->move_time = 0.5;
    p->imu_timeout = 3;
    p->ramp_time = 8.4e-3;
    p->torque_max = 251.0;
}

static int fin(double x) { return isfinite(x); }

int hil_ctrl_init(struct hil_ctrl *c, const struct hil_ctrl_params *p)
{
    if (!c || !p || !(p->T > 0.0) || !fin(p->T) || !fin(p->kp) || !fin(p->kd) || !fin(p->k_tip) ||
        !fin(p->move) || !fin(p->move_start) || !(p->move_time > 0.0) || !fin(p->move_time) ||
        p->imu_timeout < 1 || !(p->ramp_time > 0.0) || !fin(p->ramp_time) ||
        !(p->torque_max > 0.0) || !fin(p->torque_max))
        return HIL_E_ARG;
    memset(c, 0, sizeof *c);
    c->p = *p;
    memset(c->hb_state, 0xFF, sizeof c->hb_state);
    return HIL_OK;
}

static void add_step(struct hil_ctrl_boot_dev *b, uint16_t index, uint8_t sub, unsigned bytes, uint32_t v)
{
    if (b->n < HIL_CTRL_BOOT_MAX) {
        struct hil_ctrl_sdo_step *s = &b->step[b->n++];
        s->index = index;
        s->sub = sub;
        s->bytes = (uint8_t)bytes;
        s->value = v;
    }
}

static int64_t eds_value(const struct hil_od *od, uint16_t index, uint8_t sub, int *found)
{
    int i = hil_od_find(od, index, sub, NULL);
    *found = i >= 0;
    return i >= 0 ? od->e[i].dflt : 0;
}

/* The boot steps of one device from its dictionary table (= its EDS). */
static void boot_plan(struct hil_ctrl_boot_dev *b, uint8_t node, const struct hil_od *od)
{
    int found, n, k;
    memset(b, 0, sizeof *b);
    b->node = node;
    add_step(b, 0x1000, 0, 0, (uint32_t)eds_value(od, 0x1000, 0, &found));
    add_step(b, 0x1018, 1, 0, (uint32_t)eds_value(od, 0x1018, 1, &found));
    add_step(b, 0x1018, 2, 0, (uint32_t)eds_value(od, 0x1018, 2, &found));
    for (n = 0; n < 2 * HIL_PDO_MAX; n++) {
        uint16_t comm = (uint16_t)(n < HIL_PDO_MAX ? 0x1400 + n : 0x1800 + n - HIL_PDO_MAX);
        uint32_t cob = (uint32_t)eds_value(od, comm, 1, &found), count;
        if (!found)
            continue;
        add_step(b, comm, 1, 4, cob | 0x80000000u);
        count = (uint32_t)eds_value(od, (uint16_t)(comm + 0x200), 0, &found);
        add_step(b, (uint16_t)(comm + 0x200), 0, 1, 0);
        for (k = 1; k <= (int)count; k++)
            add_step(b, (uint16_t)(comm + 0x200), (uint8_t)k, 4, (uint32_t)eds_value(od, (uint16_t)(comm + 0x200), (uint8_t)k, &found));
        if (count)
            add_step(b, (uint16_t)(comm + 0x200), 0, 1, count);
        add_step(b, comm, 2, 1, (uint32_t)eds_value(od, comm, 2, &found));
        if (!(cob & 0x80000000u))
            add_step(b, comm, 1, 4, cob);
    }
    add_step(b, 0x1017, 0, 2, (uint32_t)eds_value(od, 0x1017, 0, &found));
    (void)eds_value(od, 0x6060, 0, &found);
    if (found)
        add_step(b, 0x6060, 0, 1, (uint32_t)eds_value(od, 0x6060, 0, &found));
}

static void boot_send(struct hil_ctrl *c, struct hil_ctrl_boot_dev *b, struct hil_out *out)
{
    struct hil_can_frame f;
    const struct hil_ctrl_sdo_step *s = &b->step[b->at];
    if (s->bytes)
        hil_sdo_download_req(&f, b->node, s->index, s->sub, s->value, s->bytes);
    else
        hil_sdo_upload_req(&f, b->node, s->index, s->sub);
    if (hil_out_push(out, &f) == HIL_OK)
        c->sdo_requests++;
}

int hil_ctrl_boot(struct hil_ctrl *c, struct hil_out *out)
{
    struct hil_can_frame f;
    int k;
    if (!c || !out)
        return HIL_E_ARG;
    boot_plan(&c->boot[0], HIL_NODE_DRIVE, &hil_drive_od);
    boot_plan(&c->boot[1], HIL_NODE_IMU, &hil_imu_od);
    c->boot_status = 0;
    c->boot_error[0] = '\0';
    hil_co_nmt_encode(&f, HIL_NMT_RESET_COMM, 0);
    hil_out_push(out, &f);
    for (k = 0; k < 2; k++)
        boot_send(c, &c->boot[k], out);
    return HIL_OK;
}

/* An SDO response during the boot: check it, send the device's next step. */
static int boot_response(struct hil_ctrl *c, const struct hil_can_frame *f, struct hil_out *out)
{
    struct hil_ctrl_boot_dev *b = &c->boot[f->id == HIL_COB_SDO_TX(HIL_NODE_DRIVE) ? 0 : 1];
    const struct hil_ctrl_sdo_step *s;
    uint32_t v = 0, ab = 0;
    int st;
    if (c->boot_status != 0 || b->at >= b->n) {
        c->rx.other++;
        return HIL_E_STATE;
    }
    s = &b->step[b->at];
    st = hil_sdo_client_response(f, s->index, s->sub, &v, &ab);
    if (st == HIL_E_FORMAT) {
        c->rx.bad_value++;
        return st;
    }
    c->rx.accepted++;
    if (st == HIL_E_STATE || (s->bytes == 0 && v != s->value)) {
        c->boot_status = -1;
        if (st == HIL_E_STATE)
            snprintf(c->boot_error, sizeof c->boot_error, "node %u: SDO %s 0x%04X:%u aborted 0x%08X (%s)",
                     b->node, s->bytes ? "write" : "read", s->index, s->sub, (unsigned)ab, hil_sdo_abort_str(ab));
        else
            snprintf(c->boot_error, sizeof c->boot_error, "node %u: 0x%04X:%u is 0x%08X, the EDS says 0x%08X",
                     b->node, s->index, s->sub, (unsigned)v, (unsigned)s->value);
        return HIL_OK;
    }
    if (++b->at < b->n)
        boot_send(c, b, out);
    else if (c->boot[0].at >= c->boot[0].n && c->boot[1].at >= c->boot[1].n)
        c->boot_status = 1;
    return HIL_OK;
}

/* cos^2 point-to-point profile: r = A sin^2(pi s / (2 t_m)), s in [0, t_m]. */
void hil_ctrl_reference(const struct hil_ctrl_params *p, double t, double *r, double *rd)
{
    double s = t - p->move_start;
    if (s <= 0.0) {
        *r = 0.0;
        *rd = 0.0;
    } else if (s >= p->move_time) {
        *r = p->move;
        *rd = 0.0;
    } else {
        double w = M_PI / p->move_time;
        *r = p->move * 0.5 * (1.0 - cos(w * s));
        *rd = p->move * 0.5 * w * sin(w * s);
    }
}

static void send_emcy_info(struct hil_ctrl *c, uint16_t code, unsigned info, struct hil_out *out)
{
    struct hil_emcy e;
    struct hil_can_frame f;
    memset(&e, 0, sizeof e);
    e.code = code;
    e.error_register = code ? 0x01 : 0x00;
    hil_put_u16(e.info, (uint16_t)info);
    if (hil_co_emcy_encode(&f, HIL_NODE_CTRL, &e) == HIL_OK && hil_out_push(out, &f) == HIL_OK)
        c->emcy_sent++;
}

static void send_emcy(struct hil_ctrl *c, uint16_t code, struct hil_out *out) { send_emcy_info(c, code, 0, out); }

static double clamp(double x, double m) { return x > m ? m : (x < -m ? -m : x); }

/* CiA 402 device control driven by the reported state: fault -> fault reset
 * (bit 7 edge), switch on disabled -> shutdown, ready -> switch on, switched
 * on / enabled -> enable operation. Before any TPDO (statusword 0): shutdown. */
static uint16_t controlword_for(uint16_t sw)
{
    if ((sw & 0x004Fu) == 0x0008u)
        return HIL_CW_FAULT_RESET;
    if ((sw & 0x004Fu) == 0x0040u || sw == 0)
        return HIL_CW_SHUTDOWN;
    if ((sw & 0x006Fu) == 0x0021u)
        return HIL_CW_SWITCH_ON;
    return HIL_CW_ENABLE_OP;
}

/* PD test law with the node's IMU watchdog and fault ramp (hil/ctrl.h). */
static double pd_law(struct hil_ctrl *c, uint64_t k, int enabled, double ref, double refd, struct hil_out *out)
{
    if (enabled && c->imu_seen && k - c->imu_last_cycle > c->p.imu_timeout && !c->fault) {
        c->fault = 1;
        c->faults++;
        c->fault_cycle = k;
        c->ramp_from = c->sig.torque_cmd;
        send_emcy(c, HIL_EMCY_SENSOR, out);
    }
    if (c->fault) {
        double s = (double)(k - c->fault_cycle + 1) * c->p.T / c->p.ramp_time;
        return s >= 1.0 ? 0.0 : c->ramp_from * (1.0 - s);
    }
    if (enabled)
        return c->p.kp * (ref - c->theta) + c->p.kd * (refd - c->omega) - c->p.k_tip * c->imu_rate;
    return 0.0;
}

void hil_ctrl_set_law(struct hil_ctrl *c, hil_ctrl_law law, void *ctx)
{
    if (c) {
        c->law = law;
        c->law_ctx = ctx;
    }
}

static void run_law(struct hil_ctrl *c, struct hil_out *out)
{
    struct hil_drive_rpdo r;
    struct hil_can_frame f;
    double t = (double)(c->cycle - 1) * c->p.T, ref, refd, u = 0.0;
    int64_t q;
    int enabled = (c->statusword & 0x006Fu) == 0x0027u;
    uint64_t k = c->cycle - 1;

    if (c->law) {
        struct hil_ctrl_law_in in;
        int st;
        in.t = t;
        in.theta = c->theta;
        in.omega = c->omega;
        in.drive_fresh = c->have_tpdo1 && c->have_tpdo2;
        in.imu_rate = c->imu_rate;
        in.imu_readings = c->imu_readings;
        in.enabled = enabled;
        ref = 0.0;
        st = c->law(c->law_ctx, &in, &u, &ref);
        if (st > 0)
            c->law_running = 1;
        if (st < 0)
            c->law_status = st < -65535 ? 65535u : (unsigned)-st;
        if (st < 0 && !c->fault) {
            c->faults++;
            send_emcy_info(c, HIL_EMCY_SENSOR, c->law_status, out);
        } else if (st >= 0 && c->fault) {
            send_emcy(c, HIL_EMCY_NO_ERROR, out);
        }
        c->fault = st < 0;
        if (!isfinite(u))
            u = 0.0;
    } else {
        hil_ctrl_reference(&c->p, t, &ref, &refd);
        u = pd_law(c, k, enabled, ref, refd, out);
    }
    u = clamp(u, c->p.torque_max);
    r.controlword = controlword_for(c->statusword);
    hil_co_quantize(u, HIL_TORQUE_LSB, INT32_MIN, INT32_MAX, &q);
    r.torque_mnm = (int32_t)q;
    if (hil_co_drive_rpdo_encode(&f, &r) == HIL_OK)
        hil_out_push(out, &f);
    c->commanded = 1;
    c->sig.t = t;
    c->sig.ref = ref;
    c->sig.torque_cmd = u;
    c->sig.theta = c->theta;
    c->sig.omega = c->omega;
    c->sig.imu_rate = c->imu_rate;
    c->sig.statusword = c->statusword;
    c->sig.fault = c->fault;
    c->sig.run = c->law ? c->law_running : enabled;
}

int hil_ctrl_tick(struct hil_ctrl *c, struct hil_out *out)
{
    struct hil_can_frame f;
    if (!c || !out)
        return HIL_E_ARG;
    if (c->cycle == 0 && hil_co_nmt_encode(&f, HIL_NMT_START, 0) == HIL_OK)
        hil_out_push(out, &f);
    c->sync_counter = (uint8_t)(c->sync_counter % 240u + 1u);
    if (hil_co_sync_encode(&f, c->sync_counter) == HIL_OK)
        hil_out_push(out, &f);
    c->cycle++;
    c->have_tpdo1 = c->have_tpdo2 = c->commanded = 0;
    return HIL_OK;
}

int hil_ctrl_deadline(struct hil_ctrl *c, struct hil_out *out)
{
    if (!c || !out || c->cycle == 0)
        return HIL_E_ARG;
    if (!c->commanded) {
        c->missed_inputs++;
        run_law(c, out);
    }
    return HIL_OK;
}

int hil_ctrl_stop(struct hil_ctrl *c, struct hil_out *out)
{
    struct hil_can_frame f;
    if (!c || !out)
        return HIL_E_ARG;
    hil_co_nmt_encode(&f, HIL_NMT_STOP, 0);
    return hil_out_push(out, &f);
}

/* The law uses the gyro z rate of TPDO1 (the thesis uses only the tip rate,
 * y_3); TPDO2 (acceleration) is validated and counted, not used. */
static void on_imu_rate(struct hil_ctrl *c, const struct hil_imu_tpdo *t, struct hil_out *out)
{
    c->imu_rate = t->xyz[2] * HIL_GYRO_LSB;
    if (!c->imu_seen || t->seq != c->imu_seq) {
        c->imu_seen = 1;
        c->imu_seq = t->seq;
        c->imu_last_cycle = c->cycle ? c->cycle - 1 : 0;
        c->imu_readings++;
        if (c->fault && !c->law) {
            c->fault = 0;
            send_emcy(c, HIL_EMCY_NO_ERROR, out);
        }
    }
}

int hil_ctrl_on_frame(struct hil_ctrl *c, const struct hil_can_frame *f, struct hil_out *out)
{
    int st;
    if (!c || !f || !out)
        return HIL_E_ARG;
    st = hil_rx_screen(&c->rx, f);
    if (st != HIL_OK)
        return st;
    switch (f->id) {
    case HIL_COB_SDO_TX(HIL_NODE_DRIVE):
    case HIL_COB_SDO_TX(HIL_NODE_IMU):
        return boot_response(c, f, out);
    case HIL_COB_TPDO1(HIL_NODE_DRIVE): {
        struct hil_drive_tpdo1 t;
        hil_co_drive_tpdo1_decode(f, &t);
        c->rx.accepted++;
        c->statusword = t.statusword;
        c->theta = t.position_inc * (2.0 * M_PI / HIL_ENC_COUNTS_PER_REV);
        c->have_tpdo1 = 1;
        break;
    }
    case HIL_COB_TPDO2(HIL_NODE_DRIVE): {
        struct hil_drive_tpdo2 t;
        hil_co_drive_tpdo2_decode(f, &t);
        c->rx.accepted++;
        c->omega = t.velocity_urads * HIL_VEL_LSB;
        c->have_tpdo2 = 1;
        break;
    }
    case HIL_COB_TPDO1(HIL_NODE_IMU):
    case HIL_COB_TPDO2(HIL_NODE_IMU): {
        struct hil_imu_tpdo t;
        int which = f->id == HIL_COB_TPDO1(HIL_NODE_IMU) ? 1 : 2;
        hil_co_imu_decode(f, which, &t);
        c->rx.accepted++;
        if (which == 1)
            on_imu_rate(c, &t, out);
        return HIL_OK;
    }
    default: {
        uint8_t node, state;
        struct hil_emcy e;
        int st_hb = hil_co_heartbeat_decode(f, &node, &state);
        if (st_hb == HIL_OK) {
            c->rx.accepted++;
            c->hb_state[node] = state;
            return HIL_OK;
        }
        if (st_hb == HIL_E_FORMAT) { /* a heartbeat with no valid NMT state */
            c->rx.bad_value++;
            return HIL_E_FORMAT;
        }
        if (hil_co_emcy_decode(f, &node, &e) == HIL_OK && node != HIL_NODE_CTRL) {
            c->rx.accepted++;
            c->emcy_received++;
            return HIL_OK;
        }
        c->rx.other++;
        return HIL_E_UNKNOWN_ID;
    }
    }
    if (c->cycle > 0 && c->have_tpdo1 && c->have_tpdo2 && !c->commanded)
        run_law(c, out);
    return HIL_OK;
}
