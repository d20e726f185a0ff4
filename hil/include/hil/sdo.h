/* SDO (CiA 301 sec. 7.2.4): the server of an emulated device and the frame
 * codec the controller's client uses.
 *
 * Server: the default SDO channel, requests on 0x600 + node, responses on
 * 0x580 + node, every frame 8 bytes (a request of another length is counted
 * bad_dlc by the dictionary check and not answered). Services: expedited
 * and segmented upload and download (segments of 7 bytes with the toggle
 * bit); block transfer and unknown command specifiers are answered with
 * abort 0x05040001, a segment out of sequence with 0x05040001 and a wrong
 * toggle bit with 0x05030000 (the transfer ends); an abort from the client
 * ends the transfer without answer. A download's indicated size must be the
 * object's (0x06070010); the object's access rules are hil_od_write's. A
 * segmented download collects at most HIL_SDO_BUF bytes (a longer one:
 * 0x06070010). The server answers only in pre-operational and operational
 * (CiA 301: no SDO in stopped). One request, at most one response: bounded
 * time, no allocation. */
#ifndef HIL_SDO_H
#define HIL_SDO_H
#include "hil/can.h"
#include "hil/od.h"

#define HIL_COB_SDO_TX(n) (0x580u + (n)) /* server -> client */
#define HIL_COB_SDO_RX(n) (0x600u + (n)) /* client -> server */
#define HIL_SDO_BUF 64

struct hil_sdo_server {
    uint8_t node;
    int state;          /* 0 idle, 1 segmented upload, 2 segmented download */
    uint16_t index;
    uint8_t sub;
    uint8_t toggle;
    uint8_t buf[HIL_SDO_BUF];
    size_t len, pos;
    uint64_t requests, aborts, protocol_errors;
    uint32_t last_abort;
};

void hil_sdo_server_init(struct hil_sdo_server *s, uint8_t node);

/* Handles request f (identifier 0x600 + node, DLC 8, screened by the
 * caller) against dictionary d; *resp receives the response. Returns 1 when
 * a response is to be sent, 0 when none (client abort), and -1 when the
 * request broke the protocol (an abort response is still in *resp). */
int hil_sdo_server_on_frame(struct hil_sdo_server *s, const struct hil_od_dev *d, const struct hil_can_frame *f,
                            struct hil_can_frame *resp);

/* Client side, expedited only (values of 1..4 bytes). */
void hil_sdo_upload_req(struct hil_can_frame *f, uint8_t node, uint16_t index, uint8_t sub);
void hil_sdo_download_req(struct hil_can_frame *f, uint8_t node, uint16_t index, uint8_t sub, uint32_t v,
                          unsigned bytes);
/* Decodes a server response to (index, sub): HIL_OK with *v (expedited
 * upload value, 0 for a download confirmation), HIL_E_STATE with *abort set
 * when the server aborted, HIL_E_FORMAT when it is not an answer to that
 * request (other object, segmented, unknown command). */
int hil_sdo_client_response(const struct hil_can_frame *f, uint16_t index, uint8_t sub, uint32_t *v,
                            uint32_t *abort);

#endif
