/* libFuzzer target: arbitrary frames into the SDO servers of the drive and
 * the IMU (hil/sdo.h), interleaved with NMT commands and SYNCs so every NMT
 * state and the PDO parameter rules are reached.
 *
 * Input: records of 10 bytes [op, dlc, 8 data bytes]; op bit 0 selects the
 * device, bits 1-2 the frame: 0-1 an SDO request (identifier 0x600 + node,
 * length dlc & 15, screened like every frame), 2 an NMT command (data[0],
 * to all), 3 a SYNC. Invariants checked after every frame (abort() when one
 * breaks, which libFuzzer reports): a device answers at most one frame per
 * request, an answer is 8 bytes on 0x580 + node, a request of another length
 * than 8 is not answered, and every writable integer object of both
 * dictionaries holds a value within its [low, high]. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "hil/canopen.h"
#include "hil/drive.h"
#include "hil/imu.h"
#include "hil/sdo.h"

static void in_range(const struct hil_od *od, const uint32_t *val)
{
    int i;
    for (i = 0; i < od->n; i++) {
        const struct hil_od_entry *e = &od->e[i];
        int64_t x;
        if (e->access != HIL_OD_RW || e->type == HIL_OD_VSTRING)
            continue;
        x = hil_od_value(e, val[i]);
        if (x < e->low || x > e->high)
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static struct hil_drive d;
    static struct hil_imu m;
    struct hil_drive_params dp;
    struct hil_imu_params ip;
    struct hil_out out;
    size_t at;
    hil_drive_params_default(&dp);
    hil_imu_params_default(&ip);
    out.n = 0;
    if (hil_drive_init(&d, &dp, &out) != HIL_OK || hil_imu_init(&m, &ip, &out) != HIL_OK)
        abort();
    for (at = 0; at + 10 <= size; at += 10) {
        const uint8_t *r = data + at;
        int imu = r[0] & 1, kind = (r[0] >> 1) & 3, i, answers = 0;
        uint8_t node = imu ? HIL_NODE_IMU : HIL_NODE_DRIVE;
        struct hil_can_frame f;
        memset(&f, 0, sizeof f);
        if (kind <= 1) {
            f.id = HIL_COB_SDO_RX(node);
            f.dlc = (uint8_t)(r[1] & 15);
        } else if (kind == 2) {
            f.id = HIL_COB_NMT;
            f.dlc = 2;
        } else {
            f.id = HIL_COB_SYNC;
            f.dlc = 1;
        }
        memcpy(f.data, r + 2, 8);
        if (kind == 2)
            f.data[1] = 0;
        if (kind == 3)
            f.data[0] = 1;
        out.n = 0;
        if (imu)
            hil_imu_on_frame(&m, &f, &out);
        else
            hil_drive_on_frame(&d, &f, &out);
        for (i = 0; i < out.n; i++) {
            if (out.f[i].id == HIL_COB_SDO_TX(node)) {
                answers++;
                if (out.f[i].dlc != 8)
                    abort();
            }
        }
        if (kind <= 1 && (answers > 1 || (f.dlc != 8 && answers != 0)))
            abort();
        in_range(&hil_drive_od, d.od);
        in_range(&hil_imu_od, m.od);
    }
    return 0;
}
