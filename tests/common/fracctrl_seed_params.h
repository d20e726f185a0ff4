/*
 * The seed parameter sets of the FracCtrl example loops, shared by their
 * tests (test_foloop.c, test_damploop.c) and the block-call benchmark
 * (bench/bench_plc.c), so that all of them run the same controllers.
 */
#ifndef FRACCTRL_SEED_PARAMS_H
#define FRACCTRL_SEED_PARAMS_H
#include <string.h>
#include "FracCtrl.h"

#ifdef __GNUC__
#define FRACCTRL_SEED_UNUSED __attribute__((unused))
#else
#define FRACCTRL_SEED_UNUSED
#endif

/*
 * FoLoop's realization at T = 2 ms, without gains (these come from a
 * table or from seed001_fopi52): error weights 1, limits +-10, s^-lambda
 * = s^-1 s^(1 - lambda) (frac/fopid.h) with the fractional part by
 * Oustaloup N = 8 over 1e-4..1e3 rad/s. The slow fractional creep of the
 * seed's full-memory reference needs the low frequencies that a GL short
 * memory (here at most 512 terms, 1 s) would cut off.
 */
static FRACCTRL_SEED_UNUSED void seed001_realization(FOPIDParType *p)
{
    memset(p, 0, sizeof *p);
    p->B = 1.0f;
    p->C = 1.0f;
    p->Y_min = -10.0f;
    p->Y_max = 10.0f;
    p->Ts = 0.002f;
    p->Method = fracFO_OUSTALOUP;
    p->Wb = 1e-4f;
    p->Wh = 1e3f;
    p->N = 8;
}

/* The FO-PI (52) of seed 001 (notes 001 8.3): Kp 0.1219, Ki 0.1255, lambda 0.88. */
static FRACCTRL_SEED_UNUSED void seed001_fopi52(FOPIDParType *p)
{
    seed001_realization(p);
    p->Kp = 0.1219f;
    p->Ki = 0.1255f;
    p->Lambda = 0.88f;
}

/*
 * The collocated law and prefilter of seed 002, (48) and (52): Kc 5.31,
 * alpha 0.8, m 2, n1 0.0142, prefilter 0.116 / 0.55 / 0.011, at
 * T = 0.4 ms with Oustaloup N = 6 over 0.01..3000 rad/s.
 */
static FRACCTRL_SEED_UNUSED void seed002_law(FracDampParType *p)
{
    memset(p, 0, sizeof *p);
    p->Kc = 5.31f; /* (48) */
    p->Alpha = 0.8f;
    p->M = 2;
    p->N1 = 0.0142f;
    p->Fa = 0.116f; /* (52) */
    p->Fbeta = 0.55f;
    p->Fb = 0.011f;
    p->Ts = 0.0004f;
    p->Method = fracFO_OUSTALOUP;
    p->Wb = 0.01f;
    p->Wh = 3000.0f;
    p->N = 6;
}
#endif
