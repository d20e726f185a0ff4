/* What every emulated node shares: the output buffer a handler fills, the
 * receive counters, and the validation of a bus frame against the rig's
 * frame dictionary (hil/canopen.h) before any node looks at its content.
 *
 * A node is a plain struct owned by the caller. Its handler
 * `hil_xxx_on_frame(node, frame, out)` consumes one received frame and appends
 * the frames it must send to `out`; it never blocks, allocates or prints.
 * Frames that fail validation are counted and ignored, the handler returns
 * the negative code and the node state is untouched. */
#ifndef HIL_NODE_H
#define HIL_NODE_H
#include <stdint.h>
#include "hil/can.h"

#define HIL_OUT_MAX 16

struct hil_out {
    struct hil_can_frame f[HIL_OUT_MAX];
    int n;
};

struct hil_rx_stats {
    uint64_t accepted;   /* valid frames this node consumed */
    uint64_t other;      /* valid frames of the dictionary meant for other nodes */
    uint64_t unknown_id; /* identifiers not in the rig's dictionary */
    uint64_t bad_dlc;    /* known identifier, wrong length */
    uint64_t bad_value;  /* right length, content invalid (NaN, bad NMT command, ...) */
};

/* Appends f; HIL_E_FULL when the buffer already holds HIL_OUT_MAX frames. */
int hil_out_push(struct hil_out *out, const struct hil_can_frame *f);

/* Checks f against the dictionary: HIL_OK when its identifier is one of the
 * rig's and its DLC the one that identifier requires; HIL_E_UNKNOWN_ID,
 * HIL_E_DLC or HIL_E_FORMAT otherwise. */
int hil_dict_check(const struct hil_can_frame *f);

/* Runs hil_dict_check and counts a failure in s (unknown_id / bad_dlc /
 * bad_value). Returns the check's status. */
int hil_rx_screen(struct hil_rx_stats *s, const struct hil_can_frame *f);

/* NMT node control (CiA 301) for node `self`, after hil_rx_screen: decodes f,
 * counts it in s (bad_value for an invalid command, other when addressed to
 * another node, accepted otherwise) and applies start, stop and
 * pre-operational to *state. A reset command leaves *state alone and sets
 * *reset = 1: the node resets itself, sends its boot-up heartbeat and enters
 * pre-operational. Returns HIL_OK, HIL_E_FORMAT or HIL_E_UNKNOWN_ID. */
int hil_nmt_on_frame(struct hil_rx_stats *s, const struct hil_can_frame *f, uint8_t self, uint8_t *state,
                     int *reset);

#endif
