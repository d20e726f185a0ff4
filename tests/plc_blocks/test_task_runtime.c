/* Host emulation of the B&R task model (plc_blocks/runtime/plc_rt.h):
 * configuration (Table 2.3), priority scheduling on the simulated clock,
 * the I/O image, _INIT/_EXIT order, cycle-time violations, wall clock,
 * the idle task class. */
#include "frac_test.h"
#include "plc_rt.h"

#include <string.h>
#include <time.h>

#define US 1000u

/* ---- trace recording ---- */
typedef struct ev_log {
    plc_rt_event ev[256];
    size_t n;
} ev_log;

static void record(void *ctx, const plc_rt_event *e)
{
    ev_log *l = (ev_log *)ctx;
    if (l->n < 256) {
        l->ev[l->n++] = *e;
    }
}

static void expect_event(const ev_log *l, size_t i, plc_rt_event_kind kind, unsigned cls, unsigned t_us)
{
    if (i >= l->n) {
        fail_msg("event %u missing (only %u recorded)", (unsigned)i, (unsigned)l->n);
    }
    if (l->ev[i].kind != kind || l->ev[i].cls != cls || l->ev[i].t_ns != (uint64_t)t_us * US) {
        fail_msg("event %u: got kind %d class %u t %.1f us, expected kind %d class %u t %u us", (unsigned)i,
                 (int)l->ev[i].kind, l->ev[i].cls, (double)l->ev[i].t_ns / US, (int)kind, cls, t_us);
    }
}

/* Starts the runtime with every trace event recorded into `log` and runs
 * `ticks` system ticks on the simulated clock. */
static void run_traced(plc_rt *rt, ev_log *log, unsigned ticks)
{
    memset(log, 0, sizeof *log);
    rt->trace_hook = record;
    rt->trace_ctx = log;
    assert_int_equal(plc_rt_start(rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_sim(rt, ticks), PLC_RT_OK);
}

static void load(plc_rt_config *cfg, const char *text)
{
    char err[256];
    int rc = plc_rt_config_parse(cfg, text, "test", err, sizeof err);
    if (rc != PLC_RT_OK) {
        fail_msg("config rejected: %s", err);
    }
}

static void build(plc_rt *rt, const plc_rt_config *cfg, const plc_program *const *reg, size_t n)
{
    char err[256];
    int rc = plc_rt_init(rt, cfg, reg, n, err, sizeof err);
    if (rc != PLC_RT_OK) {
        fail_msg("init failed: %s", err);
    }
}

/* ---- configuration ---- */
static void test_config_file_mirrors_table_2_3(void **state)
{
    plc_rt_config cfg;
    char err[256];
    (void)state;
    assert_int_equal(plc_rt_config_load(&cfg, FRAC_SOURCE_DIR "/plc_blocks/runtime/x20cp1586.cfg", err, sizeof err),
                     PLC_RT_OK);
    assert_int_equal(cfg.interface_cycle_us, 400);
    assert_int_equal(cfg.tick_us, 100);
    assert_int_equal(cfg.cls[0].duration_us, 1200);
    assert_int_equal(cfg.cls[1].duration_us, 600);
    assert_int_equal(cfg.cyclic_resources, 8);
    assert_int_equal(cfg.idle_task_class, 2);
    assert_int_equal(cfg.idle_time_us, 600);
    assert_int_equal(cfg.reaction, PLC_RT_REACT_SERVICE);
    assert_string_equal(cfg.cls[0].programs[0], "ArmCtrl");
    assert_string_equal(cfg.cls[1].programs[0], "ImuRead");
}

static void expect_rejected(const char *text, const char *msg_part)
{
    plc_rt_config cfg;
    char err[256] = "";
    assert_int_equal(plc_rt_config_parse(&cfg, text, "bad.cfg", err, sizeof err), PLC_RT_E_CONFIG);
    if (!strstr(err, msg_part)) {
        fail_msg("message '%s' does not mention '%s'", err, msg_part);
    }
}

static void test_config_rejects_violations_of_the_timing_rules(void **state)
{
    (void)state;
    expect_rejected("[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n[cyclic1]\nduration_us = 1250\n",
                    "not a multiple of the system tick 100 us");
    expect_rejected("[timing]\ninterface_cycle_us = 500\n[cyclic1]\nduration_us = 1000\n",
                    "not a positive multiple of 400 us");
    expect_rejected("[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.3\n",
                    "not a positive integer or the reciprocal of one");
    expect_rejected("[timing]\ninterface_cycle_us = 400\n[resources]\ncyclic_resources = 2\n[cyclic3]\nduration_us = 400\n",
                    "[cyclic3] is configured but cyclic_resources = 2");
    expect_rejected("[timing]\ninterface_cycle_us = 400\n[cyclic9]\n", "unknown section [cyclic9]");
    expect_rejected("[timing]\ninterface_cycle_us = 400\ncycle = 3\n", "bad.cfg:3: unknown key 'cycle'");
    expect_rejected("[timing]\ninterface_cycle_us = -400\n", "bad.cfg:2: interface_cycle_us = '-400'");
    expect_rejected("[timing]\ninterface_cycle_us = 400\n[cyclic1]\nprograms = A\n", "has programs but no duration_us");
}

static void test_unknown_program_is_reported(void **state)
{
    plc_rt_config cfg;
    plc_rt rt;
    char err[256];
    (void)state;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n[cyclic1]\nduration_us = 1200\n"
               "programs = Nope\n");
    assert_int_equal(plc_rt_init(&rt, &cfg, NULL, 0, err, sizeof err), PLC_RT_E_PROGRAM);
    assert_non_null(strstr(err, "'Nope'"));
}

