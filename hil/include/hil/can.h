/* CAN frame type and the status codes shared by the whole rig.
 *
 * A frame is a classic CAN 2.0 data frame (no CAN FD, no RTR): an 11-bit
 * (standard) or 29-bit (extended, HIL_CAN_EFF_FLAG set) identifier, a length
 * 0..8 and up to 8 data bytes. The identifier flag bits are those of Linux
 * struct can_frame so SocketCAN frames convert without translation.
 *
 * Every function of the rig that can fail returns a status: 0 on success, a
 * negative HIL_E_* code on error. Nothing asserts or aborts on bad input. */
#ifndef HIL_CAN_H
#define HIL_CAN_H
#include <stdint.h>

#define HIL_CAN_EFF_FLAG 0x80000000u /* extended 29-bit identifier */
#define HIL_CAN_RTR_FLAG 0x40000000u /* remote frame (rejected by the rig) */
#define HIL_CAN_ERR_FLAG 0x20000000u /* error frame (rejected by the rig) */
#define HIL_CAN_SFF_MASK 0x000007FFu
#define HIL_CAN_EFF_MASK 0x1FFFFFFFu
#define HIL_CAN_MAX_DLC 8

struct hil_can_frame {
    uint32_t id;     /* identifier, plus HIL_CAN_EFF_FLAG for 29-bit ids */
    uint8_t dlc;     /* 0..8 */
    uint8_t data[HIL_CAN_MAX_DLC];
};

enum hil_status {
    HIL_OK = 0,
    HIL_E_ARG = -1,         /* NULL pointer or parameter out of its documented range */
    HIL_E_DLC = -2,         /* frame length not the one its identifier requires */
    HIL_E_UNKNOWN_ID = -3,  /* identifier not handled by this node */
    HIL_E_FORMAT = -4,      /* malformed frame, datagram or log line */
    HIL_E_IO = -5,          /* operating-system call failed (errno kept) */
    HIL_E_TIMEOUT = -6,     /* nothing received within the timeout */
    HIL_E_UNSUPPORTED = -7, /* e.g. the kernel lacks AF_CAN */
    HIL_E_RANGE = -8,       /* value not finite or not representable on the wire */
    HIL_E_FULL = -9,        /* caller-owned buffer too small */
    HIL_E_STATE = -10       /* valid frame, not acceptable in the current state */
};

/* Name of a status code ("ok", "wrong DLC", ...); never NULL. */
const char *hil_status_str(int status);

/* Checks that f is a classic data frame: dlc <= 8, no RTR/error flag, the
 * identifier within 11 bits (or 29 bits with HIL_CAN_EFF_FLAG).
 * Returns HIL_OK, HIL_E_ARG for NULL, HIL_E_DLC or HIL_E_FORMAT. */
int hil_can_frame_check(const struct hil_can_frame *f);

/* Little-endian field access, the CANopen byte order. No bounds checks:
 * callers check the DLC first. */
uint16_t hil_get_u16(const uint8_t *p);
uint32_t hil_get_u32(const uint8_t *p);
void hil_put_u16(uint8_t *p, uint16_t v);
void hil_put_u32(uint8_t *p, uint32_t v);
float hil_get_f32(const uint8_t *p);
void hil_put_f32(uint8_t *p, float v);

#endif
