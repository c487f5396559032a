/* FMI 2.0 calls common to Model Exchange and Co-Simulation, over the model
 * interface of model.h, and the instance machinery both interfaces share.
 *
 * Every call checks the instance state against the states the standard
 * allows it in; any fmi2Error is logged with the call's name and moves the
 * instance to the Error state, from which only getters, fmi2Reset and
 * fmi2FreeInstance lead on (FMI 2.0.4 §2.1.3). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmi2_instance.h"
#include "model_description.h"

static const char *const LOG_CATEGORY[N_LOG_CATEGORIES] = {
    "logEvents", "logStatusWarning", "logStatusError", "logAll"
};

const char *instance_state_name(InstanceState s)
{
    switch (s) {
    case Instantiated: return "Instantiated";
    case InitializationMode: return "InitializationMode";
    case EventMode: return "EventMode";
    case ContinuousTimeMode: return "ContinuousTimeMode";
    case StepComplete: return "StepComplete";
    case Terminated: return "Terminated";
    default: return "Error";
    }
}

/* The logger takes a format string: a '%' in our text must reach it doubled. */
static void emit(Instance *in, fmi2Status status, int category, const char *text)
{
    char escaped[2048];
    size_t j = 0;
    for (size_t i = 0; text[i] && j + 2 < sizeof escaped; ++i) {
        if (text[i] == '%') escaped[j++] = '%';
        escaped[j++] = text[i];
    }
    escaped[j] = '\0';
    if (in->cb.logger)
        in->cb.logger(in->cb.componentEnvironment, in->name, status, LOG_CATEGORY[category], escaped);
}

static void emit_call(Instance *in, fmi2Status status, int category, const char *call, const char *fmt,
                      va_list ap)
{
    char text[1024];
    const int n = snprintf(text, sizeof text, "%s: ", call);
    vsnprintf(text + n, sizeof text - (size_t)n, fmt, ap);
    emit(in, status, category, text);
}

void instance_log_event(Instance *in, const char *fmt, ...)
{
    if (!in->log_on[LOG_EVENTS] && !in->log_on[LOG_ALL]) return;
    char text[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    emit(in, fmi2OK, LOG_EVENTS, text);
}

fmi2Status instance_fail(Instance *in, const char *call, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    emit_call(in, fmi2Error, LOG_ERROR, call, fmt, ap);
    va_end(ap);
    in->state = Error;
    return fmi2Error;
}

fmi2Status instance_discard(Instance *in, const char *call, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    emit_call(in, fmi2Discard, LOG_WARNING, call, fmt, ap);
    va_end(ap);
    return fmi2Discard;
}

Model *instance_model(Instance *in)
{
    if (in->state == InitializationMode) model_decide_initial_mode(&in->model);
    return &in->model;
}

fmi2Status instance_event_update(Instance *in, const char *call, bool *states_changed)
{
    ModelEvent e;
    REQUIRE(call, model_event_update(&in->model, in->time, &e), "%s", e.text);
    if (e.switched || e.states_changed) instance_log_event(in, "%s", e.text);
    *states_changed = e.switched || e.states_changed;
    return fmi2OK;
}

/* ---------------------------------------------------------------- common */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    BEGIN("fmi2SetDebugLogging", ANY_BUT_FATAL);
    REQUIRE("fmi2SetDebugLogging", nCategories == 0 || categories, "categories is NULL");
    bool on[N_LOG_CATEGORIES];
    for (int k = 0; k < N_LOG_CATEGORIES; ++k) on[k] = nCategories == 0 ? loggingOn : in->log_on[k];
    for (size_t i = 0; i < nCategories; ++i) {
        int k = 0;
        while (k < N_LOG_CATEGORIES && !(categories[i] && strcmp(categories[i], LOG_CATEGORY[k]) == 0)) ++k;
        REQUIRE("fmi2SetDebugLogging", k < N_LOG_CATEGORIES,
                "unknown log category '%.100s' (known: logEvents, logStatusWarning, logStatusError, logAll)",
                categories[i] ? categories[i] : "(NULL)");
        on[k] = loggingOn;
    }
    memcpy(in->log_on, on, sizeof on);
    return fmi2OK;
}

