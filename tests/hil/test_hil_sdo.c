/* The devices as CANopen devices: the object dictionary behind the SDO
 * server (expedited and segmented transfers, every CiA 301 abort path), the
 * PDO rules and the mapping applied at NMT start, the default PDOs equal to
 * the frames the controller's codec decodes, 0x1017, the CiA 402 additions
 * (quick stop options, fault reset with EMCY, over-temperature fault with
 * 0x603F / 0x1001) and the controller's boot by SDO failing with the reason. */
#include <string.h>
#include "frac_test.h"
#include "hil/canopen.h"
#include "hil/ctrl.h"
#include "hil/drive.h"
#include "hil/imu.h"
#include "hil/sdo.h"

static struct hil_out o;

static struct hil_can_frame frame8(uint32_t id, const uint8_t d[8])
{
    struct hil_can_frame f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.dlc = 8;
    memcpy(f.data, d, 8);
    return f;
}

/* One request to the drive, the only response frame (asserted). */
static struct hil_can_frame drive_req(struct hil_drive *d, const uint8_t req[8])
{
    struct hil_can_frame f = frame8(HIL_COB_SDO_RX(HIL_NODE_DRIVE), req);
    o.n = 0;
    hil_drive_on_frame(d, &f, &o);
    assert_int_equal(o.n, 1);
    assert_int_equal(o.f[0].id, HIL_COB_SDO_TX(HIL_NODE_DRIVE));
    assert_int_equal(o.f[0].dlc, 8);
    return o.f[0];
}

static uint32_t up(struct hil_drive *d, uint16_t ix, uint8_t sub, uint32_t *abort)
{
    struct hil_can_frame f, r;
    uint32_t v = 0;
    hil_sdo_upload_req(&f, HIL_NODE_DRIVE, ix, sub);
    r = drive_req(d, f.data);
    *abort = 0;
    hil_sdo_client_response(&r, ix, sub, &v, abort);
    return v;
}

static uint32_t down(struct hil_drive *d, uint16_t ix, uint8_t sub, uint32_t v, unsigned bytes)
{
    struct hil_can_frame f, r;
    uint32_t got = 0, abort = 0;
    hil_sdo_download_req(&f, HIL_NODE_DRIVE, ix, sub, v, bytes);
    r = drive_req(d, f.data);
    hil_sdo_client_response(&r, ix, sub, &got, &abort);
    return abort;
}

static void boot_drive(struct hil_drive *d)
{
    struct hil_drive_params p;
    hil_drive_params_default(&p);
    o.n = 0;
    assert_int_equal(hil_drive_init(d, &p, &o), HIL_OK);
}

static void nmt(struct hil_drive *d, uint8_t cmd)
{
    struct hil_can_frame f;
    hil_co_nmt_encode(&f, cmd, 0);
    o.n = 0;
    assert_int_equal(hil_drive_on_frame(d, &f, &o), HIL_OK);
}

static void sync1(struct hil_drive *d)
{
    struct hil_can_frame f;
    hil_co_sync_encode(&f, 1);
    o.n = 0;
    assert_int_equal(hil_drive_on_frame(d, &f, &o), HIL_OK);
}

static const struct hil_can_frame *find(uint32_t id)
{
    int i;
    for (i = 0; i < o.n; i++)
        if (o.f[i].id == id)
            return &o.f[i];
    return NULL;
}

static void rpdo(struct hil_drive *d, uint16_t cw, int32_t mnm)
{
    struct hil_can_frame f;
    struct hil_drive_rpdo r;
    r.controlword = cw;
    r.torque_mnm = mnm;
    hil_co_drive_rpdo_encode(&f, &r);
    o.n = 0;
    hil_drive_on_frame(d, &f, &o);
}

