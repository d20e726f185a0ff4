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

static int fracop_load(struct FracOp* inst, frac_fo *fresh, UDINT bank)
{
    const FracOpParType *p = &inst->Parameters;
    frac_fo_params prm;
    prm.method = (int)p->Method;
    prm.order = (frac_real)p->Order;
    prm.ts = (frac_real)p->Ts;
    prm.memory = (size_t)p->Memory;
    prm.wb = (frac_real)p->Wb;
    prm.wh = (frac_real)p->Wh;
    prm.n = (unsigned)p->N;
    if (frac_fo_storage_len(&prm) > (size_t)fracFO_STORAGE_LEN) {
        return FRAC_E_STORAGE;
    }
    return frac_fo_init(fresh, &prm, inst->Storage[bank], (size_t)fracFO_STORAGE_LEN);
}

void FracOp(struct FracOp* inst)
{
    int enable_edge, st;
    frac_real y;

    if (!inst->Enable) {
        fracctrl_disable(&inst->Fb);
        fracctrl_report_disabled(&inst->Valid, &inst->Busy, &inst->Error, &inst->StatusID);
        inst->Y = 0.0f;
        inst->ResetOld = 0;
        return;
    }
    if (fracctrl_load_edge(&inst->Fb, inst->Enable, inst->Update, &enable_edge)) {
        frac_fo fresh;
        UDINT bank = inst->Fb.ParOk ? 1u - inst->Bank : inst->Bank;
        st = fracop_load(inst, &fresh, bank);
        fracctrl_par_result(&inst->Fb, fracctrl_status_id(st), enable_edge);
        if (st == FRAC_OK) {
            inst->Op = fresh;
            inst->Bank = bank;
        }
    }
    if (!inst->Fb.ParOk) {
        fracctrl_report_no_par(&inst->Fb, &inst->Valid, &inst->Busy, &inst->Error, &inst->StatusID);
        inst->Y = 0.0f;
        return;
    }
    if (inst->Reset && !inst->ResetOld) {
        (void)frac_fo_reset(&inst->Op);
    }
    inst->ResetOld = inst->Reset;
    st = frac_fo_step(&inst->Op, (frac_real)inst->X, &y);
    inst->Y = (REAL)y;
    fracctrl_report(&inst->Fb, st, &inst->Valid, &inst->Busy, &inst->Error, &inst->StatusID);
}