/* ---- scheduling on the simulated clock ---- */
static void test_lower_class_number_runs_first_and_preempts(void **state)
{
    plc_rt_config cfg;
    plc_rt rt;
    ev_log log;
    size_t i = 0;
    (void)state;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n"
               "[cyclic1]\nduration_us = 1200\nsim_cost_us = 300\n"
               "[cyclic2]\nduration_us = 600\nsim_cost_us = 100\n"
               "[cyclic3]\nduration_us = 2400\nsim_cost_us = 600\n");
    build(&rt, &cfg, NULL, 0);
    run_traced(&rt, &log, 24);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 1, 0);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 2, 0);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 3, 0);
    expect_event(&log, i++, PLC_RT_EV_START, 1, 0);
    expect_event(&log, i++, PLC_RT_EV_END, 1, 300);
    expect_event(&log, i++, PLC_RT_EV_START, 2, 300);
    expect_event(&log, i++, PLC_RT_EV_END, 2, 400);
    expect_event(&log, i++, PLC_RT_EV_START, 3, 400);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 2, 600);
    expect_event(&log, i++, PLC_RT_EV_PREEMPT, 3, 600);
    expect_event(&log, i++, PLC_RT_EV_START, 2, 600);
    expect_event(&log, i++, PLC_RT_EV_END, 2, 700);
    expect_event(&log, i++, PLC_RT_EV_END, 3, 1100);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 1, 1200);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 2, 1200);
    expect_event(&log, i++, PLC_RT_EV_START, 1, 1200);
    expect_event(&log, i++, PLC_RT_EV_END, 1, 1500);
    expect_event(&log, i++, PLC_RT_EV_START, 2, 1500);
    expect_event(&log, i++, PLC_RT_EV_END, 2, 1600);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 2, 1800);
    expect_event(&log, i++, PLC_RT_EV_START, 2, 1800);
    expect_event(&log, i++, PLC_RT_EV_END, 2, 1900);
    assert_int_equal(log.n, i);
    assert_int_equal(rt.stats[0].cycles, 2);
    assert_int_equal(rt.stats[1].cycles, 4);
    assert_int_equal(rt.stats[2].cycles, 1);
    assert_int_equal(rt.stats[2].response_ns_max, 1100 * US);
    assert_int_equal(rt.stats[0].violations + rt.stats[1].violations + rt.stats[2].violations, 0);
    plc_rt_stop(&rt);
}

/* Producer in Cyclic #1 publishes a counter; a tick hook (the "hardware")
 * watches the process image and feeds a sensor value every tick. */
typedef struct io_fixture {
    int img_count, img_sensor;      /* process image */
    int loc_count, loc_sensor;      /* program-local copies */
    int seen_sensor[8];
    int n_cycles;
    int image_at_tick[24];
    char order[64];
    size_t n_order;
} io_fixture;

static void producer_init(void *ctx)
{
    io_fixture *f = (io_fixture *)ctx;
    f->order[f->n_order++] = 'I';
}

