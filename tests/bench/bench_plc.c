/*
 * bench_plc: workloads for bench_plc.sh (callgrind instruction counts).
 *   bench_plc armctrl A|B|C|D N  : N Cyclic #1 cycles of ArmCtrl (armctrl_cyclic)
 *   bench_plc block NAME N       : N calls of one block (lqg, lut1d, lut2d, friction, trajlut,
 *                                  fracop, fracop_cfe, fracop_gl, fopid, fracdamp);
 *                                  the script compares the block's inclusive count
 *                                  with that of the libfrac call inside it.
 * Sizes are those of Exp. D (Table 8.8): n = 16, d_i = 4, d_o = (0, 0, 3),
 * p = 3, T = 1.2 ms; feedforward tables of 3 s. The gains are arbitrary
 * finite values with a stable A' = 0.5 I (a design is not needed to count
 * instructions: frac_lqg_step's cost does not depend on the values).
 */
#include "ArmCtrl.h"
#include "fracctrl_seed_params.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NX 16
#define DI 4
#define NBAR (NX + DI + 3)
#define NFF 2500

static frac_real A[NX * NX], B[NX], C[3 * NX], K[NBAR], L[(NBAR + 1) * 3];
static frac_real ff[ARMCTRL_FF_N][NFF];

static void fill(void)
{
    int i, c;
    for (i = 0; i < NX; i++) {
        A[i * NX + i] = FRAC_R(0.5);
        B[i] = FRAC_R(0.001) * (frac_real)(i + 1);
    }
    C[0] = 1;
    C[NX + 1] = 1;
    C[2 * NX + 2] = 1;
    for (i = 0; i < NBAR; i++) {
        K[i] = FRAC_R(0.1) * (frac_real)(i % 5);
    }
    for (i = 0; i < (NBAR + 1) * 3; i++) {
        L[i] = FRAC_R(0.01) * (frac_real)(i % 7);
    }
    for (c = 0; c < ARMCTRL_FF_N; c++) {
        for (i = 0; i < NFF; i++) {
            ff[c][i] = FRAC_SIN(FRAC_R(0.001) * (frac_real)(i * (c + 1)));
        }
    }
}

static void params(armctrl_params *p, armctrl_variant v)
{
    int c;
    memset(p, 0, sizeof *p);
    p->Variant = v;
    p->CycleTime = 1.2e-3f;
    p->Ff.Channels = ARMCTRL_FF_N;
    p->Ff.N = NFF;
    for (c = 0; c < ARMCTRL_FF_N; c++) {
        p->Ff.pData[c] = ff[c];
    }
    p->Ff.Dt = 1.2e-3;
    p->Ff.Ts = 1.2e-3;
    p->Ff.TMotionStart = 0.5;
    p->Ff.TMotionEnd = 2.0;
    if (v == ARMCTRL_EXP_D) {
        p->Ff.Lead[ARMCTRL_FF_TAU] = DI;
        p->Ff.Lead[ARMCTRL_FF_DPSI] = -3;
    }
    p->Kp = 320.0f;
    p->Kd = 200.0f;
    p->Friction.K = 60.0f;
    p->Friction.B1 = 3.04f;
    p->Friction.B0 = 7.684f;
    p->Lqg.N = NX;
    p->Lqg.Di = v == ARMCTRL_EXP_D ? DI : 0;
    p->Lqg.P = 3;
    p->Lqg.Do[2] = v == ARMCTRL_EXP_D ? 3 : 0;
    p->Lqg.pA = A;
    p->Lqg.pB = B;
    p->Lqg.pC = C;
    p->Lqg.pK = K;
    p->Lqg.pL = L;
    p->WdDrive.MaxStaleCycles = 5;
    p->WdDrive.RampRate = 100.0f;
    p->WdDrive.CycleTime = 1.2e-3f;
    p->WdImu = p->WdDrive;
    p->TorqueLimit = 250.0f;
}

static int run_armctrl(char variant, long n)
{
    static armctrl a;
    static armctrl_params par;
    plc_program prog;
    armctrl_inputs img_in;
    armctrl_outputs img_out;
    long k;
    if (variant < 'A' || variant > 'D') {
        return 2;
    }
    params(&par, (armctrl_variant)(variant - 'A'));
    memset(&img_in, 0, sizeof img_in);
    armctrl_program(&a, &prog, &par, &img_in, NULL, &img_out);
    armctrl_init(&a);
    if (a.out.Error) {
        fprintf(stderr, "ArmCtrl _INIT failed: StatusID %u\n", (unsigned)a.out.StatusID);
        return 1;
    }
    for (k = 0; k < n; k++) {
        a.in.Start = k > 0;
        a.in.DriveCounter = (UDINT)k + 1;
        a.in.ImuCounter = (UDINT)k + 1;
        a.in.MotorAngle = 0.001f * (REAL)(k % 50);
        a.in.MotorVelocity = 0.01f;
        a.in.TipRate = 0.02f;
        armctrl_cyclic(&a);
    }
    printf("torque %g status %u\n", (double)a.out.TorqueSetpoint, (unsigned)a.out.StatusID);
    return 0;
}

