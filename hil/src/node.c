/* Frame dictionary check and output buffer shared by the nodes. */
#include "hil/node.h"
#include "hil/canopen.h"
#include "hil/sdo.h"

int hil_out_push(struct hil_out *out, const struct hil_can_frame *f)
{
    if (!out || !f)
        return HIL_E_ARG;
    if (out->n < 0 || out->n >= HIL_OUT_MAX)
        return HIL_E_FULL;
    out->f[out->n++] = *f;
    return HIL_OK;
}

/* Required DLC of every identifier the rig uses, or -1 when unknown. */
static int dict_dlc(uint32_t id)
{
    if (id == HIL_COB_NMT)
        return 2;
    if (id == HIL_COB_SYNC)
        return 1;
    if (id >= HIL_COB_EMCY(1) && id <= HIL_COB_EMCY(127))
        return 8;
    if (id >= HIL_COB_HEARTBEAT(1) && id <= HIL_COB_HEARTBEAT(127))
        return 1;
    switch (id) {
    case HIL_COB_RPDO1(HIL_NODE_DRIVE): return 6;
    case HIL_COB_TPDO1(HIL_NODE_DRIVE): return 6;
    case HIL_COB_TPDO2(HIL_NODE_DRIVE): return 8;
    case HIL_COB_TPDO1(HIL_NODE_IMU): return 8;
    case HIL_COB_TPDO2(HIL_NODE_IMU): return 8;
    case HIL_COB_RIG_TORQUE:
    case HIL_COB_RIG_MOTOR:
    case HIL_COB_RIG_TIP:
    case HIL_COB_RIG_TIPPOS: return 8;
    case HIL_COB_RIG_IMU_DONE: return 2;
    case HIL_COB_SDO_RX(HIL_NODE_DRIVE):
    case HIL_COB_SDO_TX(HIL_NODE_DRIVE):
    case HIL_COB_SDO_RX(HIL_NODE_IMU):
    case HIL_COB_SDO_TX(HIL_NODE_IMU): return 8; /* SDO frames are always 8 bytes (CiA 301 7.2.4.3) */
    default: return -1;
    }
}

int hil_dict_check(const struct hil_can_frame *f)
{
    int st = hil_can_frame_check(f);
    int dlc;
    if (st != HIL_OK)
        return st;
    if (f->id & HIL_CAN_EFF_FLAG)
        return HIL_E_UNKNOWN_ID;
    dlc = dict_dlc(f->id);
    if (dlc < 0)
        return HIL_E_UNKNOWN_ID;
    return f->dlc == dlc ? HIL_OK : HIL_E_DLC;
}

int hil_rx_screen(struct hil_rx_stats *s, const struct hil_can_frame *f)
{
    int st = hil_dict_check(f);
    if (!s)
        return HIL_E_ARG;
    if (st == HIL_E_UNKNOWN_ID)
        s->unknown_id++;
    else if (st == HIL_E_DLC)
        s->bad_dlc++;
    else if (st != HIL_OK)
        s->bad_value++;
    return st;
}

int hil_nmt_on_frame(struct hil_rx_stats *s, const struct hil_can_frame *f, uint8_t self, uint8_t *state,
                     int *reset)
{
    uint8_t cmd, node;
    if (!s || !f || !state || !reset)
        return HIL_E_ARG;
    *reset = 0;
    if (hil_co_nmt_decode(f, &cmd, &node) != HIL_OK) {
        s->bad_value++;
        return HIL_E_FORMAT;
    }
    if (node != 0 && node != self) {
        s->other++;
        return HIL_E_UNKNOWN_ID;
    }
    s->accepted++;
    if (cmd == HIL_NMT_START)
        *state = HIL_NMT_STATE_OPERATIONAL;
    else if (cmd == HIL_NMT_STOP)
        *state = HIL_NMT_STATE_STOPPED;
    else if (cmd == HIL_NMT_PREOP)
        *state = HIL_NMT_STATE_PREOP;
    else
        *reset = 1;
    return HIL_OK;
}
