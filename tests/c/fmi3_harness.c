/* SPDX-License-Identifier: BSD-2-Clause */
/* Shared by the FMI 3.0 driver and fuzz target: see fmi3_harness.h. */
#include "fmi3_harness.h"

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool fmi3_api_load(Fmi3Api *f, const char *path, char *err, size_t n)
{
    memset(f, 0, sizeof *f);
    f->handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!f->handle) {
        snprintf(err, n, "dlopen(%s): %s", path, dlerror());
        return false;
    }
#define FMI3_LOOKUP(name)                                               \
    {                                                                   \
        void *sym = dlsym(f->handle, "fmi3" #name);                     \
        if (!sym) {                                                     \
            snprintf(err, n, "%s does not export fmi3" #name, path);    \
            fmi3_api_unload(f);                                         \
            return false;                                               \
        }                                                               \
        memcpy(&f->name, &sym, sizeof sym);                             \
    }
    FMI3_FUNCTIONS(FMI3_LOOKUP)
#undef FMI3_LOOKUP
    return true;
}

void fmi3_api_unload(Fmi3Api *f)
{
#ifndef HARNESS_KEEP_LOADED
    if (f->handle) dlclose(f->handle);
#endif
    memset(f, 0, sizeof *f);
}

void harness3_logger(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message)
{
    (void)env;
    ++harness.messages;
    const bool error = status == fmi3Error || status == fmi3Fatal;
    if (error) ++harness.error_messages;
    if (!category || !message || (unsigned)status > fmi3Fatal) {
        ++harness.bad_messages;
        snprintf(harness.last_bad, sizeof harness.last_bad, "status = %d, category = %s, message = %.400s",
                 (int)status, category ? category : "(NULL)", message ? message : "(NULL)");
        return;
    }
    /* FMI 3.0's message is text, not a format: kept as it is. */
    snprintf(harness.last_message, sizeof harness.last_message, "%s", message);
    if (error) memcpy(harness.last_error, harness.last_message, sizeof harness.last_error);
    if (getenv("HARNESS_PRINT_LOG")) fprintf(stderr, "[%s] %s\n", category, message);
}

fmi3Instance harness3_instantiate_me(const Fmi3Api *f, const char *name, bool logging)
{
    return f->InstantiateModelExchange(name, harness_guid, "file:///nonexistent/resources", fmi3False,
                                       logging ? fmi3True : fmi3False, NULL, harness3_logger);
}

fmi3Instance harness3_instantiate_cs(const Fmi3Api *f, const char *name, bool logging, bool event_mode_used,
                                     bool early_return_allowed)
{
    return f->InstantiateCoSimulation(name, harness_guid, "file:///nonexistent/resources", fmi3False,
                                      logging ? fmi3True : fmi3False, event_mode_used ? fmi3True : fmi3False,
                                      early_return_allowed ? fmi3True : fmi3False, NULL, 0, NULL, harness3_logger,
                                      NULL);
}

fmi3Status harness3_update_discrete_states(const Fmi3Api *f, fmi3Instance c, bool *states_changed)
{
    fmi3Boolean again = fmi3True, terminate = fmi3False, nominals = fmi3False, values = fmi3False,
                next_defined = fmi3False;
    fmi3Float64 next = 0;
    *states_changed = false;
    /* An FMU that keeps asking for updates is caught by the bound. */
    for (int i = 0; i < 1000 && again; ++i) {
        const fmi3Status st = f->UpdateDiscreteStates(c, &again, &terminate, &nominals, &values, &next_defined, &next);
        if (st != fmi3OK) return st;
        *states_changed |= values != fmi3False;
        if (terminate) return fmi3Discard;
    }
    return again ? fmi3Discard : fmi3OK;
}

fmi3Status harness3_do_step(const Fmi3Api *f, fmi3Instance c, double *t, double h, int *events)
{
    fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
    double last = *t;
    fmi3Status st = f->DoStep(c, *t, h, fmi3True, &event, &terminate, &early, &last);
    if (st != fmi3OK) return st;
    *t = last;
    if (terminate) return fmi3Discard;
    if (event) {
        bool changed;
        st = f->EnterEventMode(c);
        if (st == fmi3OK) st = harness3_update_discrete_states(f, c, &changed);
        if (st == fmi3OK) st = f->EnterStepMode(c);
        if (events) ++*events;
    }
    return st;
}
