/* PLCopen state handling shared by the FracCtrl bodies (fracctrl_status.h). */
#include "fracctrl_status.h"

UINT fracctrl_status_id(int status)
{
    if (status == FRAC_OK) {
        return fracSTAT_OK;
    }
    if (status < 0 && status > -1000) {
        return (UINT)(fracERR_LIBFRAC + (UINT)(-status));
    }
    if (status > 0 && status < 1000) {
        return (UINT)(fracWRN_LIBFRAC + (UINT)status);
    }
    return fracERR_LIBFRAC;
}

UDINT fracctrl_spare_bank(const FracFbStateType *fb, UDINT bank)
{
    return fb->ParOk ? 1u - bank : bank;
}

int fracctrl_enter(const fracctrl_block *blk, void *inst, FracFbStateType *fb, const BOOL *enable_pin,
                   const BOOL *update_pin, BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id)
{
    BOOL enable = *enable_pin, update = *update_pin;
    int enable_edge, load;
    if (!enable) {
        fb->EnableOld = 0;
        fb->UpdateOld = 0;
        fb->ParOk = 0;
        fb->ParStatus = fracSTAT_DISABLED;
        *valid = 0;
        *busy = 0;
        *error = 0;
        *status_id = fracSTAT_DISABLED;
        fb->Steady = 0;
        fb->Reported = FRACCTRL_UNREPORTED;
        blk->hold(inst, 1);
        return FRACCTRL_HOLD;
    }
    enable_edge = !fb->EnableOld;
    load = enable_edge || (update && !fb->UpdateOld);
    fb->EnableOld = 1;
    fb->UpdateOld = update ? 1 : 0;
    if (load) {
        fb->ParStatus = fracctrl_status_id(blk->load(inst, enable_edge));
        if (fb->ParStatus == fracSTAT_OK) {
            fb->ParOk = 1;
        } else if (enable_edge) {
            fb->ParOk = 0;
        }
    }
    fb->Steady = fb->ParOk ? FRACCTRL_KEY(1, fb->UpdateOld) : 0;
    fb->Reported = FRACCTRL_UNREPORTED;
    if (!fb->ParOk) {
        *valid = 0;
        *busy = 0;
        *error = 1;
        *status_id = fb->ParStatus;
        blk->hold(inst, 0);
        return FRACCTRL_HOLD;
    }
    return enable_edge ? FRACCTRL_STARTED : FRACCTRL_RUN;
}

void fracctrl_report(FracFbStateType *fb, int status, BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id)
{
    fb->Reported = status;
    *busy = 1;
    if (status < 0) {
        *valid = 0;
        *error = 1;
        *status_id = fracctrl_status_id(status);
        return;
    }
    *valid = 1;
    *error = fb->ParStatus != fracSTAT_OK;
    *status_id = *error ? fb->ParStatus : fracctrl_status_id(status);
}