static void producer_cyclic(void *ctx)
{
    io_fixture *f = (io_fixture *)ctx;
    if (f->n_cycles < 8) {
        f->seen_sensor[f->n_cycles] = f->loc_sensor;
    }
    f->n_cycles++;
    f->loc_count = f->n_cycles;
    f->order[f->n_order++] = 'C';
}

static void producer_exit(void *ctx)
{
    io_fixture *f = (io_fixture *)ctx;
    f->order[f->n_order++] = 'X';
}

static void second_init(void *ctx)
{
    io_fixture *f = (io_fixture *)ctx;
    f->order[f->n_order++] = 'i';
}

static void second_exit(void *ctx)
{
    io_fixture *f = (io_fixture *)ctx;
    f->order[f->n_order++] = 'x';
}

static void hardware_tick(void *ctx, uint64_t t_ns)
{
    io_fixture *f = (io_fixture *)ctx;
    unsigned k = (unsigned)(t_ns / (100 * US));
    if (k < 24) {
        f->image_at_tick[k] = f->img_count;
    }
    f->img_sensor = (int)k;
}

static void test_inputs_latched_at_start_outputs_published_at_end(void **state)
{
    static io_fixture f;
    plc_io in[1], out[1];
    plc_program prod, second;
    const plc_program *reg[2];
    plc_rt_config cfg;
    plc_rt rt;
    (void)state;
    memset(&f, 0, sizeof f);
    in[0].image = &f.img_sensor; in[0].local = &f.loc_sensor; in[0].size = sizeof(int);
    out[0].image = &f.img_count; out[0].local = &f.loc_count; out[0].size = sizeof(int);
    memset(&prod, 0, sizeof prod);
    prod.name = "Producer"; prod.init = producer_init; prod.cyclic = producer_cyclic; prod.exit = producer_exit;
    prod.ctx = &f; prod.inputs = in; prod.n_inputs = 1; prod.outputs = out; prod.n_outputs = 1;
    memset(&second, 0, sizeof second);
    second.name = "Second"; second.init = second_init; second.exit = second_exit; second.ctx = &f;
    reg[0] = &second;
    reg[1] = &prod;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n"
               "[cyclic1]\nduration_us = 1200\nsim_cost_us = 300\nprograms = Producer\n"
               "[cyclic4]\nduration_us = 2400\nprograms = Second\n");
    build(&rt, &cfg, reg, 2);
    rt.tick_hook = hardware_tick;
    rt.tick_ctx = &f;
    assert_int_equal(plc_rt_run_sim(&rt, 1), PLC_RT_E_STATE);
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    assert_int_equal(plc_rt_start(&rt), PLC_RT_E_STATE);
    assert_int_equal(plc_rt_run_sim(&rt, 24), PLC_RT_OK);
    /* the cycle at 0 computed count 1 immediately, but the image shows it
     * only from its end at 300 us on; the cycle at 1200 publishes at 1500 */
    assert_int_equal(f.image_at_tick[0], 0);
    assert_int_equal(f.image_at_tick[1], 0);
    assert_int_equal(f.image_at_tick[2], 0);
    assert_int_equal(f.image_at_tick[3], 1);
    assert_int_equal(f.image_at_tick[14], 1);
    assert_int_equal(f.image_at_tick[15], 2);
    /* inputs are the image at the cycle start: tick 0 and tick 12 */
    assert_int_equal(f.n_cycles, 2);
    assert_int_equal(f.seen_sensor[0], 0);
    assert_int_equal(f.seen_sensor[1], 12);
    plc_rt_stop(&rt);
    f.order[f.n_order] = '\0';
    /* _INIT class 1 before class 4, _EXIT in reverse order, each once */
    assert_string_equal(f.order, "IiCCxX");
}

static void test_overrun_is_detected_and_releases_skipped(void **state)
{
    plc_rt_config cfg;
    plc_rt rt;
    ev_log log;
    size_t i;
    int violations = 0;
    (void)state;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = continue\n"
               "[cyclic1]\nduration_us = 1200\nsim_cost_us = 1500\n");
    build(&rt, &cfg, NULL, 0);
    memset(&log, 0, sizeof log);
    rt.violation_hook = record;
    rt.violation_ctx = &log;
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_sim(&rt, 48), PLC_RT_OK);
    for (i = 0; i < log.n; i++) {
        violations += log.ev[i].kind == PLC_RT_EV_VIOLATION;
    }
    assert_int_equal(violations, 2);
    expect_event(&log, 0, PLC_RT_EV_VIOLATION, 1, 1200);
    expect_event(&log, 1, PLC_RT_EV_VIOLATION, 1, 3600);
    assert_int_equal(rt.stats[0].violations, 2);
    assert_int_equal(rt.stats[0].skipped, 2);
    assert_int_equal(rt.stats[0].cycles, 2);
    assert_int_equal(rt.stats[0].response_ns_max, 1500 * US);
    {
        /* the report names the class, its cycle time and the violations */
        char line[256], text[1024] = "";
        FILE *f = tmpfile();
        assert_non_null(f);
        plc_rt_report(&rt, f);
        rewind(f);
        while (fgets(line, sizeof line, f)) {
            strncat(text, line, sizeof text - strlen(text) - 1);
        }
        fclose(f);
        if (!strstr(text, "Cyclic #1        1200       2           2        2")) {
            fail_msg("report:\n%s", text);
        }
    }
}

