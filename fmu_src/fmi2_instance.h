/* What the FMI 2.0 files share: the instance, its states, the call guards.
 * The model is reached only through model.h. */
#ifndef FMI2_INSTANCE_H
#define FMI2_INSTANCE_H

#include <stdbool.h>

#include "fmi2Functions.h"
#include "model.h"

/* The standard's fmi2Functions.h prefixes the fmi2 names with
 * FMI2_FUNCTION_PREFIX; fmpy's copy, which the build uses, was changed to add
 * none. Either way the exported names get the prefix, as our own do. */
#ifdef FMI2_FUNCTION_PREFIX
#undef fmi2FullName
#define fmi2FullName(name) NAMESPACED(name)
#endif

typedef enum {
    Instantiated = 1 << 0,
    InitializationMode = 1 << 1,
    EventMode = 1 << 2,          /* Model Exchange */
    ContinuousTimeMode = 1 << 3, /* Model Exchange */
    StepComplete = 1 << 4,       /* Co-Simulation, initialized */
    Terminated = 1 << 5,
    Error = 1 << 6,
} InstanceState;

/* States each call is allowed in (FMI 2.0.4 §3.2.3 and §4.2.4). */
#define ANY_BUT_FATAL (Instantiated | InitializationMode | EventMode | ContinuousTimeMode | StepComplete | Terminated | Error)
#define READABLE (InitializationMode | EventMode | ContinuousTimeMode | StepComplete | Terminated | Error)
#define BEFORE_INIT_ENDS (Instantiated | InitializationMode)
#define SIMULATING (EventMode | ContinuousTimeMode)

enum { LOG_EVENTS, LOG_WARNING, LOG_ERROR, LOG_ALL, N_LOG_CATEGORIES };

typedef struct {
    fmi2CallbackFunctions cb;
    char *name;
    fmi2Type type;
    InstanceState state;
    bool log_on[N_LOG_CATEGORIES];
    double time;
    Model model;
    double tolerance;               /* fmi2SetupExperiment's, else the DefaultExperiment's */
    void *solver;                   /* Co-Simulation's integrator, made on the first step */
    void (*free_solver)(void *);
    bool solver_live;               /* the solver holds this trajectory at `time`: a step continues it */
    double last_successful_time;
} Instance;

const char *instance_state_name(InstanceState s);
void instance_log_event(Instance *in, const char *fmt, ...);

/* Logs "call: reason", enters the Error state, returns fmi2Error. */
fmi2Status instance_fail(Instance *in, const char *call, const char *fmt, ...);

/* Logs "call: reason" as a warning and returns fmi2Discard: a legal call the
 * FMU cannot answer; the instance stays as it was. */
fmi2Status instance_discard(Instance *in, const char *call, const char *fmt, ...);

/* The model with the initial mode decided while initializing. */
Model *instance_model(Instance *in);

/* The event update at the instance's time, logged; fmi2Error on failure. */
fmi2Status instance_event_update(Instance *in, const char *call, bool *states_changed);

/* NULL-safe instance check: a call on a NULL instance cannot log anything. */
#define BEGIN(call, allowed)                                                              \
    Instance *in = (Instance *)c;                                                         \
    if (!in) return fmi2Error;                                                            \
    if (!(in->state & (allowed)))                                                         \
        return instance_fail(in, call, "not allowed in state %s", instance_state_name(in->state))

#define REQUIRE(call, cond, ...) \
    if (!(cond)) return instance_fail(in, call, __VA_ARGS__)

/* For the calls of one interface only. */
#define INTERFACE(call, t, what) \
    REQUIRE(call, in->type == (t), "is a " what " call; this instance was instantiated for the other interface")

#endif
