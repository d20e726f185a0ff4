/*
 * FoLoop.h - example program: the fractional-order outer loop of seed 001
 * (Gharab et al.; notes 001 sections 3-6) on the FOPID block.
 *
 * Plant seen by the loop (notes 001 6.2, (51)): the tip angle theta_d of a
 * single-link flexible arm whose motor angle follows its reference through
 * a fast inner loop, G(s) = K e^{-tau s} / (1 + T s^lambda), with
 * K = 1, T = 1/omega_0^2 = 0.0292866, lambda = 1.92, tau = 0.1613 s,
 * sampled at Ts = 2 ms. The program's output u is the inner-loop reference.
 * Laws (FOPID, frac/fopid.h), e = r - y:
 *   FO-PI^alpha  (5):  u = Kp e + Ki s^{-alpha} e          (Delta = 0)
 *   FO-PD^mu    (41):  u = Kp e + Kd s^{mu} e + Delta y    (positive feedback
 *                      Delta = 1/K makes the step error zero, (37)-(39);
 *                      Kp = K_p + delta, C of (41) acts on e)
 * (52): Kp = 0.1219, Ki = 0.1255, alpha = 0.88 (designed at
 * omega_c = 6.36 rad/s, erratum E4); (53) reading (c): C = 1 + 0.0256 s^0.88,
 * i.e. Kp = 1, Kd = 0.0256, mu = 0.88, Delta = 1 (notes 6.4, erratum E5).
 * The paper realizes the operators by GL with short memory (notes 001
 * section 7). _INIT enables FOPID; a parameter error latches a fault and
 * the output stays 0.
 */
#ifndef FOLOOP_H
#define FOLOOP_H

#include "FracCtrl.h"
#include "plc_rt.h"
#include "frac/ptable.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct foloop_params {
    FOPIDParType Pid; /* gains, orders, Delta, limits, realization, Ts */
} foloop_params;

typedef struct foloop_inputs {
    REAL Reference;   /* y* */
    REAL Measurement; /* y (tip angle estimate (48)) */
} foloop_inputs;

typedef struct foloop_outputs {
    REAL U;           /* inner-loop reference */
    BOOL Error;
    UINT StatusID;
} foloop_outputs;

/*
 * Controller from a parameter table of `fracdesign table emit` (from a
 * frac.design.fopi or frac.design.fopd document, docs/param_table_format.md):
 *   table "fopi": Kp, Ki, alpha            -> Kp, Ki, Lambda (Kd = Delta = 0)
 *   table "fopd": Kp (of C^), Kd, mu, delta -> Kp + delta, Kd, Mu, Delta (Ki = 0)
 * into p->Pid; the realization, limits and Ts already in p are kept.
 * Returns FRAC_OK, FRAC_E_NOT_FOUND (entry missing), FRAC_E_DIM (entry
 * not 1 x 1), FRAC_E_FORMAT (table neither "fopi" nor "fopd"), FRAC_E_NULL.
 */
int foloop_params_from_table(foloop_params *p, const frac_ptable *t);

typedef struct foloop {
    const foloop_params *par;
    const void *table;       /* data object, or NULL when par is given directly */
    UDINT table_size;
    foloop_params loaded;    /* par with the table's controller */
    struct ParTable partable;
    foloop_inputs in;
    foloop_outputs out;
    struct FOPID pid;
    BOOL fault;
    plc_io io_in, io_out;
} foloop;

/* Fills `prog` (name "FoLoop"); `par` must stay valid while it runs. */
void foloop_program(foloop *f, plc_program *prog, const foloop_params *par, foloop_inputs *image_in,
                    foloop_outputs *image_out);

/*
 * As foloop_program, but the controller comes from the data object `table`
 * (size bytes) at _INIT, validated by ParTable; `base` gives the rest. A
 * table that fails leaves the program in fault with its StatusID (output 0).
 */
void foloop_program_table(foloop *f, plc_program *prog, const foloop_params *base, const void *table, UDINT size,
                          foloop_inputs *image_in, foloop_outputs *image_out);

void foloop_init(void *ctx);
void foloop_cyclic(void *ctx);
void foloop_exit(void *ctx);

#ifdef __cplusplus
}
#endif

#endif /* FOLOOP_H */
