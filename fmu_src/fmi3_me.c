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

static fmi3Status check_size(Instance *in, const char *call, const void *array, size_t n, size_t expected)
{
    REQUIRE(call, array, "array is NULL");
    REQUIRE(call, n == expected, "size %zu given, %s has %zu", n, MODEL_NAME, expected);
    return fmi3OK;
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    static const char call[] = "fmi3SetContinuousStates";
    BEGIN(call, ContinuousTimeMode);
    if (check_size(in, call, continuousStates, nContinuousStates, MODEL_NX) != fmi3OK ||
        instance_check_states(in, call, continuousStates) != STATUS_OK)
        return fmi3Error;
    model_set_states(&in->model, continuousStates);
    return fmi3OK;
}

/* Reads an array of the model at the current point after checking it is finite. */
static fmi3Status get_finite(Instance *in, const char *call, fmi3Float64 out[], size_t n, size_t expected,
                             void (*read)(Model *, double *), const char *what)
{
    if (check_size(in, call, out, n, expected) != fmi3OK) return fmi3Error;
    read(instance_model(in), out);
    for (size_t i = 0; i < n; ++i)
        REQUIRE(call, isfinite(out[i]), "%s %zu is not finite at t = %g", what, i, in->time);
    return fmi3OK;
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
    BEGIN("fmi3GetContinuousStateDerivatives", READABLE);
    INTERFACE("fmi3GetContinuousStateDerivatives", MODEL_EXCHANGE, "Model Exchange");
    return get_finite(in, "fmi3GetContinuousStateDerivatives", derivatives, nContinuousStates, MODEL_NX,
                      model_get_derivatives, "derivative");
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[], size_t nEventIndicators)
{
    BEGIN("fmi3GetEventIndicators", READABLE);
    INTERFACE("fmi3GetEventIndicators", MODEL_EXCHANGE, "Model Exchange");
    return get_finite(in, "fmi3GetEventIndicators", eventIndicators, nEventIndicators, MODEL_NZ, model_get_indicators,
                      "event indicator");
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[], size_t nContinuousStates)
{
    BEGIN("fmi3GetContinuousStates", READABLE);
    INTERFACE("fmi3GetContinuousStates", MODEL_EXCHANGE, "Model Exchange");
    if (check_size(in, "fmi3GetContinuousStates", continuousStates, nContinuousStates, MODEL_NX) != fmi3OK)
        return fmi3Error;
    model_get_states(&in->model, continuousStates);
    return fmi3OK;
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[], size_t nContinuousStates)
{
    /* FMI 3.0 §2.3.3-2.3.6: Initialization Mode, Initialized, Terminated; not Instantiated (FMI 2.0 allowed it). */
    BEGIN("fmi3GetNominalsOfContinuousStates", READABLE);
    INTERFACE("fmi3GetNominalsOfContinuousStates", MODEL_EXCHANGE, "Model Exchange");
    if (check_size(in, "fmi3GetNominalsOfContinuousStates", nominals, nContinuousStates, MODEL_NX) != fmi3OK)
        return fmi3Error;
    model_get_nominals(&in->model, nominals);
    return fmi3OK;
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