static void reset_instance(Instance *in)
{
    model_reset(&in->model);
    in->state = Instantiated;
    in->time = 0;
    in->tolerance = MODEL_DEFAULT_TOLERANCE;
    in->solver_live = false;
    in->last_successful_time = 0;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn)
{
    (void)fmuResourceLocation;
    (void)visible;
    if (!functions || !functions->allocateMemory || !functions->freeMemory) return NULL;
    Instance probe = { .cb = *functions, .name = (char *)(instanceName ? instanceName : MODEL_NAME),
                       .log_on = { true, true, true, true } };
    if (!instanceName || !*instanceName) {
        instance_fail(&probe, "fmi2Instantiate", "instanceName must be a non-empty string");
        return NULL;
    }
    if (fmuType != fmi2ModelExchange && fmuType != fmi2CoSimulation) {
        instance_fail(&probe, "fmi2Instantiate", "fmuType %d is neither fmi2ModelExchange nor fmi2CoSimulation",
                      (int)fmuType);
        return NULL;
    }
    if (!fmuGUID || strcmp(fmuGUID, MODEL_GUID) != 0) {
        instance_fail(&probe, "fmi2Instantiate",
                      "GUID '%.64s' does not match this binary's %s: modelDescription.xml and binary are from "
                      "different builds", fmuGUID ? fmuGUID : "(NULL)", MODEL_GUID);
        return NULL;
    }
    Instance *in = functions->allocateMemory(1, sizeof(Instance));
    char *name = functions->allocateMemory(strlen(instanceName) + 1, 1);
    if (!in || !name) {
        if (in) functions->freeMemory(in);
        if (name) functions->freeMemory(name);
        instance_fail(&probe, "fmi2Instantiate", "out of memory");
        return NULL;
    }
    memcpy(name, instanceName, strlen(instanceName) + 1);
    *in = (Instance){ .cb = *functions, .name = name, .type = fmuType };
    for (int k = 0; k < N_LOG_CATEGORIES; ++k) in->log_on[k] = loggingOn;
    reset_instance(in);
    return in;
}

void fmi2FreeInstance(fmi2Component c)
{
    Instance *in = (Instance *)c;
    if (!in) return;
    if (in->free_solver) in->free_solver(in->solver);
    fmi2CallbackFreeMemory free_memory = in->cb.freeMemory;
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
    in->tolerance = toleranceDefined ? tolerance : MODEL_DEFAULT_TOLERANCE;
    return fmi2OK;
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
    model_start(&in->model, in->time);
    const double mode = model_get(&in->model, VR_MODE), contact = model_get(&in->model, VR_CONTACT);
    instance_log_event(in, "t = %.17g: initial mode contact = %g, mode = %+g", in->time, contact, mode);
    in->state = EventMode;
    if (in->type == fmi2ModelExchange) return fmi2OK;
    /* Co-Simulation does its own initial event iteration. */
    bool changed;
    if (instance_event_update(in, "fmi2ExitInitializationMode", &changed) != fmi2OK) return fmi2Error;
    in->last_successful_time = in->time;
    in->state = StepComplete;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    BEGIN("fmi2Terminate", SIMULATING | StepComplete);
    in->state = Terminated;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    BEGIN("fmi2Reset", ANY_BUT_FATAL);
    reset_instance(in);
    return fmi2OK;
}

/* ------------------------------------------------------ getters, setters */

static const char *const TYPE_NAME[] = { "Real", "Integer", "Boolean" };

/* The variable behind value reference vr if it has `type`, else NULL and the
 * instance in Error with a message. */
