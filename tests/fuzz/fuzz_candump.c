/* libFuzzer target: the candump reader (hil/candump.h). Any input is one
 * line; the reader must not crash, and whatever it reads the writer must
 * write and the reader read back to the same time, interface and frame (one
 * grammar for both). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "hil/candump.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char line[256], out[HIL_CANDUMP_LINE_MAX], iface[HIL_CANDUMP_IFACE_MAX], iface2[HIL_CANDUMP_IFACE_MAX];
    struct hil_can_frame f, g;
    double t, t2;
    if (size >= sizeof line)
        return 0;
    memcpy(line, data, size);
    line[size] = '\0';
    if (hil_candump_parse(line, &t, iface, &f) != HIL_OK)
        return 0;
    if (hil_candump_format(out, sizeof out, t, iface, &f) <= 0 || hil_candump_parse(out, &t2, iface2, &g) != HIL_OK ||
        strcmp(iface, iface2) != 0 || g.id != f.id || g.dlc != f.dlc || memcmp(g.data, f.data, f.dlc) != 0 ||
        !(fabs(t2 - t) <= 1e-15 * t + 5e-7))
        abort();
    return 0;
}
