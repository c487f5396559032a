/* SPDX-License-Identifier: BSD-2-Clause */
/* The fmi2* functions of an FMU's shared library, looked up as an importer does
 * (dlopen, dlsym): the one C loader of the tests' driver and fuzz target
 * (tests/c) and the benchmark's native driver (bench/native). */
#ifndef FMI2_FUNCTIONS_H
#define FMI2_FUNCTIONS_H

#include <stdbool.h>
#include <stddef.h>

#include "fmi2FunctionTypes.h"

/* FMI 2.0's functions by interface: common to both, Model Exchange only, Co-Simulation only. */
#define FMI2_COMMON_FUNCTIONS(X)                                                                         \
    X(GetTypesPlatform) X(GetVersion) X(SetDebugLogging) X(Instantiate) X(FreeInstance)                  \
    X(SetupExperiment) X(EnterInitializationMode) X(ExitInitializationMode) X(Terminate) X(Reset)       \
    X(GetReal) X(GetInteger) X(GetBoolean) X(GetString) X(SetReal) X(SetInteger) X(SetBoolean)         \
    X(SetString) X(GetFMUstate) X(SetFMUstate) X(FreeFMUstate) X(SerializedFMUstateSize)               \
    X(SerializeFMUstate) X(DeSerializeFMUstate) X(GetDirectionalDerivative)
#define FMI2_MODEL_EXCHANGE_FUNCTIONS(X)                                                                 \
    X(EnterEventMode) X(NewDiscreteStates) X(EnterContinuousTimeMode) X(CompletedIntegratorStep)       \
    X(SetTime) X(SetContinuousStates) X(GetDerivatives) X(GetEventIndicators) X(GetContinuousStates)   \
    X(GetNominalsOfContinuousStates)
#define FMI2_CO_SIMULATION_FUNCTIONS(X)                                                                  \
    X(SetRealInputDerivatives) X(GetRealOutputDerivatives) X(DoStep) X(CancelStep) X(GetStatus)        \
    X(GetRealStatus) X(GetIntegerStatus) X(GetBooleanStatus) X(GetStringStatus)

typedef struct {
    void *handle;
#define FMI2_FUNCTION_FIELD(name) fmi2##name##TYPE *name;
    FMI2_COMMON_FUNCTIONS(FMI2_FUNCTION_FIELD)
    FMI2_MODEL_EXCHANGE_FUNCTIONS(FMI2_FUNCTION_FIELD)
    FMI2_CO_SIMULATION_FUNCTIONS(FMI2_FUNCTION_FIELD)
#undef FMI2_FUNCTION_FIELD
} Fmi2Functions;

/* dlopen of the library at `path` and dlsym of every fmi2* function. The common ones
 * and those of each interface asked for must be there (the others may be NULL);
 * false, with a message in err and nothing loaded, if one is missing. */
bool fmi2_functions_load(Fmi2Functions *f, const char *path, bool model_exchange, bool co_simulation, char *err,
                         size_t n);

/* dlclose (not when built with FMI2_FUNCTIONS_KEEP_LOADED: under AddressSanitizer the
 * library stays loaded, so that a leak found at exit is reported with symbolized frames
 * of the FMU); safe after a failed load. */
void fmi2_functions_unload(Fmi2Functions *f);

#endif
