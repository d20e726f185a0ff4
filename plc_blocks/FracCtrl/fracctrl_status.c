/* PLCopen state handling shared by the FracCtrl bodies (fracctrl_status.h). */
#include "fracctrl_status.h"
#include "frac/frac_types.h"

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

int fracctrl_load_edge(FracFbStateType *fb, BOOL enable, BOOL update, int *enable_edge)
{
    int load;
    *enable_edge = (enable && !fb->EnableOld) ? 1 : 0;
    load = *enable_edge || (enable && update && !fb->UpdateOld);
    fb->EnableOld = enable ? 1 : 0;
    fb->UpdateOld = update ? 1 : 0;
    return load;
}

void fracctrl_par_result(FracFbStateType *fb, UINT status_id, int enable_edge)
{
    fb->ParStatus = status_id;
    if (status_id == fracSTAT_OK) {
        fb->ParOk = 1;
    } else if (enable_edge) {
        fb->ParOk = 0;
    }
}

void fracctrl_disable(FracFbStateType *fb)
{
    fb->EnableOld = 0;
    fb->UpdateOld = 0;
    fb->ParOk = 0;
    fb->ParStatus = fracSTAT_DISABLED;
}

void fracctrl_report(const FracFbStateType *fb, int status, BOOL *valid, BOOL *busy, BOOL *error,
                     UINT *status_id)
{
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

void fracctrl_report_no_par(const FracFbStateType *fb, BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id)
{
    *valid = 0;
    *busy = 0;
    *error = 1;
    *status_id = fb->ParStatus;
}

void fracctrl_report_disabled(BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id)
{
    *valid = 0;
    *busy = 0;
    *error = 0;
    *status_id = fracSTAT_DISABLED;
}
