/* Whole-file reading (hil/file.h). */
#include <stdio.h>
#include <stdlib.h>
#include "hil/file.h"

unsigned char *hil_read_file(const char *path, unsigned long max, unsigned long *size)
{
    FILE *f = fopen(path, "rb");
    unsigned char *b = NULL;
    long n = -1;
    if (f && fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && (unsigned long)n <= max &&
        fseek(f, 0, SEEK_SET) == 0 && (b = (unsigned char *)malloc(n > 0 ? (size_t)n : 1u)) &&
        fread(b, 1, (size_t)n, f) == (size_t)n) {
        fclose(f);
        *size = (unsigned long)n;
        return b;
    }
    if (f)
        fclose(f);
    free(b);
    return NULL;
}
