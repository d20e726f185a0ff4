/* FoLoop: the seed 001 FO-PI / FO-PD example program (FoLoop.h). */
#include "FoLoop.h"
#include "plcprog.h"

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
        UINT st = plcprog_open_table(&f->partable, f->table, f->table_size);
        if (st == fracSTAT_OK) {
            st = plcprog_status_id(foloop_params_from_table(&f->loaded, FracPtableObj_C(f->partable.Handle)));
        }
        if (st != fracSTAT_OK) {
            f->fault = 1;
            f->out.Error = 1;
            f->out.StatusID = st;
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
    plcprog_io(&f->io_in, image_in, &f->in, sizeof f->in);
    plcprog_io(&f->io_out, image_out, &f->out, sizeof f->out);
    plcprog_describe(prog, "FoLoop", foloop_init, foloop_cyclic, foloop_exit, f, &f->io_in, 1, &f->io_out);
}

void foloop_program_table(foloop *f, plc_program *prog, const foloop_params *base, const void *table, UDINT size,
                          foloop_inputs *image_in, foloop_outputs *image_out)
{
    foloop_program(f, prog, base, image_in, image_out);
    f->table = table;
    f->table_size = size;
    f->loaded = *base;
}
