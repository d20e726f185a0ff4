/* DampLoop: the seed 002 collocated damping example program (DampLoop.h). */
#include "DampLoop.h"
#include "plcprog.h"
#include "frac/frac_types.h"

#include <string.h>

int damploop_params_from_table(FracDampParType *p, const frac_ptable *t)
{
    static const char *const names[10] = {"Kc", "alpha", "m", "n1", "n2", "d1", "d2", "fa", "fbeta", "fb"};
    char name[FRAC_PTABLE_TABLE_NAME_LEN];
    frac_real v[10];
    int i, st;
    if (!p || !t) {
        return FRAC_E_NULL;
    }
    if ((st = frac_ptable_name(t, name)) != FRAC_OK) {
        return st;
    }
    if (strcmp(name, "collocated")) {
        return FRAC_E_FORMAT;
    }
    for (i = 0; i < 10; i++) {
        if ((st = frac_ptable_get(t, names[i], 1, 1, &v[i])) != FRAC_OK) {
            return st;
        }
    }
    if (!(v[2] == FRAC_R(0.0) || v[2] == FRAC_R(1.0) || v[2] == FRAC_R(2.0))) {
        return FRAC_E_PARAM;
    }
    p->Kc = (REAL)v[0];
    p->Alpha = (REAL)v[1];
    p->M = (UDINT)v[2];
    p->N1 = (REAL)v[3];
    p->N2 = (REAL)v[4];
    p->D1 = (REAL)v[5];
    p->D2 = (REAL)v[6];
    p->Fa = (REAL)v[7];
    p->Fbeta = (REAL)v[8];
    p->Fb = (REAL)v[9];
    return FRAC_OK;
}

void damploop_init(void *ctx)
{
    damploop *d = (damploop *)ctx;
    memset(&d->law, 0, sizeof d->law);
    memset(&d->out, 0, sizeof d->out);
    if (d->table) {
        UINT st = plcprog_open_table(&d->partable, d->table, d->table_size);
        if (st == fracSTAT_OK) {
            st = plcprog_status_id(damploop_params_from_table(&d->loaded, FracPtableObj_C(d->partable.Handle)));
        }
        if (st != fracSTAT_OK) {
            d->fault = 1;
            d->out.Error = 1;
            d->out.StatusID = st;
            return;
        }
        d->par = &d->loaded;
    }
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
    d->partable.Enable = 0;
    ParTable(&d->partable);
    d->out.MotorReference = 0.0f;
}

void damploop_program(damploop *d, plc_program *prog, const FracDampParType *par, damploop_inputs *image_in,
                      damploop_outputs *image_out)
{
    memset(d, 0, sizeof *d);
    d->par = par;
    plcprog_io(&d->io_in, image_in, &d->in, sizeof d->in);
    plcprog_io(&d->io_out, image_out, &d->out, sizeof d->out);
    plcprog_describe(prog, "DampLoop", damploop_init, damploop_cyclic, damploop_exit, d, &d->io_in, 1, &d->io_out);
}

void damploop_program_table(damploop *d, plc_program *prog, const FracDampParType *base, const void *table,
                            UDINT size, damploop_inputs *image_in, damploop_outputs *image_out)
{
    damploop_program(d, prog, base, image_in, image_out);
    d->table = table;
    d->table_size = size;
    d->loaded = *base;
}
