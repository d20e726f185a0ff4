/* ptable.c - binary parameter table reader and validator (see frac/ptable.h). */
#include "frac/ptable.h"

#include <string.h>

#define PT_MASK32 0xFFFFFFFFUL

static unsigned long rd_u16(const unsigned char *p)
{
    return (unsigned long)p[0] | ((unsigned long)p[1] << 8);
}

static unsigned long rd_u32(const unsigned char *p)
{
    return ((unsigned long)p[0] | ((unsigned long)p[1] << 8) | ((unsigned long)p[2] << 16) |
            ((unsigned long)p[3] << 24)) & PT_MASK32;
}

/* CRC-32 of the low and the high half of a byte (reflected polynomial
 * 0xEDB88320): crc_nibble[i] is the CRC register after shifting the 4 bits
 * of i out of it, i.e. four steps of the bitwise algorithm at once. */
static const unsigned long crc_nibble[16] = {
    0x00000000UL, 0x1DB71064UL, 0x3B6E20C8UL, 0x26D930ACUL, 0x76DC4190UL, 0x6B6B51F4UL, 0x4DB26158UL, 0x5005713CUL,
    0xEDB88320UL, 0xF00F9344UL, 0xD6D6A3E8UL, 0xCB61B38CUL, 0x9B64C2B0UL, 0x86D3D2D4UL, 0xA00AE278UL, 0xBDBDF21CUL};

unsigned long frac_crc32(const unsigned char *bytes, unsigned long n)
{
    /* CRC-32 (ISO-HDLC, as zlib), reflected, two nibble-table steps per byte:
     * a 64-byte constant table instead of the 1 KiB byte table, 4 x fewer
     * steps than the bitwise form; bounded time O(n). */
    unsigned long crc = PT_MASK32, i;
    if (bytes == NULL) return 0UL;
    for (i = 0; i < n; i++) {
        crc ^= (unsigned long)bytes[i];
        crc = (crc >> 4) ^ crc_nibble[crc & 0x0FUL];
        crc = (crc >> 4) ^ crc_nibble[crc & 0x0FUL];
    }
    return (crc ^ PT_MASK32) & PT_MASK32;
}

/* Host byte order of float and double: 0 little-endian, 1 big-endian, -1 other. */
static int host_order(int f64)
{
    unsigned char b[8];
    if (f64) {
        double one = 1.0;
        if (sizeof(double) != 8) return -1;
        memcpy(b, &one, 8);
        if (b[7] == 0x3F && b[6] == 0xF0) return 0;
        if (b[0] == 0x3F && b[1] == 0xF0) return 1;
    } else {
        float one = 1.0f;
        if (sizeof(float) != 4) return -1;
        memcpy(b, &one, 4);
        if (b[3] == 0x3F && b[2] == 0x80) return 0;
        if (b[0] == 0x3F && b[1] == 0x80) return 1;
    }
    return -1;
}

/* Value v (element index) of an entry starting at byte p, as double; the
 * caller has checked the host order. */
static double rd_value(const unsigned char *p, unsigned long v, unsigned int elem_type)
{
    unsigned char b[8];
    unsigned int sz = elem_type == FRAC_PTABLE_F64 ? 8u : 4u, k;
    int big = host_order(elem_type == FRAC_PTABLE_F64);
    const unsigned char *s = p + v * sz;
    for (k = 0; k < sz; k++) b[k] = big ? s[sz - 1u - k] : s[k];
    if (sz == 8u) {
        double d;
        memcpy(&d, b, 8);
        return d;
    } else {
        float f;
        memcpy(&f, b, 4);
        return (double)f;
    }
}

/* Finite in double and, for a float frac_real, within float range. */
static int value_ok(double d)
{
    if (!(d == d) || (d - d) != 0.0) return 0;
    if (FRAC_REAL_IS_FLOAT && (d > (double)FRAC_REAL_MAX || d < -(double)FRAC_REAL_MAX)) return 0;
    return 1;
}

