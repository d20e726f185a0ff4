/* FoLoop: the seed 001 FO-PI / FO-PD example program (FoLoop.h). */
#include "FoLoop.h"

#include <string.h>

void foloop_init(void *ctx)
{
    foloop *f = (foloop *)ctx;
    memset(&f->pid, 0, sizeof f->pid);
    memset(&f->out, 0, sizeof f->out);
    f->pid.Parameters = f->par->Pid;
    f->pid.Enable = 1;
    FOPID(&f->pid);
    f->fault = f->pid.Error;
    f->out.Error = f->fault;
    f->out.StatusID = f->pid.StatusID;
    /* the evaluation at rest above must not leave state behind */
    f->pid.Reset = 1;
}

void foloop_cyclic(void *ctx)
{
    foloop *f = (foloop *)ctx;
    if (f->fault) {
        f->out.U = 0.0f;
        return;
    }
    f->pid.W = f->in.Reference;
    f->pid.X = f->in.Measurement;
    FOPID(&f->pid);
    f->pid.Reset = 0;
    f->out.U = f->pid.Y; /* holds the last finite value on a bad input */
    f->out.Error = f->pid.Error;
    f->out.StatusID = f->pid.StatusID;
}

void foloop_exit(void *ctx)
{
    foloop *f = (foloop *)ctx;
    f->pid.Enable = 0;
    FOPID(&f->pid);
    f->out.U = 0.0f;
}

void foloop_program(foloop *f, plc_program *prog, const foloop_params *par, foloop_inputs *image_in,
                    foloop_outputs *image_out)
{
    memset(f, 0, sizeof *f);
    f->par = par;
    f->io_in.image = image_in;
    f->io_in.local = &f->in;
    f->io_in.size = sizeof f->in;
    f->io_out.image = image_out;
    f->io_out.local = &f->out;
    f->io_out.size = sizeof f->out;
    memset(prog, 0, sizeof *prog);
    prog->name = "FoLoop";
    prog->init = foloop_init;
    prog->cyclic = foloop_cyclic;
    prog->exit = foloop_exit;
    prog->ctx = f;
    prog->inputs = &f->io_in;
    prog->n_inputs = 1;
    prog->outputs = &f->io_out;
    prog->n_outputs = 1;
}