static void test_tolerance_delays_the_violation(void **state)
{
    plc_rt_config cfg;
    plc_rt rt;
    (void)state;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = continue\n"
               "[cyclic1]\nduration_us = 1200\ntolerance_us = 400\nsim_cost_us = 1500\n");
    build(&rt, &cfg, NULL, 0);
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_sim(&rt, 24), PLC_RT_OK);
    assert_int_equal(rt.stats[0].violations, 0);
    assert_int_equal(rt.stats[0].skipped, 1);
}

static void test_service_mode_stops_every_task(void **state)
{
    plc_rt_config cfg;
    plc_rt rt;
    (void)state;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = service\n"
               "[cyclic1]\nduration_us = 1200\nsim_cost_us = 100\n[cyclic2]\nduration_us = 600\nsim_cost_us = 550\n");
    build(&rt, &cfg, NULL, 0);
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    /* Cyclic #2 gets 500 us of CPU after Cyclic #1 in [0, 600): unfinished at 600 */
    assert_int_equal(plc_rt_run_sim(&rt, 100), PLC_RT_SERVICE);
    assert_int_equal(rt.stats[1].violations, 1);
    assert_true(rt.service);
    assert_int_equal(rt.now_ns, 600 * US);
    assert_int_equal(plc_rt_run_sim(&rt, 1), PLC_RT_SERVICE);
    assert_string_equal(plc_rt_strerror(PLC_RT_SERVICE), "service mode after a cycle-time violation");
    assert_string_equal(plc_rt_strerror(PLC_RT_E_CONFIG), "configuration invalid");
    assert_string_equal(plc_rt_strerror(42), "unknown");
}

/* ---- the idle task class ---- */
static void test_config_idle_section(void **state)
{
    plc_rt_config cfg;
    plc_rt rt;
    char err[256];
    (void)state;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n"
               "[cyclic1]\nduration_us = 1200\n[idle]\nsim_cost_us = 250\nprograms = Bg, Log\n");
    assert_int_equal(cfg.cls[PLC_RT_IDLE_INDEX].sim_cost_us, 250);
    assert_int_equal(cfg.cls[PLC_RT_IDLE_INDEX].n_programs, 2);
    assert_string_equal(cfg.cls[PLC_RT_IDLE_INDEX].programs[1], "Log");
    assert_int_equal(cfg.cls[PLC_RT_IDLE_INDEX].duration_us, 0);
    assert_int_equal(plc_rt_init(&rt, &cfg, NULL, 0, err, sizeof err), PLC_RT_E_PROGRAM);
    assert_non_null(strstr(err, "[idle]: program 'Bg'"));
    expect_rejected("[timing]\ninterface_cycle_us = 400\n[idle]\nduration_us = 1200\n",
                    "bad.cfg:4: duration_us in [idle]: the idle task class has no cycle time");
    expect_rejected("[timing]\ninterface_cycle_us = 400\n[idle]\ntolerance_us = 100\n", "has no cycle time");
    expect_rejected("[timing]\ninterface_cycle_us = 400\n[idle]\nprograms = Bg\n",
                    "[idle] has programs but no sim_cost_us");
    /* a hand-built configuration is checked as well (the runtime would never leave the idle class) */
    cfg.cls[PLC_RT_IDLE_INDEX].sim_cost_us = 0;
    assert_int_equal(plc_rt_init(&rt, &cfg, NULL, 0, err, sizeof err), PLC_RT_E_ARG);
    assert_non_null(strstr(err, "sim_cost_us > 0"));
}

