/* The candump log format of can-utils ("candump -l"), one frame per line:
 *
 *     (1700000000.123456) vcan0 201#0F00A0860100
 *
 * One grammar for the writer and the reader (a line is read exactly when it
 * is one the writer could have written, up to letter case and the padding of
 * the seconds):
 *
 *     line   = "(" sec "." usec ")" " " iface " " id "#" data [CR] [LF]
 *     sec    = 1*16 DIGIT          sec + usec / 10^6 <= HIL_CANDUMP_T_MAX
 *     usec   = 6 DIGIT
 *     iface  = 1*15 (%x21-7E but "(", ")", "#")   graphic ASCII
 *     id     = 3 HEXDIG (<= 7FF, standard) / 8 HEXDIG (<= 1FFFFFFF, extended)
 *     data   = 0*8 (2 HEXDIG)
 *
 * The writer emits seconds zero-padded to at least 10 digits (candump's
 * %010ld), upper-case hex and LF. python-can (can.io.CanutilsLogReader),
 * cantools and canplayer read it; python-can reads more (RTR "#R", CAN FD
 * "##", error frames, a trailing rx/tx flag, any float time): those lines
 * are not frames of this rig and the reader refuses them
 * (tests/hil/candump_grammar_vs_python_can.py checks both readers on the
 * same lines). */
#ifndef HIL_CANDUMP_H
#define HIL_CANDUMP_H
#include <stddef.h>
#include "hil/can.h"

#define HIL_CANDUMP_LINE_MAX 96
#define HIL_CANDUMP_IFACE_MAX 16
#define HIL_CANDUMP_T_MAX 9.0e15 /* seconds; below 2^53, so the seconds are exact in a double */

/* Formats one line, newline included, into buf (size n >= HIL_CANDUMP_LINE_MAX
 * is always enough). 0 <= t <= HIL_CANDUMP_T_MAX seconds, iface as the grammar's.
 * Returns the line length, or HIL_E_ARG,
 * HIL_E_FULL, HIL_E_DLC / HIL_E_FORMAT for an invalid frame. */
int hil_candump_format(char *buf, size_t n, double t, const char *iface,
                       const struct hil_can_frame *f);

/* Parses one line (trailing newline optional). On success fills *t, iface
 * (HIL_CANDUMP_IFACE_MAX bytes, NUL-terminated) and *f, returns HIL_OK.
 * Malformed lines give HIL_E_FORMAT (or HIL_E_DLC for more than 8 bytes);
 * the outputs are then unspecified. */
int hil_candump_parse(const char *line, double *t, char *iface, struct hil_can_frame *f);

#endif
