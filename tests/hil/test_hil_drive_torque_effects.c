/* The drive's torque effects for the gap bench (hil/drive.h, item 5): the
 * shaft receives gain * dz(tau) while the drive reports tau as its torque
 * actual; bad values are rejected; the scenario keys drive.deadzone and
 * drive.gain load and appear in the run metadata. */
#include <stdio.h>
#include <string.h>
#include "frac_test.h"
#include "hil/canopen.h"
#include "hil/drive.h"
#include "hil/rig.h"

static const struct hil_can_frame *find(const struct hil_out *o, uint32_t id)
{
    int i;
    for (i = 0; i < o->n; i++)
        if (o->f[i].id == id)
            return &o->f[i];
    return NULL;
}

static void send(struct hil_drive *d, const struct hil_can_frame *f, struct hil_out *o)
{
    o->n = 0;
    assert_int_equal(hil_drive_on_frame(d, f, o), HIL_OK);
}

static struct hil_can_frame rpdo(uint16_t cw, double torque)
{
    struct hil_can_frame f;
    struct hil_drive_rpdo r;
    r.controlword = cw;
    r.torque_mnm = (int32_t)(torque * 1000.0);
    hil_co_drive_rpdo_encode(&f, &r);
    return f;
}

/* Enabled drive with delay 1 and an ideal current loop; after one SYNC with
 * command `cmd` pending: *shaft = end torque sent to the plant, *reported =
 * the torque actual of the next TPDO2. */
static void shaft_and_reported(double deadzone, double gain, double cmd, double *shaft, double *reported)
{
    static const uint16_t cws[] = {HIL_CW_SHUTDOWN, HIL_CW_SWITCH_ON, HIL_CW_ENABLE_OP};
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    struct hil_can_frame f;
    struct hil_drive_tpdo2 t2;
    const struct hil_can_frame *t;
    double a, b;
    int i;
    hil_drive_params_default(&p);
    p.delay = 1;
    p.tau_current = 0.0;
    p.deadzone = deadzone;
    p.gain = gain;
    o.n = 0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_OK);
    hil_co_nmt_encode(&f, HIL_NMT_START, 0);
    send(&d, &f, &o);
    for (i = 0; i < 3; i++) {
        f = rpdo(cws[i], 0.0);
        send(&d, &f, &o);
    }
    f = rpdo(HIL_CW_ENABLE_OP, cmd);
    send(&d, &f, &o);
    hil_co_sync_encode(&f, 1);
    send(&d, &f, &o);
    t = find(&o, HIL_COB_RIG_TORQUE);
    assert_non_null(t);
    assert_int_equal(hil_co_rig_decode(t, HIL_COB_RIG_TORQUE, &a, &b), HIL_OK);
    *shaft = b;
    f = rpdo(HIL_CW_ENABLE_OP, cmd);
    send(&d, &f, &o);
    hil_co_sync_encode(&f, 2);
    send(&d, &f, &o);
    t = find(&o, HIL_COB_TPDO2(HIL_NODE_DRIVE));
    assert_non_null(t);
    assert_int_equal(hil_co_drive_tpdo2_decode(t, &t2), HIL_OK);
    *reported = t2.torque_mnm * HIL_TORQUE_LSB;
}

static void test_drive_dead_zone_and_gain_act_on_the_shaft_torque_only(void **state)
{
    double shaft, rep;
    (void)state;
    shaft_and_reported(0.0, 1.0, 20.0, &shaft, &rep);
    assert_close(shaft, 20.0, 1e-9);
    shaft_and_reported(5.0, 1.0, 20.0, &shaft, &rep);
    assert_close(shaft, 15.0, 1e-9);
    assert_close(rep, 20.0, 1e-9);
    shaft_and_reported(5.0, 1.0, -20.0, &shaft, &rep);
    assert_close(shaft, -15.0, 1e-9);
    shaft_and_reported(5.0, 1.0, 4.0, &shaft, &rep);
    assert_close(shaft, 0.0, 1e-12);
    assert_close(rep, 4.0, 1e-9);
    shaft_and_reported(0.0, 1.25, 20.0, &shaft, &rep);
    assert_close(shaft, 25.0, 1e-9);
    assert_close(rep, 20.0, 1e-9);
    shaft_and_reported(2.0, 0.5, -20.0, &shaft, &rep);
    assert_close(shaft, -9.0, 1e-9);
}

static void test_drive_rejects_negative_dead_zone_and_non_positive_gain(void **state)
{
    struct hil_drive d;
    struct hil_drive_params p;
    struct hil_out o;
    (void)state;
    o.n = 0;
    hil_drive_params_default(&p);
    assert_close(p.gain, 1.0, 0.0);
    assert_close(p.deadzone, 0.0, 0.0);
    p.deadzone = -1.0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_E_ARG);
    hil_drive_params_default(&p);
    p.gain = 0.0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_E_ARG);
    p.gain = -1.0;
    assert_int_equal(hil_drive_init(&d, &p, &o), HIL_E_ARG);
}

static void test_rig_keys_set_dead_zone_and_gain_and_the_metadata_records_them(void **state)
{
    struct hil_rig_config c;
    char buf[16384];
    FILE *f;
    size_t n;
    (void)state;
    hil_rig_config_default(&c);
    assert_int_equal(hil_rig_config_set(&c, "drive.deadzone", "3.5"), HIL_OK);
    assert_int_equal(hil_rig_config_set(&c, "drive.gain", "0.8"), HIL_OK);
    assert_int_equal(hil_rig_config_set(&c, "drive.gain", "x"), HIL_E_FORMAT);
    assert_close(c.drive.deadzone, 3.5, 0.0);
    assert_close(c.drive.gain, 0.8, 0.0);
    f = tmpfile();
    assert_non_null(f);
    assert_int_equal(hil_rig_meta_begin(&c, "lockstep", f), HIL_OK);
    rewind(f);
    n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    assert_non_null(strstr(buf, "\"drive.deadzone\": 3.5,"));
    assert_non_null(strstr(buf, "\"drive.gain\": 0.80000000000000004,"));
    assert_non_null(strstr(buf, "\"torque_deadzone\": 3.5, \"torque_gain\": 0.80000000000000004}"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drive_dead_zone_and_gain_act_on_the_shaft_torque_only),
        cmocka_unit_test(test_drive_rejects_negative_dead_zone_and_non_positive_gain),
        cmocka_unit_test(test_rig_keys_set_dead_zone_and_gain_and_the_metadata_records_them),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
