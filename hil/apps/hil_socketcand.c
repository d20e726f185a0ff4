/* hil_socketcand: the drive (node 1), the IMU (node 2) and the plant as
 * CANopen devices behind a socketcand server on 127.0.0.1, so that any
 * CANopen master on python-can (interface "socketcand", no kernel CAN
 * support needed) can boot and run them as it would real devices.
 *
 * Protocol (socketcand rawmode, the subset python-can speaks): on connect
 * the server sends "< hi >"; the client sends "< open BUS >" and
 * "< rawmode >", each answered "< ok >"; then the client sends
 * "< send ID LEN B0 .. Bn >" (hex fields) and the server sends every frame
 * the devices put on the bus as "< frame ID SECONDS.MICROS DATA >" (hex id of
 * 3 digits, or 8 for an extended one; data as one hex string). Nothing is
 * sent to the client before its first frame (python-can reads its "< ok >"
 * replies with single reads), so the devices' boot-up heartbeats are not
 * forwarded: a master resets the nodes first anyway. A malformed command
 * ("< send >" with a bad identifier, length > 8, a byte count unlike LEN or
 * a byte > 0xFF, an unknown command, a message over 256 characters) is
 * counted, answered "< error ... >" and ignored; valid frames then go through
 * each device's own screening (hil/node.h).
 *
 * The devices share an in-memory bus as in the lockstep bench (hil/rig.h):
 * a frame from the client reaches the drive, the IMU and the plant, each
 * node's frames reach the other nodes and the client; the rig-internal
 * frames (RIG_*, the physical wiring) stay inside. Time is the master's:
 * the drive runs one cycle per SYNC the client sends, the plant one step of
 * T per cycle, so simulated time = SYNCs x T whatever the wall clock does.
 * One client; when it disconnects the server prints HIL_SOCKETCAND (frames
 * in/out, malformed commands, SYNCs) and the nodes' HIL_STATS and exits. */
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>
#include "app_common.h"
#include "hil/canopen.h"
#include "hil/drive.h"
#include "hil/imu.h"
#include "hil/plant.h"

#define QMAX 256
#define MSG_MAX 256

struct server {
    int fd, started;
    struct hil_drive drive;
    struct hil_imu imu;
    struct hil_plant plant;
    struct hil_can_frame q[QMAX];
    int q_from[QMAX], q_head, q_len;
    char in[4096];
    size_t in_len;
    char out[65536];
    size_t out_len;
    uint64_t frames_in, frames_out, malformed, syncs, overflow;
};

enum { FROM_DRIVE, FROM_IMU, FROM_PLANT, FROM_CLIENT, NODES = 3 };

static int is_rig(uint32_t id) { return id >= HIL_COB_RIG_TORQUE && id <= HIL_COB_RIG_IMU_DONE; }