static void test_sdo_expedited_transfers_and_every_abort_path(void **state)
{
    struct hil_drive d;
    uint32_t ab;
    uint8_t bad[8] = {0xC0, 0, 0x10, 0, 0, 0, 0, 0};
    (void)state;
    boot_drive(&d);
    assert_int_equal(up(&d, 0x1000, 0, &ab), 0x00020192u);
    assert_int_equal(ab, 0);
    assert_int_equal(up(&d, 0x1018, 2, &ab), 1u);
    assert_int_equal(up(&d, 0x6076, 0, &ab), 95700u);
    assert_int_equal(up(&d, 0x6072, 0, &ab), 2623u); /* 251 / 95.7 per mille */
    assert_int_equal(down(&d, 0x1017, 0, 250, 2), 0);
    assert_int_equal(up(&d, 0x1017, 0, &ab), 250u);
    up(&d, 0x5555, 0, &ab);
    assert_int_equal(ab, HIL_SDO_ABORT_NO_OBJECT);
    up(&d, 0x1018, 9, &ab);
    assert_int_equal(ab, HIL_SDO_ABORT_NO_SUB);
    assert_int_equal(down(&d, 0x5555, 0, 1, 1), HIL_SDO_ABORT_NO_OBJECT);
    assert_int_equal(down(&d, 0x6041, 0, 0, 2), HIL_SDO_ABORT_READ_ONLY);
    assert_int_equal(down(&d, 0x1000, 0, 0, 4), HIL_SDO_ABORT_READ_ONLY);
    assert_int_equal(down(&d, 0x6040, 0, 6, 4), HIL_SDO_ABORT_LENGTH);
    assert_int_equal(down(&d, 0x6060, 0, 8, 1), HIL_SDO_ABORT_RANGE);     /* CSP: unsupported */
    assert_int_equal(down(&d, 0x6060, 0, 11, 1), HIL_SDO_ABORT_RANGE);    /* above the table's high */
    assert_int_equal(down(&d, 0x2101, 0, 0, 2), HIL_SDO_ABORT_RANGE);     /* trip 0: below low */
    assert_int_equal(down(&d, 0x605A, 0, 3, 2), HIL_SDO_ABORT_RANGE);
    assert_int_equal(up(&d, 0x1017, 0, &ab), 250u); /* untouched by the refused writes */
    assert_int_equal(hil_get_u32(drive_req(&d, bad).data + 4), HIL_SDO_ABORT_COMMAND);
    assert_int_equal(d.rx.bad_value, 1);
    /* PDO parameters only in pre-operational */
    nmt(&d, HIL_NMT_START);
    assert_int_equal(down(&d, 0x1A02, 0, 0, 1), HIL_SDO_ABORT_STATE);
    assert_int_equal(down(&d, 0x1017, 0, 100, 2), 0);
    /* stopped: no SDO answer; a request of another length is not answered either */
    nmt(&d, HIL_NMT_STOP);
    {
        struct hil_can_frame f;
        hil_sdo_upload_req(&f, HIL_NODE_DRIVE, 0x1000, 0);
        o.n = 0;
        assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_E_STATE);
        assert_int_equal(o.n, 0);
        nmt(&d, HIL_NMT_PREOP);
        f.dlc = 7;
        o.n = 0;
        assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_E_DLC);
        assert_int_equal(o.n, 0);
        assert_int_equal(d.rx.bad_dlc, 1);
    }
}

