/* Emulated tip IMU; behaviour in hil/imu.h. */
#include <math.h>
#include <string.h>
#include "hil/canopen.h"
#include "hil/imu.h"

#define HIL_GRAVITY 9.80665

void hil_imu_params_default(struct hil_imu_params *p)
{
    memset(p, 0, sizeof *p);
    p->reading_cycles = 4;
    p->seed = 1;
    p->acq_period = 0.6e-3;
}

static int nonneg(double x) { return isfinite(x) && x >= 0.0; }

int hil_imu_init(struct hil_imu *m, const struct hil_imu_params *p, struct hil_out *out)
{
    struct hil_can_frame f;
    if (!m || !p || !out || p->reading_cycles < 1 || p->reading_cycles > 8 ||
        !(p->jitter_prob >= 0.0 && p->jitter_prob <= 1.0) || !isfinite(p->gyro_bias) ||
        !isfinite(p->acc_bias) || !nonneg(p->gyro_noise) || !nonneg(p->acc_noise) ||
        !nonneg(p->gyro_quant) || !nonneg(p->acc_quant) || !(p->acq_period > 0.0) || !isfinite(p->acq_period))
        return HIL_E_ARG;
    memset(m, 0, sizeof *m);
    m->p = *p;
    m->ix_rate = (int16_t)hil_od_find(&hil_imu_od, 0x2000, 1, NULL);
    m->ix_acc = (int16_t)hil_od_find(&hil_imu_od, 0x2001, 1, NULL);
    m->ix_seq = (int16_t)hil_od_find(&hil_imu_od, 0x2002, 0, NULL);
    m->ix_status = (int16_t)hil_od_find(&hil_imu_od, 0x2003, 1, NULL);
    m->ix_heartbeat = (int16_t)hil_od_find(&hil_imu_od, 0x1017, 0, NULL);
    {
        struct hil_od_dev v = hil_imu_od_dev(m);
        int i;
        for (i = 0; i < hil_imu_od.n; i++)
            m->od[i] = (uint32_t)hil_imu_od.e[i].dflt;
        hil_od_reset(&v, 0);
    }
    hil_sdo_server_init(&m->sdo, HIL_NODE_IMU);
    hil_rng_seed(&m->rng, p->seed);
    if (hil_co_heartbeat_encode(&f, HIL_NODE_IMU, HIL_NMT_STATE_BOOTUP) == HIL_OK)
        hil_out_push(out, &f);
    m->nmt = HIL_NMT_STATE_PREOP;
    return HIL_OK;
}

/* Device rule of a write (hil/od.h hook): TPDOs are event-driven only. */
static uint32_t write_hook(void *ctx, int i, uint32_t v)
{
    const struct hil_od_entry *e = &hil_imu_od.e[i];
    (void)ctx;
    if (e->index >= 0x1800u && e->index < 0x1800u + HIL_PDO_MAX && e->sub == 2 && v != 254u && v != 255u)
        return HIL_SDO_ABORT_RANGE;
    return 0;
}

struct hil_od_dev hil_imu_od_dev(struct hil_imu *m)
{
    struct hil_od_dev v;
    v.od = &hil_imu_od;
    v.val = m->od;
    v.write = write_hook;
    v.ctx = m;
    v.nmt = &m->nmt;
    return v;
}

static void heartbeat(struct hil_imu *m, struct hil_out *out)
{
    struct hil_can_frame f;
    if (hil_co_heartbeat_encode(&f, HIL_NODE_IMU, m->nmt) == HIL_OK)
        hil_out_push(out, &f);
    m->since_heartbeat = 0;
}

/* Measurement model: x + bias + noise, then rounded to a multiple of quant. */
static double measure(struct hil_imu *m, double x, double bias, double noise, double quant)
{
    double y = x + bias + (noise > 0.0 ? noise * hil_rng_normal(&m->rng) : 0.0);
    return quant > 0.0 ? quant * floor(y / quant + 0.5) : y;
}

/* Counts of the three axes into the dictionary at slot ix..ix+2; returns
 * the status (bit 0: an axis saturated). */
static uint8_t to_wire(struct hil_imu *m, int ix, const double v[3], double lsb)
{
    uint8_t status = 0;
    int i;
    for (i = 0; i < 3; i++) {
        int64_t q;
        int st = hil_co_quantize(v[i], lsb, INT16_MIN, INT16_MAX, &q);
        if (st != HIL_OK)
            status |= HIL_IMU_ST_SATURATED;
        m->od[ix + i] = (uint32_t)(uint16_t)(int16_t)q;
    }
    return status;
}

static void send_reading(struct hil_imu *m, const struct hil_imu_sample *s, struct hil_out *out)
{
    struct hil_can_frame f;
    struct hil_od_dev v = hil_imu_od_dev(m);
    double g[3], a[3];
    int k;
    g[0] = 0.0;
    g[1] = 0.0;
    g[2] = s->rate;
    a[0] = s->acc_r;
    a[1] = s->acc_t;
    a[2] = HIL_GRAVITY;
    m->od[m->ix_seq] = ++m->seq;
    m->od[m->ix_status] = to_wire(m, m->ix_rate, g, HIL_GYRO_LSB);
    m->od[m->ix_status + 1] = to_wire(m, m->ix_acc, a, HIL_ACC_LSB);
    for (k = 0; k < m->pdo.ntx; k++) {
        hil_pdo_pack(&v, &m->pdo.tx[k], &f);
        hil_out_push(out, &f);
    }
    m->readings_sent++;
}

