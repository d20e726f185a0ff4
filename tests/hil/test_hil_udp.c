/* The UDP loopback transport on this host: frames reach every other node of
 * the bus and not the sender, bit for bit; invalid datagrams are counted and
 * dropped; bad specs are refused. SocketCAN is opened too: on a kernel without
 * AF_CAN it must say so (HIL_E_UNSUPPORTED), not crash. */
#include <arpa/inet.h>
#include <netinet/in.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>
#include "frac_test.h"
#include "hil/transport.h"

/* A port base per process so parallel test runs do not collide. */
static unsigned port_base(void) { return 20000u + (unsigned)(getpid() % 1000) * 16u; }

static void open_bus(struct hil_transport *t, unsigned n)
{
    char spec[64];
    unsigned i;
    for (i = 0; i < n; i++) {
        snprintf(spec, sizeof spec, "udp:%u:%u:%u", port_base(), i, n);
        assert_int_equal(hil_transport_open(&t[i], spec), HIL_OK);
    }
}

static void test_udp_frame_reaches_every_other_node_unchanged(void **state)
{
    struct hil_transport t[3];
    struct hil_can_frame f, g;
    int i, k;
    (void)state;
    open_bus(t, 3);
    for (k = 0; k < 20; k++) {
        memset(&f, 0, sizeof f);
        f.id = k % 2 ? (0x1ABCDE00u + k) | HIL_CAN_EFF_FLAG : 0x180u + k;
        f.dlc = (uint8_t)(k % 9);
        for (i = 0; i < f.dlc; i++)
            f.data[i] = (uint8_t)(17 * k + i);
        assert_int_equal(hil_transport_send(&t[k % 3], &f), HIL_OK);
        for (i = 0; i < 3; i++) {
            if (i == k % 3) {
                assert_int_equal(hil_transport_recv(&t[i], &g, 0), HIL_E_TIMEOUT);
                continue;
            }
            assert_int_equal(hil_transport_recv(&t[i], &g, 1000000), HIL_OK);
            assert_int_equal(g.id, f.id);
            assert_int_equal(g.dlc, f.dlc);
            assert_memory_equal(g.data, f.data, 8);
        }
    }
    assert_int_equal(t[0].tx_frames + t[1].tx_frames + t[2].tx_frames, 20);
    assert_int_equal(t[0].rx_frames + t[1].rx_frames + t[2].rx_frames, 40);
    for (i = 0; i < 3; i++)
        hil_transport_close(&t[i]);
}

static void test_udp_counts_and_drops_invalid_datagrams(void **state)
{
    struct hil_transport t[2];
    struct hil_can_frame g;
    struct sockaddr_in a;
    uint8_t d[17];
    int s = socket(AF_INET, SOCK_DGRAM, 0);
    (void)state;
    open_bus(t, 2);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)(port_base() + 1));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    memset(d, 0, sizeof d);
    sendto(s, d, 15, 0, (struct sockaddr *)&a, sizeof a); /* short */
    sendto(s, d, 17, 0, (struct sockaddr *)&a, sizeof a); /* long */
    d[4] = 9;
    sendto(s, d, 16, 0, (struct sockaddr *)&a, sizeof a); /* DLC 9 */
    d[4] = 1;
    d[6] = 1;
    sendto(s, d, 16, 0, (struct sockaddr *)&a, sizeof a); /* padding not zero */
    d[6] = 0;
    d[3] = 0x40;
    sendto(s, d, 16, 0, (struct sockaddr *)&a, sizeof a); /* RTR flag */
    d[3] = 0;
    d[0] = 0x80;
    sendto(s, d, 16, 0, (struct sockaddr *)&a, sizeof a); /* valid SYNC-like frame */
    assert_int_equal(hil_transport_recv(&t[1], &g, 1000000), HIL_E_FORMAT);
    assert_int_equal(hil_transport_recv(&t[1], &g, 1000000), HIL_E_FORMAT);
    assert_int_equal(hil_transport_recv(&t[1], &g, 1000000), HIL_E_FORMAT);
    assert_int_equal(hil_transport_recv(&t[1], &g, 1000000), HIL_E_FORMAT);
    assert_int_equal(hil_transport_recv(&t[1], &g, 1000000), HIL_E_FORMAT);
    assert_int_equal(hil_transport_recv(&t[1], &g, 1000000), HIL_OK);
    assert_int_equal(g.id, 0x80);
    assert_int_equal(t[1].rx_invalid, 5);
    assert_int_equal(t[1].rx_frames, 1);
    close(s);
    hil_transport_close(&t[0]);
    hil_transport_close(&t[1]);
}

static void test_send_refuses_invalid_frames(void **state)
{
    struct hil_transport t[2];
    struct hil_can_frame f;
    (void)state;
    open_bus(t, 2);
    memset(&f, 0, sizeof f);
    f.id = 0x123;
    f.dlc = 9;
    assert_int_equal(hil_transport_send(&t[0], &f), HIL_E_DLC);
    f.dlc = 1;
    f.id = 0x900;
    assert_int_equal(hil_transport_send(&t[0], &f), HIL_E_FORMAT);
    assert_int_equal(t[0].tx_frames, 0);
    hil_transport_close(&t[0]);
    hil_transport_close(&t[0]); /* twice is harmless */
    assert_int_equal(hil_transport_send(&t[0], &f), HIL_E_ARG);
    hil_transport_close(&t[1]);
}

static void test_bad_specs_are_refused(void **state)
{
    static const char *bad[] = {"", "udp:", "udp:40000:2:2", "udp:40000:0:1", "udp:80:0:2",
                                "udp:40000:0:2:9", "udp:x:0:2", "udp:40000:0:17", "tcp:1",
                                "socketcan:", "socketcan:an-interface-name-too-long"};
    struct hil_transport t;
    size_t i;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(hil_transport_open(&t, bad[i]), HIL_E_ARG);
    assert_int_equal(hil_transport_open(NULL, "udp:40000:0:2"), HIL_E_ARG);
}

static void test_socketcan_reports_missing_af_can_or_interface(void **state)
{
    struct hil_transport t;
    int st = hil_transport_open(&t, "socketcan:hilnosuch0");
    (void)state;
    /* no AF_CAN in this kernel -> unsupported; AF_CAN but no such interface -> I/O */
    assert_true(st == HIL_E_UNSUPPORTED || st == HIL_E_IO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_udp_frame_reaches_every_other_node_unchanged),
        cmocka_unit_test(test_udp_counts_and_drops_invalid_datagrams),
        cmocka_unit_test(test_send_refuses_invalid_frames),
        cmocka_unit_test(test_bad_specs_are_refused),
        cmocka_unit_test(test_socketcan_reports_missing_af_can_or_interface),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
