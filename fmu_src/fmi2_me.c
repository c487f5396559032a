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
    if (instance_event_update(in, "fmi2NewDiscreteStates", &changed) != STATUS_OK) return fmi2Error;
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

static fmi2Status check_size(Instance *in, const char *call, const void *array, size_t n, size_t expected)
{
    REQUIRE(call, array, "array is NULL");
    REQUIRE(call, n == expected, "size %zu given, %s has %zu", n, MODEL_NAME, expected);
    return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx)
{
    static const char call[] = "fmi2SetContinuousStates";
    BEGIN(call, ContinuousTimeMode);
    INTERFACE(call, MODEL_EXCHANGE, "Model Exchange");
    if (check_size(in, call, x, nx, MODEL_NX) != fmi2OK || instance_check_states(in, call, x) != STATUS_OK)
        return fmi2Error;
    model_set_states(&in->model, x);
    return fmi2OK;
}

/* Reads an array of the model at the current point after checking it is finite. */
static fmi2Status get_finite(Instance *in, const char *call, fmi2Real out[], size_t n, size_t expected,
                             void (*read)(Model *, double *), const char *what)
{
    if (check_size(in, call, out, n, expected) != fmi2OK) return fmi2Error;
    read(instance_model(in), out);
    for (size_t i = 0; i < n; ++i)
        REQUIRE(call, isfinite(out[i]), "%s %zu is not finite at t = %g", what, i, in->time);
    return fmi2OK;
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx)
{
    BEGIN("fmi2GetDerivatives", READABLE);
    INTERFACE("fmi2GetDerivatives", MODEL_EXCHANGE, "Model Exchange");
    return get_finite(in, "fmi2GetDerivatives", derivatives, nx, MODEL_NX, model_get_derivatives, "derivative");
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real z[], size_t ni)
{
    BEGIN("fmi2GetEventIndicators", READABLE);
    INTERFACE("fmi2GetEventIndicators", MODEL_EXCHANGE, "Model Exchange");
    return get_finite(in, "fmi2GetEventIndicators", z, ni, MODEL_NZ, model_get_indicators, "event indicator");
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx)
{
    BEGIN("fmi2GetContinuousStates", READABLE);
    INTERFACE("fmi2GetContinuousStates", MODEL_EXCHANGE, "Model Exchange");
    if (check_size(in, "fmi2GetContinuousStates", x, nx, MODEL_NX) != fmi2OK) return fmi2Error;
    model_get_states(&in->model, x);
    return fmi2OK;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real nominal[], size_t nx)
{
    BEGIN("fmi2GetNominalsOfContinuousStates", Instantiated | READABLE);
    INTERFACE("fmi2GetNominalsOfContinuousStates", MODEL_EXCHANGE, "Model Exchange");
    if (check_size(in, "fmi2GetNominalsOfContinuousStates", nominal, nx, MODEL_NX) != fmi2OK) return fmi2Error;
    model_get_nominals(&in->model, nominal);
    return fmi2OK;
}
