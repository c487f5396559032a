/* SPDX-License-Identifier: BSD-2-Clause */
/* The instance under any FMI version (instance.h): logging, errors, the
 * event update, checked access to the model's variables and derivatives. */
#include "instance.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "model_description.h"

const char *const instance_log_categories[N_LOG_CATEGORIES] = {
    "logEvents", "logStatusWarning", "logStatusError", "logStatistics", "logAll"
};

const char *instance_state_name(InstanceState s)
{
    switch (s) {
    case Instantiated: return "Instantiated";
    case InitializationMode: return "InitializationMode";
    case EventMode: return "EventMode";
    case ContinuousTimeMode: return "ContinuousTimeMode";
    case StepMode: return "StepMode";
    case Terminated: return "Terminated";
    default: return "Error";
    }
}

void instance_reset(Instance *in)
{
    model_reset(&in->model);
    in->state = Instantiated;
    in->time = 0;
    in->tolerance = MODEL_DEFAULT_TOLERANCE;
    in->solver_live = false;
    in->solver_implicit = false;
    in->last_successful_time = 0;
}

Status instance_set_logging(Instance *in, const char *call, bool on, size_t n, const char *const categories[])
{
    bool set[N_LOG_CATEGORIES];
    for (int k = 0; k < N_LOG_CATEGORIES; ++k) set[k] = n == 0 ? on : in->log_on[k];
    for (size_t i = 0; i < n; ++i) {
        int k = 0;
        while (k < N_LOG_CATEGORIES && !(categories[i] && strcmp(categories[i], instance_log_categories[k]) == 0)) ++k;
        if (k == N_LOG_CATEGORIES)
            return instance_fail(in, call, "unknown log category '%.100s' (known: logEvents, logStatusWarning, "
                                 "logStatusError, logStatistics, logAll)", categories[i] ? categories[i] : "(NULL)");
        set[k] = on;
    }
    memcpy(in->log_on, set, sizeof set);
    return STATUS_OK;
}

/* The importer's logger takes a format string: a '%' in our text reaches it doubled. */
static void emit(const Instance *in, Status status, int category, const char *text)
{
    char escaped[2048];
    size_t j = 0;
    for (size_t i = 0; text[i] && j + 2 < sizeof escaped; ++i) {
        if (text[i] == '%') escaped[j++] = '%';
        escaped[j++] = text[i];
    }
    escaped[j] = '\0';
    if (in->logger) in->logger(in, status, instance_log_categories[category], escaped);
}

static void emit_call(const Instance *in, Status status, int category, const char *call, const char *fmt, va_list ap)
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
    emit(in, STATUS_OK, LOG_EVENTS, text);
}

bool instance_logs_statistics(const Instance *in)
{
    return in->log_on[LOG_STATISTICS] || in->log_on[LOG_ALL];
}

void instance_log_statistics(Instance *in, const char *call, const char *fmt, ...)
{
    if (!instance_logs_statistics(in)) return;
    va_list ap;
    va_start(ap, fmt);
    emit_call(in, STATUS_OK, LOG_STATISTICS, call, fmt, ap);
    va_end(ap);
}

Status instance_fail(Instance *in, const char *call, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    emit_call(in, STATUS_ERROR, LOG_ERROR, call, fmt, ap);
    va_end(ap);
    in->state = Error;
    return STATUS_ERROR;
}

Status instance_set_tolerance(Instance *in, const char *call, bool defined, double tolerance)
{
    const double wanted = defined ? tolerance : MODEL_DEFAULT_TOLERANCE;
    in->tolerance = fmin(fmax(wanted, INSTANCE_TOLERANCE_MIN), INSTANCE_TOLERANCE_MAX);
    if (in->tolerance == wanted || in->interface != CO_SIMULATION) return STATUS_OK;
    char text[512];
    snprintf(text, sizeof text, "%s: tolerance = %g is outside %g to %g, the range in which a step's answer is "
             "right: the embedded solver uses %g", call, wanted, INSTANCE_TOLERANCE_MIN, INSTANCE_TOLERANCE_MAX,
             in->tolerance);
    emit(in, STATUS_WARNING, LOG_WARNING, text);
    return STATUS_WARNING;
}

Status instance_discard(Instance *in, const char *call, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    emit_call(in, STATUS_DISCARD, LOG_WARNING, call, fmt, ap);
    va_end(ap);
    return STATUS_DISCARD;
}

Model *instance_model(Instance *in)
{
    model_set_time(&in->model, in->time);
    if (in->state == InitializationMode) model_decide_initial_mode(&in->model);
    return &in->model;
}