static int write_all(int fd, const char *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

static void reply(struct server *s, const char *text)
{
    write_all(s->fd, text, strlen(text));
}

static void to_client(struct server *s, const struct hil_can_frame *f)
{
    char line[64];
    int n, i;
    double t = app_now();
    if (!s->started)
        return;
    if (f->id & HIL_CAN_EFF_FLAG)
        n = snprintf(line, sizeof line, "< frame %08X %.6f ", f->id & HIL_CAN_EFF_MASK, t);
    else
        n = snprintf(line, sizeof line, "< frame %03X %.6f ", f->id, t);
    for (i = 0; i < f->dlc; i++)
        n += snprintf(line + n, sizeof line - (size_t)n, "%02X", f->data[i]);
    n += snprintf(line + n, sizeof line - (size_t)n, " >");
    if (s->out_len + (size_t)n > sizeof s->out) {
        write_all(s->fd, s->out, s->out_len);
        s->out_len = 0;
    }
    memcpy(s->out + s->out_len, line, (size_t)n);
    s->out_len += (size_t)n;
    s->frames_out++;
}

static void enqueue(struct server *s, const struct hil_out *out, int from)
{
    int i;
    for (i = 0; i < out->n; i++) {
        int at;
        if (s->q_len >= QMAX) {
            s->overflow++;
            continue;
        }
        at = (s->q_head + s->q_len) % QMAX;
        s->q[at] = out->f[i];
        s->q_from[at] = from;
        s->q_len++;
    }
}

/* Delivers until the bus is idle (CAN semantics: everyone but the sender). */
static void drain(struct server *s)
{
    while (s->q_len > 0) {
        struct hil_can_frame f = s->q[s->q_head];
        int from = s->q_from[s->q_head], n;
        s->q_head = (s->q_head + 1) % QMAX;
        s->q_len--;
        if (from != FROM_CLIENT && !is_rig(f.id))
            to_client(s, &f);
        for (n = 0; n < NODES; n++) {
            struct hil_out out;
            if (n == from)
                continue;
            out.n = 0;
            if (n == FROM_DRIVE)
                hil_drive_on_frame(&s->drive, &f, &out);
            else if (n == FROM_IMU)
                hil_imu_on_frame(&s->imu, &f, &out);
            else
                hil_plant_on_frame(&s->plant, &f, &out);
            enqueue(s, &out, n);
        }
    }
    if (s->out_len) {
        write_all(s->fd, s->out, s->out_len);
        s->out_len = 0;
    }
}

/* Parses "send ID LEN B0 .. Bn" (the text between "< " and " >"); 0 or -1. */
static int parse_send(const char *m, struct hil_can_frame *f)
{
    char *end;
    const char *p = m + 4;
    unsigned long id, len, b;
    size_t digits;
    unsigned i;
    memset(f, 0, sizeof *f);
    while (*p == ' ')
        p++;
    errno = 0;
    id = strtoul(p, &end, 16);
    digits = (size_t)(end - p);
    if (errno || digits == 0 || *end != ' ' || (digits <= 3 ? id > 0x7FFu : (digits != 8 || id > 0x1FFFFFFFu)))
        return -1;
    f->id = (uint32_t)id | (digits == 8 ? HIL_CAN_EFF_FLAG : 0u);
    p = end;
    len = strtoul(p, &end, 16);
    if (end == p || len > 8)
        return -1;
    f->dlc = (uint8_t)len;
    p = end;
    for (i = 0; i < len; i++) {
        while (*p == ' ')
            p++;
        b = strtoul(p, &end, 16);
        if (end == p || (size_t)(end - p) > 2 || b > 0xFF || (*end != ' ' && *end != '\0'))
            return -1;
        f->data[i] = (uint8_t)b;
        p = end;
    }
    while (*p == ' ')
        p++;
    return *p == '\0' ? 0 : -1;
}

static void command(struct server *s, char *m)
{
    struct hil_can_frame f;
    if (strncmp(m, "open ", 5) == 0 || strcmp(m, "rawmode") == 0) {
        reply(s, "< ok >");
        return;
    }
    if (strncmp(m, "send ", 5) == 0 && parse_send(m, &f) == 0) {
        struct hil_out out;
        s->started = 1;
        s->frames_in++;
        if (f.id == HIL_COB_SYNC)
            s->syncs++;
        out.n = 1;
        out.f[0] = f;
        enqueue(s, &out, FROM_CLIENT);
        drain(s);
        return;
    }
    s->malformed++;
    reply(s, "< error malformed command >");
}

/* Splits the input into "< ... >" messages. */
static void consume(struct server *s)
{
    size_t start = 0;
    for (;;) {
        char *lt = memchr(s->in + start, '<', s->in_len - start), *gt;
        if (!lt) {
            start = s->in_len;
            break;
        }
        gt = memchr(lt, '>', s->in_len - (size_t)(lt - s->in));
        if (!gt) {
            start = (size_t)(lt - s->in);
            if (s->in_len - start > MSG_MAX) {
                s->malformed++;
                start = s->in_len;
            }
            break;
        }
        *gt = '\0';
        {
            char *m = lt + 1, *e = gt;
            while (*m == ' ')
                m++;
            while (e > m && e[-1] == ' ')
                *--e = '\0';
            if ((size_t)(gt - lt) > MSG_MAX) {
                s->malformed++;
                reply(s, "< error malformed command >");
            } else {
                command(s, m);
            }
        }
        start = (size_t)(gt - s->in) + 1;
    }
    memmove(s->in, s->in + start, s->in_len - start);
    s->in_len -= start;
}

static void rx_stats(const char *name, const struct hil_rx_stats *rx)
{
    printf("HIL_STATS node=%s accepted=%llu other=%llu unknown_id=%llu bad_dlc=%llu bad_value=%llu\n", name,
           (unsigned long long)rx->accepted, (unsigned long long)rx->other, (unsigned long long)rx->unknown_id,
           (unsigned long long)rx->bad_dlc, (unsigned long long)rx->bad_value);
}

int main(int argc, char **argv)
{
    static struct server s;
    struct app_opts o;
    struct hil_out boot;
    struct sockaddr_in a;
    socklen_t alen = sizeof a;
    int lfd, one = 1, i;
    long port = 0;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--port") == 0 && i + 1 < argc) {
            char *end;
            port = strtol(argv[i + 1], &end, 10);
            if (*end || port < 0 || port > 65535) {
                fprintf(stderr, "hil_socketcand: --port wants 0..65535 (0: any free port), got %s\n", argv[i + 1]);
                return 2;
            }
            memmove(&argv[i], &argv[i + 2], (size_t)(argc - i - 1) * sizeof *argv);
            argc -= 2;
            i--;
        }
    }
    app_parse(argc, argv, &o,
              "usage: hil_socketcand [--port P] [options]\n"
              "The drive, IMU and plant as CANopen devices behind a socketcand server (rawmode) on\n"
              "127.0.0.1:P (default 0: a free port); prints 'HIL_SOCKETCAND port=P' when listening,\n"
              "serves one client (python-can interface 'socketcand', channel any name) and exits\n"
              "when it disconnects. Simulated time advances T per SYNC of the client.\n"
              "  --port P            TCP port, 0..65535\n");
    boot.n = 0;
    if (hil_drive_init(&s.drive, &o.cfg.drive, &boot) != HIL_OK || hil_imu_init(&s.imu, &o.cfg.imu, &boot) != HIL_OK ||
        hil_plant_init(&s.plant, &o.cfg.plant_p) != HIL_OK) {
        fprintf(stderr, "hil_socketcand: invalid device parameters%s%s\n", s.plant.err[0] ? ": " : "", s.plant.err);
        return 2;
    }
    lfd = socket(AF_INET, SOCK_STREAM, 0);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    setsockopt(lfd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (lfd < 0 || bind(lfd, (struct sockaddr *)&a, sizeof a) != 0 || listen(lfd, 1) != 0 ||
        getsockname(lfd, (struct sockaddr *)&a, &alen) != 0) {
        fprintf(stderr, "hil_socketcand: cannot listen on 127.0.0.1:%ld: %s\n", port, strerror(errno));
        return 1;
    }
    printf("HIL_SOCKETCAND port=%u\n", ntohs(a.sin_port));
    fflush(stdout);
    s.fd = accept(lfd, NULL, NULL);
    close(lfd);
    if (s.fd < 0) {
        perror("hil_socketcand: accept");
        return 1;
    }
    setsockopt(s.fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    reply(&s, "< hi >");
    for (;;) {
        ssize_t n = read(s.fd, s.in + s.in_len, sizeof s.in - s.in_len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        s.in_len += (size_t)n;
        consume(&s);
        if (s.in_len == sizeof s.in) { /* no '<' ... '>' in a full buffer */
            s.malformed++;
            s.in_len = 0;
        }
    }
    close(s.fd);
    printf("HIL_SOCKETCAND frames_in=%llu frames_out=%llu malformed=%llu syncs=%llu queue_overflow=%llu "
           "sim_s=%.6f drive_state=%d drive_emcy=%llu imu_readings=%llu\n",
           (unsigned long long)s.frames_in, (unsigned long long)s.frames_out, (unsigned long long)s.malformed,
           (unsigned long long)s.syncs, (unsigned long long)s.overflow, (double)s.syncs * o.cfg.drive.T,
           (int)s.drive.state, (unsigned long long)s.drive.emcy_sent, (unsigned long long)s.imu.readings_sent);
    rx_stats("drive", &s.drive.rx);
    rx_stats("imu", &s.imu.rx);
    rx_stats("plant", &s.plant.rx);
    return 0;
}
