/* Object dictionary access; rules in hil/od.h. */
#include <string.h>
#include "hil/od.h"
#include "hil/canopen.h"
#include "hil/pdo.h"

int hil_od_find(const struct hil_od *od, uint16_t index, uint8_t sub, int *index_exists)
{
    int lo = 0, hi = od->n - 1;
    uint32_t key = ((uint32_t)index << 8) | sub;
    if (index_exists)
        *index_exists = 0;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        uint32_t k = ((uint32_t)od->e[mid].index << 8) | od->e[mid].sub;
        if (k == key) {
            if (index_exists)
                *index_exists = 1;
            return mid;
        }
        if (k < key)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    if (index_exists) {
        /* lo is the insertion point: a neighbour with the same index means
         * the object exists without this sub-index */
        *index_exists = (lo < od->n && od->e[lo].index == index) || (lo > 0 && od->e[lo - 1].index == index);
    }
    return -1;
}

size_t hil_od_size(const struct hil_od_entry *e)
{
    switch (e->type) {
    case HIL_OD_BOOLEAN:
    case HIL_OD_I8:
    case HIL_OD_U8: return 1;
    case HIL_OD_I16:
    case HIL_OD_U16: return 2;
    case HIL_OD_VSTRING: return e->str ? strlen(e->str) : 0;
    default: return 4;
    }
}

int64_t hil_od_value(const struct hil_od_entry *e, uint32_t raw)
{
    switch (e->type) {
    case HIL_OD_I8: return (int8_t)(uint8_t)raw;
    case HIL_OD_I16: return (int16_t)(uint16_t)raw;
    case HIL_OD_I32: return (int32_t)raw;
    default: return raw;
    }
}

void hil_od_reset(const struct hil_od_dev *d, int comm_only)
{
    int i;
    for (i = 0; i < d->od->n; i++) {
        const struct hil_od_entry *e = &d->od->e[i];
        if ((e->flags & HIL_OD_LIVE) || (comm_only && (e->index < 0x1000u || e->index > 0x1FFFu)))
            continue;
        d->val[i] = (uint32_t)e->dflt;
    }
}

static uint32_t locate(const struct hil_od *od, uint16_t index, uint8_t sub, int *i)
{
    int exists;
    *i = hil_od_find(od, index, sub, &exists);
    if (*i >= 0)
        return 0;
    return exists ? HIL_SDO_ABORT_NO_SUB : HIL_SDO_ABORT_NO_OBJECT;
}

uint32_t hil_od_read(const struct hil_od_dev *d, uint16_t index, uint8_t sub, uint8_t *buf, size_t cap,
                     size_t *len)
{
    int i;
    uint32_t ab = locate(d->od, index, sub, &i);
    const struct hil_od_entry *e;
    size_t n;
    if (ab)
        return ab;
    e = &d->od->e[i];
    n = hil_od_size(e);
    if (n > cap)
        return HIL_SDO_ABORT_LENGTH;
    if (e->type == HIL_OD_VSTRING) {
        if (n)
            memcpy(buf, e->str, n);
    } else {
        uint8_t tmp[4];
        hil_put_u32(tmp, d->val[i]);
        memcpy(buf, tmp, n);
    }
    *len = n;
    return 0;
}

uint32_t hil_od_write(const struct hil_od_dev *d, uint16_t index, uint8_t sub, const uint8_t *buf, size_t len)
{
    int i;
    uint32_t ab = locate(d->od, index, sub, &i), v;
    const struct hil_od_entry *e;
    uint8_t tmp[4] = {0, 0, 0, 0};
    int64_t x;
    if (ab)
        return ab;
    e = &d->od->e[i];
    if (e->access != HIL_OD_RW)
        return HIL_SDO_ABORT_READ_ONLY;
    if (len != hil_od_size(e))
        return HIL_SDO_ABORT_LENGTH;
    memcpy(tmp, buf, len);
    v = hil_get_u32(tmp);
    x = hil_od_value(e, v);
    if (x < e->low || x > e->high)
        return HIL_SDO_ABORT_RANGE;
    if ((e->flags & HIL_OD_PREOP) && d->nmt && *d->nmt != HIL_NMT_STATE_PREOP)
        return HIL_SDO_ABORT_STATE;
    if ((ab = hil_pdo_param_check(d, i, v)) != 0)
        return ab;
    if (d->write && (ab = d->write(d->ctx, i, v)) != 0)
        return ab;
    d->val[i] = v;
    return 0;
}

const char *hil_sdo_abort_str(uint32_t code)
{
    switch (code) {
    case HIL_SDO_ABORT_TOGGLE: return "toggle bit not alternated";
    case HIL_SDO_ABORT_TIMEOUT: return "SDO protocol timed out";
    case HIL_SDO_ABORT_COMMAND: return "client/server command specifier not valid or unknown";
    case HIL_SDO_ABORT_UNSUPPORTED: return "unsupported access to an object";
    case HIL_SDO_ABORT_WRITE_ONLY: return "attempt to read a write only object";
    case HIL_SDO_ABORT_READ_ONLY: return "attempt to write a read only object";
    case HIL_SDO_ABORT_NO_OBJECT: return "object does not exist in the object dictionary";
    case HIL_SDO_ABORT_NOT_MAPPABLE: return "object cannot be mapped to the PDO";
    case HIL_SDO_ABORT_PDO_LENGTH: return "number and length of the objects to be mapped would exceed PDO length";
    case HIL_SDO_ABORT_LENGTH: return "data type does not match, length of service parameter does not match";
    case HIL_SDO_ABORT_NO_SUB: return "sub-index does not exist";
    case HIL_SDO_ABORT_RANGE: return "invalid value for parameter";
    case HIL_SDO_ABORT_GENERAL: return "general error";
    case HIL_SDO_ABORT_STATE: return "data cannot be transferred because of the present device state";
    default: return "unknown abort code";
    }
}
