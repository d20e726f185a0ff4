/*
 * ParTable - validation of the binary parameter table (FracCtrl.fun) on
 * frac_ptable (frac/ptable.h). Parameters load at _INIT from the data
 * object that fracdesign table emits; a table that fails any check (magic,
 * version, size, CRC32, layout, dimensions, finiteness) leaves the block in
 * Error with the check's StatusID and the failing field, so the program
 * never uses it. The table is validated once per Enable or Update edge
 * (O(size)); other calls only report. The handle in effect is replaced
 * only by a table that passed.
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/ptable.h"

static void copy_field(plcstring *dst, const char *src, unsigned cap)
{
    unsigned i = 0;
    if (src) {
        for (; i + 1 < cap && src[i]; i++) {
            dst[i] = src[i];
        }
    }
    dst[i] = '\0';
}

static int partable_load(void *vinst, int enable_edge)
{
    struct ParTable *inst = (struct ParTable *)vinst;
    frac_ptable fresh;
    int st = frac_ptable_open(&fresh, inst->pData, (unsigned long)inst->Size);
    (void)enable_edge;
    if (st == FRAC_OK) {
        *FracPtableObj_C(inst->Handle) = fresh;
        inst->Entries = (UDINT)fresh.n_entries;
    }
    inst->FailEntry = st == FRAC_OK ? -1 : (DINT)fresh.fail_entry;
    copy_field(inst->FailField, st == FRAC_OK ? "" : fresh.fail_field, sizeof inst->FailField);
    return st;
}

static void partable_hold(void *vinst, int disabled)
{
    struct ParTable *inst = (struct ParTable *)vinst;
    inst->Entries = 0;
    if (disabled) {
        inst->FailEntry = -1;
        copy_field(inst->FailField, "", sizeof inst->FailField);
    }
}

static const fracctrl_block partable_block = {partable_load, partable_hold};

void ParTable(struct ParTable* inst)
{
    if (!FRACCTRL_ENTER(&partable_block, inst)) {
        return;
    }
    FRACCTRL_OUTPUTS(inst, FRAC_OK);
}
