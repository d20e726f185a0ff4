/* PDO communication and mapping parameters (CiA 301 sec. 7.5.2.35-38) of an
 * emulated device: the rules their SDO writes must follow, and the PDOs in
 * effect, compiled from the dictionary when the node is started.
 *
 * Parameters: RPDO n communication 0x1400+n (sub 1 COB-ID, sub 2
 * transmission type), RPDO mapping 0x1600+n, TPDO communication 0x1800+n
 * (sub 1 COB-ID, 2 transmission type, 3 inhibit time, 5 event timer), TPDO
 * mapping 0x1A00+n; a mapping entry is index << 16 | sub-index << 8 | bits.
 * Rules (hil_pdo_param_check, called by hil_od_write after the generic
 * checks): a COB-ID is an 11-bit identifier (bits 11-29 zero, bit 30 "no
 * RTR" free, bit 31 "not valid"), the identifier of a valid PDO cannot
 * change (set bit 31 first: 0x06090030), a valid PDO's identifier is not
 * one of CiA 301's restricted CAN-IDs (0x000-0x07F, 0x101-0x180,
 * 0x581-0x5FF, 0x601-0x67F, 0x6E0-0x6FF, 0x701-0x7FF: 0x06090030); a transmission type 241..253 is
 * reserved (0x06090030); a mapping changes only while its PDO is not valid
 * (0x08000022) and a mapping entry only while sub-index 0 is 0 (0x08000022);
 * an entry names an existing PDO-mappable object whose length is the bit
 * count (writable for an RPDO) (0x06040041); sub-index 0 = n enables n
 * entries whose lengths add up to at most 64 bits (0x06040042).
 *
 * The set compiled at NMT start (hil_pdo_compile) is what the device sends
 * and receives until the next start: writes in pre-operational take effect
 * on start (hil/od.h: PDO parameters are HIL_OD_PREOP). */
#ifndef HIL_PDO_H
#define HIL_PDO_H
#include "hil/can.h"
#include "hil/od.h"

#define HIL_PDO_MAX 4     /* PDOs per direction per device */
#define HIL_PDO_MAX_MAP 8 /* mapped objects per PDO */

struct hil_pdo {
    uint32_t cob;     /* 11-bit identifier */
    uint8_t trans;    /* transmission type: 1..240 every n-th SYNC, 254/255 event driven */
    uint8_t n, dlc;   /* mapped objects, bytes */
    int16_t slot[HIL_PDO_MAX_MAP]; /* their positions in the dictionary */
    uint8_t bytes[HIL_PDO_MAX_MAP];
};

struct hil_pdo_set {
    struct hil_pdo rx[HIL_PDO_MAX], tx[HIL_PDO_MAX];
    int nrx, ntx;       /* valid PDOs */
    int tx_num[HIL_PDO_MAX]; /* TPDO number - 1 of tx[k] (0x1800 + tx_num) */
};

/* The PDO rules above for writing v to entry i; 0 or the abort code. Entries
 * that are not PDO parameters pass. */
uint32_t hil_pdo_param_check(const struct hil_od_dev *d, int i, uint32_t v);

/* The valid PDOs of the dictionary's current values. */
void hil_pdo_compile(const struct hil_od_dev *d, struct hil_pdo_set *s);

/* The frame of TPDO p from the current values. */
void hil_pdo_pack(const struct hil_od_dev *d, const struct hil_pdo *p, struct hil_can_frame *f);

/* The valid RPDO with identifier id, or NULL. */
const struct hil_pdo *hil_pdo_rx_find(const struct hil_pdo_set *s, uint32_t id);

/* Writes the objects of RPDO p from frame f (f->dlc == p->dlc checked by the
 * caller) through the device's write hook, in mapping order; returns 0 or the
 * first abort code (the later objects are still written). */
uint32_t hil_pdo_unpack(const struct hil_od_dev *d, const struct hil_pdo *p, const struct hil_can_frame *f);

#endif
