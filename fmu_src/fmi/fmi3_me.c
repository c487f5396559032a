/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 Model Exchange: the calls of FMI 3.0 §3.2 over the instance; the
 * importer integrates, the model decides at events (fmi3UpdateDiscreteStates
 * in fmi3_common.c). */
#include <math.h>

#include "fmi3_instance.h"

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{
    BEGIN("fmi3EnterContinuousTimeMode", EventMode);
    INTERFACE("fmi3EnterContinuousTimeMode", MODEL_EXCHANGE, "Model Exchange");
    model_begin_integration(&in->model);
    in->state = ContinuousTimeMode;
    return fmi3OK;
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance, fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode, fmi3Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    BEGIN("fmi3CompletedIntegratorStep", ContinuousTimeMode);
    REQUIRE("fmi3CompletedIntegratorStep", enterEventMode && terminateSimulation, "an output pointer is NULL");
    *enterEventMode = fmi3False;
    *terminateSimulation = fmi3False;
    return fmi3OK;
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{
    BEGIN("fmi3SetTime", ContinuousTimeMode);
    REQUIRE("fmi3SetTime", isfinite(time), "time = %g must be finite", time);
    in->time = time;
    return fmi3OK;
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    BEGIN("fmi3SetContinuousStates", ContinuousTimeMode);
    return (fmi3Status)instance_set_states(in, "fmi3SetContinuousStates", continuousStates, nContinuousStates);
}

/* The model's vectors, read and checked by the instance. */
#define READ_ARRAY(call, allowed, which, out, n)         \
    BEGIN(call, allowed);                               \
    INTERFACE(call, MODEL_EXCHANGE, "Model Exchange");  \
    return (fmi3Status)instance_read_array(in, call, which, out, n)

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
    READ_ARRAY("fmi3GetContinuousStateDerivatives", READABLE, ARRAY_DERIVATIVES, derivatives, nContinuousStates);
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[], size_t nEventIndicators)
{
    READ_ARRAY("fmi3GetEventIndicators", READABLE, ARRAY_EVENT_INDICATORS, eventIndicators, nEventIndicators);
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[], size_t nContinuousStates)
{
    READ_ARRAY("fmi3GetContinuousStates", READABLE, ARRAY_STATES, continuousStates, nContinuousStates);
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[], size_t nContinuousStates)
{
    /* FMI 3.0 §2.3.3-2.3.6: Initialization Mode, Initialized, Terminated; not Instantiated (FMI 2.0 allowed it). */
    READ_ARRAY("fmi3GetNominalsOfContinuousStates", READABLE, ARRAY_NOMINALS, nominals, nContinuousStates);
}

/* FMI 3.0 §2.3.2 and §2.3.5: in Instantiated and Event Mode, Model Exchange only. */
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators)
{
    BEGIN("fmi3GetNumberOfEventIndicators", Instantiated | EventMode);
    INTERFACE("fmi3GetNumberOfEventIndicators", MODEL_EXCHANGE, "Model Exchange");
    REQUIRE("fmi3GetNumberOfEventIndicators", nEventIndicators, "nEventIndicators is NULL");
    *nEventIndicators = MODEL_NZ;
    return fmi3OK;
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates)
{
    BEGIN("fmi3GetNumberOfContinuousStates", Instantiated | EventMode);
    INTERFACE("fmi3GetNumberOfContinuousStates", MODEL_EXCHANGE, "Model Exchange");
    REQUIRE("fmi3GetNumberOfContinuousStates", nContinuousStates, "nContinuousStates is NULL");
    *nContinuousStates = MODEL_NX;
    return fmi3OK;
}
