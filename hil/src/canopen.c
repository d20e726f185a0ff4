/* CANopen-style codec of the rig's frames; layout in hil/canopen.h. */
#include <math.h>
#include <string.h>
#include "hil/canopen.h"

static int expect(const struct hil_can_frame *f, uint32_t id, uint8_t dlc)
{
    int st;
    if (!f)
        return HIL_E_ARG;
    st = hil_can_frame_check(f);
    if (st != HIL_OK)
        return st;
    if (f->id != id)
        return HIL_E_UNKNOWN_ID;
    return f->dlc == dlc ? HIL_OK : HIL_E_DLC;
}

static void start(struct hil_can_frame *f, uint32_t id, uint8_t dlc)
{
    memset(f, 0, sizeof *f);
    f->id = id;
    f->dlc = dlc;
}

int hil_co_quantize(double x, double lsb, int64_t lo, int64_t hi, int64_t *out)
{
    double q;
    if (!out || !(lsb > 0.0) || lo > hi)
        return HIL_E_ARG;
    *out = 0;
    if (!isfinite(x))
        return HIL_E_RANGE;
    q = floor(x / lsb + 0.5);
    if (q < (double)lo) {
        *out = lo;
        return 1;
    }
    if (q > (double)hi) {
        *out = hi;
        return 1;
    }
    *out = (int64_t)q;
    return HIL_OK;
}

int hil_co_sync_encode(struct hil_can_frame *f, uint8_t counter)
{
    if (!f || counter < 1 || counter > 240)
        return HIL_E_ARG;
    start(f, HIL_COB_SYNC, 1);
    f->data[0] = counter;
    return HIL_OK;
}

int hil_co_sync_decode(const struct hil_can_frame *f, uint8_t *counter)
{
    int st = expect(f, HIL_COB_SYNC, 1);
    if (st != HIL_OK)
        return st;
    if (f->data[0] < 1 || f->data[0] > 240)
        return HIL_E_FORMAT;
    if (counter)
        *counter = f->data[0];
    return HIL_OK;
}

int hil_co_nmt_encode(struct hil_can_frame *f, uint8_t command, uint8_t node)
{
    if (!f || node > 127)
        return HIL_E_ARG;
    if (command != HIL_NMT_START && command != HIL_NMT_STOP && command != HIL_NMT_PREOP &&
        command != HIL_NMT_RESET_NODE && command != HIL_NMT_RESET_COMM)
        return HIL_E_ARG;
    start(f, HIL_COB_NMT, 2);
    f->data[0] = command;
    f->data[1] = node;
    return HIL_OK;
}

int hil_co_nmt_decode(const struct hil_can_frame *f, uint8_t *command, uint8_t *node)
{
    int st = expect(f, HIL_COB_NMT, 2);
    uint8_t c;
    if (st != HIL_OK)
        return st;
    c = f->data[0];
    if ((c != HIL_NMT_START && c != HIL_NMT_STOP && c != HIL_NMT_PREOP &&
         c != HIL_NMT_RESET_NODE && c != HIL_NMT_RESET_COMM) || f->data[1] > 127)
        return HIL_E_FORMAT;
    if (command)
        *command = c;
    if (node)
        *node = f->data[1];
    return HIL_OK;
}

int hil_co_heartbeat_encode(struct hil_can_frame *f, uint8_t node, uint8_t state)
{
    if (!f || node < 1 || node > 127)
        return HIL_E_ARG;
    start(f, HIL_COB_HEARTBEAT(node), 1);
    f->data[0] = state;
    return HIL_OK;
}

int hil_co_heartbeat_decode(const struct hil_can_frame *f, uint8_t *node, uint8_t *state)
{
    int st;
    uint8_t s;
    if (!f)
        return HIL_E_ARG;
    st = hil_can_frame_check(f);
    if (st != HIL_OK)
        return st;
    if (f->id < HIL_COB_HEARTBEAT(1) || f->id > HIL_COB_HEARTBEAT(127))
        return HIL_E_UNKNOWN_ID;
    if (f->dlc != 1)
        return HIL_E_DLC;
    s = f->data[0];
    if (s != HIL_NMT_STATE_BOOTUP && s != HIL_NMT_STATE_STOPPED &&
        s != HIL_NMT_STATE_OPERATIONAL && s != HIL_NMT_STATE_PREOP)
        return HIL_E_FORMAT;
    if (node)
        *node = (uint8_t)(f->id - HIL_COB_HEARTBEAT(0));
    if (state)
        *state = s;
    return HIL_OK;
}

