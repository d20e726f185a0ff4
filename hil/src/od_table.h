/* Building blocks of the devices' dictionary tables (drive_od.c, imu_od.c):
 * one macro per CiA 301 object pattern, so a table reads like the
 * standard's object list. Private to hil/src. */
#ifndef HIL_OD_TABLE_H
#define HIL_OD_TABLE_H
#include "hil/od.h"

#define U8MAX 0xFF
#define U16MAX 0xFFFF
#define U32MAX 0xFFFFFFFFll
#define I16R -32768, 32767
#define I32R -2147483647ll - 1, 2147483647ll
#define V(...) V_(__VA_ARGS__)
#define V_(ix, t, a, f, name, lo, hi, d) {ix, 0, HIL_OD_VAR, t, a, f, name, name, lo, hi, d, NULL}
#define S(...) S_(__VA_ARGS__)
#define S_(ix, sub, ot, t, a, f, obj, name, lo, hi, d) {ix, sub, ot, t, a, f, obj, name, lo, hi, d, NULL}
#define REC0(ix, obj, n) S(ix, 0, HIL_OD_RECORD, HIL_OD_U8, HIL_OD_CONST, 0, obj, "Highest sub-index supported", n, n, n)
#define PRE (HIL_OD_PREOP)
#define RPDO_COMM(ix, obj, cob) REC0(ix, obj, 2), \
    S(ix, 1, HIL_OD_RECORD, HIL_OD_U32, HIL_OD_RW, PRE, obj, "COB-ID used by RPDO", 0, U32MAX, cob), \
    S(ix, 2, HIL_OD_RECORD, HIL_OD_U8, HIL_OD_RW, PRE, obj, "Transmission type", 0, U8MAX, 255)
#define TPDO_COMM(ix, obj, cob, tt) REC0(ix, obj, 5), \
    S(ix, 1, HIL_OD_RECORD, HIL_OD_U32, HIL_OD_RW, PRE, obj, "COB-ID used by TPDO", 0, U32MAX, cob), \
    S(ix, 2, HIL_OD_RECORD, HIL_OD_U8, HIL_OD_RW, PRE, obj, "Transmission type", 0, U8MAX, tt), \
    S(ix, 3, HIL_OD_RECORD, HIL_OD_U16, HIL_OD_RW, PRE, obj, "Inhibit time", 0, U16MAX, 0), \
    S(ix, 5, HIL_OD_RECORD, HIL_OD_U16, HIL_OD_RW, PRE, obj, "Event timer", 0, U16MAX, 0)
#define MAPE(ix, obj, k, d) S(ix, k, HIL_OD_RECORD, HIL_OD_U32, HIL_OD_RW, PRE, obj, "Application object " #k, 0, U32MAX, d)
#define MAP(ix, obj, n, a, b, c, d, e) \
    S(ix, 0, HIL_OD_RECORD, HIL_OD_U8, HIL_OD_RW, PRE, obj, "Number of mapped application objects", 0, 8, n), \
    MAPE(ix, obj, 1, a), MAPE(ix, obj, 2, b), MAPE(ix, obj, 3, c), MAPE(ix, obj, 4, d), MAPE(ix, obj, 5, e), \
    MAPE(ix, obj, 6, 0), MAPE(ix, obj, 7, 0), MAPE(ix, obj, 8, 0)
#define LIVE_RO (HIL_OD_PDO | HIL_OD_LIVE)

#define ARR0(ix, obj, n) S(ix, 0, HIL_OD_ARRAY, HIL_OD_U8, HIL_OD_CONST, 0, obj, "Highest sub-index supported", n, n, n)
#define IDENTITY(product) REC0(0x1018, "Identity object", 4), \
    S(0x1018, 1, HIL_OD_RECORD, HIL_OD_U32, HIL_OD_RO, 0, "Identity object", "Vendor-ID", 0, U32MAX, 0), \
    S(0x1018, 2, HIL_OD_RECORD, HIL_OD_U32, HIL_OD_RO, 0, "Identity object", "Product code", 0, U32MAX, product), \
    S(0x1018, 3, HIL_OD_RECORD, HIL_OD_U32, HIL_OD_RO, 0, "Identity object", "Revision number", 0, U32MAX, 0x00010000), \
    S(0x1018, 4, HIL_OD_RECORD, HIL_OD_U32, HIL_OD_RO, 0, "Identity object", "Serial number", 0, U32MAX, 1)
#define DEVICE_NAME(text) {0x1008, 0, HIL_OD_VAR, HIL_OD_VSTRING, HIL_OD_CONST, 0, "Manufacturer device name", \
     "Manufacturer device name", 0, 0, 0, text}

#endif
