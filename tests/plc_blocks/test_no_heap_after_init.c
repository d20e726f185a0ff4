/* No heap allocation after _INIT: this executable is linked with
 * -Wl,--wrap=malloc,calloc,realloc (plc_blocks/CMakeLists.txt), so every
 * allocation made by the blocks, the programs, the runtime or libfrac goes
 * through the counters below; the cyclic phase must leave them at zero. */
#include "frac_test.h"
#include "ArmCtrl.h"
#include "ImuRead.h"
#include "FoLoop.h"
#include "plc_rt.h"

#include <stdlib.h>
#include <string.h>

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t m);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t m);
void *__wrap_realloc(void *p, size_t n);

/* volatile: GCC assumes malloc reads no user globals and would move these stores */
static volatile int armed;
static volatile unsigned long n_alloc;

void *__wrap_malloc(size_t n)
{
    n_alloc += armed;
    return __real_malloc(n);
}

void *__wrap_calloc(size_t n, size_t m)
{
    n_alloc += armed;
    return __real_calloc(n, m);
}

void *__wrap_realloc(void *p, size_t n)
{
    n_alloc += armed;
    return __real_realloc(p, n);
}

/* volatile: the compiler may not elide the malloc/free pair */
static void *volatile heap_sink;

static void test_the_counter_sees_an_allocation(void **state)
{
    (void)state;
    n_alloc = 0;
    armed = 1;
    heap_sink = malloc(16);
    armed = 0;
    free(heap_sink);
    assert_int_equal(n_alloc, 1);
}

#define N_TAB 64
static frac_real tab[N_TAB];
static frac_real lqg_A[1] = {1.0}, lqg_B[1] = {0.0}, lqg_C[3], lqg_K[8], lqg_L[27];

static void params(armctrl_params *p, armctrl_variant v)
{
    int ch;
    memset(p, 0, sizeof *p);
    p->Variant = v;
    p->CycleTime = 1.2e-3f;
    p->Ff.Channels = ARMCTRL_FF_N;
    p->Ff.N = N_TAB;
    for (ch = 0; ch < ARMCTRL_FF_N; ch++) {
        p->Ff.pData[ch] = tab;
    }
    p->Ff.Dt = 0.01;
    p->Ff.Ts = 1.2e-3;
    p->Ff.TMotionEnd = 0.5;
    p->Kp = 320.0f;
    p->Kd = 200.0f;
    p->Friction.K = 60.0f;
    p->Friction.B1 = 3.04f;
    p->Friction.B0 = 7.684f;
    p->Lqg.N = 1;
    p->Lqg.Di = 4;
    p->Lqg.P = 3;
    p->Lqg.Do[2] = 3;
    p->Lqg.pA = lqg_A;
    p->Lqg.pB = lqg_B;
    p->Lqg.pC = lqg_C;
    p->Lqg.pK = lqg_K;
    p->Lqg.pL = lqg_L;
    p->WdDrive.MaxStaleCycles = 5;
    p->WdDrive.RampRate = 100.0f;
    p->WdDrive.CycleTime = 1.2e-3f;
    p->WdImu = p->WdDrive;
    p->TorqueLimit = 100.0f;
}

typedef struct hw {
    armctrl_inputs drive;
    armctrl_outputs out;
    imuread_inputs can;
    imuread_outputs imu;
    UDINT ticks;
} hw;

static void hw_tick(void *ctx, uint64_t t_ns)
{
    hw *h = (hw *)ctx;
    (void)t_ns;
    h->ticks++;
    h->drive.MotorAngle = 0.001f * (REAL)(h->ticks % 100);
    h->drive.DriveCounter = h->ticks / 4;
    h->drive.Start = h->ticks > 30;
    h->can.RawRate = 0.01f;
    h->can.FrameCounter = h->ticks / 6;
}

