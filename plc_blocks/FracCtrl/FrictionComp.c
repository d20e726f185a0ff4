/*
 * FrictionComp - static friction compensation (FracCtrl.fun) on
 * frac_friction (frac/friction.h): seed 004 (5.2)-(5.4) with sgn replaced
 * by tanh(K v) as the thesis implements it (Table 8.6: K = 60). Exp. A/B
 * add the estimate to the PD torque, (5.1). Parameters map onto
 * frac_friction_init, Velocity onto frac_friction_eval. Cost per call: one
 * tanh (plus exp and pow for Stribeck).
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/friction.h"

typedef char friction_check_model[((int)fracFRICTION_LINEAR == (int)FRAC_FRICTION_LINEAR
    && (int)fracFRICTION_ASYMMETRIC == (int)FRAC_FRICTION_ASYMMETRIC && (int)fracFRICTION_STRIBECK == (int)FRAC_FRICTION_STRIBECK) ? 1 : -1];

static int friction_load(void *vinst, int enable_edge)
{
    struct FrictionComp *inst = (struct FrictionComp *)vinst;
    const FrictionCompParType *p = &inst->Parameters;
    frac_friction fresh;
    frac_friction_params fp;
    int st;
    (void)enable_edge;
    fp.model = (int)p->Model;
    fp.k = (frac_real)p->K;
    fp.b1 = (frac_real)p->B1;
    fp.b0 = (frac_real)p->B0;
    fp.b1n = (frac_real)p->B1n;
    fp.b1p = (frac_real)p->B1p;
    fp.b0n = (frac_real)p->B0n;
    fp.b0p = (frac_real)p->B0p;
    fp.b1s = (frac_real)p->B1s;
    fp.b2s = (frac_real)p->B2s;
    fp.b3s = (frac_real)p->B3s;
    fp.v_s = (frac_real)p->Vs;
    fp.delta = (frac_real)p->Delta;
    st = frac_friction_init(&fresh, &fp);
    if (st == FRAC_OK) {
        *FracFrictionObj_C(inst->Friction) = fresh;
    }
    return st;
}

static void friction_hold(void *vinst, int disabled)
{
    (void)disabled;
    ((struct FrictionComp *)vinst)->Torque = 0.0f;
}

static const fracctrl_block friction_block = {friction_load, friction_hold};

/* The libfrac result goes to Out, in the instance: the body needs no stack frame. */
void FrictionComp(struct FrictionComp* inst)
{
    int st;

    if (!FRACCTRL_ENTER(&friction_block, inst)) {
        return;
    }
    st = frac_friction_eval(FracFrictionObj_C(inst->Friction), (frac_real)inst->Velocity, &inst->Out);
    inst->Torque = (REAL)inst->Out;
    FRACCTRL_OUTPUTS(inst, st);
}
