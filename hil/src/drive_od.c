/* The drive's object dictionary (node 1): CiA 301 communication objects and
 * the CiA 402 objects of cyclic synchronous torque (mode 10), the single
 * source of truth for drive.c, the controller's boot and hil/drive.eds.
 * Units: torques per mille of 0x6076 (CiA 402) and, manufacturer-specific,
 * in mNm (0x2071 target, 0x2077 actual: the project's unit, hil/canopen.h);
 * position 2^20 increments/rev, velocity urad/s. Defaults of 0x6072 and 0x6076
 * are those of hil_drive_params_default (the device sets them from its
 * parameters). */
#include <stdint.h>
#include "hil/drive.h"

#include "od_table.h"

static const struct hil_od_entry entries[] = {
    V(0x1000, HIL_OD_U32, HIL_OD_CONST, 0, "Device type", 0, U32MAX, 0x00020192), /* CiA 402, servo drive */
    V(0x1001, HIL_OD_U8, HIL_OD_RO, LIVE_RO, "Error register", 0, U8MAX, 0),
    DEVICE_NAME("fracarm HIL servo drive (CiA 402 cyclic synchronous torque)"),
    V(0x1017, HIL_OD_U16, HIL_OD_RW, 0, "Producer heartbeat time", 0, U16MAX, 100),
    IDENTITY(1), /* vendor 0: CiA has assigned the project none */
    RPDO_COMM(0x1400, "RPDO1 communication parameter", 0x00000201),
    RPDO_COMM(0x1401, "RPDO2 communication parameter", 0x80000301),
    MAP(0x1600, "RPDO1 mapping parameter", 2, 0x60400010, 0x20710020, 0, 0, 0),
    MAP(0x1601, "RPDO2 mapping parameter", 0, 0, 0, 0, 0, 0),
    TPDO_COMM(0x1800, "TPDO1 communication parameter", 0x40000181, 1),
    TPDO_COMM(0x1801, "TPDO2 communication parameter", 0x40000281, 1),
    TPDO_COMM(0x1802, "TPDO3 communication parameter", 0xC0000381, 1),
    MAP(0x1A00, "TPDO1 mapping parameter", 2, 0x60410010, 0x60640020, 0, 0, 0),
    MAP(0x1A01, "TPDO2 mapping parameter", 2, 0x606C0020, 0x20770020, 0, 0, 0),
    MAP(0x1A02, "TPDO3 mapping parameter", 0, 0, 0, 0, 0, 0),
    V(0x2071, HIL_OD_I32, HIL_OD_RW, HIL_OD_PDO, "Target torque mNm", I32R, 0),
    V(0x2077, HIL_OD_I32, HIL_OD_RO, LIVE_RO, "Torque actual value mNm", I32R, 0),
    V(0x2100, HIL_OD_U16, HIL_OD_RO, LIVE_RO, "i2t estimate per mille of rated squared", 0, U16MAX, 0),
    V(0x2101, HIL_OD_U16, HIL_OD_RW, 0, "Over-temperature trip per mille of rated squared", 1, U16MAX, 1100),
    V(0x603F, HIL_OD_U16, HIL_OD_RO, LIVE_RO, "Error code", 0, U16MAX, 0),
    V(0x6040, HIL_OD_U16, HIL_OD_RW, HIL_OD_PDO, "Controlword", 0, U16MAX, 0),
    V(0x6041, HIL_OD_U16, HIL_OD_RO, LIVE_RO, "Statusword", 0, U16MAX, 0x0240),
    V(0x605A, HIL_OD_I16, HIL_OD_RW, 0, "Quick stop option code", 2, 6, 6),
    V(0x6060, HIL_OD_I8, HIL_OD_RW, HIL_OD_PDO, "Modes of operation", 0, 10, 10),
    V(0x6061, HIL_OD_I8, HIL_OD_RO, LIVE_RO, "Modes of operation display", -128, 127, 10),
    V(0x6064, HIL_OD_I32, HIL_OD_RO, LIVE_RO, "Position actual value", I32R, 0),
    V(0x606C, HIL_OD_I32, HIL_OD_RO, LIVE_RO, "Velocity actual value", I32R, 0),
    V(0x6071, HIL_OD_I16, HIL_OD_RW, HIL_OD_PDO, "Target torque", I16R, 0),
    V(0x6072, HIL_OD_U16, HIL_OD_RW, HIL_OD_PDO, "Max torque", 0, U16MAX, 2623),
    V(0x6076, HIL_OD_U32, HIL_OD_RO, 0, "Motor rated torque", 1, U32MAX, 95700),
    V(0x6077, HIL_OD_I16, HIL_OD_RO, LIVE_RO, "Torque actual value", I16R, 0),
    V(0x6502, HIL_OD_U32, HIL_OD_RO, 0, "Supported drive modes", 0, U32MAX, 0x00000200), /* bit 9: CST */
};

const struct hil_od hil_drive_od = {"fracarm HIL servo drive", entries, (int)(sizeof entries / sizeof entries[0])};

/* the dictionary fits the devices' value arrays */
typedef char hil_drive_od_fits[(sizeof entries / sizeof entries[0]) <= HIL_OD_MAX ? 1 : -1];
