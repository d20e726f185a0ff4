/* SocketCAN and UDP-loopback transports; contract in hil/transport.h. */
#define _GNU_SOURCE
#include <arpa/inet.h>
#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <time.h>
#include <unistd.h>
#include "hil/transport.h"

/* The UDP datagram is the Linux struct can_frame image; keep them in step. */
_Static_assert(sizeof(struct can_frame) == HIL_UDP_DATAGRAM, "can_frame is 16 bytes");
_Static_assert(CAN_EFF_FLAG == HIL_CAN_EFF_FLAG && CAN_RTR_FLAG == HIL_CAN_RTR_FLAG &&
               CAN_ERR_FLAG == HIL_CAN_ERR_FLAG, "identifier flags match Linux");

static int parse_uint(const char *s, char **end, unsigned long max, unsigned long *out)
{
    unsigned long v;
    if (*s < '0' || *s > '9')
        return HIL_E_ARG;
    errno = 0;
    v = strtoul(s, end, 10);
    if (errno || v > max)
        return HIL_E_ARG;
    *out = v;
    return HIL_OK;
}

/* Larger receive queue and the kernel's drop counter; both best effort (a
 * kernel without them still carries frames). */
static void tune_rx(int fd)
{
    int size = HIL_RX_BUFFER, on = 1;
    if (setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &size, sizeof size) != 0)
        (void)setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &size, sizeof size);
    (void)setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on);
}

static int open_socketcan(struct hil_transport *t, const char *ifname)
{
    struct sockaddr_can addr;
    unsigned idx;
    int fd;
    if (!*ifname || strlen(ifname) >= IFNAMSIZ || strlen(ifname) >= sizeof t->name)
        return HIL_E_ARG;
    fd = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0)
        return (errno == EAFNOSUPPORT || errno == EPROTONOSUPPORT) ? HIL_E_UNSUPPORTED : HIL_E_IO;
    idx = if_nametoindex(ifname);
    if (idx == 0) {
        close(fd);
        return HIL_E_IO;
    }
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    addr.can_ifindex = (int)idx;
    if (bind(fd, (struct sockaddr *)&addr, sizeof addr) < 0) {
        close(fd);
        return HIL_E_IO;
    }
    tune_rx(fd);
    t->kind = HIL_TRANSPORT_SOCKETCAN;
    t->fd = fd;
    strcpy(t->name, ifname);
    return HIL_OK;
}

static void udp_addr(struct sockaddr_in *a, unsigned port)
{
    memset(a, 0, sizeof *a);
    a->sin_family = AF_INET;
    a->sin_port = htons((uint16_t)port);
    a->sin_addr.s_addr = htonl(INADDR_LOOPBACK);
}

static int open_udp(struct hil_transport *t, const char *spec)
{
    unsigned long port, slot, nodes;
    char *end;
    struct sockaddr_in a;
    int fd;
    if (parse_uint(spec, &end, 65535, &port) || *end != ':' ||
        parse_uint(end + 1, &end, HIL_UDP_MAX_NODES - 1, &slot) || *end != ':' ||
        parse_uint(end + 1, &end, HIL_UDP_MAX_NODES, &nodes) || *end != '\0')
        return HIL_E_ARG;
    if (nodes < 2 || slot >= nodes || port < 1024 || port + nodes - 1 > 65535)
        return HIL_E_ARG;
    fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return HIL_E_IO;
    udp_addr(&a, (unsigned)(port + slot));
    if (bind(fd, (struct sockaddr *)&a, sizeof a) < 0) {
        close(fd);
        return HIL_E_IO;
    }
    tune_rx(fd);
    t->kind = HIL_TRANSPORT_UDP;
    t->fd = fd;
    t->udp_port_base = (uint16_t)port;
    t->udp_slot = (uint8_t)slot;
    t->udp_nodes = (uint8_t)nodes;
    snprintf(t->name, sizeof t->name, "udp%lu", port);
    return HIL_OK;
}

int hil_transport_open(struct hil_transport *t, const char *spec)
{
    if (!t || !spec)
        return HIL_E_ARG;
    memset(t, 0, sizeof *t);
    t->fd = -1;
    if (strncmp(spec, "socketcan:", 10) == 0)
        return open_socketcan(t, spec + 10);
    if (strncmp(spec, "udp:", 4) == 0)
        return open_udp(t, spec + 4);
    return HIL_E_ARG;
}

static void to_linux(struct can_frame *lf, const struct hil_can_frame *f)
{
    memset(lf, 0, sizeof *lf);
    lf->can_id = f->id;
    lf->len = f->dlc;
    memcpy(lf->data, f->data, f->dlc);
}

static void encode_datagram(uint8_t *d, const struct hil_can_frame *f)
{
    memset(d, 0, HIL_UDP_DATAGRAM);
    hil_put_u32(d, f->id);
    d[4] = f->dlc;
    memcpy(d + 8, f->data, f->dlc);
}

