/* SPDX-License-Identifier: BSD-2-Clause */
/* platform_fmi.h over FMI 2.0 and FMI 3.0: the library loaded with the
 * platform's own loader, each call mapped onto its version's function. */
#include "platform_fmi.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
#else
#include <dlfcn.h>
#endif

#include "fmi2FunctionTypes.h"
#include "fmi3FunctionTypes.h"

#define FMI2_FUNCTIONS(X)                                                                                   \
    X(fmi2, Instantiate) X(fmi2, FreeInstance) X(fmi2, SetupExperiment) X(fmi2, EnterInitializationMode)  \
    X(fmi2, ExitInitializationMode) X(fmi2, SetReal) X(fmi2, GetReal) X(fmi2, DoStep)                     \
    X(fmi2, NewDiscreteStates) X(fmi2, EnterContinuousTimeMode) X(fmi2, EnterEventMode) X(fmi2, SetTime)   \
    X(fmi2, SetContinuousStates) X(fmi2, GetContinuousStates) X(fmi2, GetDerivatives)                    \
    X(fmi2, GetEventIndicators) X(fmi2, CompletedIntegratorStep)
#define FMI3_FUNCTIONS(X)                                                                                   \
    X(fmi3, InstantiateModelExchange) X(fmi3, InstantiateCoSimulation) X(fmi3, FreeInstance)             \
    X(fmi3, EnterInitializationMode) X(fmi3, ExitInitializationMode) X(fmi3, SetFloat64)                  \
    X(fmi3, GetFloat64) X(fmi3, DoStep) X(fmi3, UpdateDiscreteStates) X(fmi3, EnterContinuousTimeMode)    \
    X(fmi3, EnterEventMode) X(fmi3, SetTime) X(fmi3, SetContinuousStates) X(fmi3, GetContinuousStates)    \
    X(fmi3, GetContinuousStateDerivatives) X(fmi3, GetEventIndicators) X(fmi3, CompletedIntegratorStep)

struct Fmu {
    int version;
    bool cosimulation;
    void *library;
    void *instance;
#define FIELD(v, name) v##name##TYPE *v##name;
    FMI2_FUNCTIONS(FIELD)
    FMI3_FUNCTIONS(FIELD)
#undef FIELD
};

typedef void (*AnyFunction)(void);

static AnyFunction symbol(void *library, const char *name)
{
#ifdef _WIN32
    return (AnyFunction)(void (*)(void))GetProcAddress((HMODULE)library, name);
#else
    void *address = dlsym(library, name);
    AnyFunction f;
    memcpy(&f, &address, sizeof f); /* POSIX: a function's address fits an object pointer */
    return f;
#endif
}

Fmu *fmu_load(const char *path, int version)
{
    Fmu *fmu = calloc(1, sizeof *fmu);
    if (!fmu) return NULL;
    fmu->version = version;
#ifdef _WIN32
    fmu->library = (void *)LoadLibraryA(path);
#else
    fmu->library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
#endif
    if (!fmu->library) {
        fprintf(stderr, "cannot load %s\n", path);
        free(fmu);
        return NULL;
    }
    bool complete = true;
#define LOAD(v, name)                                                                                     \
    if (version == (#v)[3] - '0') {                                                                        \
        fmu->v##name = (v##name##TYPE *)symbol(fmu->library, #v #name);                                    \
        if (!fmu->v##name) {                                                                               \
            fprintf(stderr, "%s has no %s\n", path, #v #name);                                             \
            complete = false;                                                                              \
        }                                                                                                  \
    }
    FMI2_FUNCTIONS(LOAD)
    FMI3_FUNCTIONS(LOAD)
#undef LOAD
    if (!complete) {
        fmu_unload(fmu);
        return NULL;
    }
    return fmu;
}

void fmu_unload(Fmu *fmu)
{
    if (!fmu) return;
#ifdef _WIN32
    FreeLibrary((HMODULE)fmu->library);
#else
    dlclose(fmu->library);
#endif
    free(fmu);
}

static void log_fmi2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status, fmi2String category,
                 fmi2String message, ...)
{
    (void)env;
    va_list args;
    va_start(args, message);
    fprintf(stderr, "[%s %d %s] ", name ? name : "", (int)status, category ? category : "");
    vfprintf(stderr, message, args);
    fputc('\n', stderr);
    va_end(args);
}

static void log_fmi3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message)
{
    (void)env;
    fprintf(stderr, "[%d %s] %s\n", (int)status, category ? category : "", message ? message : "");
}

static const fmi2CallbackFunctions callbacks2 = { log_fmi2, calloc, free, NULL, NULL };

int fmu_instantiate(Fmu *fmu, const char *token, bool cosimulation)
{
    fmu->cosimulation = cosimulation;
    if (fmu->version == 2)
        fmu->instance = fmu->fmi2Instantiate("platform", cosimulation ? fmi2CoSimulation : fmi2ModelExchange,
                                             token, "", &callbacks2, fmi2False, fmi2False);
    else if (cosimulation)
        fmu->instance = fmu->fmi3InstantiateCoSimulation("platform", token, "", fmi3False, fmi3False, fmi3False,
                                                         fmi3False, NULL, 0, NULL, log_fmi3, NULL);
    else
        fmu->instance = fmu->fmi3InstantiateModelExchange("platform", token, "", fmi3False, fmi3False, NULL, log_fmi3);
    return fmu->instance ? 0 : 3;
}

