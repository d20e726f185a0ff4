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
 * parameter load and its own outputs (fracctrl_block).
 *
 * The per-call interface cost is kept to two compares on the steady path
 * (the block-call overhead goal of issue 8, tests/bench/bench_plc.sh):
 * - FRACCTRL_STEADY compares the pins Enable and Update, packed into one
 *   number, with Fb.Steady, which fracctrl_enter sets when a call with
 *   those pins would change nothing (Enable held TRUE, Update unchanged,
 *   parameters in effect); such a call skips fracctrl_enter;
 * - FRACCTRL_OUTPUTS compares the step's status with Fb.Reported, the
 *   status the outputs were last set from; when they are equal (and
 *   nothing else changed the outputs since, which fracctrl_enter records
 *   by resetting Fb.Reported) the outputs already hold what
 *   fracctrl_report would write, so nothing is written.
 * Both give exactly the outputs and state of the full rules
 * (tests/plc_blocks/test_fracctrl_status.c, for every state and over long
 * random call sequences). The NaN check stays the libfrac step's.
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

/*
 * Marks a block's own function that runs only off the steady path (edges,
 * parameter loads): kept out of line, so that the steady path does not
 * carry its register set-up. Only an inlining hint (no effect on what a
 * call does); empty for compilers without the GNU attribute.
 */
#if defined(__GNUC__)
#define FRACCTRL_COLD __attribute__((noinline))
#else
#define FRACCTRL_COLD
#endif

/* Results of fracctrl_enter. */
#define FRACCTRL_HOLD 0    /* the block does not run: outputs are set, return */
#define FRACCTRL_RUN 1     /* parameters in effect: run the step */
#define FRACCTRL_STARTED 2 /* as FRACCTRL_RUN, on the rising edge of Enable */

/*
 * The Enable/Update sequence up to the step (the pins are passed by
 * address: the steady path that calls it only when FRACCTRL_STEADY fails
 * then needs no register for their values):
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
 * Every call sets Fb.Steady and resets Fb.Reported.
 */
int fracctrl_enter(const fracctrl_block *blk, void *inst, FracFbStateType *fb, const BOOL *enable,
                   const BOOL *update, BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id);

/*
 * Fb.Steady after a call: the key of the pins (Enable 1, Update equal to
 * the edge memory) with which the next call changes nothing, or 0. The +1
 * keeps every key nonzero, so a zero-initialized instance is not steady.
 * Pins other than 0/1 never give a key a call can leave in Fb.Steady, so
 * they take fracctrl_enter. FracCtrl.fun declares Update right after
 * Enable in every block, so that the compiler reads both pins in one
 * 16-bit load (the key's value does not depend on the layout).
 */
#define FRACCTRL_KEY(enable, update) (((UDINT)(enable) | (UDINT)(update) << 8) + 1u)

/* Fb.Reported when the status outputs are not those of a step's status. */
#define FRACCTRL_UNREPORTED 32767

/*
 * Nonzero when fracctrl_enter would return FRACCTRL_RUN and change
 * nothing: Enable exactly TRUE and held, Update equal to its previous
 * value, a parameter set in effect. Any other call takes fracctrl_enter.
 */
#define FRACCTRL_STEADY(fb, enable, update) (FRACCTRL_KEY(enable, update) == (fb)->Steady)

/*
 * Outputs after a libfrac step that returned `status`: an error clears
 * Valid and sets Error with its StatusID (the block's output holds the last
 * finite value, as libfrac guarantees); otherwise Valid is TRUE and
 * StatusID is a pending parameter error (a rejected Update), else the
 * step's warning or fracSTAT_OK. Busy is TRUE. Records `status` in
 * Fb.Reported.
 */
void fracctrl_report(FracFbStateType *fb, int status, BOOL *valid, BOOL *busy, BOOL *error, UINT *status_id);

/*
 * fracctrl_report on the output pins themselves (lvalues), skipped when
 * they already hold its result: the same status as the last report, and
 * no fracctrl_enter since (which resets Fb.Reported).
 */
#define FRACCTRL_REPORT(fb, status, valid, busy, error, status_id)                      \
    do {                                                                               \
        if ((status) != (fb)->Reported) {                                              \
            fracctrl_report((fb), (status), &(valid), &(busy), &(error), &(status_id)); \
        }                                                                              \
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
     || fracctrl_enter((blk), (inst), &(inst)->Fb, &(inst)->Enable, &(inst)->Update, &(inst)->Valid, \
                       &(inst)->Busy, &(inst)->Error, &(inst)->StatusID) != FRACCTRL_HOLD)
#define FRACCTRL_OUTPUTS(inst, status) \
    FRACCTRL_REPORT(&(inst)->Fb, (status), (inst)->Valid, (inst)->Busy, (inst)->Error, (inst)->StatusID)

#endif /* FRACCTRL_STATUS_H */
