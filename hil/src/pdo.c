/* PDO parameters and the PDOs in effect; rules in hil/pdo.h. */
#include <string.h>
#include "hil/pdo.h"

#define PDO_NOT_VALID 0x80000000u
#define PDO_NO_RTR 0x40000000u

static int is_comm(uint16_t ix) { return (ix >= 0x1400u && ix < 0x1400u + HIL_PDO_MAX) || (ix >= 0x1800u && ix < 0x1800u + HIL_PDO_MAX); }
static int is_map(uint16_t ix) { return (ix >= 0x1600u && ix < 0x1600u + HIL_PDO_MAX) || (ix >= 0x1A00u && ix < 0x1A00u + HIL_PDO_MAX); }
static int is_rx(uint16_t ix) { return ix < 0x1800u; }

/* CiA 301 table 3, restricted CAN-IDs: identifiers of NMT, SYNC-less
 * reserved ranges, the default SDO channels and NMT error control, which no
 * PDO may use (a TPDO on 0x580 + node would be taken for an SDO answer). */
static int restricted_id(uint32_t id)
{
    return id <= 0x07Fu || (id >= 0x101u && id <= 0x180u) || (id >= 0x581u && id <= 0x5FFu) ||
           (id >= 0x601u && id <= 0x67Fu) || (id >= 0x6E0u && id <= 0x6FFu) || id >= 0x701u;
}

static int slot(const struct hil_od_dev *d, uint16_t ix, uint8_t sub) { return hil_od_find(d->od, ix, sub, NULL); }

/* Position of the object a mapping entry names when it may be mapped into
 * an RPDO (rx) or TPDO with that length, else -1. */
static int mappable(const struct hil_od_dev *d, uint32_t m, int rx)
{
    int j = slot(d, (uint16_t)(m >> 16), (uint8_t)(m >> 8));
    const struct hil_od_entry *e;
    if (j < 0)
        return -1;
    e = &d->od->e[j];
    if (!(e->flags & HIL_OD_PDO) || (rx && e->access != HIL_OD_RW) || (m & 0xFFu) != 8u * hil_od_size(e))
        return -1;
    return j;
}

/* The communication parameter's COB-ID of the PDO a mapping belongs to. */
static uint32_t cob_of_map(const struct hil_od_dev *d, uint16_t map_ix)
{
    int j = slot(d, (uint16_t)(map_ix - 0x200u), 1);
    return j >= 0 ? d->val[j] : PDO_NOT_VALID;
}

uint32_t hil_pdo_param_check(const struct hil_od_dev *d, int i, uint32_t v)
{
    const struct hil_od_entry *e = &d->od->e[i];
    if (is_comm(e->index)) {
        if (e->sub == 1) {
            uint32_t cur = d->val[i];
            if (v & 0x3FFFF800u)
                return HIL_SDO_ABORT_RANGE;
            if (!(cur & PDO_NOT_VALID) && !(v & PDO_NOT_VALID) && (cur & 0x7FFu) != (v & 0x7FFu))
                return HIL_SDO_ABORT_RANGE;
            if ((v & 0x7FFu) == 0 || (!(v & PDO_NOT_VALID) && restricted_id(v & 0x7FFu)))
                return HIL_SDO_ABORT_RANGE;
        } else if (e->sub == 2 && v > 240u && v < 254u) {
            return HIL_SDO_ABORT_RANGE;
        }
        return 0;
    }
    if (!is_map(e->index))
        return 0;
    if (!(cob_of_map(d, e->index) & PDO_NOT_VALID))
        return HIL_SDO_ABORT_STATE;
    if (e->sub == 0) {
        unsigned k, bits = 0;
        for (k = 1; k <= v; k++) {
            int m = slot(d, e->index, (uint8_t)k);
            if (m < 0 || mappable(d, d->val[m], is_rx(e->index)) < 0)
                return HIL_SDO_ABORT_NOT_MAPPABLE;
            bits += d->val[m] & 0xFFu;
        }
        return bits > 64u ? HIL_SDO_ABORT_PDO_LENGTH : 0;
    }
    {
        int n = slot(d, e->index, 0); /* the mapping's number of entries */
        if (n < 0 || d->val[n] != 0)
            return HIL_SDO_ABORT_STATE;
    }
    if (v != 0 && mappable(d, v, is_rx(e->index)) < 0)
        return HIL_SDO_ABORT_NOT_MAPPABLE;
    return 0;
}

static int compile_one(const struct hil_od_dev *d, uint16_t comm, struct hil_pdo *p)
{
    int c1 = slot(d, comm, 1), c2 = slot(d, comm, 2), m0 = slot(d, (uint16_t)(comm + 0x200u), 0);
    unsigned k;
    if (c1 < 0 || c2 < 0 || m0 < 0 || (d->val[c1] & PDO_NOT_VALID))
        return 0;
    memset(p, 0, sizeof *p);
    p->cob = d->val[c1] & 0x7FFu;
    p->trans = (uint8_t)d->val[c2];
    for (k = 1; k <= d->val[m0] && k <= HIL_PDO_MAX_MAP; k++) {
        int m = m0 + (int)k, j = mappable(d, d->val[m], comm < 0x1800u);
        if (j < 0)
            return 0;
        p->slot[p->n] = (int16_t)j;
        p->bytes[p->n] = (uint8_t)((d->val[m] & 0xFFu) / 8u);
        p->dlc = (uint8_t)(p->dlc + p->bytes[p->n]);
        p->n++;
    }
    return p->dlc <= 8;
}

void hil_pdo_compile(const struct hil_od_dev *d, struct hil_pdo_set *s)
{
    int n;
    memset(s, 0, sizeof *s);
    for (n = 0; n < HIL_PDO_MAX; n++) {
        if (compile_one(d, (uint16_t)(0x1400u + n), &s->rx[s->nrx]))
            s->nrx++;
        if (compile_one(d, (uint16_t)(0x1800u + n), &s->tx[s->ntx]))
            s->tx_num[s->ntx++] = n;
    }
}

void hil_pdo_pack(const struct hil_od_dev *d, const struct hil_pdo *p, struct hil_can_frame *f)
{
    unsigned k, at = 0;
    memset(f, 0, sizeof *f);
    f->id = p->cob;
    f->dlc = p->dlc;
    for (k = 0; k < p->n; k++) {
        uint8_t tmp[4];
        hil_put_u32(tmp, d->val[p->slot[k]]);
        memcpy(f->data + at, tmp, p->bytes[k]);
        at += p->bytes[k];
    }
}

const struct hil_pdo *hil_pdo_rx_find(const struct hil_pdo_set *s, uint32_t id)
{
    int k;
    for (k = 0; k < s->nrx; k++)
        if (s->rx[k].cob == id)
            return &s->rx[k];
    return NULL;
}

uint32_t hil_pdo_unpack(const struct hil_od_dev *d, const struct hil_pdo *p, const struct hil_can_frame *f)
{
    unsigned k, at = 0;
    uint32_t first = 0;
    for (k = 0; k < p->n; k++) {
        uint8_t tmp[4] = {0, 0, 0, 0};
        uint32_t v, ab = 0;
        memcpy(tmp, f->data + at, p->bytes[k]);
        at += p->bytes[k];
        v = hil_get_u32(tmp);
        if (d->write)
            ab = d->write(d->ctx, p->slot[k], v);
        if (ab == 0)
            d->val[p->slot[k]] = v;
        else if (first == 0)
            first = ab;
    }
    return first;
}