static const VariableInfo *variable_of(Instance *in, const char *call, fmi2ValueReference vr, VariableType type)
{
    const VariableInfo *info = model_variable(vr);
    if (info && info->type == type) return info;
    instance_fail(in, call, "value reference %u is not a%s %s variable of %s", vr, type == TYPE_INTEGER ? "n" : "",
                  TYPE_NAME[type], MODEL_NAME);
    return NULL;
}

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
        const VariableInfo *info = variable_of(in, call, vr[i], type);
        if (!info) return fmi2Error;
        const double v = model_get(instance_model(in), vr[i]);
        REQUIRE(call, isfinite(v), "%s is not finite at t = %g", info->name, in->time);
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
    BEGIN(call, BEFORE_INIT_ENDS | SIMULATING | StepComplete);
    if (check_arrays(in, call, vr, nvr, value) != fmi2OK) return fmi2Error;
    /* Check all, then set all: a rejected call changes nothing. */
    for (size_t i = 0; i < nvr; ++i) {
        const VariableInfo *info = variable_of(in, call, vr[i], TYPE_REAL);
        if (!info) return fmi2Error;
        REQUIRE(call, model_settable(info), "%s is calculated by the model and cannot be set", info->name);
        REQUIRE(call, in->state & BEFORE_INIT_ENDS, "%s can be set only before fmi2ExitInitializationMode (state is %s)",
                info->name, instance_state_name(in->state));
        const char *reason = model_check(vr[i], value[i]);
        REQUIRE(call, !reason, "%s = %g %s: allowed range is [%g, %g]", info->name, value[i], reason, info->min,
                info->max);
    }
    for (size_t i = 0; i < nvr; ++i) model_set(&in->model, vr[i], value[i]);
    return fmi2OK;
}

/* Integer, Boolean and String variables are all outputs: none can be set. */
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
    BEGIN("fmi2SetInteger", BEFORE_INIT_ENDS | SIMULATING | StepComplete);
    return set_none(in, "fmi2SetInteger", vr, nvr, value, "Integer");
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    BEGIN("fmi2SetBoolean", BEFORE_INIT_ENDS | SIMULATING | StepComplete);
    return set_none(in, "fmi2SetBoolean", vr, nvr, value, "Boolean");
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    BEGIN("fmi2SetString", BEFORE_INIT_ENDS | SIMULATING | StepComplete);
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
    const bool initializing = in->state == InitializationMode;
    for (size_t j = 0; j < nKnown; ++j) {
        const VariableInfo *k = model_variable(vKnown_ref[j]);
        REQUIRE(call, k && (k->kind == KIND_STATE || (initializing && k->kind == KIND_PARAMETER)),
                "known value reference %u is not a continuous state%s", vKnown_ref[j],
                initializing ? " nor a parameter" : " (parameters are knowns in Initialization Mode only)");
        REQUIRE(call, isfinite(dvKnown[j]), "dvKnown[%zu] is not finite", j);
    }
    for (size_t i = 0; i < nUnknown; ++i) {
        const VariableInfo *u = model_variable(vUnknown_ref[i]);
        REQUIRE(call, u && u->type == TYPE_REAL,
                "unknown value reference %u is not a Real variable: FMI 2.0 defines directional derivatives for "
                "Reals only", vUnknown_ref[i]);
    }
    Model *m = instance_model(in);
    for (size_t i = 0; i < nUnknown; ++i) {
        double sum = 0;
        for (size_t j = 0; j < nKnown; ++j) {
            double partial = 0;
            const char *why = model_partial_derivative(m, vUnknown_ref[i], vKnown_ref[j], &partial);
            REQUIRE(call, !why, "unknown value reference %u: %s", vUnknown_ref[i], why);
            sum += partial * dvKnown[j];
        }
        REQUIRE(call, isfinite(sum), "the derivative of value reference %u is not finite", vUnknown_ref[i]);
        dvUnknown[i] = sum;
    }
    return fmi2OK;
}
