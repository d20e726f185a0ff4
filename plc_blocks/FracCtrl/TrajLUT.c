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

static int trajlut_load(const TrajLUTParType *p, frac_trajlut *fresh)
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

void TrajLUT(struct TrajLUT* inst)
{
    int enable_edge, st, seg;
    frac_real y[fracTRAJ_MAX_CHANNELS];
    size_t c;

    if (!inst->Enable) {
        fracctrl_disable(&inst->Fb);
        fracctrl_report_disabled(&inst->Valid, &inst->Busy, &inst->Error, &inst->StatusID);
        for (c = 0; c < fracTRAJ_MAX_CHANNELS; c++) {
            inst->Y[c] = 0.0f;
        }
        inst->Segment = fracSEG_BEFORE;
        inst->Cycle = 0;
        inst->RestartOld = 0;
        return;
    }
    if (fracctrl_load_edge(&inst->Fb, inst->Enable, inst->Update, &enable_edge)) {
        frac_trajlut fresh;
        st = trajlut_load(&inst->Parameters, &fresh);
        fracctrl_par_result(&inst->Fb, fracctrl_status_id(st), enable_edge);
        if (st == FRAC_OK) {
            inst->Traj = fresh;
        }
    }
    if (!inst->Fb.ParOk) {
        fracctrl_report_no_par(&inst->Fb, &inst->Valid, &inst->Busy, &inst->Error, &inst->StatusID);
        return;
    }
    if (inst->Restart && !inst->RestartOld) {
        (void)frac_trajlut_seek(&inst->Traj, 0);
    }
    inst->RestartOld = inst->Restart;
    inst->Cycle = (UDINT)inst->Traj.k;
    if (inst->Run) {
        st = frac_trajlut_step(&inst->Traj, y, &seg);
    } else {
        st = frac_trajlut_eval(&inst->Traj, inst->Traj.k, y, &seg);
    }
    for (c = 0; c < inst->Traj.channels; c++) {
        inst->Y[c] = (REAL)y[c];
    }
    inst->Segment = (FracTrajSegmentEnum)seg;
    fracctrl_report(&inst->Fb, st, &inst->Valid, &inst->Busy, &inst->Error, &inst->StatusID);
}