int hil_transport_send(struct hil_transport *t, const struct hil_can_frame *f)
{
    int st;
    if (!t || !f || t->fd < 0)
        return HIL_E_ARG;
    st = hil_can_frame_check(f);
    if (st != HIL_OK)
        return st;
    if (t->kind == HIL_TRANSPORT_SOCKETCAN) {
        struct can_frame lf;
        int tries;
        to_linux(&lf, f);
        /* A vcan/can device queue can be momentarily full (ENOBUFS); a
         * bounded retry keeps send() bounded at about 10 ms. */
        for (tries = 0; tries < 100; tries++) {
            if (write(t->fd, &lf, sizeof lf) == (ssize_t)sizeof lf) {
                t->tx_frames++;
                return HIL_OK;
            }
            if (errno != ENOBUFS && errno != EAGAIN && errno != EINTR)
                break;
            {
                struct timespec ts = {0, 100000};
                nanosleep(&ts, NULL);
            }
        }
        t->tx_errors++;
        return HIL_E_IO;
    } else {
        uint8_t d[HIL_UDP_DATAGRAM];
        unsigned i;
        int failed = 0;
        encode_datagram(d, f);
        for (i = 0; i < t->udp_nodes; i++) {
            struct sockaddr_in a;
            if (i == t->udp_slot)
                continue;
            udp_addr(&a, t->udp_port_base + i);
            /* A peer that is not (yet) listening is a node missing from
             * the bus, not a send error: unconnected UDP does not report it. */
            if (sendto(t->fd, d, sizeof d, 0, (struct sockaddr *)&a, sizeof a) != (ssize_t)sizeof d)
                failed = 1;
        }
        if (failed) {
            t->tx_errors++;
            return HIL_E_IO;
        }
        t->tx_frames++;
        return HIL_OK;
    }
}

/* ppoll, not poll: the timeout keeps microseconds, which the real-time
 * controller loop needs at T = 1.2 ms. */
static int wait_readable(int fd, long timeout_us)
{
    struct pollfd p;
    struct timespec ts, *tp = NULL;
    int r;
    if (timeout_us >= 0) {
        ts.tv_sec = timeout_us / 1000000;
        ts.tv_nsec = (timeout_us % 1000000) * 1000;
        tp = &ts;
    }
    p.fd = fd;
    p.events = POLLIN;
    p.revents = 0;
    do {
        r = ppoll(&p, 1, tp, NULL);
    } while (r < 0 && errno == EINTR);
    if (r < 0)
        return HIL_E_IO;
    return r == 0 ? HIL_E_TIMEOUT : HIL_OK;
}

int hil_transport_recv(struct hil_transport *t, struct hil_can_frame *f, long timeout_us)
{
    uint8_t d[HIL_UDP_DATAGRAM + 1];
    ssize_t n;
    int st;
    if (!t || !f || t->fd < 0)
        return HIL_E_ARG;
    st = wait_readable(t->fd, timeout_us);
    if (st != HIL_OK)
        return st;
    {
        struct can_frame lf;
        struct sockaddr_in src;
        struct iovec iov;
        struct msghdr msg;
        struct cmsghdr *cm;
        union {
            char buf[CMSG_SPACE(sizeof(uint32_t))];
            struct cmsghdr align;
        } ctl;
        memset(&msg, 0, sizeof msg);
        memset(&src, 0, sizeof src);
        if (t->kind == HIL_TRANSPORT_SOCKETCAN) {
            iov.iov_base = &lf;
            iov.iov_len = sizeof lf;
        } else {
            iov.iov_base = d;
            iov.iov_len = sizeof d;
            msg.msg_name = &src;
            msg.msg_namelen = sizeof src;
        }
        msg.msg_iov = &iov;
        msg.msg_iovlen = 1;
        msg.msg_control = ctl.buf;
        msg.msg_controllen = sizeof ctl.buf;
        n = recvmsg(t->fd, &msg, 0);
        if (n < 0)
            return (errno == EAGAIN || errno == EINTR) ? HIL_E_TIMEOUT : HIL_E_IO;
        for (cm = CMSG_FIRSTHDR(&msg); cm; cm = CMSG_NXTHDR(&msg, cm)) {
            if (cm->cmsg_level == SOL_SOCKET && cm->cmsg_type == SO_RXQ_OVFL) {
                uint32_t drops;
                memcpy(&drops, CMSG_DATA(cm), sizeof drops);
                t->rx_dropped = drops; /* the kernel's cumulative count */
            }
        }
        if (t->kind == HIL_TRANSPORT_SOCKETCAN) {
            if (n != (ssize_t)sizeof lf || lf.len > CAN_MAX_DLEN) {
                t->rx_invalid++;
                return HIL_E_FORMAT;
            }
            f->id = lf.can_id;
            f->dlc = lf.len;
            memset(f->data, 0, sizeof f->data);
            memcpy(f->data, lf.data, lf.len);
        } else {
            /* Only datagrams of exactly one frame from the loopback net, with
             * zero padding, are frames of this bus. */
            if (n != HIL_UDP_DATAGRAM || msg.msg_namelen != sizeof src || src.sin_family != AF_INET ||
                (ntohl(src.sin_addr.s_addr) >> 24) != 127 || d[5] || d[6] || d[7] || d[4] > 8) {
                t->rx_invalid++;
                return HIL_E_FORMAT;
            }
            f->id = hil_get_u32(d);
            f->dlc = d[4];
            memset(f->data, 0, sizeof f->data);
            memcpy(f->data, d + 8, f->dlc);
        }
    }
    st = hil_can_frame_check(f);
    if (st != HIL_OK) {
        t->rx_invalid++;
        return HIL_E_FORMAT;
    }
    t->rx_frames++;
    return HIL_OK;
}

void hil_transport_close(struct hil_transport *t)
{
    if (t && t->fd >= 0) {
        close(t->fd);
        t->fd = -1;
    }
}
