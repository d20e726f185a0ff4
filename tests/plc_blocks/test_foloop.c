/* FoLoop (seed 001 example program) in the task runtime, lockstep with the
 * delayed fractional process of notes 001 (51) simulated by frac/foprocess.h:
 * the FO-PI (52) and the FO-PD with positive feedback (53, reading (c)) on FOPID
 * track a unit step as the notes' reference simulations (notes 001 8.3). */
#include "frac_test.h"
#include "FoLoop.h"
#include "fracctrl_seed_params.h"
#include "plc_rt.h"
#include "frac/foprocess.h"

#include <string.h>

#define TS 0.002
#define PLANT_MEMORY 21000 /* GL terms: 42 s, the whole run (notes 001 8.3 use full memory) */

typedef struct rig {
    frac_foprocess plant;
    frac_real storage[3 * PLANT_MEMORY + 256];
    foloop_inputs in_img;
    foloop_outputs out_img;
    uint64_t ticks;
    double y, max_abs_y, max_err_tail, y_at_41;
} rig;

static void rig_init(rig *r)
{
    frac_foprocess_params p;
    memset(r, 0, sizeof *r);
    memset(&p, 0, sizeof p);
    p.k = 1.0;
    p.t = FRAC_R(0.0292866); /* 1/omega_0^2, omega_0 = 5.8434 rad/s */
    p.lambda = FRAC_R(1.92);
    p.tau = FRAC_R(0.1613);
    p.ts = FRAC_R(TS);
    p.op.method = FRAC_FO_GL;
    p.op.memory = PLANT_MEMORY;
    assert_true(frac_foprocess_storage_len(&p) <= sizeof r->storage / sizeof r->storage[0]);
    assert_int_equal(frac_foprocess_init(&r->plant, &p, r->storage, sizeof r->storage / sizeof r->storage[0]),
                     FRAC_OK);
}

/* Every 2 ms (20 ticks): one plant sample with the published u, then the
 * measurement and the reference (unit step at 1 s) into the image. */
static void rig_tick(void *ctx, uint64_t t_ns)
{
    rig *r = (rig *)ctx;
    frac_real y;
    double t = (double)t_ns * 1e-9;
    if (r->ticks++ % 20) {
        return;
    }
    assert_int_equal(frac_foprocess_step(&r->plant, (frac_real)r->out_img.U, &y), FRAC_OK);
    r->y = (double)y;
    r->in_img.Measurement = (REAL)y;
    r->in_img.Reference = t >= 1.0 ? 1.0f : 0.0f;
    if (fabs(r->y) > r->max_abs_y) {
        r->max_abs_y = fabs(r->y);
    }
    if (r->ticks - 1 == 410000) {
        r->y_at_41 = r->y; /* 40 s after the step */
    }
    if (t >= 15.0 && fabs(r->y - 1.0) > r->max_err_tail) {
        r->max_err_tail = fabs(r->y - 1.0);
    }
}

static unsigned char table[4096];
static unsigned long table_size;

static void read_table(const char *name)
{
    char path[512];
    FILE *fp;
    snprintf(path, sizeof path, "%s/tests/plc_blocks/fixtures/%s", FRAC_SOURCE_DIR, name);
    fp = fopen(path, "rb");
    assert_non_null(fp);
    table_size = (unsigned long)fread(table, 1, sizeof table, fp);
    fclose(fp);
    assert_true(table_size > 52);
}

/* from_table: the controller comes from `table` (the data object). */
static void run_loop_from(rig *r, const foloop_params *par, int from_table)
{
    static foloop f;
    plc_program prog;
    const plc_program *reg[1];
    plc_rt_config cfg;
    plc_rt rt;
    char err[256];
    if (from_table) {
        foloop_program_table(&f, &prog, par, table, (UDINT)table_size, &r->in_img, &r->out_img);
    } else {
        foloop_program(&f, &prog, par, &r->in_img, &r->out_img);
    }
    reg[0] = &prog;
    assert_int_equal(plc_rt_config_parse(&cfg,
        "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n"
        "[cyclic3]\nduration_us = 2000\nprograms = FoLoop\n", "foloop", err, sizeof err), PLC_RT_OK);
    assert_int_equal(plc_rt_init(&rt, &cfg, reg, 1, err, sizeof err), PLC_RT_OK);
    rt.tick_hook = rig_tick;
    rt.tick_ctx = r;
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_sim(&rt, 420000), PLC_RT_OK); /* 42 s */
    plc_rt_stop(&rt);
}

static void run_loop(rig *r, const foloop_params *par)
{
    run_loop_from(r, par, 0);
    assert_false(r->out_img.Error);
    assert_int_equal(r->out_img.StatusID, fracSTAT_OK);
}

/* Realization, limits and Ts of the program; the gains come from a table. */
static void base_params(foloop_params *par)
{
    memset(par, 0, sizeof *par);
    seed001_realization(&par->Pid);
}