/* A background program: counts its calls and publishes the count. */
typedef struct idle_fixture {
    int img_count, loc_count;
    int calls;
    char order[64];
    size_t n_order;
} idle_fixture;

/* Records an entry point in the call order (the first 63 calls). */
static void note(idle_fixture *f, char c)
{
    if (f->n_order < sizeof f->order - 1) {
        f->order[f->n_order++] = c;
    }
}

/* The programs' entry points record their calls in order: Bg (idle) as
 * i, c, x and Fg as I, C, X; Bg's cyclic also counts itself into its output. */
static void bg_init(void *ctx) { note((idle_fixture *)ctx, 'i'); }
static void bg_exit(void *ctx) { note((idle_fixture *)ctx, 'x'); }
static void fg_init(void *ctx) { note((idle_fixture *)ctx, 'I'); }
static void fg_cyclic(void *ctx) { note((idle_fixture *)ctx, 'C'); }
static void fg_exit(void *ctx) { note((idle_fixture *)ctx, 'X'); }

static void bg_cyclic(void *ctx)
{
    idle_fixture *f = (idle_fixture *)ctx;
    f->loc_count = ++f->calls;
    note(f, 'c');
}

static void idle_programs(idle_fixture *f, plc_io *out, plc_program *bg, plc_program *fg)
{
    memset(f, 0, sizeof *f);
    out->image = &f->img_count;
    out->local = &f->loc_count;
    out->size = sizeof(int);
    memset(bg, 0, sizeof *bg);
    bg->name = "Bg"; bg->init = bg_init; bg->cyclic = bg_cyclic; bg->exit = bg_exit; bg->ctx = f;
    bg->outputs = out; bg->n_outputs = 1;
    memset(fg, 0, sizeof *fg);
    fg->name = "Fg"; fg->init = fg_init; fg->cyclic = fg_cyclic; fg->exit = fg_exit; fg->ctx = f;
}

/* The idle-class fixture registered as Bg (idle) and Fg, built from `text`
 * and started. */
typedef struct idle_bench {
    idle_fixture f;
    plc_io out;
    plc_program bg, fg;
    const plc_program *reg[2];
    plc_rt_config cfg;
    plc_rt rt;
} idle_bench;

static void idle_bench_start(idle_bench *b, const char *text)
{
    idle_programs(&b->f, &b->out, &b->bg, &b->fg);
    b->reg[0] = &b->bg;
    b->reg[1] = &b->fg;
    load(&b->cfg, text);
    build(&b->rt, &b->cfg, b->reg, 2);
    assert_int_equal(plc_rt_start(&b->rt), PLC_RT_OK);
}

#define TWO_CLASSES "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n" \
                    "[cyclic1]\nduration_us = 1200\nsim_cost_us = 300\n[cyclic2]\nduration_us = 600\nsim_cost_us = 100\n"

