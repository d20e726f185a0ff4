/*
 * LUT1D - 1-D lookup table block (FracCtrl.fun) on frac_lut1 (frac/lut.h).
 *
 * Seed 004 stores the feedforward trajectories as tables interpolated every
 * PLC cycle (thesis Sec. 5.1, 6.4; notes 004b 4.5). The body maps
 * Parameters onto frac_lut1_init / frac_lut1_init_uniform and X onto
 * frac_lut1_eval; all numerics are libfrac's. A new parameter set is built
 * in a separate object and replaces the one in effect only if it is valid.
 * Cost per call: one frac_lut1_eval (O(1) on a uniform grid or a cached
 * segment, O(log N) otherwise).
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/lut.h"

/* The IEC enumerations carry libfrac's values (checked at compile time). */
typedef char lut1d_check_interp[((int)fracINTERP_LINEAR == (int)FRAC_LUT_LINEAR && (int)fracINTERP_CUBIC == (int)FRAC_LUT_CUBIC) ? 1 : -1];
typedef char lut1d_check_range[((int)fracRANGE_CLAMP == (int)FRAC_LUT_CLAMP && (int)fracRANGE_EXTRAPOLATE == (int)FRAC_LUT_EXTRAPOLATE) ? 1 : -1];

static int lut1d_load(void *vinst, int enable_edge)
{
    struct LUT1D *inst = (struct LUT1D *)vinst;
    const LUT1DParType *p = &inst->Parameters;
    frac_lut1 fresh;
    int st;
    (void)enable_edge;
    if (p->pX) {
        st = frac_lut1_init(&fresh, p->pX, p->pY, (size_t)p->N, (int)p->Interpolation, (int)p->Range, p->pSlopes);
    } else {
        st = frac_lut1_init_uniform(&fresh, (frac_real)p->X0, (frac_real)p->Dx, p->pY, (size_t)p->N,
                                    (int)p->Interpolation, (int)p->Range, p->pSlopes);
    }
    if (st == FRAC_OK) {
        *FracLut1Obj_C(inst->Lut) = fresh;
    }
    return st;
}

static void lut1d_hold(void *vinst, int disabled)
{
    (void)disabled;
    ((struct LUT1D *)vinst)->Y = 0.0f;
}

static const fracctrl_block lut1d_block = {lut1d_load, lut1d_hold};

void LUT1D(struct LUT1D* inst)
{
    int st;
    frac_real y;

    if (!FRACCTRL_ENTER(&lut1d_block, inst)) {
        return;
    }
    st = frac_lut1_eval(FracLut1Obj_C(inst->Lut), (frac_real)inst->X, &y);
    inst->Y = (REAL)y;
    FRACCTRL_OUTPUTS(inst, st);
}
