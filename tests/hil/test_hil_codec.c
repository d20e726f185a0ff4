/* Frames, the CANopen-style codec, the frame dictionary and the candump log
 * format: round trips and every rejection path. */
#include <string.h>
#include "frac_test.h"
#include "hil/candump.h"
#include "hil/canopen.h"
#include "hil/node.h"

static void test_frame_check_rejects_bad_dlc_flags_and_ids(void **state)
{
    struct hil_can_frame f;
    (void)state;
    memset(&f, 0, sizeof f);
    f.id = 0x7FF;
    assert_int_equal(hil_can_frame_check(&f), HIL_OK);
    f.dlc = 9;
    assert_int_equal(hil_can_frame_check(&f), HIL_E_DLC);
    f.dlc = 8;
    f.id = 0x800;
    assert_int_equal(hil_can_frame_check(&f), HIL_E_FORMAT);
    f.id = 0x123 | HIL_CAN_RTR_FLAG;
    assert_int_equal(hil_can_frame_check(&f), HIL_E_FORMAT);
    f.id = 0x1FFFFFFF | HIL_CAN_EFF_FLAG;
    assert_int_equal(hil_can_frame_check(&f), HIL_OK);
    assert_int_equal(hil_can_frame_check(NULL), HIL_E_ARG);
    assert_string_equal(hil_status_str(HIL_E_DLC), "wrong DLC");
    assert_string_equal(hil_status_str(12345), "unknown status");
}

static void test_drive_pdos_round_trip_little_endian(void **state)
{
    struct hil_can_frame f;
    struct hil_drive_rpdo r = {0x000F, -123456}, r2;
    struct hil_drive_tpdo1 t1 = {0x0237, 1048576}, t1b;
    struct hil_drive_tpdo2 t2 = {-5000000, 95700}, t2b;
    (void)state;
    assert_int_equal(hil_co_drive_rpdo_encode(&f, &r), HIL_OK);
    assert_int_equal(f.id, 0x201);
    assert_int_equal(f.dlc, 6);
    assert_int_equal(f.data[0], 0x0F);
    assert_int_equal(f.data[2], 0xC0); /* -123456 = 0xFFFE1DC0 */
    assert_int_equal(f.data[5], 0xFF);
    assert_int_equal(hil_co_drive_rpdo_decode(&f, &r2), HIL_OK);
    assert_int_equal(r2.controlword, 0x000F);
    assert_int_equal(r2.torque_mnm, -123456);
    assert_int_equal(hil_co_drive_tpdo1_encode(&f, &t1), HIL_OK);
    assert_int_equal(f.id, 0x181);
    assert_int_equal(hil_co_drive_tpdo1_decode(&f, &t1b), HIL_OK);
    assert_int_equal(t1b.position_inc, 1048576);
    assert_int_equal(hil_co_drive_tpdo2_encode(&f, &t2), HIL_OK);
    assert_int_equal(f.id, 0x281);
    assert_int_equal(hil_co_drive_tpdo2_decode(&f, &t2b), HIL_OK);
    assert_int_equal(t2b.velocity_urads, -5000000);
    assert_int_equal(t2b.torque_mnm, 95700);
}

static void test_decoders_reject_wrong_dlc_and_foreign_ids(void **state)
{
    struct hil_can_frame f;
    struct hil_drive_rpdo r = {6, 0};
    struct hil_imu_tpdo m;
    (void)state;
    hil_co_drive_rpdo_encode(&f, &r);
    f.dlc = 5;
    assert_int_equal(hil_co_drive_rpdo_decode(&f, &r), HIL_E_DLC);
    f.dlc = 6;
    f.id = 0x202;
    assert_int_equal(hil_co_drive_rpdo_decode(&f, &r), HIL_E_UNKNOWN_ID);
    assert_int_equal(hil_co_imu_decode(&f, 1, &m), HIL_E_UNKNOWN_ID);
    assert_int_equal(hil_co_imu_decode(&f, 3, &m), HIL_E_ARG);
    f.dlc = 12;
    assert_int_equal(hil_co_drive_rpdo_decode(&f, &r), HIL_E_DLC);
    assert_int_equal(hil_co_drive_rpdo_decode(NULL, &r), HIL_E_ARG);
}

static void test_imu_pdos_round_trip_with_sequence(void **state)
{
    struct hil_can_frame f;
    struct hil_imu_tpdo a = {{-32768, 0, 32767}, 200, 1}, b;
    (void)state;
    assert_int_equal(hil_co_imu_encode(&f, 1, &a), HIL_OK);
    assert_int_equal(f.id, 0x182);
    assert_int_equal(hil_co_imu_decode(&f, 1, &b), HIL_OK);
    assert_int_equal(b.xyz[0], -32768);
    assert_int_equal(b.xyz[2], 32767);
    assert_int_equal(b.seq, 200);
    assert_int_equal(b.status, 1);
    assert_int_equal(hil_co_imu_encode(&f, 2, &a), HIL_OK);
    assert_int_equal(f.id, 0x282);
    assert_int_equal(hil_co_imu_encode(&f, 0, &a), HIL_E_ARG);
}