static void test_idle_class_runs_in_leftover_time_and_every_class_preempts_it(void **state)
{
    static idle_fixture f;
    plc_io out;
    plc_program bg, fg;
    const plc_program *reg[2];
    plc_rt_config cfg;
    plc_rt rt, ref;
    ev_log log, ref_log;
    size_t i = 0, j, k;
    (void)state;
    idle_programs(&f, &out, &bg, &fg);
    reg[0] = &bg;
    reg[1] = &fg;
    load(&cfg, TWO_CLASSES "[idle]\nsim_cost_us = 250\nprograms = Bg\n");
    build(&rt, &cfg, reg, 2);
    run_traced(&rt, &log, 24);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 1, 0);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 2, 0);
    expect_event(&log, i++, PLC_RT_EV_START, 1, 0);
    expect_event(&log, i++, PLC_RT_EV_END, 1, 300);
    expect_event(&log, i++, PLC_RT_EV_START, 2, 300);
    expect_event(&log, i++, PLC_RT_EV_END, 2, 400);
    expect_event(&log, i++, PLC_RT_EV_START, PLC_RT_IDLE, 400);    /* iteration 0 */
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 2, 600);
    expect_event(&log, i++, PLC_RT_EV_PREEMPT, PLC_RT_IDLE, 600);  /* 50 us left */
    expect_event(&log, i++, PLC_RT_EV_START, 2, 600);
    expect_event(&log, i++, PLC_RT_EV_END, 2, 700);
    expect_event(&log, i++, PLC_RT_EV_END, PLC_RT_IDLE, 750);
    expect_event(&log, i++, PLC_RT_EV_START, PLC_RT_IDLE, 750);    /* iteration 1 */
    expect_event(&log, i++, PLC_RT_EV_END, PLC_RT_IDLE, 1000);
    expect_event(&log, i++, PLC_RT_EV_START, PLC_RT_IDLE, 1000);   /* iteration 2 */
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 1, 1200);
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 2, 1200);
    expect_event(&log, i++, PLC_RT_EV_PREEMPT, PLC_RT_IDLE, 1200); /* 50 us left */
    expect_event(&log, i++, PLC_RT_EV_START, 1, 1200);
    expect_event(&log, i++, PLC_RT_EV_END, 1, 1500);
    expect_event(&log, i++, PLC_RT_EV_START, 2, 1500);
    expect_event(&log, i++, PLC_RT_EV_END, 2, 1600);
    expect_event(&log, i++, PLC_RT_EV_END, PLC_RT_IDLE, 1650);
    expect_event(&log, i++, PLC_RT_EV_START, PLC_RT_IDLE, 1650);   /* iteration 3 */
    expect_event(&log, i++, PLC_RT_EV_RELEASE, 2, 1800);
    expect_event(&log, i++, PLC_RT_EV_PREEMPT, PLC_RT_IDLE, 1800); /* 100 us left */
    expect_event(&log, i++, PLC_RT_EV_START, 2, 1800);
    expect_event(&log, i++, PLC_RT_EV_END, 2, 1900);
    expect_event(&log, i++, PLC_RT_EV_END, PLC_RT_IDLE, 2000);
    expect_event(&log, i++, PLC_RT_EV_START, PLC_RT_IDLE, 2000);   /* iteration 4 */
    expect_event(&log, i++, PLC_RT_EV_END, PLC_RT_IDLE, 2250);
    expect_event(&log, i++, PLC_RT_EV_START, PLC_RT_IDLE, 2250);   /* iteration 5, 100 us left at 2400 */
    assert_int_equal(log.n, i);
    /* 2400 us - 2 x 300 - 4 x 100 = 1400 us left over = 5.6 iterations of 250 us */
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].cycles, 5);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].preempted, 3);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].cpu_ns_total, 5 * 250 * US);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].response_ns_max, 650 * US); /* iteration 2: 1000..1650 */
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].violations, 0);
    assert_int_equal(f.calls, 6);
    /* outputs published at the end of an iteration: 5 ended, the 6th computed 6 */
    assert_int_equal(f.img_count, 5);
    assert_int_equal(f.loc_count, 6);
    /* the cyclic classes see exactly the schedule they have without the idle class */
    load(&cfg, TWO_CLASSES);
    build(&ref, &cfg, reg, 2);
    memset(&ref_log, 0, sizeof ref_log);
    ref.trace_hook = record;
    ref.trace_ctx = &ref_log;
    assert_int_equal(plc_rt_start(&ref), PLC_RT_OK);
    assert_int_equal(plc_rt_run_sim(&ref, 24), PLC_RT_OK);
    for (j = 0, k = 0; j < log.n; j++) {
        if (log.ev[j].cls == PLC_RT_IDLE) {
            continue;
        }
        assert_true(k < ref_log.n);
        assert_int_equal(log.ev[j].kind, ref_log.ev[k].kind);
        assert_int_equal(log.ev[j].cls, ref_log.ev[k].cls);
        assert_int_equal(log.ev[j].t_ns, ref_log.ev[k].t_ns);
        k++;
    }
    assert_int_equal(k, ref_log.n);
    for (j = 0; j < PLC_RT_CLASSES; j++) {
        assert_int_equal(rt.stats[j].response_ns_max, ref.stats[j].response_ns_max);
        assert_int_equal(rt.stats[j].violations, 0);
    }
    {
        char line[256], text[1024] = "";
        FILE *fp = tmpfile();
        assert_non_null(fp);
        plc_rt_report(&rt, fp);
        rewind(fp);
        while (fgets(line, sizeof line, fp)) {
            strncat(text, line, sizeof text - strlen(text) - 1);
        }
        fclose(fp);
        if (!strstr(text, "Idle         iterations 5  preempted 3  late 0  cpu mean[us] 250.00")) {
            fail_msg("report:\n%s", text);
        }
    }
    plc_rt_stop(&rt);
    plc_rt_stop(&ref);
}

