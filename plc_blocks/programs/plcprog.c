/* Scaffolding shared by the programs (plcprog.h). */
#include "plcprog.h"
#include "frac/frac_types.h"

#include <string.h>

void plcprog_io(plc_io *io, void *image, void *local, size_t size)
{
    io->image = image;
    io->local = local;
    io->size = size;
}

void plcprog_describe(plc_program *prog, const char *name, void (*init)(void *ctx), void (*cyclic)(void *ctx),
                      void (*exit)(void *ctx), void *ctx, const plc_io *inputs, size_t n_inputs,
                      const plc_io *output)
{
    memset(prog, 0, sizeof *prog);
    prog->name = name;
    prog->init = init;
    prog->cyclic = cyclic;
    prog->exit = exit;
    prog->ctx = ctx;
    prog->inputs = inputs;
    prog->n_inputs = n_inputs;
    prog->outputs = output;
    prog->n_outputs = 1;
}

UINT plcprog_open_table(struct ParTable *pt, const void *table, UDINT size)
{
    memset(pt, 0, sizeof *pt);
    pt->pData = (USINT *)table;
    pt->Size = size;
    pt->Enable = 1;
    ParTable(pt);
    return pt->Error ? pt->StatusID : fracSTAT_OK;
}

UINT plcprog_status_id(int status)
{
    return status == FRAC_OK ? fracSTAT_OK : (UINT)(fracERR_LIBFRAC + (UINT)(-status));
}