static void test_nmt_sync_heartbeat_emcy_validate_content(void **state)
{
    struct hil_can_frame f;
    struct hil_emcy e = {HIL_EMCY_RPDO_TIMEOUT, 1, {5, 0, 0, 0, 0}}, e2;
    uint8_t a, b;
    (void)state;
    assert_int_equal(hil_co_nmt_encode(&f, HIL_NMT_START, 0), HIL_OK);
    assert_int_equal(hil_co_nmt_decode(&f, &a, &b), HIL_OK);
    assert_int_equal(a, 1);
    f.data[0] = 0x33;
    assert_int_equal(hil_co_nmt_decode(&f, &a, &b), HIL_E_FORMAT);
    assert_int_equal(hil_co_nmt_encode(&f, 0x33, 0), HIL_E_ARG);
    assert_int_equal(hil_co_sync_encode(&f, 0), HIL_E_ARG);
    assert_int_equal(hil_co_sync_encode(&f, 240), HIL_OK);
    f.data[0] = 241;
    assert_int_equal(hil_co_sync_decode(&f, &a), HIL_E_FORMAT);
    assert_int_equal(hil_co_heartbeat_encode(&f, 2, HIL_NMT_STATE_OPERATIONAL), HIL_OK);
    assert_int_equal(f.id, 0x702);
    assert_int_equal(hil_co_heartbeat_decode(&f, &a, &b), HIL_OK);
    assert_int_equal(a, 2);
    assert_int_equal(b, 5);
    f.data[0] = 3;
    assert_int_equal(hil_co_heartbeat_decode(&f, &a, &b), HIL_E_FORMAT);
    assert_int_equal(hil_co_emcy_encode(&f, 1, &e), HIL_OK);
    assert_int_equal(f.id, 0x081);
    assert_int_equal(hil_co_emcy_decode(&f, &a, &e2), HIL_OK);
    assert_int_equal(e2.code, 0x8250);
    assert_int_equal(e2.info[0], 5);
    f.id = 0x080;
    assert_int_equal(hil_co_emcy_decode(&f, &a, &e2), HIL_E_UNKNOWN_ID);
}

static void test_rig_frames_carry_float32_and_reject_nan(void **state)
{
    struct hil_can_frame f;
    double a, b;
    (void)state;
    assert_int_equal(hil_co_rig_encode(&f, HIL_COB_RIG_TIP, 1.5, -0.25), HIL_OK);
    assert_int_equal(hil_co_rig_decode(&f, HIL_COB_RIG_TIP, &a, &b), HIL_OK);
    assert_true(a == 1.5 && b == -0.25);
    assert_int_equal(hil_co_rig_encode(&f, HIL_COB_RIG_TIP, NAN, 0.0), HIL_E_RANGE);
    assert_int_equal(hil_co_rig_encode(&f, 0x6F4, 0.0, 0.0), HIL_E_ARG);
    hil_put_f32(f.data, (float)INFINITY);
    assert_int_equal(hil_co_rig_decode(&f, HIL_COB_RIG_TIP, &a, &b), HIL_E_RANGE);
    assert_int_equal(hil_co_rig_decode(&f, HIL_COB_RIG_MOTOR, &a, &b), HIL_E_UNKNOWN_ID);
}

static void test_quantize_rounds_and_saturates(void **state)
{
    int64_t q;
    (void)state;
    assert_int_equal(hil_co_quantize(1.2344, 1e-3, -10000, 10000, &q), HIL_OK);
    assert_int_equal(q, 1234);
    assert_int_equal(hil_co_quantize(-1.2346, 1e-3, -10000, 10000, &q), HIL_OK);
    assert_int_equal(q, -1235);
    assert_int_equal(hil_co_quantize(40.0, 1e-3, INT16_MIN, INT16_MAX, &q), 1);
    assert_int_equal(q, INT16_MAX);
    assert_int_equal(hil_co_quantize(NAN, 1e-3, -1, 1, &q), HIL_E_RANGE);
    assert_int_equal(q, 0);
    assert_int_equal(hil_co_quantize(1.0, 0.0, -1, 1, &q), HIL_E_ARG);
}

