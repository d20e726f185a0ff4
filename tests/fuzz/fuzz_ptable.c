/* libFuzzer target: the binary parameter table reader (frac/ptable.h). A
 * table that opens must give every entry of its directory by index and by
 * name, and copy each one out (frac_ptable_get) with finite values. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "frac/ptable.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static frac_real buf[1u << 16];
    frac_ptable t;
    unsigned long i;
    if (frac_ptable_open(&t, data, (unsigned long)size) != FRAC_OK) {
        if (t.valid || !t.fail_field || !t.fail_field[0])
            abort();
        return 0;
    }
    for (i = 0; i < t.n_entries; i++) {
        frac_ptable_entry e, e2;
        unsigned long k, n;
        if (frac_ptable_entry_at(&t, i, &e) != FRAC_OK || frac_ptable_find(&t, e.name, &e2) != FRAC_OK ||
            e2.index != i || e2.rows != e.rows || e2.cols != e.cols)
            abort();
        n = (unsigned long)e.rows * e.cols;
        if (n > sizeof buf / sizeof buf[0])
            continue;
        if (frac_ptable_get(&t, e.name, e.rows, e.cols, buf) != FRAC_OK)
            abort();
        for (k = 0; k < n; k++)
            if (!FRAC_ISFINITE(buf[k]))
                abort();
    }
    return 0;
}
