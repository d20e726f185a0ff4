/* Transports: one interface, two buses carrying the same frames.
 *
 *  - "socketcan:IFACE"  a CAN_RAW socket bound to a SocketCAN interface
 *    (vcan0, can0): the production path. Frames sent by one socket are seen
 *    by every other socket on the interface, not by the sender.
 *  - "udp:PORT:SLOT:N"  a loopback stand-in for hosts whose kernel lacks
 *    AF_CAN: N nodes, node SLOT (0..N-1) binds 127.0.0.1:PORT+SLOT and sends
 *    each frame to the N-1 other ports, so every node except the sender sees
 *    it, as on a bus. A datagram is exactly the 16-byte Linux struct
 *    can_frame (id u32, len u8, 3 pad bytes, 8 data bytes; little endian).
 *
 * Every received frame is validated (hil_can_frame_check, datagram size,
 * loopback source) before it is returned; invalid ones are counted in
 * rx_invalid and reported as HIL_E_FORMAT, the transport stays usable.
 * Receive queues are enlarged to HIL_RX_BUFFER bytes (SO_RCVBUFFORCE when
 * permitted, else SO_RCVBUF up to the system limit) so a logger that is
 * scheduled out does not lose frames; what the kernel still drops is counted
 * in rx_dropped (SO_RXQ_OVFL). The caller owns the struct; no allocation. */
#ifndef HIL_TRANSPORT_H
#define HIL_TRANSPORT_H
#include <stdint.h>
#include "hil/can.h"

#define HIL_UDP_MAX_NODES 16
#define HIL_UDP_DATAGRAM 16
#define HIL_RX_BUFFER (8 * 1024 * 1024)

enum hil_transport_kind { HIL_TRANSPORT_SOCKETCAN = 1, HIL_TRANSPORT_UDP = 2 };

struct hil_transport {
    enum hil_transport_kind kind;
    int fd;
    char name[32];          /* interface name written to candump logs */
    uint16_t udp_port_base; /* udp only */
    uint8_t udp_slot, udp_nodes;
    uint64_t tx_frames, rx_frames, rx_invalid, tx_errors;
    uint64_t rx_dropped; /* frames the kernel dropped on a full receive queue (SO_RXQ_OVFL) */
};

/* Opens the transport described by spec (see above).
 * Returns HIL_OK; HIL_E_ARG for a malformed spec; HIL_E_UNSUPPORTED when the
 * kernel has no AF_CAN; HIL_E_IO when the interface or port is unavailable. */
int hil_transport_open(struct hil_transport *t, const char *spec);

/* Sends one frame (validated first: HIL_E_DLC / HIL_E_FORMAT without sending).
 * Non-blocking on UDP; on SocketCAN a full device queue is retried for at most
 * 10 ms, then HIL_E_IO. Returns HIL_OK or a negative code. */
int hil_transport_send(struct hil_transport *t, const struct hil_can_frame *f);

/* Receives one frame, waiting at most timeout_us (0: poll, <0: forever).
 * Returns HIL_OK with *f filled, HIL_E_TIMEOUT, HIL_E_FORMAT (an invalid
 * frame was received, counted and dropped) or HIL_E_IO. */
int hil_transport_recv(struct hil_transport *t, struct hil_can_frame *f, long timeout_us);

/* Closes the socket; safe to call twice. */
void hil_transport_close(struct hil_transport *t);

#endif
