/* What the C driver and the fuzz target share: the FMU's functions looked up
 * with dlopen/dlsym as an importer does, callbacks that count allocations and
 * check every log message, and an explicit-Euler simulation through FMI calls. */
#ifndef FMI_HARNESS_H
#define FMI_HARNESS_H

#include <stdbool.h>
#include <stddef.h>

#include "fmi2FunctionTypes.h"
#include "model.h" /* the FMU's metadata: value references, ROD_NX, ROD_NZ */

/* Every function of FMI 2.0 (Model Exchange, Co-Simulation and common). */
#define FMI2_FUNCTIONS(X)                                                                                \
    X(GetTypesPlatform) X(GetVersion) X(SetDebugLogging) X(Instantiate) X(FreeInstance)                  \
    X(SetupExperiment) X(EnterInitializationMode) X(ExitInitializationMode) X(Terminate) X(Reset)       \
    X(GetReal) X(GetInteger) X(GetBoolean) X(GetString) X(SetReal) X(SetInteger) X(SetBoolean)         \
    X(SetString) X(GetFMUstate) X(SetFMUstate) X(FreeFMUstate) X(SerializedFMUstateSize)               \
    X(SerializeFMUstate) X(DeSerializeFMUstate) X(GetDirectionalDerivative) X(EnterEventMode)          \
    X(NewDiscreteStates) X(EnterContinuousTimeMode) X(CompletedIntegratorStep) X(SetTime)              \
    X(SetContinuousStates) X(GetDerivatives) X(GetEventIndicators) X(GetContinuousStates)              \
    X(GetNominalsOfContinuousStates) X(SetRealInputDerivatives) X(GetRealOutputDerivatives) X(DoStep)  \
    X(CancelStep) X(GetStatus) X(GetRealStatus) X(GetIntegerStatus) X(GetBooleanStatus)                \
    X(GetStringStatus)

typedef struct {
    void *handle;
#define FMI_FIELD(name) fmi2##name##TYPE *name;
    FMI2_FUNCTIONS(FMI_FIELD)
#undef FMI_FIELD
} FmiApi;

/* dlopen + dlsym of every fmi2* function; false with a message in err. */
bool fmi_api_load(FmiApi *f, const char *path, char *err, size_t n);
void fmi_api_unload(FmiApi *f);

/* ------------------------------------------------------------ callbacks */

/* Counts of what the FMU did through the callbacks, since harness_reset. */
typedef struct {
    long allocations, frees, live; /* live = blocks allocated and not yet freed */
    long fail_allocation_at;       /* the allocation with this number returns NULL (0: none) */
    long messages, error_messages;
    long bad_messages;   /* a NULL field, or a lone '%' (the FMU passes no varargs) */
    char last_message[512];
    char last_error[512]; /* the last message logged with fmi2Error or fmi2Fatal */
    char last_bad[512];
} HarnessCounts;

extern HarnessCounts harness;

void harness_reset(void);

/* allocateMemory = counting calloc, freeMemory = counting free, logger = checking logger. */
extern const fmi2CallbackFunctions harness_callbacks;

/* The FMU's GUID, from modelDescription.xml through CMake. */
extern const char *const harness_guid;

fmi2Component harness_instantiate(const FmiApi *f, const char *name);

/* --------------------------------------------------------- simulation */

/* One instance simulated by explicit Euler through FMI calls, a step at a
 * time, so that several instances can be stepped in turn. */
typedef struct {
    fmi2Component c;
    double t, x[ROD_NX], z[ROD_NZ];
    int events; /* event iterations after initialization */
} EulerSim;

/* Set-up with the given epsilon, initialization, the initial event
 * iteration, continuous-time mode. */
fmi2Status euler_start(const FmiApi *f, EulerSim *s, double epsilon);

/* One explicit Euler step, then an event iteration if an indicator changed sign. */
fmi2Status euler_step(const FmiApi *f, EulerSim *s, double h);

/* euler_start, `steps` steps of h, fmi2Terminate; the first status other
 * than fmi2OK ends it and is returned. */
fmi2Status harness_simulate(const FmiApi *f, EulerSim *s, double epsilon, double h, int steps);

/* The event iteration of FMI 2.0 §3.2.2, then continuous-time mode. */
fmi2Status harness_event_iteration(const FmiApi *f, fmi2Component c, bool *states_changed);

#endif
