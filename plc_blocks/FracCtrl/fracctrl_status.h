/*
 * fracctrl_status.h - the PLCopen state handling shared by the FracCtrl
 * block bodies (internal to the library, not exported).
 *
 * Every block follows the same Enable-type pattern (FracCtrl.fun header):
 * a rising edge of Enable or of Update (re)loads the parameters; parameters
 * are validated before they replace the ones in effect, so a rejected
 * Update leaves the block running on the previous set and reports
 * Error/StatusID until a later edge brings a valid set.
 *
 * A body runs as
 *
 *   if (!FRACCTRL_ENTER(&block, inst)) {
 *       return;
 *   }
 *   st = <libfrac step>;
 *   FRACCTRL_OUTPUTS(inst, st);
 *
 * The Enable/Update edges, the parameter check and the outputs while the
 * block does not run are fracctrl_enter's; the block supplies only its
 * parameter load and its own outputs (fracctrl_block). FRACCTRL_STEADY
 * skips fracctrl_enter on the calls where it would change nothing (Enable
 * held, no Update edge, parameters in effect), and FRACCTRL_REPORT sets
 * the outputs of a clean step without a call; both give exactly the
 * outputs and state of the full path.
 */
#ifndef FRACCTRL_STATUS_H
#define FRACCTRL_STATUS_H

#include "FracCtrl.h"
#include "frac/frac_types.h"

/*
 * StatusID of a libfrac status code (frac/frac_types.h): 0 for FRAC_OK,
 * fracERR_LIBFRAC + |s| for an error s < 0, fracWRN_LIBFRAC + s for a
 * warning s > 0. Codes beyond the UINT range map to fracERR_LIBFRAC.
 */
UINT fracctrl_status_id(int status);

/* The parts of the Enable/Update sequence that differ between blocks. */
typedef struct fracctrl_block {
    /*
     * Validates the block's Parameters into a fresh object (or the storage
     * bank not in use) and makes it the set in effect only if it is valid.
     * enable_edge is 1 on a rising edge of Enable, 0 on one of Update.
     * Returns the libfrac status of the check (FRAC_OK: accepted).
     */
    int (*load)(void *inst, int enable_edge);
    /*
     * Sets the block's own outputs while it does not run: disabled = 1
     * when Enable is FALSE (the block also clears its edge memories),
     * 0 when no valid parameter set is in effect.
     */
    void (*hold)(void *inst, int disabled);
} fracctrl_block;

/*
 * Storage bank for a new parameter set of a block with two banks (the
 * libfrac object points into its storage): the one not in use while a set
 * is in effect, else `bank` itself.
 */
UDINT fracctrl_spare_bank(const FracFbStateType *fb, UDINT bank);

/* Results of fracctrl_enter. */
#define FRACCTRL_HOLD 0    /* the block does not run: outputs are set, return */
#define FRACCTRL_RUN 1     /* parameters in effect: run the step */
#define FRACCTRL_STARTED 2 /* as FRACCTRL_RUN, on the rising edge of Enable */

/*
 * The Enable/Update sequence up to the step:
 * - Enable FALSE: edge memory and parameter state cleared, outputs
 *   all FALSE with StatusID fracSTAT_DISABLED, blk->hold(inst, 1);
 *   returns FRACCTRL_HOLD.
 * - a rising edge of Enable, or of Update while enabled: blk->load; its
 *   StatusID becomes the parameter status. A valid set is in effect from
 *   now on; a rejected one on an Enable edge leaves no set in effect,
 *   on an Update edge the previous set stays.
 * - no set in effect: Error with the parameter StatusID, Valid and Busy
 *   FALSE, blk->hold(inst, 0); returns FRACCTRL_HOLD.
 * - else FRACCTRL_STARTED on an Enable edge, FRACCTRL_RUN otherwise
 *   (the outputs are left to the step and fracctrl_report).
 */
int fracctrl_enter(const fracctrl_block *blk, void *inst, FracFbStateType *fb, BOOL enable, BOOL update,
                   BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id);

/*
 * Nonzero when fracctrl_enter would return FRACCTRL_RUN and change
 * nothing: Enable held TRUE, Update equal to its previous value (the edge
 * memory holds 0 or 1, so no edge and nothing to update), a parameter set
 * in effect. Any other call takes fracctrl_enter.
 */
#define FRACCTRL_STEADY(fb, enable, update) \
    ((enable) && (fb)->EnableOld && (fb)->ParOk && (update) == (fb)->UpdateOld)

/*
 * Outputs after a libfrac step that returned `status`: an error clears
 * Valid and sets Error with its StatusID (the block's output holds the last
 * finite value, as libfrac guarantees); otherwise Valid is TRUE and
 * StatusID is a pending parameter error (a rejected Update), else the
 * step's warning or fracSTAT_OK. Busy is TRUE.
 */
void fracctrl_report(const FracFbStateType *fb, int status, BOOL *valid, BOOL *busy, BOOL *error,
                     UINT *status_id);

/*
 * fracctrl_report on the output pins themselves (lvalues), with the common
 * case (FRAC_OK, no pending parameter error: Valid, Busy, no Error,
 * fracSTAT_OK) set in place.
 */
#define FRACCTRL_REPORT(fb, status, valid, busy, error, status_id)                                  \
    do {                                                                                           \
        if ((status) == FRAC_OK && (fb)->ParStatus == fracSTAT_OK) {                                     \
            (valid) = 1;                                                                           \
            (busy) = 1;                                                                            \
            (error) = 0;                                                                           \
            (status_id) = fracSTAT_OK;                                                             \
        } else {                                                                                   \
            fracctrl_report((fb), (status), &(valid), &(busy), &(error), &(status_id));            \
        }                                                                                          \
    } while (0)

/*
 * The realization of the fractional operators (frac_fo_params of
 * frac/fo_op.h) from the parameter pins Method, Ts, Memory, Wb, Wh, N that
 * FracOp, FOPID and FracDamp share, with order `order` (FOPID and FracDamp
 * pass 0: libfrac sets each of their operators' own order).
 */
#define FRACCTRL_FO_REALIZATION(op, p, order_) \
    do {                                     \
        (op).method = (int)(p)->Method;      \
        (op).order = (order_);               \
        (op).ts = (frac_real)(p)->Ts;        \
        (op).memory = (size_t)(p)->Memory;   \
        (op).wb = (frac_real)(p)->Wb;        \
        (op).wh = (frac_real)(p)->Wh;        \
        (op).n = (unsigned)(p)->N;           \
    } while (0)

/*
 * The two steps on a block with the standard pins and state (Enable,
 * Update, Valid, Busy, Error, StatusID, Fb): FRACCTRL_ENTER is nonzero
 * when the step is to run (FRACCTRL_STEADY, else fracctrl_enter);
 * FRACCTRL_OUTPUTS sets the status outputs after the step.
 */
#define FRACCTRL_ENTER(blk, inst)                                                                   \
    (FRACCTRL_STEADY(&(inst)->Fb, (inst)->Enable, (inst)->Update)                                  \
     || fracctrl_enter((blk), (inst), &(inst)->Fb, (inst)->Enable, (inst)->Update, &(inst)->Valid, \
                       &(inst)->Busy, &(inst)->Error, &(inst)->StatusID) != FRACCTRL_HOLD)
#define FRACCTRL_OUTPUTS(inst, status) \
    FRACCTRL_REPORT(&(inst)->Fb, (status), (inst)->Valid, (inst)->Busy, (inst)->Error, (inst)->StatusID)

#endif /* FRACCTRL_STATUS_H */