static int run_block(const char *name, long n)
{
    static armctrl_params par;
    long k;
    params(&par, ARMCTRL_EXP_D);
    if (!strcmp(name, "lqg")) {
        static struct LQGDelay b;
        b.Parameters = par.Lqg;
        b.Enable = 1;
        for (k = 0; k < n; k++) {
            b.UStar = 0.5f;
            b.YRef[0] = 0.001f * (REAL)(k % 50);
            b.Y[1] = 0.01f;
            b.Y[2] = 0.02f;
            LQGDelay(&b);
        }
        printf("U %g status %u\n", (double)b.U, (unsigned)b.StatusID);
    } else if (!strcmp(name, "lut1d")) {
        static struct LUT1D b;
        b.Parameters.Dx = 1.2e-3;
        b.Parameters.N = NFF;
        b.Parameters.pY = ff[0];
        b.Enable = 1;
        for (k = 0; k < n; k++) {
            b.X = 1.2e-3f * (REAL)(k % NFF) + 3e-4f;
            LUT1D(&b);
        }
        printf("Y %g status %u\n", (double)b.Y, (unsigned)b.StatusID);
    } else if (!strcmp(name, "friction")) {
        static struct FrictionComp b;
        b.Parameters = par.Friction;
        b.Enable = 1;
        for (k = 0; k < n; k++) {
            b.Velocity = 0.001f * (REAL)(k % 100);
            FrictionComp(&b);
        }
        printf("Torque %g status %u\n", (double)b.Torque, (unsigned)b.StatusID);
    } else if (!strcmp(name, "trajlut")) {
        static struct TrajLUT b;
        b.Parameters = par.Ff;
        b.Enable = 1;
        b.Run = 1;
        for (k = 0; k < n; k++) {
            TrajLUT(&b);
        }
        printf("Y0 %g status %u\n", (double)b.Y[0], (unsigned)b.StatusID);
    } else if (!strncmp(name, "fracop", 6)) {
        /* s^0.5 in each realization: Oustaloup N = 4 over 0.1..1000 rad/s,
         * CFE (Tustin) order 4, GL with the longest memory the block's
         * storage holds (341 terms) */
        static struct FracOp b;
        b.Parameters.Order = 0.5;
        b.Parameters.Ts = 1.2e-3;
        if (!strcmp(name, "fracop")) {
            b.Parameters.Method = fracFO_OUSTALOUP;
            b.Parameters.Wb = 0.1;
            b.Parameters.Wh = 1000.0;
            b.Parameters.N = 4;
        } else if (!strcmp(name, "fracop_cfe")) {
            b.Parameters.Method = fracFO_CFE_TUSTIN;
            b.Parameters.N = 4;
        } else if (!strcmp(name, "fracop_gl")) {
            b.Parameters.Method = fracFO_GL;
            b.Parameters.Memory = 341;
        } else {
            return 2;
        }
        b.Enable = 1;
        for (k = 0; k < n; k++) {
            b.X = 0.001f * (REAL)(k % 100);
            FracOp(&b);
        }
        printf("Y %g status %u\n", (double)b.Y, (unsigned)b.StatusID);
    } else if (!strcmp(name, "fopid")) {
        /* the seed 001 FO-PI (52) of the FoLoop example */
        static struct FOPID b;
        seed001_fopi52(&b.Parameters);
        b.Enable = 1;
        for (k = 0; k < n; k++) {
            b.W = 1.0f;
            b.X = 0.001f * (REAL)(k % 100);
            FOPID(&b);
        }
        printf("Y %g status %u\n", (double)b.Y, (unsigned)b.StatusID);
    } else if (!strcmp(name, "fracdamp")) {
        /* the seed 002 law and prefilter of the DampLoop example */
        static struct FracDamp b;
        seed002_law(&b.Parameters);
        b.Enable = 1;
        for (k = 0; k < n; k++) {
            b.W = 0.1f;
            b.X = 0.01f * (REAL)(k % 100);
            FracDamp(&b);
        }
        printf("Y %g status %u\n", (double)b.Y, (unsigned)b.StatusID);
    } else if (!strcmp(name, "lut2d")) {
        /* a 50 x 50 uniform grid over the feedforward data, read along a
         * diagonal path */
        static struct LUT2D b;
        b.Parameters.Dx1 = 0.02;
        b.Parameters.N1 = 50;
        b.Parameters.Dx2 = 0.02;
        b.Parameters.N2 = 50;
        b.Parameters.pZ = ff[0];
        b.Enable = 1;
        for (k = 0; k < n; k++) {
            b.X1 = 0.0011f * (REAL)(k % 800);
            b.X2 = 0.0007f * (REAL)(k % 900);
            LUT2D(&b);
        }
        printf("Y %g status %u\n", (double)b.Y, (unsigned)b.StatusID);
    } else {
        return 2;
    }
    return 0;
}

int main(int argc, char **argv)
{
    long n;
    if (argc != 4 || (n = atol(argv[3])) <= 0) {
        fprintf(stderr, "usage: bench_plc armctrl A|B|C|D N | bench_plc block lqg|lut1d|lut2d|friction|trajlut|fracop|fracop_cfe|fracop_gl|fopid|fracdamp N\n");
        return 2;
    }
    fill();
    if (!strcmp(argv[1], "armctrl")) {
        return run_armctrl(argv[2][0], n);
    }
    if (!strcmp(argv[1], "block")) {
        return run_block(argv[2], n);
    }
    fprintf(stderr, "unknown mode %s\n", argv[1]);
    return 2;
}
