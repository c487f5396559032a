/* FMI 2.0 on top of the model interface of model.h: the calls common to both
 * interfaces and those of Model Exchange (Co-Simulation: fmi2_cs.c).
 *
 * Every call checks the instance state against the states the standard
 * allows it in; any fmi2Error is logged with the call's name and moves the
 * instance to the Error state, from which only getters, fmi2Reset and
 * fmi2FreeInstance lead on (FMI 2.0 §2.1.3). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmi2_instance.h"
#include "model_guid.h"
#include "rod_partials.h"

/* Events within one window of the contact's fastest time scale, eps^2, that
 * end the run as a Zeno error: a physical IWC has at most four there. */
#define MAX_EVENTS_IN_WINDOW 100

static const char *const LOG_CATEGORY[N_LOG_CATEGORIES] = {
    "logEvents", "logStatusWarning", "logStatusError", "logAll"
};

const char *state_name(InstanceState s)
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

void log_event(Instance *in, const char *fmt, ...)
{
    if (!in->log_on[LOG_EVENTS] && !in->log_on[LOG_ALL]) return;
    char text[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    emit(in, fmi2OK, LOG_EVENTS, text);
}

fmi2Status fail(Instance *in, const char *call, const char *fmt, ...)
{
    char text[1024];
    int n = snprintf(text, sizeof text, "%s: ", call);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text + n, sizeof text - (size_t)n, fmt, ap);
    va_end(ap);
    emit(in, fmi2Error, LOG_ERROR, text);
    in->state = Error;
    return fmi2Error;
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
    model_set_start_values(&in->model);
    in->state = Instantiated;
    in->time = 0;
    in->initial_event = false;
    in->window_start = -INFINITY;
    in->events_in_window = 0;
    in->tolerance = 0;
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
    Instance probe = { .cb = *functions, .name = (char *)(instanceName ? instanceName : "PainleveRod") };
    if (!instanceName || !*instanceName) {
        fail(&probe, "fmi2Instantiate", "instanceName must be a non-empty string");
        return NULL;
    }
    if (fmuType != fmi2ModelExchange && fmuType != fmi2CoSimulation) {
        fail(&probe, "fmi2Instantiate", "fmuType %d is neither fmi2ModelExchange nor fmi2CoSimulation", (int)fmuType);
        return NULL;
    }
    if (!fmuGUID || strcmp(fmuGUID, MODEL_GUID) != 0) {
        fail(&probe, "fmi2Instantiate", "GUID '%.64s' does not match this binary's %s: modelDescription.xml and binary are from different builds",
             fmuGUID ? fmuGUID : "(NULL)", MODEL_GUID);
        return NULL;
    }
    Instance *in = functions->allocateMemory(1, sizeof(Instance));
    char *name = functions->allocateMemory(strlen(instanceName) + 1, 1);
    if (!in || !name) {
        if (in) functions->freeMemory(in);
        if (name) functions->freeMemory(name);
        fail(&probe, "fmi2Instantiate", "out of memory");
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
    cs_free(in);
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
    in->tolerance = toleranceDefined ? tolerance : 0;
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
    model_initial_mode(&in->model);
    log_event(in, "t = %.17g: initial mode contact = %d, mode = %+d", in->time,
              in->model.mode.contact, in->model.mode.slip);
    in->initial_event = true;
    in->state = EventMode;
    if (in->type == fmi2ModelExchange) return fmi2OK;
    /* Co-Simulation does its own initial event iteration. */
    bool changed;
    if (handle_event(in, "fmi2ExitInitializationMode", &changed) != fmi2OK) return fmi2Error;
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

Model *current(Instance *in)
{
    if (in->state == InitializationMode) model_initial_mode(&in->model);
    model_update_derived(&in->model);
    return &in->model;
}


static fmi2Status check_arrays(Instance *in, const char *call, const void *vr, size_t nvr, const void *value)
{
    REQUIRE(call, nvr == 0 || (vr && value), "vr or value is NULL with nvr = %zu", nvr);
    return fmi2OK;
}

static fmi2Status get_reals(Instance *in, const char *call, const fmi2ValueReference vr[], size_t nvr,
                            fmi2Real value[])
{
    if (check_arrays(in, call, vr, nvr, value) != fmi2OK) return fmi2Error;
    for (size_t i = 0; i < nvr; ++i) {
        const VariableInfo *info = model_real_info(vr[i]);
        REQUIRE(call, info, "value reference %u is not a Real variable (Reals are 0..%d)", vr[i], N_REALS - 1);
        value[i] = model_get_real(current(in), vr[i]);
        REQUIRE(call, isfinite(value[i]), "%s is not finite at t = %g", info->name, in->time);
    }
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    BEGIN("fmi2GetReal", READABLE);
    return get_reals(in, "fmi2GetReal", vr, nvr, value);
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[])
{
    BEGIN("fmi2GetInteger", READABLE);
    if (check_arrays(in, "fmi2GetInteger", vr, nvr, value) != fmi2OK) return fmi2Error;
    for (size_t i = 0; i < nvr; ++i) {
        REQUIRE("fmi2GetInteger", vr[i] == VR_MODE, "value reference %u is not an Integer variable (mode is %d)",
                vr[i], VR_MODE);
        value[i] = current(in)->mode.slip;
    }
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    BEGIN("fmi2GetBoolean", READABLE);
    if (check_arrays(in, "fmi2GetBoolean", vr, nvr, value) != fmi2OK) return fmi2Error;
    for (size_t i = 0; i < nvr; ++i) {
        REQUIRE("fmi2GetBoolean", vr[i] == VR_CONTACT,
                "value reference %u is not a Boolean variable (contact is %d)", vr[i], VR_CONTACT);
        value[i] = current(in)->mode.contact;
    }
    return fmi2OK;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    BEGIN("fmi2GetString", READABLE);
    if (check_arrays(in, "fmi2GetString", vr, nvr, value) != fmi2OK) return fmi2Error;
    REQUIRE("fmi2GetString", nvr == 0, "value reference %u is not a String variable (there are none)", vr[0]);
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{
    BEGIN("fmi2SetReal", BEFORE_INIT_ENDS | SIMULATING | StepComplete);
    if (check_arrays(in, "fmi2SetReal", vr, nvr, value) != fmi2OK) return fmi2Error;
    /* Check all, then set all: a rejected call changes nothing. */
    for (size_t i = 0; i < nvr; ++i) {
        const VariableInfo *info = model_real_info(vr[i]);
        REQUIRE("fmi2SetReal", info, "value reference %u is not a Real variable (Reals are 0..%d)",
                vr[i], N_REALS - 1);
        REQUIRE("fmi2SetReal", info->kind != KIND_CALCULATED, "%s is calculated by the model and cannot be set",
                info->name);
        REQUIRE("fmi2SetReal", in->state & BEFORE_INIT_ENDS,
                "%s can be set only before fmi2ExitInitializationMode (state is %s)", info->name,
                state_name(in->state));
        const char *reason = model_check_real(vr[i], value[i]);
        REQUIRE("fmi2SetReal", !reason, "%s = %g %s: allowed range is [%g, %g]", info->name, value[i], reason,
                info->min, info->max);
    }
    for (size_t i = 0; i < nvr; ++i) model_set_real(&in->model, vr[i], value[i]);
    return fmi2OK;
}

static fmi2Status no_settable(Instance *in, const char *call, const void *vr, size_t nvr, const void *value,
                              const char *type)
{
    if (check_arrays(in, call, vr, nvr, value) != fmi2OK) return fmi2Error;
    REQUIRE(call, nvr == 0, "value reference %u is not a settable %s variable (PainleveRod has none)",
            ((const fmi2ValueReference *)vr)[0], type);
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[])
{
    BEGIN("fmi2SetInteger", BEFORE_INIT_ENDS | SIMULATING | StepComplete);
    return no_settable(in, "fmi2SetInteger", vr, nvr, value, "Integer");
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    BEGIN("fmi2SetBoolean", BEFORE_INIT_ENDS | SIMULATING | StepComplete);
    return no_settable(in, "fmi2SetBoolean", vr, nvr, value, "Boolean");
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    BEGIN("fmi2SetString", BEFORE_INIT_ENDS | SIMULATING | StepComplete);
    return no_settable(in, "fmi2SetString", vr, nvr, value, "String");
}

/* ------------------------------------------------- directional derivatives */

/* Column of `vr` in rod_partials' matrices: states 0..ROD_NX-1, then the
 * parameters; -1 for any other variable. */
static int known_column(unsigned int vr)
{
    switch (vr) {
    case VR_ALPHA: return ROD_NX + ROD_P_ALPHA;
    case VR_MU: return ROD_NX + ROD_P_MU;
    case VR_DELTA: return ROD_NX + ROD_P_DELTA;
    case VR_EPSILON: return ROD_NX + ROD_P_EPSILON;
    default: return vr >= VR_X && vr <= VR_PHI ? (int)(vr - VR_X) : -1;
    }
}

/* d unknown / d known (Reals only) of the current mode's smooth branch. A known
 * as unknown (a parameter, or a state as output) is its own identity. */
static double partial(const RodPartials *d, unsigned int unknown, int column)
{
    const int own = known_column(unknown);
    if (own >= 0) return own == column ? 1.0 : 0.0;
    const bool by_state = column < ROD_NX;
    const int j = by_state ? column : column - ROD_NX;
    if (unknown >= VR_DER_X && unknown <= VR_DER_PHI) {
        const int i = (int)(unknown - VR_DER_X);
        return by_state ? d->dx_x[i][j] : d->dx_p[i][j];
    }
    const int i = unknown == VR_F_N ? ROD_OUT_F_N : unknown == VR_F_T ? ROD_OUT_F_T : ROD_OUT_ENERGY;
    return by_state ? d->out_x[i][j] : d->out_p[i][j];
}

/* FMI 2.0 defines directional derivatives of Real variables only: an Integer or
 * Boolean reference (mode, contact) on either side is an error. In Initialization
 * Mode current() decides the mode from the initial state (model_initial_mode);
 * the derivatives are those of that mode's branch. */
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                        const fmi2ValueReference vKnown_ref[], size_t nKnown,
                                        const fmi2Real dvKnown[], fmi2Real dvUnknown[])
{
    static const char call[] = "fmi2GetDirectionalDerivative";
    BEGIN(call, READABLE);
    REQUIRE(call, (nUnknown == 0 || (vUnknown_ref && dvUnknown)) && (nKnown == 0 || (vKnown_ref && dvKnown)),
            "an array is NULL");
    /* Knowns (FMI 2.0 §2.2.8): the continuous states; in Initialization Mode also the
     * initial="exact" parameters. */
    const bool init = in->state == InitializationMode;
    for (size_t j = 0; j < nKnown; ++j) {
        const int column = known_column(vKnown_ref[j]);
        REQUIRE(call, column >= 0 && (column < ROD_NX || init),
                "known value reference %u is not a continuous state (%d..%d)%s%s", vKnown_ref[j], VR_X, VR_PHI,
                init ? " nor a parameter" : column >= ROD_NX ? " (parameters are knowns in Initialization Mode only)" : "",
                model_real_info(vKnown_ref[j]) ? "" : ": FMI 2.0 defines directional derivatives for Reals only");
    }
    for (size_t i = 0; i < nUnknown; ++i)
        REQUIRE(call, model_real_info(vUnknown_ref[i]),
                "unknown value reference %u is not a Real variable (Reals are 0..%d): FMI 2.0 defines directional "
                "derivatives for Reals only", vUnknown_ref[i], N_REALS - 1);
    const Model *m = current(in);
    RodPartials d;
    rod_partials(&m->params, m->mode, m->x, &d);
    for (size_t i = 0; i < nUnknown; ++i) {
        double sum = 0;
        for (size_t j = 0; j < nKnown; ++j) sum += partial(&d, vUnknown_ref[i], known_column(vKnown_ref[j])) * dvKnown[j];
        dvUnknown[i] = sum;
    }
    return fmi2OK;
}

/* -------------------------------------------------------- model exchange */

fmi2Status fmi2EnterEventMode(fmi2Component c)
{
    BEGIN("fmi2EnterEventMode", SIMULATING);
    in->state = EventMode;
    return fmi2OK;
}

/* Which indicators changed sign since integration last restarted. */
static void describe_fired(Instance *in, char *text, size_t size)
{
    const Model *m = &in->model;
    size_t n = 0;
    if (in->initial_event) {
        snprintf(text, size, "none (initial event iteration)");
        return;
    }
    for (int i = 0; i < ROD_NZ && n < size; ++i)
        if ((m->z[i] > 0) != (in->z_at_restart[i] > 0) || m->z[i] == 0)
            n += (size_t)snprintf(text + n, size - n, "%s'%s' = %.3g", n ? ", " : "",
                                  rod_indicator_name(m->mode, i), m->z[i]);
    if (n == 0) snprintf(text, size, "none (time or step event)");
}

fmi2Status handle_event(Instance *in, const char *call, bool *states_changed)
{
    Model *m = &in->model;
    model_update_derived(m);
    char fired[512];
    describe_fired(in, fired, sizeof fired);
    in->initial_event = false;
    const RodMode before = m->mode;
    bool moved;
    REQUIRE(call, rod_event_update(&m->params, &m->mode, m->x, &moved),
            "mode decision does not settle at t = %.17g (contact = %d, mode = %+d): rules ping-pong", in->time,
            m->mode.contact, m->mode.slip);
    m->stale = true;
    const bool switched = before.contact != m->mode.contact || before.slip != m->mode.slip;
    if (switched || moved) {
        log_event(in, "t = %.17g: indicator %s; contact %d -> %d, mode %+d -> %+d%s", in->time, fired,
                  before.contact, m->mode.contact, before.slip, m->mode.slip,
                  moved ? "; continuous states changed" : "");
    }
    *states_changed = switched || moved;
    /* Zeno guard: a run of events that does not advance time is an error, not a hang. */
    const double eps = m->params.epsilon;
    const double window = eps * eps + 1e-12 * (1 + fabs(in->time));
    if (in->time - in->window_start > window) {
        in->window_start = in->time;
        in->events_in_window = 0;
    }
    ++in->events_in_window;
    REQUIRE(call, in->events_in_window < MAX_EVENTS_IN_WINDOW,
            "%d events between t = %.17g and %.17g (less than eps^2 = %g): the modes chatter without progress "
            "in time (last indicator %s; contact = %d, mode = %+d, theta = %g)",
            MAX_EVENTS_IN_WINDOW, in->window_start, in->time, eps * eps, fired, m->mode.contact, m->mode.slip,
            m->x[ROD_THETA]);
    return fmi2OK;
}

void mark_restart(Instance *in)
{
    model_update_derived(&in->model);
    memcpy(in->z_at_restart, in->model.z, sizeof in->z_at_restart);
}

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info)
{
    BEGIN("fmi2NewDiscreteStates", EventMode);
    REQUIRE("fmi2NewDiscreteStates", info, "fmi2EventInfo is NULL");
    bool changed;
    if (handle_event(in, "fmi2NewDiscreteStates", &changed) != fmi2OK) return fmi2Error;
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
    mark_restart(in);
    in->state = ContinuousTimeMode;
    return fmi2OK;
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi2Boolean *enterEventMode, fmi2Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    BEGIN("fmi2CompletedIntegratorStep", ContinuousTimeMode);
    REQUIRE("fmi2CompletedIntegratorStep", enterEventMode && terminateSimulation, "an output pointer is NULL");
    *enterEventMode = fmi2False;
    *terminateSimulation = fmi2False;
    return fmi2OK;
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time)
{
    BEGIN("fmi2SetTime", SIMULATING);
    REQUIRE("fmi2SetTime", isfinite(time), "time = %g must be finite", time);
    in->time = time;
    return fmi2OK;
}

static fmi2Status check_nx(Instance *in, const char *call, const void *array, size_t n, size_t expected)
{
    REQUIRE(call, array, "array is NULL");
    REQUIRE(call, n == expected, "size %zu given, PainleveRod has %zu", n, expected);
    return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx)
{
    BEGIN("fmi2SetContinuousStates", ContinuousTimeMode);
    if (check_nx(in, "fmi2SetContinuousStates", x, nx, ROD_NX) != fmi2OK) return fmi2Error;
    for (size_t i = 0; i < nx; ++i) {
        const unsigned int vr = VR_X + (unsigned int)i;
        const char *reason = model_check_real(vr, x[i]);
        const VariableInfo *info = model_real_info(vr);
        REQUIRE("fmi2SetContinuousStates", !reason, "%s = %g %s at t = %g: allowed range is [%g, %g]",
                info->name, x[i], reason, in->time, info->min, info->max);
    }
    for (size_t i = 0; i < nx; ++i) in->model.x[i] = x[i];
    in->model.stale = true;
    return fmi2OK;
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx)
{
    BEGIN("fmi2GetDerivatives", READABLE);
    INTERFACE("fmi2GetDerivatives", fmi2ModelExchange, "Model Exchange");
    if (check_nx(in, "fmi2GetDerivatives", derivatives, nx, ROD_NX) != fmi2OK) return fmi2Error;
    static const fmi2ValueReference DER[ROD_NX] = { VR_DER_X, VR_DER_V, VR_DER_Y, VR_DER_W, VR_DER_THETA,
                                                     VR_DER_PHI };
    return get_reals(in, "fmi2GetDerivatives", DER, nx, derivatives);
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real z[], size_t ni)
{
    BEGIN("fmi2GetEventIndicators", READABLE);
    INTERFACE("fmi2GetEventIndicators", fmi2ModelExchange, "Model Exchange");
    if (check_nx(in, "fmi2GetEventIndicators", z, ni, ROD_NZ) != fmi2OK) return fmi2Error;
    const Model *m = current(in);
    for (size_t i = 0; i < ni; ++i) {
        z[i] = m->z[i];
        REQUIRE("fmi2GetEventIndicators", isfinite(z[i]), "indicator '%s' is not finite at t = %g",
                rod_indicator_name(in->model.mode, (int)i), in->time);
    }
    return fmi2OK;
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx)
{
    BEGIN("fmi2GetContinuousStates", READABLE);
    INTERFACE("fmi2GetContinuousStates", fmi2ModelExchange, "Model Exchange");
    if (check_nx(in, "fmi2GetContinuousStates", x, nx, ROD_NX) != fmi2OK) return fmi2Error;
    memcpy(x, in->model.x, sizeof in->model.x);
    return fmi2OK;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real nominal[], size_t nx)
{
    BEGIN("fmi2GetNominalsOfContinuousStates", Instantiated | READABLE);
    INTERFACE("fmi2GetNominalsOfContinuousStates", fmi2ModelExchange, "Model Exchange");
    if (check_nx(in, "fmi2GetNominalsOfContinuousStates", nominal, nx, ROD_NX) != fmi2OK) return fmi2Error;
    rod_nominals(&in->model.params, nominal);
    return fmi2OK;
}