/* Identifier [A-Za-z_][A-Za-z0-9_]*, NUL-terminated inside len bytes, NUL-padded. */
static int name_ok(const unsigned char *p, unsigned int len)
{
    unsigned int i, end = len;
    for (i = 0; i < len; i++) {
        unsigned char c = p[i];
        if (c == 0) {
            end = i;
            break;
        }
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || (i > 0 && c >= '0' && c <= '9')))
            return 0;
    }
    if (end == 0 || end == len) return 0;
    for (i = end; i < len; i++)
        if (p[i] != 0) return 0;
    return 1;
}

static frac_status fail(frac_ptable *t, frac_status st, const char *field, long entry)
{
    t->valid = 0;
    t->fail_field = field;
    t->fail_entry = entry;
    return st;
}

frac_status frac_ptable_open(frac_ptable *t, const void *data, unsigned long size)
{
    const unsigned char *d = (const unsigned char *)data;
    unsigned long total, n, i, j, dir_end, data_end, crc;
    unsigned int version, et, esz;
    if (t == NULL) return FRAC_E_NULL;
    t->data = NULL;
    t->size = 0;
    t->version = 0;
    t->elem_type = 0;
    t->n_entries = 0;
    t->valid = 0;
    t->fail_field = "";
    t->fail_entry = -1;
    if (d == NULL) return fail(t, FRAC_E_NULL, "data", -1);
    if (size < FRAC_PTABLE_HEADER_SIZE + 4UL) return fail(t, FRAC_E_SIZE, "size", -1);
    if (d[0] != 0x46 || d[1] != 0x52 || d[2] != 0x50 || d[3] != 0x54) return fail(t, FRAC_E_MAGIC, "magic", -1);
    version = (unsigned int)rd_u16(d + 4);
    if (version != FRAC_PTABLE_VERSION) return fail(t, FRAC_E_VERSION, "version", -1);
    total = rd_u32(d + 8);
    n = rd_u32(d + 12);
    if (total > size || total < FRAC_PTABLE_HEADER_SIZE + 4UL) return fail(t, FRAC_E_SIZE, "total_size", -1);
    if (n > (total - FRAC_PTABLE_HEADER_SIZE - 4UL) / FRAC_PTABLE_ENTRY_SIZE)
        return fail(t, FRAC_E_SIZE, "n_entries", -1);
    crc = frac_crc32(d, total - 4UL);
    if (crc != rd_u32(d + total - 4UL)) return fail(t, FRAC_E_CRC, "crc32", -1);
    et = (unsigned int)rd_u16(d + 6);
    if (et != FRAC_PTABLE_F32 && et != FRAC_PTABLE_F64) return fail(t, FRAC_E_FORMAT, "elem_type", -1);
    if (host_order(et == FRAC_PTABLE_F64) < 0) return fail(t, FRAC_E_FORMAT, "host", -1);
    if (!name_ok(d + 16, FRAC_PTABLE_TABLE_NAME_LEN)) return fail(t, FRAC_E_FORMAT, "table_name", -1);
    esz = et == FRAC_PTABLE_F64 ? 8u : 4u;
    dir_end = FRAC_PTABLE_HEADER_SIZE + n * FRAC_PTABLE_ENTRY_SIZE;
    data_end = total - 4UL;
    for (i = 0; i < n; i++) {
        const unsigned char *e = d + FRAC_PTABLE_HEADER_SIZE + i * FRAC_PTABLE_ENTRY_SIZE;
        unsigned long rows = rd_u16(e + 24), cols = rd_u16(e + 26), off = rd_u32(e + 28), cnt, v;
        if (!name_ok(e, FRAC_PTABLE_NAME_LEN)) return fail(t, FRAC_E_FORMAT, "entry.name", (long)i);
        for (j = 0; j < i; j++)
            if (memcmp(e, d + FRAC_PTABLE_HEADER_SIZE + j * FRAC_PTABLE_ENTRY_SIZE, FRAC_PTABLE_NAME_LEN) == 0)
                return fail(t, FRAC_E_FORMAT, "entry.name", (long)i);
        if (rows == 0) return fail(t, FRAC_E_DIM, "entry.rows", (long)i);
        if (cols == 0) return fail(t, FRAC_E_DIM, "entry.cols", (long)i);
        if (off % 8UL != 0) return fail(t, FRAC_E_FORMAT, "entry.offset", (long)i);
        cnt = rows * cols;
        if (off < dir_end || off > data_end || cnt > (data_end - off) / esz)
            return fail(t, FRAC_E_DIM, "entry.offset", (long)i);
        for (v = 0; v < cnt; v++)
            if (!value_ok(rd_value(d + off, v, et))) return fail(t, FRAC_E_NONFINITE, "entry.values", (long)i);
    }
    t->data = d;
    t->size = total;
    t->version = version;
    t->elem_type = et;
    t->n_entries = n;
    t->valid = 1;
    return FRAC_OK;
}

