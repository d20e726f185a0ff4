/* Test helper: writes a binary parameter table in the layout of
 * frac/ptable.h (version 1, float64 values, little-endian, CRC-32 trailer),
 * so the tests can hand ParTable and ArmCtrl good and corrupted tables. */
#ifndef PTABLE_WRITER_H
#define PTABLE_WRITER_H

#include "frac/ptable.h"

#include <string.h>

typedef struct ptw_entry {
    const char *name;
    unsigned rows, cols;
    const double *values; /* rows * cols, row-major */
} ptw_entry;

static void ptw_u16(unsigned char *p, unsigned long v)
{
    p[0] = (unsigned char)(v & 0xFF);
    p[1] = (unsigned char)((v >> 8) & 0xFF);
}

static void ptw_u32(unsigned char *p, unsigned long v)
{
    ptw_u16(p, v & 0xFFFF);
    ptw_u16(p + 2, (v >> 16) & 0xFFFF);
}

/* Stores the CRC-32 of everything before the last 4 bytes in them. */
static void ptw_seal(unsigned char *buf, unsigned long size)
{
    ptw_u32(buf + size - 4, frac_crc32(buf, size - 4));
}

/* Writes the table into buf (cap bytes); returns its size, 0 if it does not fit. */
static unsigned long ptw_write(unsigned char *buf, unsigned long cap, const char *table_name, const ptw_entry *e,
                               unsigned n)
{
    unsigned long off = FRAC_PTABLE_HEADER_SIZE + (unsigned long)n * FRAC_PTABLE_ENTRY_SIZE, size;
    unsigned i;
    unsigned long k;
    size = off;
    for (i = 0; i < n; i++) {
        size += 8ul * e[i].rows * e[i].cols;
    }
    size += 4;
    if (size > cap) {
        return 0;
    }
    memset(buf, 0, size);
    memcpy(buf, "FRPT", 4);
    ptw_u16(buf + 4, FRAC_PTABLE_VERSION);
    ptw_u16(buf + 6, FRAC_PTABLE_F64);
    ptw_u32(buf + 8, size);
    ptw_u32(buf + 12, n);
    strncpy((char *)buf + 16, table_name, FRAC_PTABLE_TABLE_NAME_LEN - 1);
    for (i = 0; i < n; i++) {
        unsigned char *d = buf + FRAC_PTABLE_HEADER_SIZE + (unsigned long)i * FRAC_PTABLE_ENTRY_SIZE;
        strncpy((char *)d, e[i].name, FRAC_PTABLE_NAME_LEN - 1);
        ptw_u16(d + 24, e[i].rows);
        ptw_u16(d + 26, e[i].cols);
        ptw_u32(d + 28, off);
        for (k = 0; k < (unsigned long)e[i].rows * e[i].cols; k++) {
            unsigned char b[8];
            int j;
            double v = e[i].values[k];
            memcpy(b, &v, 8); /* the test hosts are little-endian (ptable checks at run time) */
            for (j = 0; j < 8; j++) {
                buf[off + 8 * k + (unsigned long)j] = b[j];
            }
        }
        off += 8ul * e[i].rows * e[i].cols;
    }
    ptw_seal(buf, size);
    return size;
}

#endif /* PTABLE_WRITER_H */
