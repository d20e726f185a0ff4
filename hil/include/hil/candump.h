/* The candump log format of can-utils ("candump -l"), one frame per line:
 *
 *     (1700000000.123456) vcan0 201#0F00A0860100
 *
 * time in seconds with exactly six decimals, interface name, identifier as 3
 * hex digits (standard) or 8 hex digits (extended), '#', 0..8 data bytes as
 * hex pairs. python-can, cantools and canplayer read it. RTR ("#R") and CAN FD
 * ("##") lines are rejected by the reader. */
#ifndef HIL_CANDUMP_H
#define HIL_CANDUMP_H
#include <stddef.h>
#include "hil/can.h"

#define HIL_CANDUMP_LINE_MAX 96
#define HIL_CANDUMP_IFACE_MAX 16

/* Formats one line, newline included, into buf (size n >= HIL_CANDUMP_LINE_MAX
 * is always enough). t >= 0 seconds. Returns the line length, or HIL_E_ARG,
 * HIL_E_FULL, HIL_E_DLC / HIL_E_FORMAT for an invalid frame. */
int hil_candump_format(char *buf, size_t n, double t, const char *iface,
                       const struct hil_can_frame *f);

/* Parses one line (trailing newline optional). On success fills *t, iface
 * (HIL_CANDUMP_IFACE_MAX bytes, NUL-terminated) and *f, returns HIL_OK.
 * Malformed lines give HIL_E_FORMAT (or HIL_E_DLC for more than 8 bytes);
 * the outputs are then unspecified. */
int hil_candump_parse(const char *line, double *t, char *iface, struct hil_can_frame *f);

#endif
