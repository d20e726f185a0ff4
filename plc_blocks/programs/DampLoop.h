/*
 * DampLoop.h - example program: the collocated fractional damping loop of
 * seed 002 (notes 002 sections 6-8, Fig. 7) on the FracDamp block.
 *
 * A single-link flexible arm (two lumped masses) with a fast inner motor
 * position loop G_m(s) = 1/(1 + 0.0071 s)^2 (41); the program closes the
 * outer loop on the collocated base moment Gamma_c:
 *   theta_m* = F(s) theta_2* - C(s) Gamma_c,
 *   C(s) = 5.31 (1 + 0.0142 s)/s^1.2 (48), F(s) = (1 + 0.116 s^0.55)/(1 + 0.011 s) (52),
 * which damps both vibration modes robustly over the tip-mass range
 * m_2 = 0.01..0.23 lb and tracks the tip reference without steady-state
 * error. _INIT enables FracDamp; a parameter error latches a fault and
 * the motor reference stays 0.
 */
#ifndef DAMPLOOP_H
#define DAMPLOOP_H

#include "FracCtrl.h"
#include "plc_rt.h"
#include "frac/ptable.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct damploop_inputs {
    REAL TipReference; /* theta_2* [rad] */
    REAL BaseMoment;   /* Gamma_c (strain gauges at the base of the arm) */
} damploop_inputs;

typedef struct damploop_outputs {
    REAL MotorReference; /* theta_m*, reference of the inner motor loop [rad] */
    BOOL Error;
    UINT StatusID;
} damploop_outputs;

/*
 * Law from a parameter table named "collocated" with 1 x 1 entries
 * Kc, alpha, m, n1, n2, d1, d2, fa, fbeta, fb (the FracDampParType fields
 * of the design; Ts and the realization stay those of p). Returns FRAC_OK,
 * FRAC_E_NOT_FOUND, FRAC_E_DIM (entry not 1 x 1), FRAC_E_FORMAT (other
 * table), FRAC_E_PARAM (m not 0, 1 or 2), FRAC_E_NULL.
 */
int damploop_params_from_table(FracDampParType *p, const frac_ptable *t);

typedef struct damploop {
    const FracDampParType *par;
    const void *table;       /* data object, or NULL when par is given directly */
    UDINT table_size;
    FracDampParType loaded;  /* par with the table's law */
    struct ParTable partable;
    damploop_inputs in;
    damploop_outputs out;
    struct FracDamp law;
    BOOL fault;
    plc_io io_in, io_out;
} damploop;

/* Fills `prog` (name "DampLoop"); `par` must stay valid while it runs. */
void damploop_program(damploop *d, plc_program *prog, const FracDampParType *par, damploop_inputs *image_in,
                      damploop_outputs *image_out);

/* As damploop_program, the law from the data object `table` at _INIT
 * (ParTable); a table that fails leaves the program in fault (output 0). */
void damploop_program_table(damploop *d, plc_program *prog, const FracDampParType *base, const void *table,
                            UDINT size, damploop_inputs *image_in, damploop_outputs *image_out);

void damploop_init(void *ctx);
void damploop_cyclic(void *ctx);
void damploop_exit(void *ctx);

#ifdef __cplusplus
}
#endif

#endif /* DAMPLOOP_H */
