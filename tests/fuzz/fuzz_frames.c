/* libFuzzer target: the frame decoders (hil/canopen.h, hil/node.h) and the
 * nodes' receive paths (drive, IMU, plant, controller) on a sequence of
 * frames. Input: records of 1 byte flags/DLC, 2 (or 4 with the extended
 * flag) identifier bytes and up to 8 data bytes, at most 128 frames (a
 * plant frame integrates a half cycle: longer inputs would mostly cost
 * time). Every frame is decoded by
 * every decoder and offered to every node; each node must count it in
 * exactly one receive counter, and no decoder may crash or accept a frame
 * hil_dict_check refuses. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "hil/canopen.h"
#include "hil/ctrl.h"
#include "hil/drive.h"
#include "hil/imu.h"
#include "hil/node.h"
#include "hil/plant.h"

static uint64_t counted(const struct hil_rx_stats *s)
{
    return s->accepted + s->other + s->unknown_id + s->bad_dlc + s->bad_value;
}

static void decode_all(const struct hil_can_frame *f)
{
    struct hil_drive_rpdo rp;
    struct hil_drive_tpdo1 t1;
    struct hil_drive_tpdo2 t2;
    struct hil_imu_tpdo im;
    struct hil_emcy e;
    uint8_t a, b;
    uint16_t u;
    double x, y;
    (void)hil_co_sync_decode(f, &a);
    (void)hil_co_nmt_decode(f, &a, &b);
    (void)hil_co_heartbeat_decode(f, &a, &b);
    (void)hil_co_emcy_decode(f, &a, &e);
    (void)hil_co_drive_rpdo_decode(f, &rp);
    (void)hil_co_drive_tpdo1_decode(f, &t1);
    (void)hil_co_drive_tpdo2_decode(f, &t2);
    (void)hil_co_imu_decode(f, 1, &im);
    (void)hil_co_imu_decode(f, 2, &im);
    (void)hil_co_rig_decode(f, f->id, &x, &y);
    (void)hil_co_imu_done_decode(f, &u);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static struct hil_plant pl;
    static struct hil_drive d;
    static struct hil_imu m;
    static struct hil_ctrl c;
    struct hil_drive_params dp;
    struct hil_imu_params ip;
    struct hil_plant_params pp;
    struct hil_ctrl_params cp;
    struct hil_out o;
    size_t i = 0;
    int frames = 0;
    hil_drive_params_default(&dp);
    hil_imu_params_default(&ip);
    hil_plant_params_default(&pp);
    hil_ctrl_params_default(&cp);
    o.n = 0;
    if (hil_drive_init(&d, &dp, &o) != HIL_OK || hil_imu_init(&m, &ip, &o) != HIL_OK ||
        hil_plant_init(&pl, &pp) != HIL_OK || hil_ctrl_init(&c, &cp) != HIL_OK)
        abort();
    while (i + 3 <= size && frames++ < 128) {
        struct hil_can_frame f;
        uint64_t before[4];
        uint8_t hdr = data[i++];
        unsigned n;
        memset(&f, 0, sizeof f);
        f.dlc = (uint8_t)(hdr & 0x0F); /* 9..15 too: an invalid DLC */
        if (hdr & 0x80) {
            if (i + 4 > size)
                break;
            f.id = ((uint32_t)data[i] | (uint32_t)data[i + 1] << 8 | (uint32_t)data[i + 2] << 16 |
                    (uint32_t)data[i + 3] << 24);
            i += 4;
        } else {
            f.id = (uint32_t)(data[i] | data[i + 1] << 8) & 0x7FFu;
            i += 2;
        }
        n = f.dlc <= 8 ? f.dlc : 8;
        if (i + n > size)
            n = (unsigned)(size - i);
        memcpy(f.data, data + i, n);
        i += n;
        decode_all(&f);
        (void)hil_dict_check(&f);
        before[0] = counted(&d.rx);
        before[1] = counted(&m.rx);
        before[2] = counted(&pl.rx);
        before[3] = counted(&c.rx);
        o.n = 0;
        hil_drive_on_frame(&d, &f, &o);
        o.n = 0;
        hil_imu_on_frame(&m, &f, &o);
        o.n = 0;
        hil_plant_on_frame(&pl, &f, &o);
        o.n = 0;
        hil_ctrl_on_frame(&c, &f, &o);
        if (counted(&d.rx) != before[0] + 1 || counted(&m.rx) != before[1] + 1 || counted(&pl.rx) != before[2] + 1 ||
            counted(&c.rx) != before[3] + 1)
            abort();
    }
    return 0;
}
