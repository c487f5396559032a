/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 2.0 Model Exchange: the calls of FMI 2.0.4 §3.2 over the model
 * interface; the importer integrates, the model decides at events. */
#include <math.h>
#include <string.h>

#include "fmi2_instance.h"

fmi2Status fmi2EnterEventMode(fmi2Component c)
{
    BEGIN("fmi2EnterEventMode", SIMULATING);
    INTERFACE("fmi2EnterEventMode", MODEL_EXCHANGE, "Model Exchange");
    in->state = EventMode;
    return fmi2OK;
}

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info)
{
    BEGIN("fmi2NewDiscreteStates", EventMode);
    INTERFACE("fmi2NewDiscreteStates", MODEL_EXCHANGE, "Model Exchange");
    REQUIRE("fmi2NewDiscreteStates", info, "fmi2EventInfo is NULL");
    bool changed;
    if (instance_event_update(in, "fmi2NewDiscreteStates", true, &changed) != STATUS_OK) return fmi2Error;
    /* The model iterates its decisions to a fixpoint: one call settles them. */
    info->newDiscreteStatesNeeded = fmi2False;
    info->terminateSimulation = fmi2False;
    info->nominalsOfContinuousStatesChanged = fmi2False;
    info->valuesOfContinuousStatesChanged = changed ? fmi2True : fmi2False;
    info->nextEventTimeDefined = fmi2False;
    info->nextEventTime = 0;
    return fmi2OK;
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c)
{
    BEGIN("fmi2EnterContinuousTimeMode", EventMode);
    INTERFACE("fmi2EnterContinuousTimeMode", MODEL_EXCHANGE, "Model Exchange");
    model_begin_integration(&in->model);
    in->state = ContinuousTimeMode;
    return fmi2OK;
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi2Boolean *enterEventMode, fmi2Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    BEGIN("fmi2CompletedIntegratorStep", ContinuousTimeMode);
    INTERFACE("fmi2CompletedIntegratorStep", MODEL_EXCHANGE, "Model Exchange");
    REQUIRE("fmi2CompletedIntegratorStep", enterEventMode && terminateSimulation, "an output pointer is NULL");
    *enterEventMode = fmi2False;
    *terminateSimulation = fmi2False;
    return fmi2OK;
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time)
{
    BEGIN("fmi2SetTime", ContinuousTimeMode);   /* in Event Mode only for FMUs without states (§3.2.3) */
    INTERFACE("fmi2SetTime", MODEL_EXCHANGE, "Model Exchange");
    REQUIRE("fmi2SetTime", isfinite(time), "time = %g must be finite", time);
    in->time = time;
    return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx)
{
    BEGIN("fmi2SetContinuousStates", ContinuousTimeMode);
    INTERFACE("fmi2SetContinuousStates", MODEL_EXCHANGE, "Model Exchange");
    return (fmi2Status)instance_set_states(in, "fmi2SetContinuousStates", x, nx);
}

/* The model's vectors, read and checked by the instance. */
#define READ_ARRAY(call, allowed, which, out, n)         \
    BEGIN(call, allowed);                               \
    INTERFACE(call, MODEL_EXCHANGE, "Model Exchange");  \
    return (fmi2Status)instance_read_array(in, call, which, out, n)

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx)
{
    READ_ARRAY("fmi2GetDerivatives", READABLE, ARRAY_DERIVATIVES, derivatives, nx);
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real z[], size_t ni)
{
    READ_ARRAY("fmi2GetEventIndicators", READABLE, ARRAY_EVENT_INDICATORS, z, ni);
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx)
{
    READ_ARRAY("fmi2GetContinuousStates", READABLE, ARRAY_STATES, x, nx);
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real nominal[], size_t nx)
{
    READ_ARRAY("fmi2GetNominalsOfContinuousStates", Instantiated | READABLE, ARRAY_NOMINALS, nominal, nx);
}
