/* FoLoop: the seed 001 FO-PI / FO-PD example program (FoLoop.h). */
#include "FoLoop.h"
#include "frac/frac_types.h"

#include <string.h>

void foloop_init(void *ctx)
{
    foloop *f = (foloop *)ctx;
    const foloop_params *p = f->par;
    memset(&f->op, 0, sizeof f->op);
    memset(&f->out, 0, sizeof f->out);
    f->op.Parameters = p->Op;
    f->op.Enable = 1;
    FracOp(&f->op);
    f->fault = f->op.Error;
    f->out.StatusID = f->op.StatusID;
    if (!FRAC_ISFINITE(p->Kp) || !FRAC_ISFINITE(p->Kfo) || !FRAC_ISFINITE(p->Delta) || !(p->ULimit > 0.0f)) {
        f->fault = 1;
        f->out.StatusID = fracERR_PARAM;
    }
    f->out.Error = f->fault;
    /* the evaluation at rest above must not leave history behind */
    f->op.Reset = 1;
}

void foloop_cyclic(void *ctx)
{
    foloop *f = (foloop *)ctx;
    const foloop_params *p = f->par;
    REAL e, u;
    if (f->fault) {
        f->out.U = 0.0f;
        return;
    }
    e = f->in.Reference - f->in.Measurement;
    f->op.X = e;
    FracOp(&f->op);
    f->op.Reset = 0;
    /* (5) or (41): the fractional term from FracOp, the rest is the law's wiring */
    u = p->Kp * e + p->Kfo * f->op.Y + p->Delta * f->in.Measurement;
    if (u > p->ULimit) {
        u = p->ULimit;
    } else if (u < -p->ULimit) {
        u = -p->ULimit;
    }
    if (!f->op.Error) {
        f->out.U = u;
    }
    f->out.Error = f->op.Error;
    f->out.StatusID = f->op.StatusID;
}

void foloop_exit(void *ctx)
{
    foloop *f = (foloop *)ctx;
    f->op.Enable = 0;
    FracOp(&f->op);
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
