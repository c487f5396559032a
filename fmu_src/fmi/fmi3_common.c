/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 calls common to Model Exchange and Co-Simulation, on the instance
 * of instance.h: instantiation, the state machine's common transitions, the
 * event update, derivatives, and the features this FMU does not have
 * (Scheduled Execution, Configuration Mode, clocks, per-element
 * dependencies), which answer with a message. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3_instance.h"
#include "model_description.h"

/* The importer's logger, through the instance's adapter. The instance doubles
 * each '%' for FMI 2.0's logger, which takes a printf format; FMI 3.0's takes
 * the text itself (§2.3.1), so each "%%" is one '%' again. */
static void log_to_importer(const Instance *in, Status status, const char *category, const char *message)
{
    const Fmi3Instance *self = (const Fmi3Instance *)in;
    if (!self->log_message) return;
    char text[2048];
    size_t j = 0;
    for (size_t i = 0; message[i] && j + 1 < sizeof text; ++i) {
        text[j++] = message[i];
        if (message[i] == '%' && message[i + 1] == '%') ++i;
    }
    text[j] = '\0';
    self->log_message(self->environment, (fmi3Status)status, category, text);
}

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    BEGIN("fmi3SetDebugLogging", ANY_STATE);
    REQUIRE("fmi3SetDebugLogging", nCategories == 0 || categories, "categories is NULL");
    return (fmi3Status)instance_set_logging(in, "fmi3SetDebugLogging", loggingOn, nCategories, categories);
}

/* A new instance of either interface; NULL, with a message, on bad arguments. */
static Fmi3Instance *instantiate(const char *call, fmi3String name, fmi3String token, Interface interface,
                                 fmi3Boolean loggingOn, fmi3InstanceEnvironment environment,
                                 fmi3LogMessageCallback logMessage)
{
    Fmi3Instance probe = { .base = { .name = (char *)(name ? name : MODEL_NAME), .logger = log_to_importer },
                           .environment = environment, .log_message = logMessage };
    Instance *in = &probe.base;
    if (!name || !*name) {
        instance_fail(in, call, "instanceName must be a non-empty string");
        return NULL;
    }
    if (!token || strcmp(token, MODEL_GUID) != 0) {
        instance_fail(in, call, "instantiationToken '%.64s' does not match this binary's %s: modelDescription.xml and "
                      "binary are from different builds", token ? token : "(NULL)", MODEL_GUID);
        return NULL;
    }
    Fmi3Instance *made = calloc(1, sizeof(Fmi3Instance));
    char *copy = malloc(strlen(name) + 1);
    if (!made || !copy) {
        free(made);
        free(copy);
        instance_fail(in, call, "out of memory");
        return NULL;
    }
    memcpy(copy, name, strlen(name) + 1);
    *made = (Fmi3Instance){ .base = { .name = copy, .logger = log_to_importer, .interface = interface },
                            .environment = environment, .log_message = logMessage };
    for (int k = 0; k < N_LOG_CATEGORIES; ++k) made->base.log_on[k] = loggingOn;
    instance_reset(&made->base);
    return made;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)resourcePath, (void)visible;
    return instantiate("fmi3InstantiateModelExchange", instanceName, instantiationToken, MODEL_EXCHANGE, loggingOn,
                       instanceEnvironment, logMessage);
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                         fmi3Boolean eventModeUsed, fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference requiredIntermediateVariables[],
                                         size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment instanceEnvironment,
                                         fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback intermediateUpdate)
{
    (void)resourcePath, (void)visible, (void)requiredIntermediateVariables, (void)intermediateUpdate;
    static const char call[] = "fmi3InstantiateCoSimulation";
    if (nRequiredIntermediateVariables > 0) {   /* providesIntermediateUpdate is false */
        Fmi3Instance probe = { .base = { .name = (char *)(instanceName ? instanceName : MODEL_NAME),
                                         .logger = log_to_importer },
                               .environment = instanceEnvironment, .log_message = logMessage };
        instance_fail(&probe.base, call, "%zu intermediate variables required; %s provides none",
                      nRequiredIntermediateVariables, MODEL_NAME);
        return NULL;
    }
    Fmi3Instance *made = instantiate(call, instanceName, instantiationToken, CO_SIMULATION, loggingOn,
                                     instanceEnvironment, logMessage);
    if (made) {
        made->event_mode_used = eventModeUsed;
        made->early_return_allowed = earlyReturnAllowed;
    }
    return made;
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName, fmi3String instantiationToken,
                                               fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                               fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
                                               fmi3LockPreemptionCallback lockPreemption,
                                               fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instantiationToken, (void)resourcePath, (void)visible, (void)loggingOn, (void)clockUpdate;
    (void)lockPreemption, (void)unlockPreemption;
    Fmi3Instance probe = { .base = { .name = (char *)(instanceName ? instanceName : MODEL_NAME),
                                     .logger = log_to_importer },
                           .environment = instanceEnvironment, .log_message = logMessage };
    instance_fail(&probe.base, "fmi3InstantiateScheduledExecution",
                  "%s is a Model Exchange and Co-Simulation FMU, not Scheduled Execution", MODEL_NAME);
    return NULL;
}

