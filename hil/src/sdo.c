/* SDO server and client codec; protocol in hil/sdo.h (CiA 301 sec. 7.2.4.3). */
#include <string.h>
#include "hil/sdo.h"

/* Command specifiers: client (ccs) and server (scs), bits 7-5 of byte 0. */
#define CCS_DOWNLOAD_SEGMENT 0u
#define CCS_INITIATE_DOWNLOAD 1u
#define CCS_INITIATE_UPLOAD 2u
#define CCS_UPLOAD_SEGMENT 3u
#define CCS_ABORT 4u
#define SCS_UPLOAD_SEGMENT 0u
#define SCS_DOWNLOAD_SEGMENT 1u
#define SCS_INITIATE_UPLOAD 2u
#define SCS_INITIATE_DOWNLOAD 3u
#define CS_ABORT 4u

enum { IDLE, UPLOADING, DOWNLOADING };

void hil_sdo_server_init(struct hil_sdo_server *s, uint8_t node)
{
    memset(s, 0, sizeof *s);
    s->node = node;
}

static void answer(struct hil_can_frame *r, uint8_t node, uint8_t cmd, uint16_t index, uint8_t sub)
{
    memset(r, 0, sizeof *r);
    r->id = HIL_COB_SDO_TX(node);
    r->dlc = 8;
    r->data[0] = cmd;
    hil_put_u16(r->data + 1, index);
    r->data[3] = sub;
}

/* Abort response; the transfer in progress (if any) ends. */
static int abort_with(struct hil_sdo_server *s, struct hil_can_frame *r, uint16_t index, uint8_t sub,
                      uint32_t code, int protocol)
{
    answer(r, s->node, CS_ABORT << 5, index, sub);
    hil_put_u32(r->data + 4, code);
    s->state = IDLE;
    s->aborts++;
    s->last_abort = code;
    if (protocol) {
        s->protocol_errors++;
        return -1;
    }
    return 1;
}

static int initiate_upload(struct hil_sdo_server *s, const struct hil_od_dev *d, uint16_t index, uint8_t sub,
                           struct hil_can_frame *r)
{
    size_t n;
    uint32_t ab = hil_od_read(d, index, sub, s->buf, sizeof s->buf, &n);
    if (ab)
        return abort_with(s, r, index, sub, ab, 0);
    if (n >= 1 && n <= 4) { /* expedited, size indicated: e = 1, s = 1, n = 4 - size */
        answer(r, s->node, (uint8_t)((SCS_INITIATE_UPLOAD << 5) | ((4u - n) << 2) | 0x03u), index, sub);
        memcpy(r->data + 4, s->buf, n);
        return 1;
    }
    answer(r, s->node, (SCS_INITIATE_UPLOAD << 5) | 0x01u, index, sub); /* segmented, size indicated */
    hil_put_u32(r->data + 4, (uint32_t)n);
    s->state = UPLOADING;
    s->index = index;
    s->sub = sub;
    s->len = n;
    s->pos = 0;
    s->toggle = 0;
    return 1;
}

static int upload_segment(struct hil_sdo_server *s, const struct hil_can_frame *f, struct hil_can_frame *r)
{
    uint8_t t = (uint8_t)((f->data[0] >> 4) & 1u);
    size_t n = s->len - s->pos;
    int last;
    if (s->state != UPLOADING)
        return abort_with(s, r, 0, 0, HIL_SDO_ABORT_COMMAND, 1);
    if (t != s->toggle)
        return abort_with(s, r, s->index, s->sub, HIL_SDO_ABORT_TOGGLE, 1);
    if (n > 7)
        n = 7;
    last = s->pos + n == s->len;
    memset(r, 0, sizeof *r);
    r->id = HIL_COB_SDO_TX(s->node);
    r->dlc = 8;
    r->data[0] = (uint8_t)((SCS_UPLOAD_SEGMENT << 5) | (t << 4) | ((7u - n) << 1) | (last ? 1u : 0u));
    memcpy(r->data + 1, s->buf + s->pos, n);
    s->pos += n;
    s->toggle ^= 1u;
    if (last)
        s->state = IDLE;
    return 1;
}

/* What a download can be refused for before its data are known. */
static uint32_t download_allowed(const struct hil_od_dev *d, uint16_t index, uint8_t sub, size_t *size)
{
    int exists, i = hil_od_find(d->od, index, sub, &exists);
    if (i < 0)
        return exists ? HIL_SDO_ABORT_NO_SUB : HIL_SDO_ABORT_NO_OBJECT;
    if (d->od->e[i].access != HIL_OD_RW)
        return HIL_SDO_ABORT_READ_ONLY;
    *size = hil_od_size(&d->od->e[i]);
    return 0;
}

static int initiate_download(struct hil_sdo_server *s, const struct hil_od_dev *d, const struct hil_can_frame *f,
                             uint16_t index, uint8_t sub, struct hil_can_frame *r)
{
    uint8_t c = f->data[0];
    int expedited = (c >> 1) & 1u, indicated = c & 1u;
    size_t size = 0, n;
    uint32_t ab = download_allowed(d, index, sub, &size);
    if (ab)
        return abort_with(s, r, index, sub, ab, 0);
    if (expedited) {
        n = indicated ? 4u - ((c >> 2) & 3u) : size;
        if (n != size)
            return abort_with(s, r, index, sub, HIL_SDO_ABORT_LENGTH, 0);
        if ((ab = hil_od_write(d, index, sub, f->data + 4, n)) != 0)
            return abort_with(s, r, index, sub, ab, 0);
        answer(r, s->node, SCS_INITIATE_DOWNLOAD << 5, index, sub);
        return 1;
    }
    if (indicated && hil_get_u32(f->data + 4) != size)
        return abort_with(s, r, index, sub, HIL_SDO_ABORT_LENGTH, 0);
    s->state = DOWNLOADING;
    s->index = index;
    s->sub = sub;
    s->len = size;
    s->pos = 0;
    s->toggle = 0;
    answer(r, s->node, SCS_INITIATE_DOWNLOAD << 5, index, sub);
    return 1;
}