int hil_co_emcy_encode(struct hil_can_frame *f, uint8_t node, const struct hil_emcy *e)
{
    if (!f || !e || node < 1 || node > 127)
        return HIL_E_ARG;
    start(f, HIL_COB_EMCY(node), 8);
    hil_put_u16(f->data, e->code);
    f->data[2] = e->error_register;
    memcpy(f->data + 3, e->info, 5);
    return HIL_OK;
}

int hil_co_emcy_decode(const struct hil_can_frame *f, uint8_t *node, struct hil_emcy *e)
{
    int st;
    if (!f)
        return HIL_E_ARG;
    st = hil_can_frame_check(f);
    if (st != HIL_OK)
        return st;
    if (f->id < HIL_COB_EMCY(1) || f->id > HIL_COB_EMCY(127))
        return HIL_E_UNKNOWN_ID;
    if (f->dlc != 8)
        return HIL_E_DLC;
    if (node)
        *node = (uint8_t)(f->id - HIL_COB_EMCY(0));
    if (e) {
        e->code = hil_get_u16(f->data);
        e->error_register = f->data[2];
        memcpy(e->info, f->data + 3, 5);
    }
    return HIL_OK;
}

/* The drive PDOs carry a 16-bit word and a signed 32-bit value (6 bytes:
 * RPDO1 controlword + torque, TPDO1 statusword + position) or two signed
 * 32-bit values (8 bytes: TPDO2 velocity + torque), little-endian. */
static void put_pdo(struct hil_can_frame *f, uint32_t id, int wide, uint32_t first, int32_t second)
{
    start(f, id, wide ? 8 : 6);
    if (wide)
        hil_put_u32(f->data, first);
    else
        hil_put_u16(f->data, (uint16_t)first);
    hil_put_u32(f->data + (wide ? 4 : 2), (uint32_t)second);
}

static int get_pdo(const struct hil_can_frame *f, uint32_t id, int wide, uint32_t *first, int32_t *second)
{
    int st = expect(f, id, wide ? 8 : 6);
    if (st != HIL_OK)
        return st;
    *first = wide ? hil_get_u32(f->data) : hil_get_u16(f->data);
    *second = (int32_t)hil_get_u32(f->data + (wide ? 4 : 2));
    return HIL_OK;
}

int hil_co_drive_rpdo_encode(struct hil_can_frame *f, const struct hil_drive_rpdo *p)
{
    if (!f || !p)
        return HIL_E_ARG;
    put_pdo(f, HIL_COB_RPDO1(HIL_NODE_DRIVE), 0, p->controlword, p->torque_mnm);
    return HIL_OK;
}

int hil_co_drive_rpdo_decode(const struct hil_can_frame *f, struct hil_drive_rpdo *p)
{
    uint32_t w;
    int32_t v;
    int st = get_pdo(f, HIL_COB_RPDO1(HIL_NODE_DRIVE), 0, &w, &v);
    if (st == HIL_OK && p) {
        p->controlword = (uint16_t)w;
        p->torque_mnm = v;
    }
    return st;
}

int hil_co_drive_tpdo1_encode(struct hil_can_frame *f, const struct hil_drive_tpdo1 *p)
{
    if (!f || !p)
        return HIL_E_ARG;
    put_pdo(f, HIL_COB_TPDO1(HIL_NODE_DRIVE), 0, p->statusword, p->position_inc);
    return HIL_OK;
}

int hil_co_drive_tpdo1_decode(const struct hil_can_frame *f, struct hil_drive_tpdo1 *p)
{
    uint32_t w;
    int32_t v;
    int st = get_pdo(f, HIL_COB_TPDO1(HIL_NODE_DRIVE), 0, &w, &v);
    if (st == HIL_OK && p) {
        p->statusword = (uint16_t)w;
        p->position_inc = v;
    }
    return st;
}

