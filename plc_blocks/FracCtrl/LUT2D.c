/*
 * LUT2D - 2-D bilinear lookup table block (FracCtrl.fun) on frac_lut2
 * (frac/lut.h). Parameters map onto frac_lut2_init (each axis uniform or on
 * breakpoints), (X1, X2) onto frac_lut2_eval. A new parameter set replaces
 * the one in effect only if it is valid. Cost per call: one frac_lut2_eval.
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/lut.h"

typedef char lut2d_check_range[((int)fracRANGE_CLAMP == (int)FRAC_LUT_CLAMP && (int)fracRANGE_EXTRAPOLATE == (int)FRAC_LUT_EXTRAPOLATE) ? 1 : -1];

static int lut2d_load(void *vinst, int enable_edge)
{
    struct LUT2D *inst = (struct LUT2D *)vinst;
    const LUT2DParType *p = &inst->Parameters;
    frac_lut2 fresh;
    frac_lut_axis_params a1, a2;
    int st;
    (void)enable_edge;
    a1.x = p->pX1;
    a1.n = (size_t)p->N1;
    a1.x0 = (frac_real)p->X10;
    a1.h = (frac_real)p->Dx1;
    a2.x = p->pX2;
    a2.n = (size_t)p->N2;
    a2.x0 = (frac_real)p->X20;
    a2.h = (frac_real)p->Dx2;
    st = frac_lut2_init(&fresh, &a1, &a2, p->pZ, (int)p->Range);
    if (st == FRAC_OK) {
        *FracLut2Obj_C(inst->Lut) = fresh;
    }
    return st;
}

static void lut2d_hold(void *vinst, int disabled)
{
    (void)disabled;
    ((struct LUT2D *)vinst)->Y = 0.0f;
}

static const fracctrl_block lut2d_block = {lut2d_load, lut2d_hold};

void LUT2D(struct LUT2D* inst)
{
    int st;
    frac_real y;

    if (!FRACCTRL_ENTER(&lut2d_block, inst)) {
        return;
    }
    st = frac_lut2_eval(FracLut2Obj_C(inst->Lut), (frac_real)inst->X1, (frac_real)inst->X2, &y);
    inst->Y = (REAL)y;
    FRACCTRL_OUTPUTS(inst, st);
}
