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
    p->heartbeat_acqs = 167;
}

static int nonneg(double x) { return isfinite(x) && x >= 0.0; }

int hil_imu_init(struct hil_imu *m, const struct hil_imu_params *p, struct hil_out *out)
{
    struct hil_can_frame f;
    if (!m || !p || !out || p->reading_cycles < 1 || p->reading_cycles > 8 ||
        !(p->jitter_prob >= 0.0 && p->jitter_prob <= 1.0) || !isfinite(p->gyro_bias) ||
        !isfinite(p->acc_bias) || !nonneg(p->gyro_noise) || !nonneg(p->acc_noise) ||
        !nonneg(p->gyro_quant) || !nonneg(p->acc_quant) || p->heartbeat_acqs < 1)
        return HIL_E_ARG;
    memset(m, 0, sizeof *m);
    m->p = *p;
    hil_rng_seed(&m->rng, p->seed);
    if (hil_co_heartbeat_encode(&f, HIL_NODE_IMU, HIL_NMT_STATE_BOOTUP) == HIL_OK)
        hil_out_push(out, &f);
    m->nmt = HIL_NMT_STATE_PREOP;
    return HIL_OK;
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

static uint8_t to_wire(const double v[3], double lsb, int16_t xyz[3])
{
    uint8_t status = 0;
    int i;
    for (i = 0; i < 3; i++) {
        int64_t q;
        int st = hil_co_quantize(v[i], lsb, INT16_MIN, INT16_MAX, &q);
        if (st != HIL_OK)
            status |= HIL_IMU_ST_SATURATED;
        xyz[i] = (int16_t)q;
    }
    return status;
}

static void send_reading(struct hil_imu *m, const struct hil_imu_sample *s, struct hil_out *out)
{
    struct hil_imu_tpdo t;
    struct hil_can_frame f;
    double g[3], a[3];
    g[0] = 0.0;
    g[1] = 0.0;
    g[2] = s->rate;
    a[0] = s->acc_r;
    a[1] = s->acc_t;
    a[2] = HIL_GRAVITY;
    t.seq = ++m->seq;
    t.status = to_wire(g, HIL_GYRO_LSB, t.xyz);
    if (hil_co_imu_encode(&f, 1, &t) == HIL_OK)
        hil_out_push(out, &f);
    t.status = to_wire(a, HIL_ACC_LSB, t.xyz);
    if (hil_co_imu_encode(&f, 2, &t) == HIL_OK)
        hil_out_push(out, &f);
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
    if (++m->since_heartbeat >= m->p.heartbeat_acqs)
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
        st = hil_nmt_on_frame(&m->rx, f, HIL_NODE_IMU, &m->nmt, &reset_cmd);
        if (st != HIL_OK)
            return st;
        if (reset_cmd) {
            m->npending = 0;
            m->nmt = HIL_NMT_STATE_BOOTUP;
            heartbeat(m, out);
            m->nmt = HIL_NMT_STATE_PREOP;
            return HIL_OK;
        }
        heartbeat(m, out);
        return HIL_OK;
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
