/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 2.0 calls common to Model Exchange and Co-Simulation, on the instance
 * of instance.h.
 *
 * Every call checks the instance state against the states the standard
 * allows it in; any fmi2Error is logged with the call's name and moves the
 * instance to the Error state, from which only getters, fmi2Reset and
 * fmi2FreeInstance lead on (FMI 2.0.4 §2.1.3). The machinery is instance.c's. */
#include <math.h>
#include <string.h>

#include "fmi2_instance.h"
#include "model_description.h"

/* The importer's logger, through the instance's adapter. */
static void log_to_importer(const Instance *in, Status status, const char *category, const char *message)
{
    const fmi2CallbackFunctions *cb = &CALLBACKS(in);
    if (cb->logger) cb->logger(cb->componentEnvironment, in->name, (fmi2Status)status, category, message);
}

/* ---------------------------------------------------------------- common */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    BEGIN("fmi2SetDebugLogging", ANY_STATE);
    REQUIRE("fmi2SetDebugLogging", nCategories == 0 || categories, "categories is NULL");
    return (fmi2Status)instance_set_logging(in, "fmi2SetDebugLogging", loggingOn, nCategories, categories);
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn)
{
    (void)fmuResourceLocation;
    (void)visible;
    if (!functions || !functions->allocateMemory || !functions->freeMemory) return NULL;
    Fmi2Instance probe = { .base = { .name = (char *)(instanceName ? instanceName : MODEL_NAME),
                                     .logger = log_to_importer },
                           .cb = *functions };
    Instance *in = &probe.base;
    if (!instanceName || !*instanceName) {
        instance_fail(in, "fmi2Instantiate", "instanceName must be a non-empty string");
        return NULL;
    }
    if (fmuType != fmi2ModelExchange && fmuType != fmi2CoSimulation) {
        instance_fail(in, "fmi2Instantiate", "fmuType %d is neither fmi2ModelExchange nor fmi2CoSimulation",
                      (int)fmuType);
        return NULL;
    }
    if (!fmuGUID || strcmp(fmuGUID, MODEL_GUID) != 0) {
        instance_fail(in, "fmi2Instantiate",
                      "GUID '%.64s' does not match this binary's %s: modelDescription.xml and binary are from "
                      "different builds", fmuGUID ? fmuGUID : "(NULL)", MODEL_GUID);
        return NULL;
    }
    Fmi2Instance *made = functions->allocateMemory(1, sizeof(Fmi2Instance));
    char *name = functions->allocateMemory(strlen(instanceName) + 1, 1);
    if (!made || !name) {
        if (made) functions->freeMemory(made);
        if (name) functions->freeMemory(name);
        instance_fail(in, "fmi2Instantiate", "out of memory");
        return NULL;
    }
    memcpy(name, instanceName, strlen(instanceName) + 1);
    *made = (Fmi2Instance){ .base = { .name = name, .logger = log_to_importer,
                                      .interface = fmuType == fmi2ModelExchange ? MODEL_EXCHANGE : CO_SIMULATION },
                            .cb = *functions };
    for (int k = 0; k < N_LOG_CATEGORIES; ++k) made->base.log_on[k] = loggingOn;
    instance_reset(&made->base);
    return made;
}

void fmi2FreeInstance(fmi2Component c)
{
    Instance *in = (Instance *)c;
    if (!in) return;
    instance_free_solver(in);
    const fmi2CallbackFreeMemory free_memory = CALLBACKS(in).freeMemory;
    free_memory(in->name);
    free_memory(in);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    BEGIN("fmi2SetupExperiment", Instantiated);
    REQUIRE("fmi2SetupExperiment", !toleranceDefined || (isfinite(tolerance) && tolerance > 0),
            "tolerance = %g must be finite and > 0", tolerance);
    REQUIRE("fmi2SetupExperiment", isfinite(startTime), "startTime = %g must be finite", startTime);
    REQUIRE("fmi2SetupExperiment", !stopTimeDefined || (isfinite(stopTime) && stopTime >= startTime),
            "stopTime = %g must be finite and >= startTime = %g", stopTime, startTime);
    in->time = startTime;
    const Status status = instance_set_tolerance(in, "fmi2SetupExperiment", toleranceDefined, tolerance);
    return (fmi2Status)status;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    BEGIN("fmi2EnterInitializationMode", Instantiated);
    in->state = InitializationMode;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    BEGIN("fmi2ExitInitializationMode", InitializationMode);
    instance_start(in);
    in->state = EventMode;
    if (in->interface == MODEL_EXCHANGE) return fmi2OK;
    /* Co-Simulation does its own initial event iteration. */
    bool changed;
    if (instance_event_update(in, "fmi2ExitInitializationMode", false, &changed) != STATUS_OK) return fmi2Error;
    in->last_successful_time = in->time;
    in->state = StepMode;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    BEGIN("fmi2Terminate", SIMULATING | StepMode);
    in->state = Terminated;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    BEGIN("fmi2Reset", ANY_STATE);
    instance_reset(in);
    return fmi2OK;
}

