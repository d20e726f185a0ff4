/* libFuzzer target: the scenario parser (hil/rig.h). The input is a scenario
 * file; a file the parser accepts must write back (hil_rig_config_write) to
 * a file that loads to a configuration writing the same text (the writer's
 * %.17g loads back bit for bit), and hil_rig_init must take or refuse it
 * with a reason, never crash. Scenarios naming table files are not
 * initialised (the fuzzer would open arbitrary paths). */
#define _GNU_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>
#include "hil/rig.h"

/* The text of c as a scenario file, in buf (size cap); its length. */
static size_t written(const struct hil_rig_config *c, char *buf, size_t cap)
{
    FILE *f = fmemopen(buf, cap, "w");
    long n;
    if (!f || hil_rig_config_write(c, f) != HIL_OK)
        abort();
    n = ftell(f);
    fclose(f);
    return (size_t)n;
}

static int load(int fd, const void *text, size_t n, struct hil_rig_config *c)
{
    char path[64];
    int line;
    if (ftruncate(fd, 0) != 0 || pwrite(fd, text, n, 0) != (ssize_t)n)
        abort();
    snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    hil_rig_config_default(c);
    return hil_rig_config_load(c, path, &line);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int fd = -1;
    static struct hil_rig rig;
    static char a[65536], b[65536];
    struct hil_rig_config c, c2;
    size_t na, nb;
    if (fd < 0 && (fd = memfd_create("scenario", 0)) < 0)
        abort();
    if (size > 8192 || load(fd, data, size, &c) != HIL_OK)
        return 0;
    na = written(&c, a, sizeof a);
    if (load(fd, a, na, &c2) != HIL_OK)
        abort();
    nb = written(&c2, b, sizeof b);
    if (na != nb || memcmp(a, b, na) != 0)
        abort();
    if (c.plant_p.table[0] || c.ctrl_table[0])
        return 0;
    if (hil_rig_init(&rig, &c, NULL, NULL) != HIL_OK && !rig.err[0])
        abort();
    return 0;
}