static void test_sdo_segmented_upload_download_toggle_and_client_abort(void **state)
{
    struct hil_drive d;
    char name[80] = "";
    size_t got = 0;
    uint8_t req[8] = {0x40, 0x08, 0x10, 0, 0, 0, 0, 0}, seg[8] = {0x60, 0, 0, 0, 0, 0, 0, 0};
    struct hil_can_frame r;
    uint8_t t = 0;
    uint32_t ab;
    (void)state;
    boot_drive(&d);
    r = drive_req(&d, req);
    assert_int_equal(r.data[0], 0x41);
    for (;;) {
        size_t n;
        seg[0] = (uint8_t)(0x60 | (t << 4));
        r = drive_req(&d, seg);
        assert_int_equal(r.data[0] & 0xE0, 0x00);
        assert_int_equal((r.data[0] >> 4) & 1, t);
        n = 7u - ((r.data[0] >> 1) & 7u);
        memcpy(name + got, r.data + 1, n);
        got += n;
        t ^= 1;
        if (r.data[0] & 1)
            break;
    }
    assert_string_equal(name, "fracarm HIL servo drive (CiA 402 cyclic synchronous torque)");
    assert_int_equal(got, hil_get_u32(drive_req(&d, req).data + 4));
    seg[0] = 0x70; /* toggle 1 where 0 is due */
    r = drive_req(&d, seg);
    assert_int_equal(r.data[0], 0x80);
    assert_int_equal(hil_get_u32(r.data + 4), HIL_SDO_ABORT_TOGGLE);
    seg[0] = 0x60; /* the transfer has ended */
    assert_int_equal(hil_get_u32(drive_req(&d, seg).data + 4), HIL_SDO_ABORT_COMMAND);
    /* segmented download of 0x2101 (2 bytes): initiate with size, one last segment */
    {
        uint8_t init[8] = {0x21, 0x01, 0x21, 0, 2, 0, 0, 0}, s1[8] = {0x0B, 0x84, 0x03, 0, 0, 0, 0, 0};
        r = drive_req(&d, init);
        assert_int_equal(r.data[0], 0x60);
        r = drive_req(&d, s1); /* t = 0, n = 5 unused, c = 1 */
        assert_int_equal(r.data[0], 0x20);
        assert_int_equal(up(&d, 0x2101, 0, &ab), 900u);
        init[4] = 3; /* indicated size unlike the object's */
        assert_int_equal(hil_get_u32(drive_req(&d, init).data + 4), HIL_SDO_ABORT_LENGTH);
        init[4] = 2;
        drive_req(&d, init);
        s1[0] = 0x09; /* 6 unused: 1 byte, then last: size mismatch */
        assert_int_equal(hil_get_u32(drive_req(&d, s1).data + 4), HIL_SDO_ABORT_LENGTH);
        assert_int_equal(up(&d, 0x2101, 0, &ab), 900u);
    }
    /* a client abort ends the transfer without answer */
    {
        uint8_t abort_req[8] = {0x80, 0x08, 0x10, 0, 0, 0, 4, 5};
        struct hil_can_frame f = frame8(HIL_COB_SDO_RX(HIL_NODE_DRIVE), abort_req);
        drive_req(&d, req);
        o.n = 0;
        assert_int_equal(hil_drive_on_frame(&d, &f, &o), HIL_OK);
        assert_int_equal(o.n, 0);
        assert_int_equal(hil_get_u32(drive_req(&d, seg).data + 4), HIL_SDO_ABORT_COMMAND);
    }
}

static void test_pdo_rules_and_remap_applied_at_nmt_start(void **state)
{
    struct hil_drive d;
    const struct hil_can_frame *t3;
    (void)state;
    boot_drive(&d);
    assert_int_equal(down(&d, 0x1A02, 1, 0x60410010, 4), 0); /* sub 0 is 0: an entry may change */
    assert_int_equal(down(&d, 0x1800, 1, 0x40000191, 4), HIL_SDO_ABORT_RANGE); /* valid PDO, new id */
    assert_int_equal(down(&d, 0x1800, 1, 0x40000981, 4), HIL_SDO_ABORT_RANGE); /* bits 11-28 */
    assert_int_equal(down(&d, 0x1802, 1, 0x40000581, 4), HIL_SDO_ABORT_RANGE); /* SDO answer's id */
    assert_int_equal(down(&d, 0x1802, 1, 0x40000701, 4), HIL_SDO_ABORT_RANGE); /* heartbeat's id */
    assert_int_equal(down(&d, 0x1802, 1, 0xC0000581, 4), 0); /* not valid: any id may be parked */
    assert_int_equal(down(&d, 0x1A00, 0, 0, 1), HIL_SDO_ABORT_STATE);          /* TPDO1 is valid */
    assert_int_equal(down(&d, 0x1A02, 2, 0x10000020, 4), HIL_SDO_ABORT_NOT_MAPPABLE); /* 0x1000 */
    assert_int_equal(down(&d, 0x1A02, 2, 0x60410020, 4), HIL_SDO_ABORT_NOT_MAPPABLE); /* wrong length */
    assert_int_equal(down(&d, 0x1601, 1, 0x60410010, 4), HIL_SDO_ABORT_NOT_MAPPABLE); /* RO into an RPDO */
    assert_int_equal(down(&d, 0x1802, 2, 250, 1), HIL_SDO_ABORT_RANGE);  /* reserved type */
    assert_int_equal(down(&d, 0x1802, 2, 254, 1), HIL_SDO_ABORT_RANGE);  /* drive: synchronous only */
    assert_int_equal(down(&d, 0x1A02, 2, 0x60770010, 4), 0);
    assert_int_equal(down(&d, 0x1A02, 3, 0x606C0020, 4), 0);
    assert_int_equal(down(&d, 0x1A02, 4, 0x60640020, 4), 0);
    assert_int_equal(down(&d, 0x1A02, 0, 4, 1), HIL_SDO_ABORT_PDO_LENGTH); /* 96 bits */
    assert_int_equal(down(&d, 0x1A02, 0, 3, 1), 0);
    assert_int_equal(down(&d, 0x1A02, 1, 0x60640020, 4), HIL_SDO_ABORT_STATE); /* sub 0 is 3 */
    assert_int_equal(down(&d, 0x1802, 2, 2, 1), 0);                             /* every 2nd SYNC */
    assert_int_equal(down(&d, 0x1802, 1, 0x40000381, 4), 0);
    sync1(&d);
    assert_null(find(0x381)); /* pre-operational: no PDO */
    nmt(&d, HIL_NMT_START);
    sync1(&d);
    assert_null(find(0x381)); /* SYNC 1 of 2 */
    sync1(&d);
    t3 = find(0x381);
    assert_non_null(t3);
    assert_int_equal(t3->dlc, 8);
    assert_int_equal(hil_get_u16(t3->data), hil_drive_statusword(&d));
    assert_non_null(find(0x181));
    assert_non_null(find(0x281));
    /* reset communication restores the EDS's PDOs */
    nmt(&d, HIL_NMT_RESET_COMM);
    nmt(&d, HIL_NMT_START);
    sync1(&d);
    sync1(&d);
    assert_null(find(0x381));
}

