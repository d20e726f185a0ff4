/*
 * Watchdog - stale-sensor detection and fault reaction (FracCtrl.fun).
 *
 * The sensor task (e.g. ImuRead in Cyclic #2, Table 2.3) increments
 * SampleCounter for every new sample. If the counter has not changed for
 * more than MaxStaleCycles calls, or the torque setpoint is not finite, the
 * fault latches: TorqueOut ramps from its last finite value towards zero
 * at RampRate [Nm/s] (a step change of the setpoint would excite the
 * ~3 Hz first beam mode, seed 004 part 2, 9.2) and stays at zero until a
 * rising edge of Acknowledge while the sensor is fresh and the torque
 * finite. The ramp is libfrac's bounded-rate ramp (frac/ramp.h).
 *
 * Cost: O(1) per call, no allocation.
 */
#include "FracCtrl.h"
#include "fracctrl_status.h"
#include "frac/frac_types.h"
#include "frac/ramp.h"

static int watchdog_load(void *vinst, int enable_edge)
{
    struct Watchdog *inst = (struct Watchdog *)vinst;
    WatchdogInternalType *in = &inst->Internal;
    const WatchdogParType *p = &inst->Parameters;
    int st = FRAC_OK;
    if (p->MaxStaleCycles < 1 || !FRAC_ISFINITE(p->RampRate) || !(p->RampRate > 0.0f)
        || !FRAC_ISFINITE(p->CycleTime) || !(p->CycleTime > 0.0f)) {
        st = FRAC_E_PARAM;
    } else {
        in->Par = *p;
    }
    if (enable_edge) {
        in->Latched = 0;
        in->LastTorque = 0.0f;
        in->AckOld = inst->Acknowledge;
    }
    return st;
}

static void watchdog_hold(void *vinst, int disabled)
{
    struct Watchdog *inst = (struct Watchdog *)vinst;
    WatchdogInternalType *in = &inst->Internal;
    inst->TorqueOut = 0.0f;
    inst->RampActive = 0;
    if (disabled) {
        in->Latched = 0;
        in->LastTorque = 0.0f;
        in->AckOld = 0;
        inst->Stale = 0;
        inst->StaleCycles = 0;
    }
}

static const fracctrl_block watchdog_block = {watchdog_load, watchdog_hold};

void Watchdog(struct Watchdog* inst)
{
    WatchdogInternalType *in = &inst->Internal;
    int phase = FRACCTRL_RUN;
    BOOL ack_edge;
    frac_real ramped;

    if (!FRACCTRL_STEADY(&in->Fb, inst->Enable, inst->Update)) {
        phase = fracctrl_enter(&watchdog_block, inst, &in->Fb, &inst->Enable, &inst->Update, &inst->Active, &inst->Busy,
                               &inst->Error, &inst->StatusID);
        if (phase == FRACCTRL_HOLD) {
            return;
        }
    }

    if (phase == FRACCTRL_STARTED || inst->SampleCounter != in->CounterOld) {
        in->CounterOld = inst->SampleCounter;
        inst->StaleCycles = 0;
    } else if (inst->StaleCycles < 0xFFFFFFFFU) {
        inst->StaleCycles++;
    }
    inst->Stale = inst->StaleCycles > in->Par.MaxStaleCycles;

    ack_edge = inst->Acknowledge && !in->AckOld;
    in->AckOld = inst->Acknowledge;
    if (in->Latched && ack_edge && !inst->Stale && FRAC_ISFINITE(inst->TorqueIn)) {
        in->Latched = 0;
    }
    if (!in->Latched) {
        if (inst->Stale) {
            in->Latched = 1;
            in->FaultID = fracERR_SENSOR_STALE;
        } else if (!FRAC_ISFINITE(inst->TorqueIn)) {
            in->Latched = 1;
            in->FaultID = fracERR_TORQUE_NONFINITE;
        }
    }

    if (in->Latched) {
        /* Parameters were validated at Update and LastTorque is always
         * finite, so the ramp cannot fail here (and would fall to zero). */
        ramped = FRAC_R(0.0);
        (void)frac_ramp_step((frac_real)in->LastTorque, FRAC_R(0.0), (frac_real)in->Par.RampRate,
                             (frac_real)in->Par.CycleTime, &ramped);
        in->LastTorque = (REAL)ramped;
        inst->RampActive = in->LastTorque != 0.0f;
    } else {
        in->LastTorque = inst->TorqueIn;
        inst->RampActive = 0;
    }
    inst->TorqueOut = in->LastTorque;
    inst->Active = !in->Latched;
    inst->Busy = 1;
    inst->Error = in->Latched || in->Fb.ParStatus != fracSTAT_OK;
    inst->StatusID = in->Latched ? in->FaultID : in->Fb.ParStatus;
}
