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
    (void)enable_edge;
    if (st == FRAC_OK) {
        *FracTrajLutObj_C(inst->Traj) = fresh;
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

void TrajLUT(struct TrajLUT* inst)
{
    int st, seg;
    frac_real y[fracTRAJ_MAX_CHANNELS];
    size_t c;

    if (!FRACCTRL_ENTER(&trajlut_block, inst)) {
        return;
    }
    if (inst->Restart && !inst->RestartOld) {
        (void)frac_trajlut_seek(FracTrajLutObj_C(inst->Traj), 0);
    }
    inst->RestartOld = inst->Restart;
    inst->Cycle = (UDINT)FracTrajLutObj_C(inst->Traj)->k;
    if (inst->Run) {
        st = frac_trajlut_step(FracTrajLutObj_C(inst->Traj), y, &seg);
    } else {
        st = frac_trajlut_eval(FracTrajLutObj_C(inst->Traj), FracTrajLutObj_C(inst->Traj)->k, y, &seg);
    }
    for (c = 0; c < FracTrajLutObj_C(inst->Traj)->channels; c++) {
        inst->Y[c] = (REAL)y[c];
    }
    inst->Segment = (FracTrajSegmentEnum)seg;
    FRACCTRL_OUTPUTS(inst, st);
}