static void test_default_pdos_are_the_frames_the_controller_decodes(void **state)
{
    struct hil_drive d;
    struct hil_imu m;
    struct hil_imu_params ip;
    struct hil_drive_tpdo1 t1;
    struct hil_drive_tpdo2 t2;
    struct hil_imu_tpdo it;
    struct hil_can_frame f;
    int k, n1 = 0, n2 = 0;
    (void)state;
    boot_drive(&d);
    nmt(&d, HIL_NMT_START);
    d.theta = 0.3;
    d.omega = -1.25;
    d.tau_act = 12.5;
    sync1(&d);
    assert_int_equal(hil_co_drive_tpdo1_decode(find(0x181), &t1), HIL_OK);
    assert_int_equal(t1.statusword, hil_drive_statusword(&d));
    assert_int_equal(t1.position_inc, (int32_t)floor(0.3 * 1048576.0 / (2.0 * M_PI)));
    assert_int_equal(hil_co_drive_tpdo2_decode(find(0x281), &t2), HIL_OK);
    assert_int_equal(t2.velocity_urads, -1250000);
    assert_int_equal(t2.torque_mnm, 12500);
    rpdo(&d, HIL_CW_SHUTDOWN, -4321);
    {
        uint32_t ab;
        assert_int_equal((int32_t)up(&d, 0x2071, 0, &ab), -4321);
        assert_int_equal((int16_t)up(&d, 0x6071, 0, &ab), -45); /* -4.321 / 95.7 per mille */
        assert_int_equal(up(&d, 0x6040, 0, &ab), HIL_CW_SHUTDOWN);
    }
    /* the IMU: one reading = TPDO1 + TPDO2 as hil_co_imu_decode reads them */
    hil_imu_params_default(&ip);
    o.n = 0;
    hil_imu_init(&m, &ip, &o);
    hil_co_nmt_encode(&f, HIL_NMT_START, 0);
    hil_imu_on_frame(&m, &f, &o);
    for (k = 0; k < 8; k++) {
        hil_co_rig_encode(&f, HIL_COB_RIG_TIP, 0.75, -2.0);
        o.n = 0;
        hil_imu_on_frame(&m, &f, &o);
        if (find(0x182)) {
            assert_int_equal(hil_co_imu_decode(find(0x182), 1, &it), HIL_OK);
            assert_int_equal(it.xyz[2], 750);
            assert_int_equal(it.seq, m.seq);
            n1++;
        }
        if (find(0x282)) {
            assert_int_equal(hil_co_imu_decode(find(0x282), 2, &it), HIL_OK);
            assert_int_equal(it.xyz[1], -2000);
            assert_int_equal(it.xyz[2], 9807);
            n2++;
        }
    }
    assert_int_equal(n1, 1);
    assert_int_equal(n2, 1);
}