static void test_fo_loop_runs_the_fracdesign_tables(void **state)
{
    static rig r;
    foloop_params par;
    (void)state;
    /* fracdesign tune fopi (omega_c = 6.36) -> table emit: the same loop as (52) */
    read_table("fopi_seed001.bin");
    rig_init(&r);
    base_params(&par);
    run_loop_from(&r, &par, 1);
    print_message("fopi table: y(40 s after the step) = %.4f\n", r.y_at_41);
    assert_false(r.out_img.Error);
    assert_close(r.y_at_41, 0.909, 0.02);
    /* fracdesign tune fopd (omega_c = 6.86, spec-consistent reading (a)):
     * notes 001 8.3: overshoot 95.1 %, final value 1 */
    read_table("fopd_seed001.bin");
    rig_init(&r);
    base_params(&par);
    run_loop_from(&r, &par, 1);
    print_message("fopd table: peak %.3f, y(40 s after the step) = %.4f\n", r.max_abs_y, r.y_at_41);
    assert_false(r.out_img.Error);
    assert_close(r.max_abs_y, 1.951, 0.05);
    assert_close(r.y_at_41, 1.0, 0.01);
}

static void test_fo_loop_refuses_a_corrupted_table(void **state)
{
    static rig r;
    foloop_params par;
    (void)state;
    read_table("fopi_seed001.bin");
    table[table_size - 10] ^= 0x40;
    rig_init(&r);
    base_params(&par);
    run_loop_from(&r, &par, 1);
    assert_true(r.out_img.Error);
    assert_int_equal(r.out_img.StatusID, fracERR_TABLE_CRC);
    assert_true(r.max_abs_y == 0.0);
}

static void test_fo_pi_52_settles_a_step_without_error(void **state)
{
    static rig r;
    foloop_params par;
    (void)state;
    rig_init(&r);
    memset(&par, 0, sizeof par);
    seed001_fopi52(&par.Pid); /* Oustaloup over 7 decades (fracctrl_seed_params.h) */
    run_loop(&r, &par);
    print_message("FO-PI (52): y(40 s after the step) = %.4f, max |y| = %.3f\n", r.y_at_41, r.max_abs_y);
    /* notes 001 8.3 (GL full memory, their step 0.5): y(40 s) = 0.4544 / 0.5
     * = 0.909, a slow fractional creep without overshoot */
    assert_close(r.y_at_41, 0.909, 0.02);
    assert_true(r.max_abs_y < 1.0);
}

static void test_fo_pd_53_with_positive_feedback_settles_a_step(void **state)
{
    static rig r;
    foloop_params par;
    (void)state;
    rig_init(&r);
    memset(&par, 0, sizeof par);
    par.Pid.Kp = 1.0f;     /* K_p + delta of (41) with K_p = 0 */
    par.Pid.Kd = 0.0256f;
    par.Pid.Mu = 0.88f;
    par.Pid.B = 1.0f;
    par.Pid.C = 1.0f;
    par.Pid.Delta = 1.0f;  /* = 1/K, (37) */
    par.Pid.Y_min = -10.0f;
    par.Pid.Y_max = 10.0f;
    par.Pid.Ts = (REAL)TS;
    par.Pid.Method = fracFO_GL;
    par.Pid.Memory = 500;
    run_loop(&r, &par);
    print_message("FO-PD (53c): |y - 1| <= %.2e from 15 s on, max |y| = %.3f\n", r.max_err_tail, r.max_abs_y);
    /* notes 001 8.3: overshoot 76.3 %, 2 % settling 5.86 s, final value 1 */
    assert_close(r.max_abs_y, 1.763, 0.05);
    assert_true(r.max_err_tail < 0.02);
}

static void test_fo_loop_bad_parameters_keep_the_output_at_zero(void **state)
{
    static rig r;
    static foloop f;
    foloop_params par;
    plc_program prog;
    int k;
    (void)state;
    rig_init(&r);
    memset(&par, 0, sizeof par);
    par.Pid.Kp = 1.0f;
    par.Pid.Y_min = -1.0f;
    par.Pid.Y_max = 1.0f;
    par.Pid.Ts = 0.0f; /* invalid */
    par.Pid.Method = fracFO_GL;
    par.Pid.Memory = 10;
    foloop_program(&f, &prog, &par, &r.in_img, &r.out_img);
    foloop_init(&f);
    assert_true(f.out.Error);
    assert_int_equal(f.out.StatusID, fracERR_LIBFRAC - FRAC_E_TS);
    f.in.Reference = 1.0f;
    for (k = 0; k < 10; k++) {
        foloop_cyclic(&f);
        assert_true(f.out.U == 0.0f);
    }
    foloop_exit(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fo_pi_52_settles_a_step_without_error),
        cmocka_unit_test(test_fo_pd_53_with_positive_feedback_settles_a_step),
        cmocka_unit_test(test_fo_loop_bad_parameters_keep_the_output_at_zero),
        cmocka_unit_test(test_fo_loop_runs_the_fracdesign_tables),
        cmocka_unit_test(test_fo_loop_refuses_a_corrupted_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
