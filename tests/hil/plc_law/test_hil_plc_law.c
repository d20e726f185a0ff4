/* The controller node running plc_blocks' ArmCtrl (Exp. A) and ImuRead in the
 * plc_rt task runtime, on the bench against the twomass plant: the Table 8.5
 * move is tracked with the thesis's torque range, and the drive TPDOs
 * stopping trip ArmCtrl's watchdog: torque to zero within 10 ms, EMCY. */
#include <stdlib.h>
#include <string.h>
#include "frac_test.h"
#include "hil/candump.h"
#include "hil/canopen.h"
#include "hil/rig.h"
#include "plc_law.h"

static struct hil_rig rig;
static struct hil_plc_law law;

static void exp_a_config(struct hil_rig_config *c)
{
    hil_rig_config_default(c);
    assert_int_equal(hil_rig_config_set(c, "plant", "twomass"), HIL_OK);
    assert_int_equal(hil_rig_config_set(c, "ctrl.law", "armctrl_a"), HIL_OK);
    c->plant_p.substeps = 8;
    c->duration = 3.2;
}

static void start(const struct hil_rig_config *c, FILE *log, FILE *csv)
{
    char err[256];
    assert_int_equal(hil_rig_init(&rig, c, log, csv), HIL_OK);
    assert_int_equal(hil_plc_law_init_exp_a(&law, c->ctrl.T, c->plant_p.I_M, c->plant_p.I_L, c->plant_p.c_s, err,
                                            sizeof err),
                     HIL_OK);
    hil_ctrl_set_law(&rig.ctrl, hil_plc_law_step, &law);
}

static void test_exp_a_tracks_table_8_5_with_thesis_torque_range(void **state)
{
    struct hil_rig_config c;
    FILE *csv = tmpfile();
    char line[512];
    double tmin = 0.0, tmax = 0.0;
    int row = 0;
    (void)state;
    exp_a_config(&c);
    start(&c, NULL, csv);
    assert_int_equal(hil_rig_run(&rig), HIL_OK);
    rewind(csv);
    while (fgets(line, sizeof line, csv)) {
        char *p = line;
        double u;
        if (row++ == 0)
            continue;
        strtod(p, &p);
        strtod(p + 1, &p);
        u = strtod(p + 1, &p);
        if (u < tmin)
            tmin = u;
        if (u > tmax)
            tmax = u;
    }
    print_message("Exp. A on the bench: torque %.1f .. %.1f Nm, final tip %.6f rad\n", tmin, tmax, rig.plant.psi);
    /* thesis Exp. A: about -40 .. 60 Nm */
    assert_true(tmax > 30.0 && tmax < 60.0);
    assert_true(tmin < -20.0 && tmin > -40.0);
    assert_close(rig.plant.psi, FRAC_PI / 2, 2e-3);
    assert_close(rig.plant.psi_d, 0.0, 1e-2);
    assert_int_equal(rig.ctrl.faults, 0);
    assert_int_equal(rig.ctrl.missed_inputs, 0);
    hil_plc_law_stop(&law);
    fclose(csv);
}

static void test_drive_tpdos_stopping_ramp_torque_to_zero_with_emcy(void **state)
{
    struct hil_rig_config c;
    FILE *log = tmpfile();
    char line[128], iface[HIL_CANDUMP_IFACE_MAX];
    struct hil_can_frame f;
    double t, t_fault = -1.0, t_zero = -1.0;
    (void)state;
    exp_a_config(&c);
    c.duration = 1.5;
    c.drive_dropout_start = 1.0; /* mid-move, torque well away from zero */
    c.drive_dropout_end = 2.0;
    start(&c, log, NULL);
    assert_int_equal(hil_rig_run(&rig), HIL_OK);
    rewind(log);
    while (fgets(line, sizeof line, log)) {
        assert_int_equal(hil_candump_parse(line, &t, iface, &f), HIL_OK);
        if (f.id == HIL_COB_EMCY(HIL_NODE_CTRL) && t_fault < 0.0)
            t_fault = t;
        if (f.id == HIL_COB_RPDO1(HIL_NODE_DRIVE) && t > 0.99 && t_zero < 0.0 &&
            hil_get_u32(f.data + 2) == 0)
            t_zero = t;
    }
    assert_true(t_fault > 1.0 && t_fault < 1.0 + 4 * c.ctrl.T);
    assert_true(t_zero > 0.0);
    assert_true(t_zero - 1.0 <= 10e-3 + 4 * c.ctrl.T);
    assert_int_equal(rig.ctrl.faults, 1);
    hil_plc_law_stop(&law);
    fclose(log);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exp_a_tracks_table_8_5_with_thesis_torque_range),
        cmocka_unit_test(test_drive_tpdos_stopping_ramp_torque_to_zero_with_emcy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