void fmu_free_instance(Fmu *fmu)
{
    if (!fmu->instance) return;
    if (fmu->version == 2)
        fmu->fmi2FreeInstance(fmu->instance);
    else
        fmu->fmi3FreeInstance(fmu->instance);
    fmu->instance = NULL;
}

int fmu_initialize(Fmu *fmu, double start, double stop)
{
    int s;
    if (fmu->version == 2) {
        s = fmu->fmi2SetupExperiment(fmu->instance, fmi2False, 0.0, start, fmi2True, stop);
        if (s > 1) return s;
        s = fmu->fmi2EnterInitializationMode(fmu->instance);
        return s > 1 ? s : (int)fmu->fmi2ExitInitializationMode(fmu->instance);
    }
    s = fmu->fmi3EnterInitializationMode(fmu->instance, fmi3False, 0.0, start, fmi3True, stop);
    return s > 1 ? s : (int)fmu->fmi3ExitInitializationMode(fmu->instance);
}

int fmu_set_reals(Fmu *fmu, const unsigned *vr, size_t n, const double *values)
{
    return fmu->version == 2 ? fmu->fmi2SetReal(fmu->instance, vr, n, values)
                             : fmu->fmi3SetFloat64(fmu->instance, vr, n, values, n);
}

int fmu_get_reals(Fmu *fmu, const unsigned *vr, size_t n, double *values)
{
    return fmu->version == 2 ? fmu->fmi2GetReal(fmu->instance, vr, n, values)
                             : fmu->fmi3GetFloat64(fmu->instance, vr, n, values, n);
}

int fmu_do_step(Fmu *fmu, double t, double h)
{
    if (fmu->version == 2) return fmu->fmi2DoStep(fmu->instance, t, h, fmi2True);
    fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
    fmi3Float64 last = t;
    return fmu->fmi3DoStep(fmu->instance, t, h, fmi3True, &event, &terminate, &early, &last);
}

int fmu_update_discrete(Fmu *fmu, bool *again, bool *terminate)
{
    if (fmu->version == 2) {
        fmi2EventInfo info;
        memset(&info, 0, sizeof info);
        const int s = fmu->fmi2NewDiscreteStates(fmu->instance, &info);
        *again = info.newDiscreteStatesNeeded;
        *terminate = info.terminateSimulation;
        return s;
    }
    fmi3Boolean update = fmi3False, stop = fmi3False, nominals = fmi3False, values = fmi3False, defined = fmi3False;
    fmi3Float64 next = 0.0;
    const int s = fmu->fmi3UpdateDiscreteStates(fmu->instance, &update, &stop, &nominals, &values, &defined, &next);
    *again = update;
    *terminate = stop;
    return s;
}

int fmu_enter_continuous(Fmu *fmu)
{
    return fmu->version == 2 ? fmu->fmi2EnterContinuousTimeMode(fmu->instance)
                             : fmu->fmi3EnterContinuousTimeMode(fmu->instance);
}

int fmu_enter_event(Fmu *fmu)
{
    return fmu->version == 2 ? fmu->fmi2EnterEventMode(fmu->instance) : fmu->fmi3EnterEventMode(fmu->instance);
}

int fmu_set_time(Fmu *fmu, double t)
{
    return fmu->version == 2 ? fmu->fmi2SetTime(fmu->instance, t) : fmu->fmi3SetTime(fmu->instance, t);
}

int fmu_set_states(Fmu *fmu, const double *x, size_t n)
{
    return fmu->version == 2 ? fmu->fmi2SetContinuousStates(fmu->instance, x, n)
                             : fmu->fmi3SetContinuousStates(fmu->instance, x, n);
}

int fmu_get_states(Fmu *fmu, double *x, size_t n)
{
    return fmu->version == 2 ? fmu->fmi2GetContinuousStates(fmu->instance, x, n)
                             : fmu->fmi3GetContinuousStates(fmu->instance, x, n);
}

int fmu_get_derivatives(Fmu *fmu, double *dx, size_t n)
{
    return fmu->version == 2 ? fmu->fmi2GetDerivatives(fmu->instance, dx, n)
                             : fmu->fmi3GetContinuousStateDerivatives(fmu->instance, dx, n);
}

int fmu_get_indicators(Fmu *fmu, double *z, size_t n)
{
    return fmu->version == 2 ? fmu->fmi2GetEventIndicators(fmu->instance, z, n)
                             : fmu->fmi3GetEventIndicators(fmu->instance, z, n);
}

int fmu_completed_step(Fmu *fmu, bool *enter_event, bool *terminate)
{
    if (fmu->version == 2) {
        fmi2Boolean event = fmi2False, stop = fmi2False;
        const int s = fmu->fmi2CompletedIntegratorStep(fmu->instance, fmi2True, &event, &stop);
        *enter_event = event;
        *terminate = stop;
        return s;
    }
    fmi3Boolean event = fmi3False, stop = fmi3False;
    const int s = fmu->fmi3CompletedIntegratorStep(fmu->instance, fmi3True, &event, &stop);
    *enter_event = event;
    *terminate = stop;
    return s;
}