int hil_co_drive_tpdo2_encode(struct hil_can_frame *f, const struct hil_drive_tpdo2 *p)
{
    if (!f || !p)
        return HIL_E_ARG;
    put_pdo(f, HIL_COB_TPDO2(HIL_NODE_DRIVE), 1, (uint32_t)p->velocity_urads, p->torque_mnm);
    return HIL_OK;
}

int hil_co_drive_tpdo2_decode(const struct hil_can_frame *f, struct hil_drive_tpdo2 *p)
{
    uint32_t w;
    int32_t v;
    int st = get_pdo(f, HIL_COB_TPDO2(HIL_NODE_DRIVE), 1, &w, &v);
    if (st == HIL_OK && p) {
        p->velocity_urads = (int32_t)w;
        p->torque_mnm = v;
    }
    return st;
}

static uint32_t imu_cob(int which)
{
    return which == 1 ? HIL_COB_TPDO1(HIL_NODE_IMU) : HIL_COB_TPDO2(HIL_NODE_IMU);
}

int hil_co_imu_encode(struct hil_can_frame *f, int which, const struct hil_imu_tpdo *p)
{
    int i;
    if (!f || !p || (which != 1 && which != 2))
        return HIL_E_ARG;
    start(f, imu_cob(which), 8);
    for (i = 0; i < 3; i++)
        hil_put_u16(f->data + 2 * i, (uint16_t)p->xyz[i]);
    f->data[6] = p->seq;
    f->data[7] = p->status;
    return HIL_OK;
}

int hil_co_imu_decode(const struct hil_can_frame *f, int which, struct hil_imu_tpdo *p)
{
    int i, st;
    if (which != 1 && which != 2)
        return HIL_E_ARG;
    st = expect(f, imu_cob(which), 8);
    if (st != HIL_OK)
        return st;
    if (p) {
        for (i = 0; i < 3; i++)
            p->xyz[i] = (int16_t)hil_get_u16(f->data + 2 * i);
        p->seq = f->data[6];
        p->status = f->data[7];
    }
    return HIL_OK;
}

static int rig_cob_ok(uint32_t cob)
{
    return cob >= HIL_COB_RIG_TORQUE && cob <= HIL_COB_RIG_TIPPOS;
}

int hil_co_rig_encode(struct hil_can_frame *f, uint32_t cob, double a, double b)
{
    if (!f || !rig_cob_ok(cob))
        return HIL_E_ARG;
    if (!isfinite(a) || !isfinite(b) || fabs(a) > 3.0e38 || fabs(b) > 3.0e38)
        return HIL_E_RANGE;
    start(f, cob, 8);
    hil_put_f32(f->data, (float)a);
    hil_put_f32(f->data + 4, (float)b);
    return HIL_OK;
}

int hil_co_rig_decode(const struct hil_can_frame *f, uint32_t cob, double *a, double *b)
{
    int st;
    float x, y;
    if (!rig_cob_ok(cob))
        return HIL_E_ARG;
    st = expect(f, cob, 8);
    if (st != HIL_OK)
        return st;
    x = hil_get_f32(f->data);
    y = hil_get_f32(f->data + 4);
    if (!isfinite(x) || !isfinite(y))
        return HIL_E_RANGE;
    if (a)
        *a = x;
    if (b)
        *b = y;
    return HIL_OK;
}

int hil_co_imu_done_encode(struct hil_can_frame *f, uint16_t acquisitions)
{
    if (!f)
        return HIL_E_ARG;
    start(f, HIL_COB_RIG_IMU_DONE, 2);
    hil_put_u16(f->data, acquisitions);
    return HIL_OK;
}

int hil_co_imu_done_decode(const struct hil_can_frame *f, uint16_t *acquisitions)
{
    int st = expect(f, HIL_COB_RIG_IMU_DONE, 2);
    if (st != HIL_OK)
        return st;
    if (acquisitions)
        *acquisitions = hil_get_u16(f->data);
    return HIL_OK;
}