static int download_segment(struct hil_sdo_server *s, const struct hil_od_dev *d, const struct hil_can_frame *f,
                            struct hil_can_frame *r)
{
    uint8_t c = f->data[0], t = (uint8_t)((c >> 4) & 1u);
    size_t n = 7u - ((c >> 1) & 7u);
    uint32_t ab;
    if (s->state != DOWNLOADING)
        return abort_with(s, r, 0, 0, HIL_SDO_ABORT_COMMAND, 1);
    if (t != s->toggle)
        return abort_with(s, r, s->index, s->sub, HIL_SDO_ABORT_TOGGLE, 1);
    if (s->pos + n > s->len)
        return abort_with(s, r, s->index, s->sub, HIL_SDO_ABORT_LENGTH, 0);
    memcpy(s->buf + s->pos, f->data + 1, n);
    s->pos += n;
    s->toggle ^= 1u;
    if (c & 1u) { /* last segment */
        if (s->pos != s->len)
            return abort_with(s, r, s->index, s->sub, HIL_SDO_ABORT_LENGTH, 0);
        if ((ab = hil_od_write(d, s->index, s->sub, s->buf, s->len)) != 0)
            return abort_with(s, r, s->index, s->sub, ab, 0);
        s->state = IDLE;
    }
    memset(r, 0, sizeof *r);
    r->id = HIL_COB_SDO_TX(s->node);
    r->dlc = 8;
    r->data[0] = (uint8_t)((SCS_DOWNLOAD_SEGMENT << 5) | (t << 4));
    return 1;
}

int hil_sdo_server_on_frame(struct hil_sdo_server *s, const struct hil_od_dev *d, const struct hil_can_frame *f,
                            struct hil_can_frame *resp)
{
    uint8_t ccs = (uint8_t)(f->data[0] >> 5);
    uint16_t index = hil_get_u16(f->data + 1);
    uint8_t sub = f->data[3];
    s->requests++;
    switch (ccs) {
    case CCS_INITIATE_UPLOAD:
        s->state = IDLE; /* a new request ends an unfinished transfer (CiA 301: the server follows the client) */
        return initiate_upload(s, d, index, sub, resp);
    case CCS_UPLOAD_SEGMENT:
        return upload_segment(s, f, resp);
    case CCS_INITIATE_DOWNLOAD:
        s->state = IDLE;
        return initiate_download(s, d, f, index, sub, resp);
    case CCS_DOWNLOAD_SEGMENT:
        return download_segment(s, d, f, resp);
    case CCS_ABORT:
        s->state = IDLE;
        return 0;
    default: /* 5, 6: block upload / download (not supported); 7: none */
        return abort_with(s, resp, index, sub, HIL_SDO_ABORT_COMMAND, 1);
    }
}

void hil_sdo_upload_req(struct hil_can_frame *f, uint8_t node, uint16_t index, uint8_t sub)
{
    memset(f, 0, sizeof *f);
    f->id = HIL_COB_SDO_RX(node);
    f->dlc = 8;
    f->data[0] = CCS_INITIATE_UPLOAD << 5;
    hil_put_u16(f->data + 1, index);
    f->data[3] = sub;
}

void hil_sdo_download_req(struct hil_can_frame *f, uint8_t node, uint16_t index, uint8_t sub, uint32_t v,
                          unsigned bytes)
{
    memset(f, 0, sizeof *f);
    f->id = HIL_COB_SDO_RX(node);
    f->dlc = 8;
    if (bytes < 1 || bytes > 4)
        bytes = 4;
    f->data[0] = (uint8_t)((CCS_INITIATE_DOWNLOAD << 5) | ((4u - bytes) << 2) | 0x03u);
    hil_put_u16(f->data + 1, index);
    f->data[3] = sub;
    hil_put_u32(f->data + 4, v);
    if (bytes < 4)
        memset(f->data + 4 + bytes, 0, 4u - bytes);
}

int hil_sdo_client_response(const struct hil_can_frame *f, uint16_t index, uint8_t sub, uint32_t *v,
                            uint32_t *abort)
{
    uint8_t c = f->data[0], scs = (uint8_t)(c >> 5);
    if (f->dlc != 8 || hil_get_u16(f->data + 1) != index || f->data[3] != sub)
        return HIL_E_FORMAT;
    if (scs == CS_ABORT) {
        *abort = hil_get_u32(f->data + 4);
        return HIL_E_STATE;
    }
    if (scs == SCS_INITIATE_DOWNLOAD) {
        *v = 0;
        return HIL_OK;
    }
    if (scs == SCS_INITIATE_UPLOAD && (c & 0x03u) == 0x03u) {
        size_t n = 4u - ((c >> 2) & 3u);
        uint8_t tmp[4] = {0, 0, 0, 0};
        memcpy(tmp, f->data + 4, n);
        *v = hil_get_u32(tmp);
        return HIL_OK;
    }
    return HIL_E_FORMAT;
}
