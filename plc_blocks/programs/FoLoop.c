/* FoLoop: the seed 001 FO-PI / FO-PD example program (FoLoop.h). */
#include "FoLoop.h"

#include <string.h>

static int entry(const frac_ptable *t, const char *name, REAL *v)
{
    frac_real x;
    int st = frac_ptable_get(t, name, 1, 1, &x);
    if (st == FRAC_OK) {
        *v = (REAL)x;
    }
    return st;
}

int foloop_params_from_table(foloop_params *p, const frac_ptable *t)
{
    char name[FRAC_PTABLE_TABLE_NAME_LEN];
    REAL kp, delta;
    int st;
    if (!p || !t) {
        return FRAC_E_NULL;
    }
    if ((st = frac_ptable_name(t, name)) != FRAC_OK) {
        return st;
    }
    if (!strcmp(name, "fopi")) {
        if ((st = entry(t, "Kp", &p->Pid.Kp)) != FRAC_OK || (st = entry(t, "Ki", &p->Pid.Ki)) != FRAC_OK
            || (st = entry(t, "alpha", &p->Pid.Lambda)) != FRAC_OK) {
            return st;
        }
        p->Pid.Kd = 0.0f;
        p->Pid.Delta = 0.0f;
        return FRAC_OK;
    }
    if (!strcmp(name, "fopd")) {
        if ((st = entry(t, "Kp", &kp)) != FRAC_OK || (st = entry(t, "Kd", &p->Pid.Kd)) != FRAC_OK
            || (st = entry(t, "mu", &p->Pid.Mu)) != FRAC_OK || (st = entry(t, "delta", &delta)) != FRAC_OK) {
            return st;
        }
        /* (41): C = C^ + delta acts on the error, delta y is fed back */
        p->Pid.Kp = kp + delta;
        p->Pid.Delta = delta;
        p->Pid.Ki = 0.0f;
        return FRAC_OK;
    }
    return FRAC_E_FORMAT;
}

void foloop_init(void *ctx)
{
    foloop *f = (foloop *)ctx;
    memset(&f->pid, 0, sizeof f->pid);
    memset(&f->out, 0, sizeof f->out);
    if (f->table) {
        int st;
        memset(&f->partable, 0, sizeof f->partable);
        f->partable.pData = (USINT *)f->table;
        f->partable.Size = f->table_size;
        f->partable.Enable = 1;
        ParTable(&f->partable);
        st = f->partable.Error ? -1 : foloop_params_from_table(&f->loaded, &f->partable.Handle);
        if (st != FRAC_OK) {
            f->fault = 1;
            f->out.Error = 1;
            f->out.StatusID = f->partable.Error ? f->partable.StatusID : (UINT)(fracERR_LIBFRAC + (UINT)(-st));
            return;
        }
        f->par = &f->loaded;
    }
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
    f->partable.Enable = 0;
    ParTable(&f->partable);
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

void foloop_program_table(foloop *f, plc_program *prog, const foloop_params *base, const void *table, UDINT size,
                          foloop_inputs *image_in, foloop_outputs *image_out)
{
    foloop_program(f, prog, base, image_in, image_out);
    f->table = table;
    f->table_size = size;
    f->loaded = *base;
}
