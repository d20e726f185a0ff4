/* libFuzzer target: the UDP bus's datagram screening (hil/transport.h).
 * Input: records of 1 length byte (0..31) and that many bytes, each sent as
 * one datagram over the loopback to a UDP transport; every datagram must
 * come out as exactly one of "frame" (then it is a valid classic frame equal
 * to the datagram's id, DLC and data) or "invalid" (counted), never a crash
 * or a frame that hil_can_frame_check refuses. */
#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>
#include "hil/transport.h"

static struct hil_transport rx;
static int tx = -1;
static struct sockaddr_in to;

/* The bus lives for the process: slot 1 of a 2-node bus; datagrams come
 * from a plain socket bound to slot 0's port. The first free pair of ports
 * from one derived from the pid (other benches may hold some). */
static void setup(void)
{
    int k;
    for (k = 0; k < 200; k++) {
        char spec[32];
        struct sockaddr_in from;
        unsigned port = 50000u + (unsigned)((getpid() + k) % 7000) * 2u;
        snprintf(spec, sizeof spec, "udp:%u:1:2", port);
        if (hil_transport_open(&rx, spec) != HIL_OK)
            continue;
        tx = socket(AF_INET, SOCK_DGRAM, 0);
        memset(&from, 0, sizeof from);
        from.sin_family = AF_INET;
        from.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        from.sin_port = htons((uint16_t)port);
        if (tx >= 0 && bind(tx, (struct sockaddr *)&from, sizeof from) == 0) {
            to = from;
            to.sin_port = htons((uint16_t)(port + 1));
            return;
        }
        if (tx >= 0)
            close(tx);
        tx = -1;
        hil_transport_close(&rx);
    }
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t i = 0;
    if (tx < 0)
        setup();
    while (i < size) {
        struct hil_can_frame f;
        uint64_t before = rx.rx_frames + rx.rx_invalid;
        size_t len = data[i++] & 31u;
        int st;
        if (len > size - i)
            len = size - i;
        if (sendto(tx, data + i, len, 0, (struct sockaddr *)&to, sizeof to) != (ssize_t)len)
            abort();
        st = hil_transport_recv(&rx, &f, 1000000);
        if (st == HIL_OK) {
            const uint8_t *d = data + i;
            uint32_t id = (uint32_t)d[0] | (uint32_t)d[1] << 8 | (uint32_t)d[2] << 16 | (uint32_t)d[3] << 24;
            if (hil_can_frame_check(&f) != HIL_OK || len != 16 || f.id != id || f.dlc != d[4] ||
                memcmp(f.data, d + 8, f.dlc) != 0)
                abort();
        } else if (st != HIL_E_FORMAT) {
            abort();
        }
        if (rx.rx_frames + rx.rx_invalid != before + 1)
            abort();
        i += len;
    }
    return 0;
}
