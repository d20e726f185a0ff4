/* DampLoop: the seed 002 collocated damping example program (DampLoop.h). */
#include "DampLoop.h"

#include <string.h>

void damploop_init(void *ctx)
{
    damploop *d = (damploop *)ctx;
    memset(&d->law, 0, sizeof d->law);
    memset(&d->out, 0, sizeof d->out);
    d->law.Parameters = *d->par;
    d->law.Enable = 1;
    FracDamp(&d->law);
    d->fault = d->law.Error;
    d->out.Error = d->fault;
    d->out.StatusID = d->law.StatusID;
    /* the evaluation at rest above must not leave state behind */
    d->law.Reset = 1;
}

void damploop_cyclic(void *ctx)
{
    damploop *d = (damploop *)ctx;
    if (d->fault) {
        d->out.MotorReference = 0.0f;
        return;
    }
    d->law.W = d->in.TipReference;
    d->law.X = d->in.BaseMoment;
    FracDamp(&d->law);
    d->law.Reset = 0;
    d->out.MotorReference = d->law.Y; /* holds the last finite value on a bad input */
    d->out.Error = d->law.Error;
    d->out.StatusID = d->law.StatusID;
}

void damploop_exit(void *ctx)
{
    damploop *d = (damploop *)ctx;
    d->law.Enable = 0;
    FracDamp(&d->law);
    d->out.MotorReference = 0.0f;
}

void damploop_program(damploop *d, plc_program *prog, const FracDampParType *par, damploop_inputs *image_in,
                      damploop_outputs *image_out)
{
    memset(d, 0, sizeof *d);
    d->par = par;
    d->io_in.image = image_in;
    d->io_in.local = &d->in;
    d->io_in.size = sizeof d->in;
    d->io_out.image = image_out;
    d->io_out.local = &d->out;
    d->io_out.size = sizeof d->out;
    memset(prog, 0, sizeof *prog);
    prog->name = "DampLoop";
    prog->init = damploop_init;
    prog->cyclic = damploop_cyclic;
    prog->exit = damploop_exit;
    prog->ctx = d;
    prog->inputs = &d->io_in;
    prog->n_inputs = 1;
    prog->outputs = &d->io_out;
    prog->n_outputs = 1;
}