static void test_every_arm_variant_runs_without_heap_after_init(void **state)
{
    static armctrl a;
    static imuread m;
    static hw h;
    static const char *cfg_text =
        "[timing]\ninterface_cycle_us = 400\nmultiply_cycle_time_by = 0.25\n"
        "[cyclic1]\nduration_us = 1200\nsim_cost_us = 300\nprograms = ArmCtrl\n"
        "[cyclic2]\nduration_us = 600\nsim_cost_us = 50\nprograms = ImuRead\n";
    armctrl_params par;
    plc_program pa, pm;
    const plc_program *reg[2];
    plc_rt_config cfg;
    static plc_rt rt;
    char err[256];
    int v, i;
    (void)state;
    for (i = 0; i < N_TAB; i++) {
        tab[i] = (frac_real)i * FRAC_R(0.01);
    }
    for (v = ARMCTRL_EXP_A; v <= ARMCTRL_EXP_D; v++) {
        memset(&h, 0, sizeof h);
        params(&par, (armctrl_variant)v);
        armctrl_program(&a, &pa, &par, &h.drive, &h.imu, &h.out);
        imuread_program(&m, &pm, 1.0f, &h.can, &h.imu);
        reg[0] = &pa;
        reg[1] = &pm;
        assert_int_equal(plc_rt_config_parse(&cfg, cfg_text, "cfg", err, sizeof err), PLC_RT_OK);
        assert_int_equal(plc_rt_init(&rt, &cfg, reg, 2, err, sizeof err), PLC_RT_OK);
        rt.tick_hook = hw_tick;
        rt.tick_ctx = &h;
        assert_int_equal(plc_rt_start(&rt), PLC_RT_OK);
        n_alloc = 0;
        armed = 1;
        assert_int_equal(plc_rt_run_sim(&rt, 12000), PLC_RT_OK);
        armed = 0;
        assert_false(h.out.Error);
        assert_true(h.out.TorqueEnable);
        assert_true(h.out.Counter > 900);
        if (n_alloc != 0) {
            fail_msg("variant %d: %lu heap allocations in the cyclic phase", v, n_alloc);
        }
        plc_rt_stop(&rt);
    }
}

static void test_lut2d_block_runs_without_heap(void **state)
{
    static struct LUT2D b;
    static frac_real z[16];
    int k;
    (void)state;
    memset(&b, 0, sizeof b);
    b.Parameters.Dx1 = 1.0;
    b.Parameters.N1 = 4;
    b.Parameters.Dx2 = 1.0;
    b.Parameters.N2 = 4;
    b.Parameters.pZ = z;
    b.Enable = 1;
    LUT2D(&b);
    n_alloc = 0;
    armed = 1;
    for (k = 0; k < 1000; k++) {
        b.X1 = 0.003f * (REAL)k;
        b.X2 = 0.002f * (REAL)k;
        LUT2D(&b);
    }
    armed = 0;
    assert_true(b.Valid);
    assert_int_equal(n_alloc, 0);
}

static void test_fo_loop_and_fracop_run_without_heap(void **state)
{
    static foloop f;
    static struct FracOp op;
    foloop_params par;
    plc_program prog;
    foloop_inputs in;
    foloop_outputs out;
    int k;
    (void)state;
    memset(&par, 0, sizeof par);
    par.Pid.Kp = 0.1219f;
    par.Pid.Ki = 0.1255f;
    par.Pid.Kd = 0.01f;
    par.Pid.Lambda = 0.88f;
    par.Pid.Mu = 0.5f;
    par.Pid.B = 1.0f;
    par.Pid.C = 1.0f;
    par.Pid.Y_min = -1.0f;
    par.Pid.Y_max = 1.0f;
    par.Pid.Ts = 0.002f;
    par.Pid.Method = fracFO_GL;
    par.Pid.Memory = 200;
    foloop_program(&f, &prog, &par, &in, &out);
    foloop_init(&f);
    memset(&op, 0, sizeof op);
    op.Parameters.Method = fracFO_CFE_TUSTIN;
    op.Parameters.Order = 0.5;
    op.Parameters.Ts = 0.002;
    op.Parameters.N = 5;
    op.Enable = 1;
    FracOp(&op);
    n_alloc = 0;
    armed = 1;
    for (k = 0; k < 2000; k++) {
        f.in.Reference = 1.0f;
        f.in.Measurement = 0.001f * (REAL)k;
        foloop_cyclic(&f);
        op.X = 0.01f * (REAL)(k % 10);
        FracOp(&op);
    }
    armed = 0;
    assert_false(f.out.Error);
    assert_true(op.Valid);
    assert_int_equal(n_alloc, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_counter_sees_an_allocation),
        cmocka_unit_test(test_every_arm_variant_runs_without_heap_after_init),
        cmocka_unit_test(test_lut2d_block_runs_without_heap),
        cmocka_unit_test(test_fo_loop_and_fracop_run_without_heap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