static void test_idle_class_runs_last_and_exits_first(void **state)
{
    static idle_bench b;
    (void)state;
    /* the idle class is configured first in the file and still runs last */
    idle_bench_start(&b, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n"
                         "[idle]\nsim_cost_us = 250\nprograms = Bg\n[cyclic8]\nduration_us = 1200\nsim_cost_us = 300\n"
                         "programs = Fg\n");
    /* [0, 1200): Fg 0..300, iterations start at 300, 550, 800, 1050 */
    assert_int_equal(plc_rt_run_sim(&b.rt, 12), PLC_RT_OK);
    plc_rt_stop(&b.rt);
    b.f.order[b.f.n_order] = '\0';
    assert_string_equal(b.f.order, "IiCccccxX");
    assert_int_equal(b.rt.stats[PLC_RT_IDLE_INDEX].cycles, 3);
}

static void test_idle_class_starves_without_violations(void **state)
{
    static idle_bench b;
    idle_fixture *const fx = &b.f;
    plc_rt_config *const cfg = &b.cfg;
    plc_rt *const rt = &b.rt;
    (void)state;
    /* the cyclic classes take every microsecond: the idle class never starts */
    idle_bench_start(&b, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n"
                         "[cyclic1]\nduration_us = 1200\nsim_cost_us = 1200\n[idle]\nsim_cost_us = 100\nprograms = Bg\n");
    assert_int_equal(plc_rt_run_sim(rt, 120), PLC_RT_OK);
    assert_int_equal(fx->calls, 0);
    assert_int_equal(rt->stats[PLC_RT_IDLE_INDEX].cycles, 0);
    assert_int_equal(rt->stats[0].cycles, 10);
    assert_int_equal(rt->stats[0].violations + rt->stats[PLC_RT_IDLE_INDEX].violations, 0);
    plc_rt_stop(rt);

    /* one iteration far longer than any cycle (5 ms of CPU, 900 us left
     * per 1.2 ms): it spans many cycles, is preempted at each, ends after
     * 5.6 cycles and is never reported; service mode is not entered */
    fx->calls = 0;
    load(cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = service\n"
              "[cyclic1]\nduration_us = 1200\nsim_cost_us = 300\n[idle]\nsim_cost_us = 5000\nprograms = Bg\n");
    build(rt, cfg, b.reg, 2);
    assert_int_equal(plc_rt_start(rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_sim(rt, 120), PLC_RT_OK);
    assert_false(rt->service);
    /* 12 ms - 10 x 300 us = 9 ms left = 1.8 iterations; the first runs
     * from 300 us to 6.8 ms (5 x 900 us, then 500 us after the 6th cycle),
     * preempted at each of the 5 releases in between, the second from 6.8 ms */
    assert_int_equal(rt->stats[PLC_RT_IDLE_INDEX].cycles, 1);
    assert_int_equal(rt->stats[PLC_RT_IDLE_INDEX].response_ns_max, 6500 * US);
    assert_int_equal(rt->stats[PLC_RT_IDLE_INDEX].preempted, 9);
    assert_int_equal(fx->calls, 2);
    assert_int_equal(rt->stats[0].violations + rt->stats[PLC_RT_IDLE_INDEX].violations, 0);
    assert_int_equal(rt->stats[0].response_ns_max, 300 * US);
    plc_rt_stop(rt);
}

/* ---- wall clock ---- */
static volatile double sink;

static void burn_us(long us)
{
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    do {
        sink += 1.0;
        clock_gettime(CLOCK_MONOTONIC, &t1);
    } while ((t1.tv_sec - t0.tv_sec) * 1000000L + (t1.tv_nsec - t0.tv_nsec) / 1000L < us);
}

static void busy_50(void *ctx)
{
    (void)ctx;
    burn_us(50);
}

static void busy_1500(void *ctx)
{
    (void)ctx;
    burn_us(1500);
}

static void test_wall_clock_measures_cpu_time_and_detects_overrun(void **state)
{
    plc_program p1, p2;
    const plc_program *reg[2];
    plc_rt_config cfg;
    plc_rt rt;
    struct timespec t0, t1;
    double elapsed_us;
    (void)state;
    memset(&p1, 0, sizeof p1);
    p1.name = "Light"; p1.cyclic = busy_50;
    memset(&p2, 0, sizeof p2);
    p2.name = "Heavy"; p2.cyclic = busy_1500;
    reg[0] = &p1;
    reg[1] = &p2;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = continue\n"
               "[cyclic1]\nduration_us = 1200\nprograms = Light\n[cyclic2]\nduration_us = 6000\nprograms = Heavy\n");
    build(&rt, &cfg, reg, 2);
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    assert_int_equal(plc_rt_run_wall(&rt, 24), PLC_RT_OK);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    elapsed_us = (double)(t1.tv_sec - t0.tv_sec) * 1e6 + (double)(t1.tv_nsec - t0.tv_nsec) / 1e3;
    assert_true(elapsed_us >= 2300.0); /* the last tick starts at 2.3 ms */
    assert_int_equal(rt.stats[0].cycles, 2);
    assert_int_equal(rt.stats[1].cycles, 1);
    assert_true(rt.stats[0].cpu_ns_max > 0);
    assert_true(rt.stats[1].cpu_ns_total > 0);
    plc_rt_stop(&rt);

    /* the 1.5 ms program moved into the 1.2 ms class overruns */
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\nviolation_reaction = continue\n"
               "[cyclic1]\nduration_us = 1200\nprograms = Heavy\n");
    build(&rt, &cfg, reg, 2);
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_wall(&rt, 24), PLC_RT_OK);
    assert_true(rt.stats[0].violations >= 1);
    plc_rt_stop(&rt);
}

