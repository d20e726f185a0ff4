/* CANopen object dictionary (CiA 301 sec. 7.4) of an emulated device: one
 * constant table per device type, the single source of truth for the C
 * code (SDO server, PDO mapping, the controller's boot sequence) and for the
 * device's EDS file (CiA 306), which hil_eds prints from it.
 *
 * A table is an array of entries (one per index/sub-index), sorted by index
 * then sub-index. An object of type RECORD or ARRAY has one entry per
 * sub-index, sub-index 0 holding the highest sub-index (UNSIGNED8, const);
 * a VAR has the single entry sub-index 0. Values are at most 32 bits wide
 * except VISIBLE_STRING constants; a device keeps the current value of entry
 * i in val[i] (32-bit two's complement for the signed types), so a value is
 * one array access away from the device code.
 *
 * Access rules enforced by hil_od_write (the SDO server and the RPDO path go
 * through it): the object and sub-index exist (abort 0x06020000 /
 * 0x06090011), the entry is writable (0x06010002), the length is the type's
 * (0x06070010), the value is within [low, high] (0x06090030), entries
 * flagged HIL_OD_PREOP are written only in NMT pre-operational (0x08000022),
 * then the device's write hook may refuse with its own abort code (PDO
 * mapping rules, supported modes) and applies the value. */
#ifndef HIL_OD_H
#define HIL_OD_H
#include <stddef.h>
#include <stdint.h>

/* Data types (CiA 301 table 44, the EDS DataType codes). */
#define HIL_OD_BOOLEAN 0x01u
#define HIL_OD_I8 0x02u
#define HIL_OD_I16 0x03u
#define HIL_OD_I32 0x04u
#define HIL_OD_U8 0x05u
#define HIL_OD_U16 0x06u
#define HIL_OD_U32 0x07u
#define HIL_OD_VSTRING 0x09u

/* Object codes (CiA 301 table 42). */
#define HIL_OD_VAR 0x07u
#define HIL_OD_ARRAY 0x08u
#define HIL_OD_RECORD 0x09u

/* Access. */
#define HIL_OD_RO 0u
#define HIL_OD_RW 1u
#define HIL_OD_CONST 2u

/* Flags. */
#define HIL_OD_PDO 0x01u   /* may be mapped into a PDO */
#define HIL_OD_PREOP 0x02u /* writable only in NMT pre-operational (PDO parameters) */
#define HIL_OD_LIVE 0x04u  /* process value the device refreshes (not restored by a reset) */

/* SDO abort codes (CiA 301 table 22). */
#define HIL_SDO_ABORT_TOGGLE 0x05030000u
#define HIL_SDO_ABORT_TIMEOUT 0x05040000u
#define HIL_SDO_ABORT_COMMAND 0x05040001u
#define HIL_SDO_ABORT_UNSUPPORTED 0x06010000u
#define HIL_SDO_ABORT_WRITE_ONLY 0x06010001u
#define HIL_SDO_ABORT_READ_ONLY 0x06010002u
#define HIL_SDO_ABORT_NO_OBJECT 0x06020000u
#define HIL_SDO_ABORT_NOT_MAPPABLE 0x06040041u
#define HIL_SDO_ABORT_PDO_LENGTH 0x06040042u
#define HIL_SDO_ABORT_LENGTH 0x06070010u
#define HIL_SDO_ABORT_NO_SUB 0x06090011u
#define HIL_SDO_ABORT_RANGE 0x06090030u
#define HIL_SDO_ABORT_GENERAL 0x08000000u
#define HIL_SDO_ABORT_STATE 0x08000022u

struct hil_od_entry {
    uint16_t index;
    uint8_t sub;
    uint8_t objtype;  /* HIL_OD_VAR / ARRAY / RECORD, the same on every sub-index of an object */
    uint8_t type;     /* HIL_OD_U8 ... */
    uint8_t access;   /* HIL_OD_RO / RW / CONST */
    uint8_t flags;    /* HIL_OD_PDO | HIL_OD_PREOP | HIL_OD_LIVE */
    const char *obj;  /* object name (EDS ParameterName of the object) */
    const char *name; /* sub-index name (a VAR: the object name) */
    int64_t low, high; /* value range; unused for VISIBLE_STRING */
    int64_t dflt;     /* power-on value */
    const char *str;  /* VISIBLE_STRING: the constant value */
};

struct hil_od {
    const char *device;  /* EDS [DeviceInfo] ProductName */
    const struct hil_od_entry *e;
    int n;
};

#define HIL_OD_MAX 128 /* entries per device table */

/* The device side of a dictionary: the table, the device's values and the
 * write hook (NULL: none). The hook runs after the generic checks with the
 * new value and returns 0 to accept (it may act on it; the value is stored
 * afterwards) or an abort code. nmt points at the device's NMT state. */
typedef uint32_t (*hil_od_write_hook)(void *ctx, int i, uint32_t v);
struct hil_od_dev {
    const struct hil_od *od;
    uint32_t *val;
    hil_od_write_hook write;
    void *ctx;
    const uint8_t *nmt;
};

/* Position of (index, sub) in the table, -1 when the sub-index does not
 * exist; *index_exists (may be NULL) tells whether the object exists.
 * Binary search, O(log n). */
int hil_od_find(const struct hil_od *od, uint16_t index, uint8_t sub, int *index_exists);

/* Size in bytes of entry i's value (strings: their length). */
size_t hil_od_size(const struct hil_od_entry *e);

/* Sets every value to its power-on value; comm_only = 1 restores only the
 * communication area 0x1000-0x1FFF (NMT reset communication). LIVE entries
 * keep their values. */
void hil_od_reset(const struct hil_od_dev *d, int comm_only);

/* Reads entry (index, sub) into buf (little endian), *len its size.
 * Returns 0 or an abort code (no object / no sub-index, buffer too small:
 * HIL_SDO_ABORT_LENGTH). */
uint32_t hil_od_read(const struct hil_od_dev *d, uint16_t index, uint8_t sub, uint8_t *buf, size_t cap,
                     size_t *len);

/* Writes len bytes (little endian) to (index, sub) through the rules above.
 * Returns 0 or the abort code; the value is untouched on an abort. */
uint32_t hil_od_write(const struct hil_od_dev *d, uint16_t index, uint8_t sub, const uint8_t *buf, size_t len);

/* Value of entry i as a signed integer (sign-extended for I8/I16/I32). */
int64_t hil_od_value(const struct hil_od_entry *e, uint32_t raw);

/* Text of an abort code (CiA 301 table 22), never NULL. */
const char *hil_sdo_abort_str(uint32_t code);

#endif