void instance_start(Instance *in)
{
    char text[256];
    model_start(&in->model, in->time, text, sizeof text);
    if (in->interface == CO_SIMULATION) model_step_end(&in->model, 0);   /* no step has delivered anything yet */
    instance_log_event(in, "t = %.17g: %s", in->time, text);
}

Status instance_event_update(Instance *in, const char *call, bool located, bool *states_changed)
{
    ModelEvent e = { .describe = in->log_on[LOG_EVENTS] || in->log_on[LOG_ALL], .located = located };
    model_set_time(&in->model, in->time);
    /* Co-Simulation's update evaluates the model many times at nearly one state: anchored there
     * (model.h); Model Exchange's is not, its values libm's as the importer's own calls see them */
    const bool anchored = in->interface == CO_SIMULATION;
    double x[MODEL_NX];
    if (anchored) {
        model_get_states(&in->model, x);
        model_anchor(&in->model, x, true);
    }
    const bool updated = model_event_update(&in->model, in->time, &e);
    if (anchored) model_anchor(&in->model, x, false);
    if (!updated) return instance_fail(in, call, "%s", e.text);
    if (e.switched || e.states_changed) instance_log_event(in, "%s", e.text);
    *states_changed = e.switched || e.states_changed;
    in->fast_growth = e.fast_growth;
    return STATUS_OK;
}

/* ----------------------------------------------------------- variables */

static const char *const TYPE_NAME[] = { "Real", "Integer", "Boolean" };

static const VariableInfo *variable_of(Instance *in, const char *call, unsigned int vr, VariableType type)
{
    const VariableInfo *info = model_variable(vr);
    if (info && info->type == type) return info;
    instance_fail(in, call, "value reference %u is not a%s %s variable of %s", vr, type == TYPE_INTEGER ? "n" : "",
                  TYPE_NAME[type], MODEL_NAME);
    return NULL;
}

Status instance_get(Instance *in, const char *call, unsigned int vr, VariableType type, double *value)
{
    const VariableInfo *info = variable_of(in, call, vr, type);
    if (!info) return STATUS_ERROR;
    *value = model_get(instance_model(in), vr);
    if (!isfinite(*value)) return instance_fail(in, call, "%s is not finite at t = %g", info->name, in->time);
    return STATUS_OK;
}

/* When a variable of each kind may be set: parameters are fixed once
 * initialization ends; continuous states may also be set between events
 * (FMI 2.0.4 §3.2.3 condition 5), and a derived state only there; inputs
 * whenever the master gives them. */
static InstanceState settable_when(VariableKind kind, const char **when)
{
    switch (kind) {
    case KIND_STATE:
        *when = "before initialization ends or in Continuous-Time Mode";
        return BEFORE_INIT_ENDS | ContinuousTimeMode;
    case KIND_DERIVED_STATE:
        *when = "in Continuous-Time Mode (the model calculates it while initializing)";
        return ContinuousTimeMode;
    case KIND_INPUT:
        *when = "before initialization ends, in Event, Continuous-Time or Step Mode";
        return BEFORE_INIT_ENDS | EventMode | ContinuousTimeMode | StepMode;
    default:
        *when = "before initialization ends";
        return BEFORE_INIT_ENDS;
    }
}

Status instance_check_set(Instance *in, const char *call, unsigned int vr, VariableType type, double value)
{
    const VariableInfo *info = variable_of(in, call, vr, type);
    if (!info) return STATUS_ERROR;
    if (!model_settable(info)) return instance_fail(in, call, "%s is calculated by the model and cannot be set", info->name);
    const char *when;
    if (!(in->state & settable_when(info->kind, &when)))
        return instance_fail(in, call, "%s can be set only %s (state is %s)", info->name, when,
                             instance_state_name(in->state));
    const char *reason = model_check(vr, value);
    if (reason)
        return instance_fail(in, call, "%s = %g %s: allowed range is [%g, %g]", info->name, value, reason, info->min,
                             info->max);
    return STATUS_OK;
}

void instance_set(Instance *in, unsigned int vr, double value)
{
    const VariableInfo *info = model_variable(vr);
    const bool input = info && info->kind == KIND_INPUT;
    const bool changed = input && model_stored(&in->model, vr) != value;   /* an input is stored as set */
    model_set(&in->model, vr, value);
    if (!(input && (model_input_set(&in->model, vr, in->time) || changed))) return;
    in->inputs_jumped = true;
    /* the indicators' reference follows the input: what it moved across a surface, no integrator located */
    if (in->state == ContinuousTimeMode) model_begin_integration(&in->model);
}

static Status check_size(Instance *in, const char *call, const void *array, size_t n, size_t expected)
{
    if (n == 0 && expected == 0) return STATUS_OK; /* a model with no event indicators: NULL is an empty array */
    if (!array) return instance_fail(in, call, "array is NULL");
    if (n != expected) return instance_fail(in, call, "size %zu given, %s has %zu", n, MODEL_NAME, expected);
    return STATUS_OK;
}

