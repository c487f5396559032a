/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 2.0 Co-Simulation: fmi2DoStep integrates the model with the embedded
 * CVODE (instance_step) and runs the same event update as Model
 * Exchange at every event inside a step, unseen by the master. */
#include "fmi2_instance.h"

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    static const char call[] = "fmi2DoStep";
    BEGIN(call, StepMode);
    INTERFACE(call, CO_SIMULATION, "Co-Simulation");
    StepEnd end;
    return (fmi2Status)instance_step(in, call, t, h, THROUGH_EVENTS, &end);
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    BEGIN("fmi2CancelStep", StepMode);
    INTERFACE("fmi2CancelStep", CO_SIMULATION, "Co-Simulation");
    return (fmi2Status)instance_fail(in, "fmi2CancelStep", "steps are never asynchronous (canRunAsynchronuously is false)");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr, (void)order, (void)value;
    BEGIN("fmi2SetRealInputDerivatives", BEFORE_INIT_ENDS | StepMode);
    INTERFACE("fmi2SetRealInputDerivatives", CO_SIMULATION, "Co-Simulation");
    REQUIRE("fmi2SetRealInputDerivatives", nvr == 0, "%s does not interpolate inputs (canInterpolateInputs is false)", MODEL_NAME);
    return fmi2OK;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)order, (void)value;
    BEGIN("fmi2GetRealOutputDerivatives", StepMode | Terminated | Error);
    INTERFACE("fmi2GetRealOutputDerivatives", CO_SIMULATION, "Co-Simulation");
    REQUIRE("fmi2GetRealOutputDerivatives", nvr == 0,
            "output derivatives are not provided (maxOutputDerivativeOrder = 0)");
    return fmi2OK;
}

/* Status queries (FMI 2.0.4 §4.2.3): steps are synchronous, so a status that
 * exists only for asynchronous steps is a legal question with no answer. */
#define STATUS_STATES (StepMode | Terminated)
#define STATUS_BEGIN(call)                                                 \
    BEGIN(call, STATUS_STATES);                                            \
    INTERFACE(call, CO_SIMULATION, "Co-Simulation");                    \
    REQUIRE(call, value, "value is NULL")

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    STATUS_BEGIN("fmi2GetStatus");
    return (fmi2Status)instance_discard(in, "fmi2GetStatus", "status kind %d: no step is pending (steps are synchronous)", (int)s);
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    STATUS_BEGIN("fmi2GetRealStatus");
    if (s != fmi2LastSuccessfulTime)
        return (fmi2Status)instance_discard(in, "fmi2GetRealStatus", "status kind %d: only fmi2LastSuccessfulTime is a Real status",
                                (int)s);
    *value = in->last_successful_time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    STATUS_BEGIN("fmi2GetIntegerStatus");
    return (fmi2Status)instance_discard(in, "fmi2GetIntegerStatus", "status kind %d: there is no Integer status", (int)s);
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    STATUS_BEGIN("fmi2GetBooleanStatus");
    if (s != fmi2Terminated)
        return (fmi2Status)instance_discard(in, "fmi2GetBooleanStatus", "status kind %d: only fmi2Terminated is a Boolean status",
                                (int)s);
    *value = fmi2False; /* the rod never asks to end a simulation */
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    STATUS_BEGIN("fmi2GetStringStatus");
    return (fmi2Status)instance_discard(in, "fmi2GetStringStatus", "status kind %d: no step is pending (steps are synchronous)",
                            (int)s);
}
