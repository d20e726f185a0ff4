/*
 * TrajLUT - trajectory playback with per-channel lead/lag (FracCtrl.fun)
 * on frac_trajlut (frac/trajlut.h). The feedforward of seed 004 is stored
 * as tables and interpolated every cycle (Sec. 6.4, notes 004b 4.5); in
 * Exp. D the torque channel leads by d_i and the IMU reference lags by d_o
 * cycles (Sec. 8.6). While Run is TRUE each call plays cycle k and
 * advances k (frac_trajlut_step), which is the thesis's run-time counter;
 * with Run FALSE the current cycle is held (frac_trajlut_eval). A new
 * parameter set replaces the one in effect only if valid. Cost per call:
 * Channels O(1) uniform lookups.
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/trajlut.h"

typedef char trajlut_check_channels[(fracTRAJ_MAX_CHANNELS == FRAC_TRAJLUT_MAX_CH) ? 1 : -1];
typedef char trajlut_check_interp[((int)fracINTERP_LINEAR == (int)FRAC_LUT_LINEAR && (int)fracINTERP_CUBIC == (int)FRAC_LUT_CUBIC) ? 1 : -1];
typedef char trajlut_check_segment[((int)fracSEG_BEFORE == (int)FRAC_TRAJLUT_BEFORE && (int)fracSEG_PRE == (int)FRAC_TRAJLUT_PRE
    && (int)fracSEG_MOTION == (int)FRAC_TRAJLUT_MOTION && (int)fracSEG_POST == (int)FRAC_TRAJLUT_POST
    && (int)fracSEG_AFTER == (int)FRAC_TRAJLUT_AFTER) ? 1 : -1];

static int trajlut_init(const TrajLUTParType *p, frac_trajlut *fresh)
{
    frac_trajlut_params prm;
    const frac_real *data[fracTRAJ_MAX_CHANNELS];
    long lead[fracTRAJ_MAX_CHANNELS];
    size_t c;
    for (c = 0; c < fracTRAJ_MAX_CHANNELS; c++) {
        data[c] = p->pData[c];
        lead[c] = (long)p->Lead[c];
    }
    prm.channels = (size_t)p->Channels;
    prm.n = (size_t)p->N;
    prm.data = data;
    prm.t0 = (frac_real)p->T0;
    prm.dt = (frac_real)p->Dt;
    prm.Ts = (frac_real)p->Ts;
    prm.lead = lead;
    prm.t_motion_start = (frac_real)p->TMotionStart;
    prm.t_motion_end = (frac_real)p->TMotionEnd;
    prm.interp = (int)p->Interpolation;
    return frac_trajlut_init(fresh, &prm, p->pSlopes);
}

static int trajlut_load(void *vinst, int enable_edge)
{
    struct TrajLUT *inst = (struct TrajLUT *)vinst;
    frac_trajlut fresh;
    int st = trajlut_init(&inst->Parameters, &fresh);
    size_t c;
    (void)enable_edge;
    if (st == FRAC_OK) {
        *FracTrajLutObj_C(inst->Traj) = fresh;
        /* the channels the new set does not play keep their Y: the copy
         * Out -> Y gives it back exactly (REAL -> frac_real -> REAL) */
        for (c = fresh.channels; c < fracTRAJ_MAX_CHANNELS; c++) {
            inst->Out[c] = (FracReal)inst->Y[c];
        }
    }
    return st;
}

/* Without parameters the outputs hold; disabled they return to the start. */
static void trajlut_hold(void *vinst, int disabled)
{
    struct TrajLUT *inst = (struct TrajLUT *)vinst;
    size_t c;
    if (disabled) {
        for (c = 0; c < fracTRAJ_MAX_CHANNELS; c++) {
            inst->Y[c] = 0.0f;
        }
        inst->Segment = fracSEG_BEFORE;
        inst->Cycle = 0;
        inst->RestartOld = 0;
    }
}

static const fracctrl_block trajlut_block = {trajlut_load, trajlut_hold};

/*
 * The four BOOL pins as one number, the key of SteadyPins (FracCtrl.fun
 * declares them first and in this order, so the compiler reads them in one
 * 32-bit load; the value does not depend on the layout).
 */
#define TRAJLUT_PINS(inst) \
    ((UDINT)(inst)->Enable | (UDINT)(inst)->Update << 8 | (UDINT)(inst)->Run << 16 | (UDINT)(inst)->Restart << 24)

/*
 * The PLCopen sequence (fracctrl_enter) and the Restart edge. Sets
 * SteadyPins to the pins when the next call with the same pins changes
 * nothing but plays (FRACCTRL_STEADY, and Restart then equals RestartOld),
 * else 0. Returns 0 when the block holds.
 */
static FRACCTRL_COLD int trajlut_enter(struct TrajLUT *inst, UDINT pins)
{
    inst->SteadyPins = 0;
    if (!FRACCTRL_ENTER(&trajlut_block, inst)) {
        return 0;
    }
    if (inst->Restart && !inst->RestartOld) {
        (void)frac_trajlut_seek(FracTrajLutObj_C(inst->Traj), 0);
    }
    inst->RestartOld = inst->Restart;
    if (FRACCTRL_STEADY(&inst->Fb, inst->Enable, inst->Update)) {
        inst->SteadyPins = pins;
    }
    return 1;
}

/*
 * A call with the pins of SteadyPins (nonzero: Enable is 1 in it) skips
 * trajlut_enter: the state it would leave is the one it left. The step
 * writes the channels in play into Out, which holds Y in the others
 * (trajlut_load), so Y is copied in two fixed, branch-free halves of
 * fracTRAJ_MAX_CHANNELS / 2 channels (the second one only when the set
 * plays more than that) instead of a loop over Channels.
 */
void TrajLUT(struct TrajLUT* inst)
{
    UDINT pins = TRAJLUT_PINS(inst);
    int st;
    size_t c;

    if ((pins != inst->SteadyPins || pins == 0) && !trajlut_enter(inst, pins)) {
        return;
    }
    inst->Cycle = (UDINT)FracTrajLutObj_C(inst->Traj)->k;
    if (!inst->Run) {
        st = frac_trajlut_eval(FracTrajLutObj_C(inst->Traj), FracTrajLutObj_C(inst->Traj)->k, inst->Out,
                               &inst->OutSegment);
    } else {
        st = frac_trajlut_step(FracTrajLutObj_C(inst->Traj), inst->Out, &inst->OutSegment);
    }
    for (c = 0; c < fracTRAJ_MAX_CHANNELS / 2; c++) {
        inst->Y[c] = (REAL)inst->Out[c];
    }
    if (FracTrajLutObj_C(inst->Traj)->channels > fracTRAJ_MAX_CHANNELS / 2) {
        for (c = fracTRAJ_MAX_CHANNELS / 2; c < fracTRAJ_MAX_CHANNELS; c++) {
            inst->Y[c] = (REAL)inst->Out[c];
        }
    }
    inst->Segment = (FracTrajSegmentEnum)inst->OutSegment;
    FRACCTRL_OUTPUTS(inst, st);
}
