/* SPDX-License-Identifier: BSD-2-Clause */
/* What the FMI 3.0 driver and fuzz target share: the FMU's fmi3* functions
 * looked up with dlopen/dlsym as an importer does, a logger that counts and
 * checks every message (into the counts of fmi_harness.h, shared with the FMI
 * 2.0 harness), instantiation, the event update and a Co-Simulation step that
 * does what a master with Event Mode must do when a step ends at an event. */
#ifndef FMI3_HARNESS_H
#define FMI3_HARNESS_H

#include <stdbool.h>
#include <stddef.h>

#include "fmi3FunctionTypes.h"
#include "fmi_harness.h" /* HarnessCounts harness, harness_reset, harness_guid */

/* Every function of FMI 3.0 (fmi3FunctionTypes.h), each a field of Fmi3Api. */
#define FMI3_FUNCTIONS(X)                                                                                      \
    X(GetVersion) X(SetDebugLogging) X(InstantiateModelExchange) X(InstantiateCoSimulation)                   \
    X(InstantiateScheduledExecution) X(FreeInstance) X(EnterInitializationMode) X(ExitInitializationMode)     \
    X(EnterEventMode) X(Terminate) X(Reset) X(GetFloat32) X(GetFloat64) X(GetInt8) X(GetUInt8) X(GetInt16)   \
    X(GetUInt16) X(GetInt32) X(GetUInt32) X(GetInt64) X(GetUInt64) X(GetBoolean) X(GetString) X(GetBinary)   \
    X(GetClock) X(SetFloat32) X(SetFloat64) X(SetInt8) X(SetUInt8) X(SetInt16) X(SetUInt16) X(SetInt32)      \
    X(SetUInt32) X(SetInt64) X(SetUInt64) X(SetBoolean) X(SetString) X(SetBinary) X(SetClock)                \
    X(GetNumberOfVariableDependencies) X(GetVariableDependencies) X(GetFMUState) X(SetFMUState)              \
    X(FreeFMUState) X(SerializedFMUStateSize) X(SerializeFMUState) X(DeserializeFMUState)                    \
    X(GetDirectionalDerivative) X(GetAdjointDerivative) X(EnterConfigurationMode) X(ExitConfigurationMode)   \
    X(GetIntervalDecimal) X(GetIntervalFraction) X(GetShiftDecimal) X(GetShiftFraction)                      \
    X(SetIntervalDecimal) X(SetIntervalFraction) X(SetShiftDecimal) X(SetShiftFraction)                      \
    X(EvaluateDiscreteStates) X(UpdateDiscreteStates) X(EnterContinuousTimeMode) X(CompletedIntegratorStep)  \
    X(SetTime) X(SetContinuousStates) X(GetContinuousStateDerivatives) X(GetEventIndicators)                 \
    X(GetContinuousStates) X(GetNominalsOfContinuousStates) X(GetNumberOfEventIndicators)                    \
    X(GetNumberOfContinuousStates) X(EnterStepMode) X(GetOutputDerivatives) X(DoStep)                        \
    X(ActivateModelPartition)

typedef struct {
    void *handle;
#define FMI3_FIELD(name) fmi3##name##TYPE *name;
    FMI3_FUNCTIONS(FMI3_FIELD)
#undef FMI3_FIELD
} Fmi3Api;

/* dlopen + dlsym of every fmi3* function; false with a message in err. */
bool fmi3_api_load(Fmi3Api *f, const char *path, char *err, size_t n);
void fmi3_api_unload(Fmi3Api *f);

/* The logger: counts messages and errors into `harness`, keeps the last ones,
 * and counts as bad a message with a NULL field or a status that is not an
 * fmi3Status. */
void harness3_logger(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message);

fmi3Instance harness3_instantiate_me(const Fmi3Api *f, const char *name, bool logging);
fmi3Instance harness3_instantiate_cs(const Fmi3Api *f, const char *name, bool logging, bool event_mode_used,
                                     bool early_return_allowed);

/* fmi3UpdateDiscreteStates until it needs no more (bounded): the event
 * update of Event Mode (FMI 3.0 §2.3.5); fmi3Discard if it never settles or
 * asks to terminate. */
fmi3Status harness3_update_discrete_states(const Fmi3Api *f, fmi3Instance c, bool *states_changed);

/* One fmi3DoStep from *t by h; *t becomes lastSuccessfulTime. Where the step
 * ends with eventHandlingNeeded, the master's part follows (FMI 3.0 §4.2.2):
 * fmi3EnterEventMode, the event update, fmi3EnterStepMode; *events counts them. */
fmi3Status harness3_do_step(const Fmi3Api *f, fmi3Instance c, double *t, double h, int *events);

#endif