static void acquire(struct hil_imu *m, double rate, double acc_t, struct hil_out *out)
{
    int i, k;
    m->acq++;
    if (m->acq % m->p.reading_cycles == 0 && m->npending < HIL_IMU_MAX_PENDING) {
        struct hil_imu_sample *s = &m->pending[m->npending++];
        s->rate = measure(m, rate, m->p.gyro_bias, m->p.gyro_noise, m->p.gyro_quant);
        s->acc_r = measure(m, m->acc_r, m->p.acc_bias, m->p.acc_noise, m->p.acc_quant);
        s->acc_t = measure(m, acc_t, m->p.acc_bias, m->p.acc_noise, m->p.acc_quant);
        s->due = m->acq + m->p.reading_cycles;
        if (m->p.jitter_prob > 0.0 && hil_rng_uniform(&m->rng) < m->p.jitter_prob)
            s->due++;
    }
    /* Readings leave in sampling order; a late one holds back the next. */
    for (k = 0; k < m->npending && m->pending[k].due <= m->acq; k++)
        if (m->nmt == HIL_NMT_STATE_OPERATIONAL)
            send_reading(m, &m->pending[k], out);
    for (i = k; i < m->npending; i++)
        m->pending[i - k] = m->pending[i];
    m->npending -= k;
    m->since_heartbeat++;
    if (m->od[m->ix_heartbeat] &&
        (double)m->since_heartbeat * m->p.acq_period * 1e3 >= (double)m->od[m->ix_heartbeat] - 1e-9)
        heartbeat(m, out);
}

int hil_imu_on_frame(struct hil_imu *m, const struct hil_can_frame *f, struct hil_out *out)
{
    int st;
    double a, b;
    if (!m || !f || !out)
        return HIL_E_ARG;
    st = hil_rx_screen(&m->rx, f);
    if (st != HIL_OK)
        return st;
    switch (f->id) {
    case HIL_COB_NMT: {
        int reset_cmd;
        uint8_t before = m->nmt;
        struct hil_od_dev v = hil_imu_od_dev(m);
        st = hil_nmt_on_frame(&m->rx, f, HIL_NODE_IMU, &m->nmt, &reset_cmd);
        if (st != HIL_OK)
            return st;
        if (reset_cmd) {
            m->npending = 0;
            hil_od_reset(&v, f->data[0] == HIL_NMT_RESET_COMM);
            hil_sdo_server_init(&m->sdo, HIL_NODE_IMU);
            memset(&m->pdo, 0, sizeof m->pdo);
            m->nmt = HIL_NMT_STATE_BOOTUP;
            heartbeat(m, out);
            m->nmt = HIL_NMT_STATE_PREOP;
            return HIL_OK;
        }
        if (m->nmt == HIL_NMT_STATE_OPERATIONAL && before != HIL_NMT_STATE_OPERATIONAL)
            hil_pdo_compile(&v, &m->pdo); /* PDO parameters written in pre-operational apply now */
        heartbeat(m, out);
        return HIL_OK;
    }
    case HIL_COB_SDO_RX(HIL_NODE_IMU): {
        struct hil_od_dev v = hil_imu_od_dev(m);
        struct hil_can_frame r;
        if (m->nmt != HIL_NMT_STATE_PREOP && m->nmt != HIL_NMT_STATE_OPERATIONAL) {
            m->rx.accepted++;
            return HIL_E_STATE;
        }
        st = hil_sdo_server_on_frame(&m->sdo, &v, f, &r);
        if (st < 0)
            m->rx.bad_value++;
        else
            m->rx.accepted++;
        if (st != 0)
            hil_out_push(out, &r);
        return st < 0 ? HIL_E_FORMAT : HIL_OK;
    }
    case HIL_COB_RIG_TIPPOS:
        if (hil_co_rig_decode(f, HIL_COB_RIG_TIPPOS, &a, &b) != HIL_OK) {
            m->rx.bad_value++;
            return HIL_E_RANGE;
        }
        m->rx.accepted++;
        m->acc_r = b;
        return HIL_OK;
    case HIL_COB_RIG_MOTOR: {
        struct hil_can_frame ack;
        if (hil_co_rig_decode(f, HIL_COB_RIG_MOTOR, &a, &b) != HIL_OK) {
            m->rx.bad_value++;
            return HIL_E_RANGE;
        }
        m->rx.accepted++;
        if (hil_co_imu_done_encode(&ack, (uint16_t)m->acq) == HIL_OK)
            hil_out_push(out, &ack);
        return HIL_OK;
    }
    case HIL_COB_RIG_TIP:
        if (hil_co_rig_decode(f, HIL_COB_RIG_TIP, &a, &b) != HIL_OK) {
            m->rx.bad_value++;
            return HIL_E_RANGE;
        }
        m->rx.accepted++;
        acquire(m, a, b, out);
        return HIL_OK;
    default:
        m->rx.other++;
        return HIL_E_UNKNOWN_ID;
    }
}