void fmi3FreeInstance(fmi3Instance instance)
{
    Instance *in = (Instance *)instance;
    if (!in) return;
    instance_free_solver(in);
    free(in->name);
    free(in);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    static const char call[] = "fmi3EnterInitializationMode";
    BEGIN(call, Instantiated);
    REQUIRE(call, !toleranceDefined || (isfinite(tolerance) && tolerance > 0), "tolerance = %g must be finite and > 0",
            tolerance);
    REQUIRE(call, isfinite(startTime), "startTime = %g must be finite", startTime);
    REQUIRE(call, !stopTimeDefined || (isfinite(stopTime) && stopTime >= startTime),
            "stopTime = %g must be finite and >= startTime = %g", stopTime, startTime);
    in->time = startTime;
    const Status status = instance_set_tolerance(in, call, toleranceDefined, tolerance);
    in->state = InitializationMode;
    return (fmi3Status)status;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    static const char call[] = "fmi3ExitInitializationMode";
    BEGIN(call, InitializationMode);
    instance_start(in);
    in->state = EventMode;
    if (in->interface == MODEL_EXCHANGE || FMI3(in)->event_mode_used) return fmi3OK;
    /* Co-Simulation without Event Mode does its own initial event update. */
    bool changed;
    if (instance_event_update(in, call, false, &changed) != STATUS_OK) return fmi3Error;
    in->last_successful_time = in->time;
    in->state = StepMode;
    return fmi3OK;
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
    BEGIN("fmi3EnterEventMode", ContinuousTimeMode | StepMode);
    REQUIRE("fmi3EnterEventMode", in->interface == MODEL_EXCHANGE || FMI3(in)->event_mode_used,
            "this Co-Simulation instance was instantiated with eventModeUsed = false");
    in->state = EventMode;
    return fmi3OK;
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    BEGIN("fmi3Terminate", EventMode | ContinuousTimeMode | StepMode);
    in->state = Terminated;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance instance)
{
    BEGIN("fmi3Reset", ANY_STATE);
    instance_reset(in);
    return fmi3OK;
}

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{
    BEGIN("fmi3EvaluateDiscreteStates", EventMode);   /* FMI 3.0 §2.3.5: an Event Mode call */
    return fmi3OK;   /* the modes change only in fmi3UpdateDiscreteStates: nothing to evaluate before */
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation, fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged, fmi3Boolean *nextEventTimeDefined,
                                    fmi3Float64 *nextEventTime)
{
    static const char call[] = "fmi3UpdateDiscreteStates";
    BEGIN(call, EventMode);
    REQUIRE(call, discreteStatesNeedUpdate && terminateSimulation && nominalsOfContinuousStatesChanged &&
            valuesOfContinuousStatesChanged && nextEventTimeDefined && nextEventTime, "an output pointer is NULL");
    bool changed;
    if (instance_event_update(in, call, true, &changed) != STATUS_OK) return fmi3Error;
    if (in->interface == CO_SIMULATION) instance_choose_integrator(in);
    in->solver_live = false;   /* Co-Simulation restarts its integrator from the updated state */
    FMI3(in)->event_pending = false;
    /* The model iterates its decisions to a fixpoint: one call settles them. */
    *discreteStatesNeedUpdate = fmi3False;
    *terminateSimulation = fmi3False;
    *nominalsOfContinuousStatesChanged = fmi3False;
    *valuesOfContinuousStatesChanged = changed;
    *nextEventTimeDefined = fmi3False;
    *nextEventTime = 0;
    return fmi3OK;
}

/* ------------------------------------------------- directional derivatives */

/* Directional (J seed) or adjoint (seed^T J) derivatives: knowns are the
 * states, and in Initialization Mode the parameters too; unknowns the Float64
 * outputs and derivatives (InitialUnknowns while initializing). */
