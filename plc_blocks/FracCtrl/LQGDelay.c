/*
 * LQGDelay - state-difference LQG with delay registers and friction state
 * (FracCtrl.fun) on frac_lqg (frac/lqg.h): Exp. C (no delay model) and
 * Exp. D (d_i = 4, d_o = 3 on the IMU, T = 1.2 ms, Table 8.8) of seed 004.
 *
 * Per call: u_bar = u* + K e_hat_x - e_hat_z (7.21) and the predictor
 * update (7.27), both inside frac_lqg_step; the body only maps the IEC
 * arrays onto it. A new parameter set is initialised in the storage bank
 * not in use and replaces the running controller only if it is valid, so a
 * rejected Update leaves the loop running; an accepted one restarts the
 * estimate at 0. Cost per call: one frac_lqg_step (Exp. D: 415
 * multiply-adds, frac/lqg.h). Memory: two banks of fracLQG_STORAGE_LEN.
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/lqg.h"

typedef char lqg_check_storage[(fracLQG_STORAGE_LEN >= FRAC_LQG_STORAGE(FRAC_MAT_MAX, fracLQG_MAX_OUTPUTS)) ? 1 : -1];

static int lqg_init(struct LQGDelay* inst, frac_lqg *fresh, UDINT bank)
{
    const LQGDelayParType *p = &inst->Parameters;
    frac_lqg_params prm;
    size_t d_o[fracLQG_MAX_OUTPUTS];
    size_t j;
    if (p->P < 1 || p->P > fracLQG_MAX_OUTPUTS) {
        return FRAC_E_PARAM;
    }
    for (j = 0; j < fracLQG_MAX_OUTPUTS; j++) {
        d_o[j] = (size_t)p->Do[j];
    }
    prm.n = (size_t)p->N;
    prm.d_i = (size_t)p->Di;
    prm.p = (size_t)p->P;
    prm.d_o = d_o;
    prm.A = p->pA;
    prm.B = p->pB;
    prm.C = p->pC;
    prm.K = p->pK;
    prm.L = p->pL;
    return frac_lqg_init(fresh, &prm, inst->Storage[bank], (size_t)fracLQG_STORAGE_LEN);
}

static int lqg_load(void *vinst, int enable_edge)
{
    struct LQGDelay *inst = (struct LQGDelay *)vinst;
    UDINT bank = fracctrl_spare_bank(&inst->Fb, inst->Bank);
    frac_lqg fresh;
    int st = lqg_init(inst, &fresh, bank);
    (void)enable_edge;
    if (st == FRAC_OK) {
        *FracLqgObj_C(inst->Lqg) = fresh;
        inst->Bank = bank;
    }
    return st;
}

static void lqg_hold(void *vinst, int disabled)
{
    struct LQGDelay *inst = (struct LQGDelay *)vinst;
    inst->U = 0.0f;
    inst->FrictionEstimate = 0.0f;
    if (disabled) {
        inst->ResetOld = 0;
    }
}

static const fracctrl_block lqg_block = {lqg_load, lqg_hold};

void LQGDelay(struct LQGDelay* inst)
{
    int st;
    frac_real y_ref[fracLQG_MAX_OUTPUTS], y[fracLQG_MAX_OUTPUTS], u;
    size_t j;

    if (!FRACCTRL_ENTER(&lqg_block, inst)) {
        return;
    }
    if (inst->Reset && !inst->ResetOld) {
        (void)frac_lqg_reset(FracLqgObj_C(inst->Lqg));
    }
    inst->ResetOld = inst->Reset;
    for (j = 0; j < fracLQG_MAX_OUTPUTS; j++) {
        y_ref[j] = (frac_real)inst->YRef[j];
        y[j] = (frac_real)inst->Y[j];
    }
    st = frac_lqg_step(FracLqgObj_C(inst->Lqg), (frac_real)inst->UStar, y_ref, y, &u);
    inst->U = (REAL)u;
    inst->FrictionEstimate = (REAL)frac_lqg_friction_estimate(FracLqgObj_C(inst->Lqg));
    FRACCTRL_OUTPUTS(inst, st);
}
