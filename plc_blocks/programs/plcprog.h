/*
 * plcprog.h - scaffolding shared by the programs (ArmCtrl, ImuRead, FoLoop,
 * DampLoop): the program descriptor of the task runtime (plc_rt.h) and the
 * parameter table read at _INIT through ParTable (FracCtrl.fun).
 */
#ifndef PLCPROG_H
#define PLCPROG_H

#include "FracCtrl.h"
#include "plc_rt.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One I/O image area: `size` bytes of `image` latched into `local` (an
 * input) or published from `local` to `image` (an output). */
void plcprog_io(plc_io *io, void *image, void *local, size_t size);

/*
 * Fills `prog` (all other fields zero): its name, entry points (exit may
 * be NULL), context, `n_inputs` input areas and one output area.
 */
void plcprog_describe(plc_program *prog, const char *name, void (*init)(void *ctx), void (*cyclic)(void *ctx),
                      void (*exit)(void *ctx), void *ctx, const plc_io *inputs, size_t n_inputs,
                      const plc_io *output);

/*
 * _INIT: validates the data object `table` (size bytes) with a fresh
 * ParTable instance, left enabled (its Handle is the validated table).
 * Returns its StatusID: fracSTAT_OK, else the failed check.
 */
UINT plcprog_open_table(struct ParTable *pt, const void *table, UDINT size);

/* StatusID of the libfrac status a program's table mapping returned
 * (FRAC_OK or an error): fracSTAT_OK or fracERR_LIBFRAC + |status|. */
UINT plcprog_status_id(int status);

#ifdef __cplusplus
}
#endif

#endif /* PLCPROG_H */