static void test_heartbeat_follows_0x1017(void **state)
{
    struct hil_drive d;
    int k, beats = 0;
    (void)state;
    boot_drive(&d);
    assert_int_equal(down(&d, 0x1017, 0, 12, 2), 0); /* 12 ms = 10 SYNCs of 1.2 ms */
    nmt(&d, HIL_NMT_START);
    for (k = 0; k < 100; k++) {
        sync1(&d);
        beats += find(0x701) != NULL;
    }
    assert_int_equal(beats, 10);
    assert_int_equal(down(&d, 0x1017, 0, 0, 2), 0); /* 0: no heartbeat */
    for (k = 0, beats = 0; k < 100; k++) {
        sync1(&d);
        beats += find(0x701) != NULL;
    }
    assert_int_equal(beats, 0);
}

static void enable(struct hil_drive *d)
{
    rpdo(d, HIL_CW_SHUTDOWN, 0);
    rpdo(d, HIL_CW_SWITCH_ON, 0);
    rpdo(d, HIL_CW_ENABLE_OP, 0);
    assert_int_equal(d->state, HIL_CIA402_OPERATION_ENABLED);
}

static void test_quick_stop_options_and_fault_reset_clear_errors_with_emcy(void **state)
{
    struct hil_drive d;
    uint32_t ab;
    struct hil_emcy e;
    int k;
    (void)state;
    boot_drive(&d);
    nmt(&d, HIL_NMT_START);
    enable(&d);
    assert_true(hil_drive_statusword(&d) & 0x1000u); /* CST: following the target */
    rpdo(&d, HIL_CW_QUICK_STOP, 50000);
    assert_int_equal(d.state, HIL_CIA402_QUICK_STOP_ACTIVE);
    assert_int_equal(hil_drive_statusword(&d) & 0x6F, 0x07);
    for (k = 0; k < 6; k++) {
        sync1(&d);
        rpdo(&d, HIL_CW_QUICK_STOP, 50000);
    }
    assert_int_equal(d.state, HIL_CIA402_QUICK_STOP_ACTIVE); /* option 6: stays */
    assert_true(fabs(d.tau_act) < 1e-9);
    rpdo(&d, HIL_CW_ENABLE_OP, 0);
    assert_int_equal(d.state, HIL_CIA402_OPERATION_ENABLED); /* transition 16 */
    nmt(&d, HIL_NMT_PREOP);
    assert_int_equal(down(&d, 0x605A, 0, 2, 2), 0);
    nmt(&d, HIL_NMT_START);
    rpdo(&d, HIL_CW_QUICK_STOP, 0);
    sync1(&d);
    assert_int_equal(d.state, HIL_CIA402_SWITCH_ON_DISABLED); /* option 2 */
    /* mode 0: enabled but no torque */
    enable(&d);
    assert_int_equal(down(&d, 0x6060, 0, 0, 1), 0);
    for (k = 0; k < 8; k++) {
        rpdo(&d, HIL_CW_ENABLE_OP, 50000);
        sync1(&d);
    }
    assert_true(fabs(d.tau_act) < 1e-9);
    assert_int_equal(up(&d, 0x6061, 0, &ab), 0u);
    assert_false(hil_drive_statusword(&d) & 0x1000u);
    assert_int_equal(down(&d, 0x6060, 0, 10, 1), 0);
    /* over-temperature: trip at 10 % of rated^2, 60 Nm commanded */
    assert_int_equal(down(&d, 0x2101, 0, 100, 2), 0);
    for (k = 0; k < 1000 && d.state != HIL_CIA402_FAULT; k++) {
        rpdo(&d, HIL_CW_ENABLE_OP, 60000);
        sync1(&d);
    }
    assert_int_equal(d.state, HIL_CIA402_FAULT);
    assert_non_null(find(0x081));
    hil_co_emcy_decode(find(0x081), NULL, &e);
    assert_int_equal(e.code, HIL_EMCY_OVERTEMP);
    assert_int_equal(e.error_register, 0x09);
    assert_int_equal(up(&d, 0x603F, 0, &ab), HIL_EMCY_OVERTEMP);
    assert_int_equal(up(&d, 0x1001, 0, &ab), 0x09u);
    assert_int_equal(down(&d, 0x2101, 0, 10, 2), 0); /* still above a lower trip */
    rpdo(&d, HIL_CW_FAULT_RESET, 0);
    assert_int_equal(d.state, HIL_CIA402_FAULT);
    assert_int_equal(down(&d, 0x2101, 0, 1100, 2), 0);
    rpdo(&d, 0, 0);
    rpdo(&d, HIL_CW_FAULT_RESET, 0);
    assert_int_equal(d.state, HIL_CIA402_SWITCH_ON_DISABLED);
    assert_non_null(find(0x081));
    hil_co_emcy_decode(find(0x081), NULL, &e);
    assert_int_equal(e.code, HIL_EMCY_NO_ERROR);
    assert_int_equal(e.error_register, 0);
    assert_int_equal(up(&d, 0x603F, 0, &ab), 0u);
    assert_int_equal(up(&d, 0x1001, 0, &ab), 0u);
    /* bus-off recovered: EMCY 0x8140 with 0x603F and the communication bit */
    o.n = 0;
    hil_drive_set_bus_off(&d, 1, &o);
    hil_drive_set_bus_off(&d, 0, &o);
    hil_co_emcy_decode(find(0x081), NULL, &e);
    assert_int_equal(e.code, HIL_EMCY_BUS_OFF_RECOVERED);
    assert_int_equal(up(&d, 0x603F, 0, &ab), HIL_EMCY_BUS_OFF_RECOVERED);
    assert_int_equal(up(&d, 0x1001, 0, &ab), 0x11u);
}

