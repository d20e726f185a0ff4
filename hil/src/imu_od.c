/* The IMU's object dictionary (node 2): CiA 301 communication objects and
 * the readings as manufacturer-specific objects, the single source of truth
 * for imu.c, the controller's boot and hil/imu.eds. Units: angular rate
 * mrad/s, acceleration mm/s^2 (hil/canopen.h); status bit 0: saturated.
 * No receive PDO: the IMU only transmits, event-driven per reading. */
#include <stdint.h>
#include "hil/imu.h"
#include "od_table.h"

#define AXIS(ix, obj, k, name) S(ix, k, HIL_OD_ARRAY, HIL_OD_I16, HIL_OD_RO, LIVE_RO, obj, name, I16R, 0)

static const struct hil_od_entry entries[] = {
    V(0x1000, HIL_OD_U32, HIL_OD_CONST, 0, "Device type", 0, U32MAX, 0x00000000), /* no standard profile */
    V(0x1001, HIL_OD_U8, HIL_OD_RO, LIVE_RO, "Error register", 0, U8MAX, 0),
    DEVICE_NAME("fracarm HIL tip IMU (angular rate and acceleration)"),
    V(0x1017, HIL_OD_U16, HIL_OD_RW, 0, "Producer heartbeat time", 0, U16MAX, 100),
    IDENTITY(2), /* vendor 0: CiA has assigned the project none */
    TPDO_COMM(0x1800, "TPDO1 communication parameter", 0x40000182, 254),
    TPDO_COMM(0x1801, "TPDO2 communication parameter", 0x40000282, 254),
    TPDO_COMM(0x1802, "TPDO3 communication parameter", 0xC0000382, 254),
    MAP(0x1A00, "TPDO1 mapping parameter", 5, 0x20000110, 0x20000210, 0x20000310, 0x20020008, 0x20030108),
    MAP(0x1A01, "TPDO2 mapping parameter", 5, 0x20010110, 0x20010210, 0x20010310, 0x20020008, 0x20030208),
    MAP(0x1A02, "TPDO3 mapping parameter", 0, 0, 0, 0, 0, 0),
    ARR0(0x2000, "Angular rate", 3),
    AXIS(0x2000, "Angular rate", 1, "Angular rate x"),
    AXIS(0x2000, "Angular rate", 2, "Angular rate y"),
    AXIS(0x2000, "Angular rate", 3, "Angular rate z"),
    ARR0(0x2001, "Acceleration", 3),
    AXIS(0x2001, "Acceleration", 1, "Acceleration x"),
    AXIS(0x2001, "Acceleration", 2, "Acceleration y"),
    AXIS(0x2001, "Acceleration", 3, "Acceleration z"),
    V(0x2002, HIL_OD_U8, HIL_OD_RO, LIVE_RO, "Reading sequence", 0, U8MAX, 0),
    ARR0(0x2003, "Reading status", 2),
    S(0x2003, 1, HIL_OD_ARRAY, HIL_OD_U8, HIL_OD_RO, LIVE_RO, "Reading status", "Angular rate status", 0, U8MAX, 0),
    S(0x2003, 2, HIL_OD_ARRAY, HIL_OD_U8, HIL_OD_RO, LIVE_RO, "Reading status", "Acceleration status", 0, U8MAX, 0),
};

const struct hil_od hil_imu_od = {"fracarm HIL tip IMU", entries, (int)(sizeof entries / sizeof entries[0])};

/* the dictionary fits the devices' value arrays */
typedef char hil_imu_od_fits[(sizeof entries / sizeof entries[0]) <= HIL_OD_MAX ? 1 : -1];