/* ------------------------------------------------------ getters, setters */

static fmi2Status check_arrays(Instance *in, const char *call, const void *vr, size_t nvr, const void *value)
{
    REQUIRE(call, nvr == 0 || (vr && value), "vr or value is NULL with nvr = %zu", nvr);
    return fmi2OK;
}

/* Gets nvr values of `type`, which the model gives as doubles. */
static fmi2Status get_values(Instance *in, const char *call, const fmi2ValueReference vr[], size_t nvr,
                             void *value, VariableType type)
{
    if (check_arrays(in, call, vr, nvr, value) != fmi2OK) return fmi2Error;
    for (size_t i = 0; i < nvr; ++i) {
        double v;
        if (instance_get(in, call, vr[i], type, &v) != STATUS_OK) return fmi2Error;
        switch (type) {
        case TYPE_REAL: ((fmi2Real *)value)[i] = v; break;
        case TYPE_INTEGER: ((fmi2Integer *)value)[i] = (fmi2Integer)v; break;
        case TYPE_BOOLEAN: ((fmi2Boolean *)value)[i] = v != 0 ? fmi2True : fmi2False; break;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    BEGIN("fmi2GetReal", READABLE);
    return get_values(in, "fmi2GetReal", vr, nvr, value, TYPE_REAL);
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[])
{
    BEGIN("fmi2GetInteger", READABLE);
    return get_values(in, "fmi2GetInteger", vr, nvr, value, TYPE_INTEGER);
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    BEGIN("fmi2GetBoolean", READABLE);
    return get_values(in, "fmi2GetBoolean", vr, nvr, value, TYPE_BOOLEAN);
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    BEGIN("fmi2GetString", READABLE);
    if (check_arrays(in, "fmi2GetString", vr, nvr, value) != fmi2OK) return fmi2Error;
    REQUIRE("fmi2GetString", nvr == 0, "value reference %u is not a String variable (%s has none)", vr[0],
            MODEL_NAME);
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{
    static const char call[] = "fmi2SetReal";
    BEGIN(call, BEFORE_INIT_ENDS | SIMULATING | StepMode);
    if (check_arrays(in, call, vr, nvr, value) != fmi2OK) return fmi2Error;
    /* Check all, then set all: a rejected call changes nothing. */
    for (size_t i = 0; i < nvr; ++i)
        if (instance_check_set(in, call, vr[i], TYPE_REAL, value[i]) != STATUS_OK) return fmi2Error;
    for (size_t i = 0; i < nvr; ++i) instance_set(in, vr[i], value[i]);
    return fmi2OK;
}

/* Integer, Boolean and String variables are all outputs: none can be set.
 * (Not allowed at all in Continuous-Time Mode, FMI 2.0.4 §3.2.3.) */
static fmi2Status set_none(Instance *in, const char *call, const fmi2ValueReference vr[], size_t nvr,
                           const void *value, const char *type)
{
    if (check_arrays(in, call, vr, nvr, value) != fmi2OK) return fmi2Error;
    REQUIRE(call, nvr == 0, "value reference %u is not a settable %s variable (%s has none)", vr[0], type,
            MODEL_NAME);
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[])
{
    BEGIN("fmi2SetInteger", BEFORE_INIT_ENDS | EventMode | StepMode);
    return set_none(in, "fmi2SetInteger", vr, nvr, value, "Integer");
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    BEGIN("fmi2SetBoolean", BEFORE_INIT_ENDS | EventMode | StepMode);
    return set_none(in, "fmi2SetBoolean", vr, nvr, value, "Boolean");
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    BEGIN("fmi2SetString", BEFORE_INIT_ENDS | EventMode | StepMode);
    return set_none(in, "fmi2SetString", vr, nvr, value, "String");
}

/* ------------------------------------------------- directional derivatives */

/* Knowns are the states, and in Initialization Mode the parameters too (the
 * knowns of InitialUnknowns, FMI 2.0.4 §2.2.8); unknowns are Reals (FMI 2.0
 * defines no other). Analytic, every mode; while initializing, those of the
 * mode decided from the initial values. */
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                        const fmi2ValueReference vKnown_ref[], size_t nKnown,
                                        const fmi2Real dvKnown[], fmi2Real dvUnknown[])
{
    static const char call[] = "fmi2GetDirectionalDerivative";
    BEGIN(call, READABLE);
    REQUIRE(call, (nUnknown == 0 || (vUnknown_ref && dvUnknown)) && (nKnown == 0 || (vKnown_ref && dvKnown)),
            "an array is NULL");
    return (fmi2Status)instance_derivatives(in, call, vUnknown_ref, nUnknown, vKnown_ref, nKnown, dvKnown, dvUnknown,
                                            false);
}