frac_status frac_ptable_name(const frac_ptable *t, char *name)
{
    if (t == NULL || name == NULL) return FRAC_E_NULL;
    if (!t->valid) return FRAC_E_NOT_INIT;
    memcpy(name, t->data + 16, FRAC_PTABLE_TABLE_NAME_LEN);
    name[FRAC_PTABLE_TABLE_NAME_LEN - 1] = '\0';
    return FRAC_OK;
}

frac_status frac_ptable_entry_at(const frac_ptable *t, unsigned long i, frac_ptable_entry *e)
{
    const unsigned char *p;
    if (t == NULL || e == NULL) return FRAC_E_NULL;
    if (!t->valid) return FRAC_E_NOT_INIT;
    if (i >= t->n_entries) return FRAC_E_DIM;
    p = t->data + FRAC_PTABLE_HEADER_SIZE + i * FRAC_PTABLE_ENTRY_SIZE;
    memcpy(e->name, p, FRAC_PTABLE_NAME_LEN);
    e->rows = (unsigned int)rd_u16(p + 24);
    e->cols = (unsigned int)rd_u16(p + 26);
    e->index = i;
    return FRAC_OK;
}

frac_status frac_ptable_find(const frac_ptable *t, const char *name, frac_ptable_entry *e)
{
    unsigned long i;
    size_t len;
    if (t == NULL || name == NULL || e == NULL) return FRAC_E_NULL;
    if (!t->valid) return FRAC_E_NOT_INIT;
    len = strlen(name);
    if (len == 0 || len >= FRAC_PTABLE_NAME_LEN) return FRAC_E_NOT_FOUND;
    for (i = 0; i < t->n_entries; i++) {
        const unsigned char *p = t->data + FRAC_PTABLE_HEADER_SIZE + i * FRAC_PTABLE_ENTRY_SIZE;
        if (memcmp(p, name, len) == 0 && p[len] == 0) return frac_ptable_entry_at(t, i, e);
    }
    return FRAC_E_NOT_FOUND;
}

frac_status frac_ptable_get(const frac_ptable *t, const char *name, unsigned int rows, unsigned int cols,
                            frac_real *dst)
{
    frac_ptable_entry e;
    frac_status st;
    const unsigned char *p;
    unsigned long v, cnt;
    if (dst == NULL) return FRAC_E_NULL;
    st = frac_ptable_find(t, name, &e);
    if (st != FRAC_OK) return st;
    if (e.rows != rows || e.cols != cols) return FRAC_E_DIM;
    p = t->data + rd_u32(t->data + FRAC_PTABLE_HEADER_SIZE + e.index * FRAC_PTABLE_ENTRY_SIZE + 28);
    cnt = (unsigned long)rows * (unsigned long)cols;
    for (v = 0; v < cnt; v++) dst[v] = (frac_real)rd_value(p, v, t->elem_type);
    return FRAC_OK;
}
