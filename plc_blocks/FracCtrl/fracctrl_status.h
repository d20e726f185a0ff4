/*
 * fracctrl_status.h - the PLCopen state handling shared by the FracCtrl
 * block bodies (internal to the library, not exported).
 *
 * Every block follows the same Enable-type pattern (FracCtrl.fun header):
 * a rising edge of Enable or of Update (re)loads the parameters; parameters
 * are validated before they replace the ones in effect, so a rejected
 * Update leaves the block running on the previous set and reports
 * Error/StatusID until a later edge brings a valid set.
 */
#ifndef FRACCTRL_STATUS_H
#define FRACCTRL_STATUS_H

#include "FracCtrl.h"

/*
 * StatusID of a libfrac status code (frac/frac_types.h): 0 for FRAC_OK,
 * fracERR_LIBFRAC + |s| for an error s < 0, fracWRN_LIBFRAC + s for a
 * warning s > 0. Codes beyond the UINT range map to fracERR_LIBFRAC.
 */
UINT fracctrl_status_id(int status);

/*
 * Edge detection for Enable/Update. Returns 1 when this call must load the
 * parameters (rising edge of Enable, or rising edge of Update while
 * enabled), else 0; *enable_edge is set to 1 on a rising edge of Enable.
 * Updates the edge memory in fb.
 */
int fracctrl_load_edge(FracFbStateType *fb, BOOL enable, BOOL update, int *enable_edge);

/*
 * Records the result of a parameter check: on success (StatusID 0)
 * ParOk becomes TRUE; on failure ParOk is cleared only on an Enable edge
 * (no parameters in effect yet), an Update keeps the previous set.
 */
void fracctrl_par_result(FracFbStateType *fb, UINT status_id, int enable_edge);

/*
 * Outputs after a libfrac step that returned `status`: an error clears
 * Valid and sets Error with its StatusID (the block's output holds the last
 * finite value, as libfrac guarantees); otherwise Valid is TRUE and
 * StatusID is a pending parameter error (a rejected Update), else the
 * step's warning or fracSTAT_OK. Busy is TRUE.
 */
void fracctrl_report(const FracFbStateType *fb, int status, BOOL *valid, BOOL *busy, BOOL *error,
                     UINT *status_id);

/* Outputs when no valid parameter set is in effect: Error with the
 * parameter StatusID, Valid and Busy FALSE. */
void fracctrl_report_no_par(const FracFbStateType *fb, BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id);

/* Outputs when Enable is FALSE: all FALSE, StatusID fracSTAT_DISABLED. */
void fracctrl_report_disabled(BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id);

/* Clears the edge memory and the parameter state when Enable is FALSE. */
void fracctrl_disable(FracFbStateType *fb);

#endif /* FRACCTRL_STATUS_H */
