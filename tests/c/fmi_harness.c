/* SPDX-License-Identifier: BSD-2-Clause */
/* Shared by the driver and the fuzz target: see fmi_harness.h. */
#include "fmi_harness.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_description.h"

const char *const harness_guid = MODEL_GUID;

/* ------------------------------------------------------------ callbacks */

HarnessCounts harness;

void harness_reset(void)
{
    memset(&harness, 0, sizeof harness);
}

static void *counting_calloc(size_t nobj, size_t size)
{
    ++harness.allocations;
    if (harness.allocations == harness.fail_allocation_at) return NULL;
    void *p = calloc(nobj, size);
    if (p) ++harness.live;
    return p;
}

static void counting_free(void *p)
{
    if (!p) return;
    ++harness.frees;
    --harness.live;
    free(p);
}

/* The FMU escapes every '%' of its text and passes no arguments, so a lone
 * '%' would make an importer's printf read arguments that are not there. */
static bool only_escaped_percents(const char *s)
{
    for (; *s; ++s)
        if (*s == '%' && *++s != '%') return false;
    return true;
}

static void checking_logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                            fmi2String category, fmi2String message, ...)
{
    (void)env;
    ++harness.messages;
    if (status == fmi2Error || status == fmi2Fatal) ++harness.error_messages;
    if (!name || !category || !message || !only_escaped_percents(message)) {
        ++harness.bad_messages;
        snprintf(harness.last_bad, sizeof harness.last_bad, "name = %s, category = %s, message = %.400s",
                 name ? name : "(NULL)", category ? category : "(NULL)", message ? message : "(NULL)");
        return;
    }
    /* Format it as an importer does (only %% conversions are left, checked above). */
    va_list ap;
    va_start(ap, message);
    vsnprintf(harness.last_message, sizeof harness.last_message, message, ap);
    va_end(ap);
    if (status == fmi2Error || status == fmi2Fatal)
        memcpy(harness.last_error, harness.last_message, sizeof harness.last_error);
    if (getenv("HARNESS_PRINT_LOG")) fprintf(stderr, "[%s] %s: %s\n", category, name, harness.last_message);
}

const fmi2CallbackFunctions harness_callbacks = {
    .logger = checking_logger,
    .allocateMemory = counting_calloc,
    .freeMemory = counting_free,
    .stepFinished = NULL,
    .componentEnvironment = NULL,
};

fmi2Component harness_instantiate(const FmiApi *f, const char *name)
{
    return f->Instantiate(name, fmi2ModelExchange, harness_guid, "file:///nonexistent/resources",
                          &harness_callbacks, fmi2False, fmi2False);
}

/* --------------------------------------------------------- simulation */

#define TRY(call)                                     \
    do {                                              \
        const fmi2Status status_ = (call);            \
        if (status_ != fmi2OK) return status_;        \
    } while (0)

fmi2Status harness_event_iteration(const FmiApi *f, fmi2Component c, bool *states_changed)
{
    fmi2EventInfo info = { .newDiscreteStatesNeeded = fmi2True };
    *states_changed = false;
    /* An FMU that keeps asking for iterations is caught by the bound. */
    for (int i = 0; i < 1000 && info.newDiscreteStatesNeeded; ++i) {
        TRY(f->NewDiscreteStates(c, &info));
        *states_changed |= info.valuesOfContinuousStatesChanged != fmi2False;
        if (info.terminateSimulation) return fmi2Discard;
    }
    if (info.newDiscreteStatesNeeded) return fmi2Discard;
    return f->EnterContinuousTimeMode(c);
}

static bool any_sign_change(const double a[HARNESS_NZ], const double b[HARNESS_NZ])
{
    for (int i = 0; i < MODEL_NZ; ++i)
        if ((a[i] > 0) != (b[i] > 0)) return true;
    return false;
}

fmi2Status euler_start(const FmiApi *f, EulerSim *s, double epsilon)
{
    const fmi2ValueReference knob = PROFILE_KNOB;
    const double value = PROFILE_KNOB_VALUE(epsilon);
    fmi2Component c = s->c;
    bool changed;
    s->t = 0;
    s->events = 0;
    TRY(f->SetupExperiment(c, fmi2False, 0, s->t, fmi2False, 0));
    TRY(f->SetReal(c, &knob, 1, &value));
    TRY(f->EnterInitializationMode(c));
    TRY(f->ExitInitializationMode(c));
    TRY(harness_event_iteration(f, c, &changed));
    TRY(f->GetContinuousStates(c, s->x, MODEL_NX));
    return f->GetEventIndicators(c, s->z, MODEL_NZ);
}

fmi2Status euler_step(const FmiApi *f, EulerSim *s, double h)
{
    fmi2Component c = s->c;
    double dx[MODEL_NX], z[HARNESS_NZ];
    bool changed;
    TRY(f->GetDerivatives(c, dx, MODEL_NX));
    s->t += h;
    for (int i = 0; i < MODEL_NX; ++i) s->x[i] += h * dx[i];
    TRY(f->SetTime(c, s->t));
    TRY(f->SetContinuousStates(c, s->x, MODEL_NX));
    fmi2Boolean enter_event = fmi2False, terminate = fmi2False;
    TRY(f->CompletedIntegratorStep(c, fmi2True, &enter_event, &terminate));
    if (terminate) return fmi2Discard;
    TRY(f->GetEventIndicators(c, z, MODEL_NZ));
    if (enter_event || any_sign_change(s->z, z)) {
        TRY(f->EnterEventMode(c));
        TRY(harness_event_iteration(f, c, &changed));
        ++s->events;
        if (changed) TRY(f->GetContinuousStates(c, s->x, MODEL_NX));
        TRY(f->GetEventIndicators(c, z, MODEL_NZ));
    }
    memcpy(s->z, z, sizeof z);
    return fmi2OK;
}

fmi2Status harness_simulate(const FmiApi *f, EulerSim *s, double epsilon, double h, int steps)
{
    TRY(euler_start(f, s, epsilon));
    for (int k = 0; k < steps; ++k) TRY(euler_step(f, s, h));
    return f->Terminate(s->c);
}
