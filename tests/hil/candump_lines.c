/* Reads candump lines on stdin and prints, per line, what the rig's reader
 * and writer make of it (hil/candump.h), for
 * tests/hil/candump_grammar_vs_python_can.py:
 *   ok T IFACE ID EXT DLC DATA RT   T with %.9f, ID hex without the flag,
 *                                   EXT 0/1, DATA hex ("-" when empty), RT 1
 *                                   when the writer writes the frame and the
 *                                   reader reads that line back to the same
 *                                   time, interface and frame, else 0
 *   bad STATUS                      the reader refused it */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "hil/candump.h"

static int same(double t, const char *iface, const struct hil_can_frame *f)
{
    char line[HIL_CANDUMP_LINE_MAX], iface2[HIL_CANDUMP_IFACE_MAX];
    struct hil_can_frame g;
    double t2;
    if (hil_candump_format(line, sizeof line, t, iface, f) <= 0 || hil_candump_parse(line, &t2, iface2, &g) != HIL_OK)
        return 0;
    return fabs(t2 - t) <= 1e-15 * t + 5e-7 && strcmp(iface, iface2) == 0 && g.id == f->id && g.dlc == f->dlc &&
           memcmp(g.data, f->data, f->dlc) == 0;
}

int main(void)
{
    char line[512], iface[HIL_CANDUMP_IFACE_MAX];
    struct hil_can_frame f;
    double t;
    while (fgets(line, sizeof line, stdin)) {
        int st = hil_candump_parse(line, &t, iface, &f), i;
        if (st != HIL_OK) {
            printf("bad %d\n", st);
            continue;
        }
        printf("ok %.9f %s %X %d %d ", t, iface, (unsigned)(f.id & HIL_CAN_EFF_MASK),
               (f.id & HIL_CAN_EFF_FLAG) ? 1 : 0, f.dlc);
        for (i = 0; i < f.dlc; i++)
            printf("%02X", f.data[i]);
        printf("%s %d\n", f.dlc ? "" : "-", same(t, iface, &f));
    }
    return 0;
}
