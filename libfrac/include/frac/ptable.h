/*
 * ptable.h - reader and validator of the binary parameter table ("FRPT") that
 * fracdesign emits and the PLC loads as a data object at _INIT.
 *
 * Layout (docs/param_table_format.md, version 1), all integers little-endian:
 *   off  0  magic "FRPT" (0x46 0x52 0x50 0x54)
 *   off  4  u16 version (= 1)
 *   off  6  u16 element type: 1 = IEEE-754 float32, 2 = IEEE-754 float64 (little-endian)
 *   off  8  u32 total size in bytes, CRC trailer included
 *   off 12  u32 number of entries
 *   off 16  char[32] table name, NUL-padded
 *   off 48  entry directory, 32 bytes per entry:
 *             char[24] name (C/IEC identifier, NUL-padded), u16 rows, u16 cols,
 *             u32 byte offset of the first value from the start of the table
 *   then    values, row-major, each entry starting on an 8-byte boundary
 *   last 4  u32 CRC-32 (IEEE 802.3: reflected polynomial 0xEDB88320, initial
 *           value and final xor 0xFFFFFFFF) of every byte before it
 *
 * frac_ptable_open validates the whole table once, in this order, and returns
 * the first failure: FRAC_E_NULL, FRAC_E_SIZE (shorter than a header, total
 * size larger than the buffer or too small for the directory), FRAC_E_MAGIC,
 * FRAC_E_VERSION, FRAC_E_CRC, FRAC_E_FORMAT (element type, entry name not an
 * identifier or duplicated, offset misaligned), FRAC_E_DIM (rows or cols zero,
 * values outside the data area), FRAC_E_NONFINITE (a NaN/Inf value, or a
 * float64 value out of range of a float frac_real). The failing field is left
 * in fail_field ("magic", "version", "crc32", "entry.rows", ...) and the entry
 * index in fail_entry (-1 for the header), so a refusal names what failed.
 * The table bytes stay owned by the caller and must outlive the handle; no
 * memory is allocated. Time: O(size) for open, O(entries) for a lookup.
 * Host byte order is detected at run time; hosts whose doubles are neither
 * little- nor big-endian are refused with FRAC_E_FORMAT (field "host").
 */
#ifndef FRAC_PTABLE_H
#define FRAC_PTABLE_H

#include "frac/frac_types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FRAC_PTABLE_VERSION 1
#define FRAC_PTABLE_HEADER_SIZE 48
#define FRAC_PTABLE_ENTRY_SIZE 32
#define FRAC_PTABLE_NAME_LEN 24       /* entry name field, NUL included */
#define FRAC_PTABLE_TABLE_NAME_LEN 32 /* table name field, NUL included */
#define FRAC_PTABLE_F32 1
#define FRAC_PTABLE_F64 2

typedef struct frac_ptable {
    const unsigned char *data; /* caller's bytes */
    unsigned long size;        /* total size from the header */
    unsigned int version;
    unsigned int elem_type;    /* FRAC_PTABLE_F32 or FRAC_PTABLE_F64 */
    unsigned long n_entries;
    int valid;                 /* 1 after a successful open */
    const char *fail_field;    /* field that failed validation, "" when valid */
    long fail_entry;           /* entry index of the failure, -1 for the header */
} frac_ptable;

typedef struct frac_ptable_entry {
    char name[FRAC_PTABLE_NAME_LEN];
    unsigned int rows;
    unsigned int cols;
    unsigned long index; /* position in the directory */
} frac_ptable_entry;

/* CRC-32 (IEEE 802.3, reflected, init/xorout 0xFFFFFFFF) of n bytes; the
 * value of "123456789" is 0xCBF43926. */
unsigned long frac_crc32(const unsigned char *bytes, unsigned long n);

/* Validates `size` bytes at `data` (see above) and, on FRAC_OK, makes t a
 * handle on them. On failure t->valid = 0 and fail_field/fail_entry say why. */
frac_status frac_ptable_open(frac_ptable *t, const void *data, unsigned long size);

/* Table name (copied, NUL-terminated) into name[FRAC_PTABLE_TABLE_NAME_LEN]. */
frac_status frac_ptable_name(const frac_ptable *t, char *name);

/* Entry i of the directory. FRAC_E_NOT_INIT, FRAC_E_NULL, FRAC_E_DIM (i out of range). */
frac_status frac_ptable_entry_at(const frac_ptable *t, unsigned long i, frac_ptable_entry *e);

/* Entry by name. FRAC_E_NOT_FOUND when absent. */
frac_status frac_ptable_find(const frac_ptable *t, const char *name, frac_ptable_entry *e);

/* Copies entry `name` into dst[rows*cols] (row-major, converted to frac_real)
 * after checking that its dimensions are exactly rows x cols (FRAC_E_DIM
 * otherwise, dst untouched). FRAC_E_NOT_FOUND, FRAC_E_NOT_INIT, FRAC_E_NULL. */
frac_status frac_ptable_get(const frac_ptable *t, const char *name, unsigned int rows, unsigned int cols,
                            frac_real *dst);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_PTABLE_H */
