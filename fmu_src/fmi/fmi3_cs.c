/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 Co-Simulation: fmi3DoStep integrates the model with the embedded
 * CVODE (instance_step). What happens at an event inside a step is the
 * master's choice at instantiation:
 *   neither flag              the step goes through it (the event update runs inside)
 *   earlyReturnAllowed        the step ends right after the event's update
 *   eventModeUsed + early...  the step ends at the event (eventHandlingNeeded); the
 *                             master enters Event Mode, calls fmi3UpdateDiscreteStates
 *                             and fmi3EnterStepMode: each mode switch is its event. */
#include <math.h>

#include "fmi3_instance.h"

fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{
    BEGIN("fmi3EnterStepMode", EventMode);
    INTERFACE("fmi3EnterStepMode", CO_SIMULATION, "Co-Simulation");
    in->last_successful_time = in->time;
    in->state = StepMode;
    return fmi3OK;
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int32 orders[], fmi3Float64 values[],
                                    size_t nValues)
{
    (void)valueReferences, (void)orders, (void)values, (void)nValues;
    /* FMI 3.0 §4.2.1 and §2.3.6: Step Mode and Terminated, which an fmi3Error also leads to (§2.3.1). */
    BEGIN("fmi3GetOutputDerivatives", StepMode | Terminated | Error);
    INTERFACE("fmi3GetOutputDerivatives", CO_SIMULATION, "Co-Simulation");
    REQUIRE("fmi3GetOutputDerivatives", nValueReferences == 0,
            "output derivatives are not provided (maxOutputDerivativeOrder = 0)");
    return fmi3OK;
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean *eventHandlingNeeded,
                      fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    static const char call[] = "fmi3DoStep";
    BEGIN(call, StepMode);
    INTERFACE(call, CO_SIMULATION, "Co-Simulation");
    REQUIRE(call, eventHandlingNeeded && terminateSimulation && earlyReturn && lastSuccessfulTime,
            "an output pointer is NULL");
    Fmi3Instance *self = FMI3(in);
    REQUIRE(call, !self->event_pending, "the last step ended at an event at t = %.17g: enter Event Mode and call "
            "fmi3UpdateDiscreteStates first", in->time);
    const StepPolicy policy = !self->early_return_allowed ? THROUGH_EVENTS
                              : self->event_mode_used     ? RETURN_AT_EVENT
                                                          : RETURN_AFTER_EVENT;
    StepEnd end;
    const Status s = instance_step(in, call, currentCommunicationPoint, communicationStepSize, policy, &end);
    if (s == STATUS_ERROR) return fmi3Error;
    *earlyReturn = end == STEP_EVENT;
    *eventHandlingNeeded = self->event_pending = end == STEP_EVENT && policy == RETURN_AT_EVENT;
    *terminateSimulation = fmi3False;
    *lastSuccessfulTime = in->last_successful_time;
    return s == STATUS_DISCARD ? fmi3Discard : fmi3OK;
}