Status instance_read_array(Instance *in, const char *call, ModelArray which, double out[], size_t n)
{
    static const char *const NAME[] = { "state", "derivative", "event indicator", "nominal" };
    const size_t expected = which == ARRAY_EVENT_INDICATORS ? MODEL_NZ : MODEL_NX;
    if (check_size(in, call, out, n, expected) != STATUS_OK) return STATUS_ERROR;
    Model *m = instance_model(in);
    switch (which) {
    case ARRAY_STATES: model_get_states(m, out); break;
    case ARRAY_DERIVATIVES: model_get_derivatives(m, out); break;
    case ARRAY_EVENT_INDICATORS: model_get_indicators(m, out); break;
    case ARRAY_NOMINALS: model_get_nominals(m, out); break;
    }
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(out[i])) return instance_fail(in, call, "%s %zu is not finite at t = %g", NAME[which], i, in->time);
    return STATUS_OK;
}

Status instance_set_states(Instance *in, const char *call, const double x[], size_t n)
{
    if (check_size(in, call, x, n, MODEL_NX) != STATUS_OK) return STATUS_ERROR;
    for (size_t i = 0; i < MODEL_NX; ++i) {
        const unsigned int vr = model_state_vr(i);
        const char *reason = model_check(vr, x[i]);
        const VariableInfo *info = model_variable(vr);
        if (reason)
            return instance_fail(in, call, "%s = %g %s at t = %g: allowed range is [%g, %g]", info->name, x[i], reason,
                                 in->time, info->min, info->max);
    }
    model_set_states(&in->model, x);
    return STATUS_OK;
}

Status instance_derivatives(Instance *in, const char *call, const unsigned int unknowns[], size_t n_unknowns,
                            const unsigned int knowns[], size_t n_knowns, const double seed[], double out[],
                            bool adjoint)
{
    const bool initializing = in->state == InitializationMode;
    for (size_t j = 0; j < n_knowns; ++j) {
        const VariableInfo *k = model_variable(knowns[j]);
        if (!k || !(MODEL_KIND_IS_STATE(k->kind) || k->kind == KIND_INPUT || (initializing && k->kind == KIND_PARAMETER)))
            return instance_fail(in, call, "known value reference %u is not a continuous state or input%s", knowns[j],
                                 initializing ? " nor a parameter" : " (parameters are knowns in Initialization Mode only)");
    }
    /* Unknowns (FMI 2.0.4 §2.1.9): the Real outputs and derivatives, in
     * Continuous-Time Mode the continuous ones (the discrete are frozen there);
     * while initializing, the Real InitialUnknowns (what the model calculates,
     * discrete outputs and calculated parameters included; states and
     * parameters are set, not unknown). A calculated parameter is fixed once
     * initialization ends: no unknown after it. */
    for (size_t i = 0; i < n_unknowns; ++i) {
        const VariableInfo *u = model_variable(unknowns[i]);
        if (!u || u->type != TYPE_REAL)
            return instance_fail(in, call, "unknown value reference %u is not a Real variable: directional derivatives "
                                 "are defined for Reals only", unknowns[i]);
        const bool unknown = u->kind == KIND_CALCULATED || (u->kind == KIND_CALCULATED_PARAMETER && initializing) ||
                             (u->kind == KIND_STATE && !initializing) || u->kind == KIND_DERIVED_STATE ||
                             (u->kind == KIND_DISCRETE && in->state != ContinuousTimeMode);
        if (!unknown)
            return instance_fail(in, call, "%s is not an unknown in %s", u->name, instance_state_name(in->state));
    }
    const size_t n_seed = adjoint ? n_unknowns : n_knowns, n_out = adjoint ? n_knowns : n_unknowns;
    for (size_t k = 0; k < n_seed; ++k)
        if (!isfinite(seed[k])) return instance_fail(in, call, "seed %zu is not finite", k);
    for (size_t k = 0; k < n_out; ++k) out[k] = 0;
    Model *m = instance_model(in);
    for (size_t i = 0; i < n_unknowns; ++i)
        for (size_t j = 0; j < n_knowns; ++j) {
            double partial = 0;
            const char *why = model_partial_derivative(m, unknowns[i], knowns[j], &partial);
            if (why) return instance_fail(in, call, "value references %u, %u: %s", unknowns[i], knowns[j], why);
            if (adjoint) out[j] += seed[i] * partial;
            else out[i] += partial * seed[j];
        }
    for (size_t k = 0; k < n_out; ++k)
        if (!isfinite(out[k])) return instance_fail(in, call, "derivative %zu is not finite", k);
    return STATUS_OK;
}