static fmi3Status derivatives(fmi3Instance instance, const char *call, const fmi3ValueReference unknowns[],
                              size_t nUnknowns, const fmi3ValueReference knowns[], size_t nKnowns,
                              const fmi3Float64 seed[], size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity,
                              bool adjoint)
{
    BEGIN(call, READABLE);
    REQUIRE(call, (nUnknowns == 0 || unknowns) && (nKnowns == 0 || knowns) && (nSeed == 0 || seed) &&
            (nSensitivity == 0 || sensitivity), "an array is NULL");
    const size_t want_seed = adjoint ? nUnknowns : nKnowns, want_out = adjoint ? nKnowns : nUnknowns;
    REQUIRE(call, nSeed == want_seed && nSensitivity == want_out,
            "nSeed = %zu and nSensitivity = %zu, expected %zu and %zu (scalar variables)", nSeed, nSensitivity,
            want_seed, want_out);
    return (fmi3Status)instance_derivatives(in, call, unknowns, nUnknowns, knowns, nKnowns, seed, sensitivity,
                                            adjoint);
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,
                                        const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[],
                                        size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity)
{
    return derivatives(instance, "fmi3GetDirectionalDerivative", unknowns, nUnknowns, knowns, nKnowns, seed, nSeed,
                       sensitivity, nSensitivity, false);
}

fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,
                                    const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[],
                                    size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity)
{
    return derivatives(instance, "fmi3GetAdjointDerivative", unknowns, nUnknowns, knowns, nKnowns, seed, nSeed,
                       sensitivity, nSensitivity, true);
}

/* ------------------------------------------- what this FMU does not have */

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance, fmi3ValueReference valueReference,
                                               size_t *nDependencies)
{
    (void)valueReference, (void)nDependencies;
    BEGIN("fmi3GetNumberOfVariableDependencies", READABLE);
    return (fmi3Status)instance_fail(in, "fmi3GetNumberOfVariableDependencies",
                                     "providesPerElementDependencies is false: read the ModelStructure");
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[], fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[], fmi3DependencyKind dependencyKinds[],
                                       size_t nDependencies)
{
    (void)dependent, (void)elementIndicesOfDependent, (void)independents, (void)elementIndicesOfIndependents;
    (void)dependencyKinds, (void)nDependencies;
    BEGIN("fmi3GetVariableDependencies", READABLE);
    return (fmi3Status)instance_fail(in, "fmi3GetVariableDependencies",
                                     "providesPerElementDependencies is false: read the ModelStructure");
}

/* Configuration Mode and clocks: no structural parameters and no clocks here. */
fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{
    BEGIN("fmi3EnterConfigurationMode", ANY_STATE);
    return (fmi3Status)instance_fail(in, "fmi3EnterConfigurationMode", "%s has no structural parameters", MODEL_NAME);
}

fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{
    BEGIN("fmi3ExitConfigurationMode", ANY_STATE);
    return (fmi3Status)instance_fail(in, "fmi3ExitConfigurationMode", "%s has no structural parameters", MODEL_NAME);
}

/* Every clock call: there are no clocks, so any value reference is wrong. */
static fmi3Status no_clocks(fmi3Instance instance, const char *call)
{
    BEGIN(call, ANY_STATE);
    return (fmi3Status)instance_fail(in, call, "%s has no clocks", MODEL_NAME);
}

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, fmi3Float64 intervals[], fmi3IntervalQualifier qualifiers[])
{
    (void)valueReferences, (void)nValueReferences, (void)intervals, (void)qualifiers;
    return no_clocks(instance, "fmi3GetIntervalDecimal");
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, fmi3UInt64 counters[], fmi3UInt64 resolutions[],
                                   fmi3IntervalQualifier qualifiers[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions, (void)qualifiers;
    return no_clocks(instance, "fmi3GetIntervalFraction");
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, fmi3Float64 shifts[])
{
    (void)valueReferences, (void)nValueReferences, (void)shifts;
    return no_clocks(instance, "fmi3GetShiftDecimal");
}

fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, fmi3UInt64 counters[], fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return no_clocks(instance, "fmi3GetShiftFraction");
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, const fmi3Float64 intervals[])
{
    (void)valueReferences, (void)nValueReferences, (void)intervals;
    return no_clocks(instance, "fmi3SetIntervalDecimal");
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, const fmi3UInt64 counters[],
                                   const fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return no_clocks(instance, "fmi3SetIntervalFraction");
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, const fmi3Float64 shifts[])
{
    (void)valueReferences, (void)nValueReferences, (void)shifts;
    return no_clocks(instance, "fmi3SetShiftDecimal");
}

fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return no_clocks(instance, "fmi3SetShiftFraction");
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    (void)clockReference, (void)activationTime;
    return no_clocks(instance, "fmi3ActivateModelPartition");
}