/* Answers every SDO request of a boot with the devices, but with `lie`
 * substituted as the drive's answer to step `bad` (0: no lie). */
static int run_boot(struct hil_ctrl *c, int bad, const uint8_t lie[8])
{
    struct hil_drive d;
    struct hil_imu m;
    struct hil_imu_params ip;
    struct hil_out q, next;
    int i, round, step = 0;
    boot_drive(&d);
    hil_imu_params_default(&ip);
    o.n = 0;
    hil_imu_init(&m, &ip, &o);
    q.n = 0;
    hil_ctrl_boot(c, &q);
    for (round = 0; round < 200 && q.n > 0; round++) {
        next.n = 0;
        for (i = 0; i < q.n; i++) {
            struct hil_out r;
            int j;
            r.n = 0;
            hil_drive_on_frame(&d, &q.f[i], &r);
            hil_imu_on_frame(&m, &q.f[i], &r);
            for (j = 0; j < r.n; j++) {
                if (r.f[j].id == HIL_COB_SDO_TX(HIL_NODE_DRIVE) && ++step == bad)
                    memcpy(r.f[j].data, lie, 8);
                hil_ctrl_on_frame(c, &r.f[j], &next);
            }
        }
        q = next;
    }
    return c->boot_status;
}

static void test_ctrl_boots_by_sdo_and_names_what_failed(void **state)
{
    struct hil_ctrl c;
    struct hil_ctrl_params p;
    const uint8_t wrong_type[8] = {0x43, 0x00, 0x10, 0x00, 0x91, 0x01, 0x02, 0x00};
    const uint8_t aborted[8] = {0x80, 0x00, 0x10, 0x00, 0x00, 0x00, 0x02, 0x06};
    (void)state;
    hil_ctrl_params_default(&p);
    hil_ctrl_init(&c, &p);
    assert_int_equal(run_boot(&c, 0, NULL), 1);
    assert_int_equal(c.sdo_requests, (uint64_t)(c.boot[0].n + c.boot[1].n));
    assert_true(c.boot[0].n > 20 && c.boot[1].n > 20);
    hil_ctrl_init(&c, &p);
    assert_true(run_boot(&c, 1, wrong_type) < 0);
    assert_non_null(strstr(c.boot_error, "0x1000:0 is 0x00020191, the EDS says 0x00020192"));
    hil_ctrl_init(&c, &p);
    assert_true(run_boot(&c, 1, aborted) < 0);
    assert_non_null(strstr(c.boot_error, "aborted 0x06020000"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sdo_expedited_transfers_and_every_abort_path),
        cmocka_unit_test(test_sdo_segmented_upload_download_toggle_and_client_abort),
        cmocka_unit_test(test_pdo_rules_and_remap_applied_at_nmt_start),
        cmocka_unit_test(test_default_pdos_are_the_frames_the_controller_decodes),
        cmocka_unit_test(test_heartbeat_follows_0x1017),
        cmocka_unit_test(test_quick_stop_options_and_fault_reset_clear_errors_with_emcy),
        cmocka_unit_test(test_ctrl_boots_by_sdo_and_names_what_failed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
