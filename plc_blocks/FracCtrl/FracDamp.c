/*
 * FracDamp - collocated fractional damping law with prefilter of seed 002
 * (FracCtrl.fun) on frac_fodamp (frac/fodamp.h):
 *   Y = F(s) W - C(s) X   (W tip reference, X base moment),
 *   C(s) = Kc s^Alpha N(s) / (s^M D(s)), F(s) = (1 + Fa s^Fbeta) / (1 + Fb s)
 * (seed 002 (23), (47)-(52): C = 5.31 (1 + 0.0142 s) / s^1.2,
 * F = (1 + 0.116 s^0.55) / (1 + 0.011 s)). The body maps the pins onto
 * frac_fodamp_init / _step / _reset. frac_fodamp points into its own
 * coefficient arrays, so it cannot be copied: a new parameter set is
 * initialised in place in the object and storage bank not in use and
 * becomes the one in effect only if valid (starting from zero state).
 * Cost per call: one frac_fodamp_step (two fractional operators, at most
 * two biquads, the prefilter lag).
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/fodamp.h"

static int fracdamp_init(struct FracDamp* inst, UDINT bank)
{
    const FracDampParType *p = &inst->Parameters;
    frac_fodamp_params prm;
    prm.kc = (frac_real)p->Kc;
    prm.alpha = (frac_real)p->Alpha;
    prm.m = (unsigned)p->M;
    prm.n1 = (frac_real)p->N1;
    prm.n2 = (frac_real)p->N2;
    prm.d1 = (frac_real)p->D1;
    prm.d2 = (frac_real)p->D2;
    prm.fa = (frac_real)p->Fa;
    prm.fbeta = (frac_real)p->Fbeta;
    prm.fb = (frac_real)p->Fb;
    prm.ts = (frac_real)p->Ts;
    FRACCTRL_FO_REALIZATION(prm.op, p, FRAC_R(0.0));
    if (frac_fodamp_storage_len(&prm) > (size_t)fracFODAMP_STORAGE_LEN) {
        return FRAC_E_STORAGE;
    }
    return frac_fodamp_init(FracFodampObj_C(inst->Damp[bank]), &prm, inst->Storage[bank], (size_t)fracFODAMP_STORAGE_LEN);
}

static int fracdamp_load(void *vinst, int enable_edge)
{
    struct FracDamp *inst = (struct FracDamp *)vinst;
    UDINT bank = fracctrl_spare_bank(&inst->Fb, inst->Bank);
    int st = fracdamp_init(inst, bank);
    (void)enable_edge;
    if (st == FRAC_OK) {
        inst->Bank = bank;
    }
    return st;
}

static void fracdamp_hold(void *vinst, int disabled)
{
    struct FracDamp *inst = (struct FracDamp *)vinst;
    inst->Y = 0.0f;
    if (disabled) {
        inst->ResetOld = 0;
    }
}

static const fracctrl_block fracdamp_block = {fracdamp_load, fracdamp_hold};

void FracDamp(struct FracDamp* inst)
{
    int st;
    frac_real y;

    if (!FRACCTRL_ENTER(&fracdamp_block, inst)) {
        return;
    }
    if (inst->Reset && !inst->ResetOld) {
        (void)frac_fodamp_reset(FracFodampObj_C(inst->Damp[inst->Bank]));
    }
    inst->ResetOld = inst->Reset;
    st = frac_fodamp_step(FracFodampObj_C(inst->Damp[inst->Bank]), (frac_real)inst->W, (frac_real)inst->X, &y);
    inst->Y = (REAL)y;
    FRACCTRL_OUTPUTS(inst, st);
}