static void test_dictionary_counts_unknown_ids_and_wrong_dlc(void **state)
{
    struct hil_rx_stats s;
    struct hil_can_frame f;
    (void)state;
    memset(&s, 0, sizeof s);
    memset(&f, 0, sizeof f);
    f.id = 0x555;
    f.dlc = 8;
    assert_int_equal(hil_rx_screen(&s, &f), HIL_E_UNKNOWN_ID);
    f.id = 0x201;
    f.dlc = 5;
    assert_int_equal(hil_rx_screen(&s, &f), HIL_E_DLC);
    f.id = 0x080;
    f.dlc = 1;
    assert_int_equal(hil_rx_screen(&s, &f), HIL_OK);
    f.id = 0x181 | HIL_CAN_EFF_FLAG;
    assert_int_equal(hil_rx_screen(&s, &f), HIL_E_UNKNOWN_ID);
    f.id = 0x080;
    f.dlc = 9;
    assert_int_equal(hil_rx_screen(&s, &f), HIL_E_DLC);
    assert_int_equal(s.unknown_id, 2);
    assert_int_equal(s.bad_dlc, 2);
}

static void test_candump_line_round_trips_standard_and_extended(void **state)
{
    struct hil_can_frame f, g;
    char line[HIL_CANDUMP_LINE_MAX], iface[HIL_CANDUMP_IFACE_MAX];
    double t;
    int n;
    (void)state;
    memset(&f, 0, sizeof f);
    f.id = 0x201;
    f.dlc = 6;
    f.data[0] = 0x0F;
    f.data[5] = 0xAB;
    n = hil_candump_format(line, sizeof line, 1700000000.1234564, "vcan0", &f);
    assert_int_equal(n, (int)strlen(line));
    assert_string_equal(line, "(1700000000.123456) vcan0 201#0F00000000AB\n");
    assert_int_equal(hil_candump_parse(line, &t, iface, &g), HIL_OK);
    assert_string_equal(iface, "vcan0");
    assert_close(t, 1700000000.123456, 1e-6);
    assert_int_equal(g.id, 0x201);
    assert_int_equal(g.dlc, 6);
    assert_memory_equal(g.data, f.data, 6);
    f.id = 0x1ABCDEF0 | HIL_CAN_EFF_FLAG;
    f.dlc = 0;
    hil_candump_format(line, sizeof line, 0.9999996, "can0", &f);
    assert_string_equal(line, "(0000000001.000000) can0 1ABCDEF0#\n");
    assert_int_equal(hil_candump_parse(line, &t, iface, &g), HIL_OK);
    assert_int_equal(g.id, f.id);
    assert_int_equal(g.dlc, 0);
}

static void test_candump_rejects_malformed_lines(void **state)
{
    static const char *bad[] = {
        "",
        "(12.5 vcan0 201#00",
        "(12.500000) vcan0 201#0",
        "(12.500000) vcan0 2010#00",
        "(12.500000) vcan0 201#R",
        "(12.500000) vcan0 201##0011",
        "(12.500000) vcan0 800#00",
        "12.500000 vcan0 201#00",
        "(12.500000) vcan0 201#00 trailing",
        "(.500000) vcan0 201#00",
    };
    struct hil_can_frame f;
    char iface[HIL_CANDUMP_IFACE_MAX], line[HIL_CANDUMP_LINE_MAX];
    double t;
    size_t i;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(hil_candump_parse(bad[i], &t, iface, &f), HIL_E_FORMAT);
    assert_int_equal(hil_candump_parse("(1.000000) vcan0 201#001122334455667788", &t, iface, &f), HIL_E_DLC);
    memset(&f, 0, sizeof f);
    f.id = 0x80;
    assert_int_equal(hil_candump_format(line, sizeof line, -1.0, "vcan0", &f), HIL_E_ARG);
    assert_int_equal(hil_candump_format(line, sizeof line, 1.0, "bad iface", &f), HIL_E_ARG);
    assert_int_equal(hil_candump_format(line, 10, 1.0, "vcan0", &f), HIL_E_FULL);
    f.dlc = 9;
    assert_int_equal(hil_candump_format(line, sizeof line, 1.0, "vcan0", &f), HIL_E_DLC);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frame_check_rejects_bad_dlc_flags_and_ids),
        cmocka_unit_test(test_drive_pdos_round_trip_little_endian),
        cmocka_unit_test(test_decoders_reject_wrong_dlc_and_foreign_ids),
        cmocka_unit_test(test_imu_pdos_round_trip_with_sequence),
        cmocka_unit_test(test_nmt_sync_heartbeat_emcy_validate_content),
        cmocka_unit_test(test_rig_frames_carry_float32_and_reject_nan),
        cmocka_unit_test(test_quantize_rounds_and_saturates),
        cmocka_unit_test(test_dictionary_counts_unknown_ids_and_wrong_dlc),
        cmocka_unit_test(test_candump_line_round_trips_standard_and_extended),
        cmocka_unit_test(test_candump_rejects_malformed_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
