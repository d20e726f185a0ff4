/*
 * FracOp - fractional operator y = s^r x with a choice of realization
 * (FracCtrl.fun) on frac_fo (frac/fo_op.h): Grunwald-Letnikov (short
 * memory), Oustaloup or refined Oustaloup (biquad cascade on a band),
 * CFE of the Tustin or Al-Alaoui operator. The body maps Parameters onto
 * frac_fo_init and X onto frac_fo_step; a new parameter set is built in the
 * storage bank not in use and replaces the running realization only if it
 * is valid (an accepted one starts from zero history). Cost per call: one
 * frac_fo_step (GL: L multiply-adds; rational: N + 1 biquads). Memory: two
 * banks of fracFO_STORAGE_LEN reals.
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/fo_op.h"

typedef char fracop_check_method[((int)fracFO_GL == (int)FRAC_FO_GL && (int)fracFO_OUSTALOUP == (int)FRAC_FO_OUSTALOUP
    && (int)fracFO_OUSTALOUP_REFINED == (int)FRAC_FO_OUSTALOUP_REFINED
    && (int)fracFO_CFE_TUSTIN == (int)FRAC_FO_CFE_TUSTIN && (int)fracFO_CFE_ALALAOUI == (int)FRAC_FO_CFE_ALALAOUI) ? 1 : -1];

static int fracop_load(void *vinst, int enable_edge)
{
    struct FracOp *inst = (struct FracOp *)vinst;
    const FracOpParType *p = &inst->Parameters;
    UDINT bank = fracctrl_spare_bank(&inst->Fb, inst->Bank);
    frac_fo fresh;
    frac_fo_params prm;
    int st;
    (void)enable_edge;
    FRACCTRL_FO_REALIZATION(prm, p, (frac_real)p->Order);
    if (frac_fo_storage_len(&prm) > (size_t)fracFO_STORAGE_LEN) {
        return FRAC_E_STORAGE;
    }
    st = frac_fo_init(&fresh, &prm, inst->Storage[bank], (size_t)fracFO_STORAGE_LEN);
    if (st == FRAC_OK) {
        *FracFoObj_C(inst->Op) = fresh;
        inst->Bank = bank;
    }
    return st;
}

static void fracop_hold(void *vinst, int disabled)
{
    struct FracOp *inst = (struct FracOp *)vinst;
    inst->Y = 0.0f;
    if (disabled) {
        inst->ResetOld = 0;
    }
}

static const fracctrl_block fracop_block = {fracop_load, fracop_hold};

void FracOp(struct FracOp* inst)
{
    int st;
    frac_real y;

    if (!FRACCTRL_ENTER(&fracop_block, inst)) {
        return;
    }
    if (inst->Reset && !inst->ResetOld) {
        (void)frac_fo_reset(FracFoObj_C(inst->Op));
    }
    inst->ResetOld = inst->Reset;
    st = frac_fo_step(FracFoObj_C(inst->Op), (frac_real)inst->X, &y);
    inst->Y = (REAL)y;
    FRACCTRL_OUTPUTS(inst, st);
}
