/* File helper for the CMocka tests that read a build-time fixture whole. */
#ifndef FRAC_TEST_FILE_H
#define FRAC_TEST_FILE_H
#include <stdlib.h>
#include "frac_test.h"

/* Reads the whole file `path` into a malloc'ed buffer (the caller frees
 * it); the test fails if the file is missing, empty or unreadable. */
static unsigned char *frac_test_slurp(const char *path, unsigned long *size)
{
    FILE *f = fopen(path, "rb");
    unsigned char *b;
    long n;
    if (!f)
        fail_msg("cannot open fixture %s", path);
    assert_int_equal(fseek(f, 0, SEEK_END), 0);
    n = ftell(f);
    assert_true(n > 0);
    rewind(f);
    b = malloc((size_t)n);
    assert_non_null(b);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *size = (unsigned long)n;
    return b;
}
#endif
