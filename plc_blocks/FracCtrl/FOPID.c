/*
 * FOPID - fractional PI^lambda D^mu controller (FracCtrl.fun) on
 * frac_fopid (frac/fopid.h): FO-PI^alpha (seed 001 (5)), FO-PD^mu (29) and
 * the PD with positive feedback Delta = 1/K ((36)-(41)), with derivative
 * filter, output limits, anti-windup (clamp or back-calculation) and a
 * bumpless manual mode. The body maps the pins onto frac_fopid_init /
 * _step / _set_mode / _set_manual / _reset; a new parameter set is built
 * in the storage bank not in use and replaces the running controller only
 * if valid (an accepted one starts from zero state). Cost per call: one
 * frac_fopid_step (two fractional operators + ~20 flops).
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/fopid.h"

typedef char fopid_check_aw[((int)fracAW_NONE == (int)FRAC_FOPID_AW_NONE && (int)fracAW_CLAMP == (int)FRAC_FOPID_AW_CLAMP
    && (int)fracAW_BACKCALC == (int)FRAC_FOPID_AW_BACKCALC) ? 1 : -1];

static int fopid_init(struct FOPID* inst, frac_fopid *fresh, UDINT bank)
{
    const FOPIDParType *p = &inst->Parameters;
    frac_fopid_params prm;
    prm.kp = (frac_real)p->Kp;
    prm.ki = (frac_real)p->Ki;
    prm.kd = (frac_real)p->Kd;
    prm.lambda = (frac_real)p->Lambda;
    prm.mu = (frac_real)p->Mu;
    prm.tf = (frac_real)p->Tf;
    prm.b = (frac_real)p->B;
    prm.c = (frac_real)p->C;
    prm.delta = (frac_real)p->Delta;
    prm.umin = (frac_real)p->Y_min;
    prm.umax = (frac_real)p->Y_max;
    prm.antiwindup = (int)p->AntiWindup;
    prm.tt = (frac_real)p->Tt;
    prm.ts = (frac_real)p->Ts;
    FRACCTRL_FO_REALIZATION(prm.op, p, FRAC_R(0.0));
    if (frac_fopid_storage_len(&prm) > (size_t)fracFOPID_STORAGE_LEN) {
        return FRAC_E_STORAGE;
    }
    return frac_fopid_init(fresh, &prm, inst->Storage[bank], (size_t)fracFOPID_STORAGE_LEN);
}

static int fopid_load(void *vinst, int enable_edge)
{
    struct FOPID *inst = (struct FOPID *)vinst;
    UDINT bank = fracctrl_spare_bank(&inst->Fb, inst->Bank);
    frac_fopid fresh;
    int st = fopid_init(inst, &fresh, bank);
    (void)enable_edge;
    if (st == FRAC_OK) {
        *FracFopidObj_C(inst->Pid) = fresh;
        inst->Bank = bank;
        inst->ManualOld = 0; /* a fresh controller starts in automatic mode */
    }
    return st;
}

static void fopid_hold(void *vinst, int disabled)
{
    struct FOPID *inst = (struct FOPID *)vinst;
    inst->Y = 0.0f;
    inst->Saturated = 0;
    if (disabled) {
        inst->ResetOld = 0;
        inst->ManualOld = 0;
    }
}

static const fracctrl_block fopid_block = {fopid_load, fopid_hold};

void FOPID(struct FOPID* inst)
{
    int st;
    frac_real u;

    if (!FRACCTRL_ENTER(&fopid_block, inst)) {
        return;
    }
    if (inst->Reset && !inst->ResetOld) {
        (void)frac_fopid_reset(FracFopidObj_C(inst->Pid));
    }
    inst->ResetOld = inst->Reset;
    if (inst->Manual != inst->ManualOld) {
        (void)frac_fopid_set_mode(FracFopidObj_C(inst->Pid), inst->Manual ? FRAC_FOPID_MANUAL : FRAC_FOPID_AUTO);
        inst->ManualOld = inst->Manual;
    }
    if (inst->Manual) {
        (void)frac_fopid_set_manual(FracFopidObj_C(inst->Pid), (frac_real)inst->Y_manual);
    }
    st = frac_fopid_step(FracFopidObj_C(inst->Pid), (frac_real)inst->W, (frac_real)inst->X, &u);
    inst->Y = (REAL)u;
    inst->Saturated = st == FRAC_W_SATURATED;
    FRACCTRL_OUTPUTS(inst, st);
}