static void test_idle_class_fills_the_wall_clock_gaps(void **state)
{
    static idle_fixture f;
    plc_io out;
    plc_program bg, light;
    const plc_program *reg[2];
    plc_rt_config cfg;
    plc_rt rt;
    (void)state;
    idle_programs(&f, &out, &bg, &light);
    light.name = "Light";
    light.cyclic = busy_50;
    light.init = NULL;
    light.exit = NULL;
    reg[0] = &bg;
    reg[1] = &light;
    load(&cfg, "[timing]\ninterface_cycle_us = 400\nviolation_reaction = continue\n"
               "[cyclic1]\nduration_us = 1200\nprograms = Light\n[idle]\nsim_cost_us = 100\nprograms = Bg\n");
    build(&rt, &cfg, reg, 2);
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_wall(&rt, 100), PLC_RT_OK);
    /* ticks every 400 us for 40 ms: the cyclic class keeps its releases, the
     * idle class runs (a cheap iteration fits many times into each gap)
     * and is never reported as a violation; timing is not asserted */
    assert_int_equal(rt.stats[0].cycles, 34);
    assert_true(rt.stats[PLC_RT_IDLE_INDEX].cycles > 0);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].cycles, (uint64_t)f.img_count);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].violations, 0);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].preempted, 0);
    assert_true(rt.stats[PLC_RT_IDLE_INDEX].late <= rt.stats[PLC_RT_IDLE_INDEX].cycles);
    plc_rt_report(&rt, stdout);
    plc_rt_stop(&rt);

    /* an iteration (1.5 ms) longer than any gap between ticks (< 400 us):
     * it runs once, ends after the next tick (late), and the budget keeps
     * it from starting again; still no violation of the idle class */
    bg.cyclic = busy_1500;
    f.calls = 0;
    build(&rt, &cfg, reg, 2);
    assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
    assert_int_equal(plc_rt_run_wall(&rt, 30), PLC_RT_OK);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].cycles, 1);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].late, 1);
    assert_int_equal(rt.stats[PLC_RT_IDLE_INDEX].violations, 0);
    assert_int_equal(rt.stats[0].cycles, 10);
    plc_rt_stop(&rt);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_config_file_mirrors_table_2_3),
        cmocka_unit_test(test_config_rejects_violations_of_the_timing_rules),
        cmocka_unit_test(test_unknown_program_is_reported),
        cmocka_unit_test(test_lower_class_number_runs_first_and_preempts),
        cmocka_unit_test(test_inputs_latched_at_start_outputs_published_at_end),
        cmocka_unit_test(test_overrun_is_detected_and_releases_skipped),
        cmocka_unit_test(test_tolerance_delays_the_violation),
        cmocka_unit_test(test_service_mode_stops_every_task),
        cmocka_unit_test(test_config_idle_section),
        cmocka_unit_test(test_idle_class_runs_in_leftover_time_and_every_class_preempts_it),
        cmocka_unit_test(test_idle_class_runs_last_and_exits_first),
        cmocka_unit_test(test_idle_class_starves_without_violations),
        cmocka_unit_test(test_wall_clock_measures_cpu_time_and_detects_overrun),
        cmocka_unit_test(test_idle_class_fills_the_wall_clock_gaps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
