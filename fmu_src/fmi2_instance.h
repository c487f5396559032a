/* What the FMI 2.0 files share: the instance, its states, the call guards. */
#ifndef FMI2_INSTANCE_H
#define FMI2_INSTANCE_H

#include <stdbool.h>

#include "fmi2Functions.h"
#include "model.h"

typedef enum {
    Instantiated = 1 << 0,
    InitializationMode = 1 << 1,
    EventMode = 1 << 2,          /* Model Exchange */
    ContinuousTimeMode = 1 << 3, /* Model Exchange */
    StepComplete = 1 << 4,       /* Co-Simulation, initialized */
    Terminated = 1 << 5,
    Error = 1 << 6,
} InstanceState;

/* States each call is allowed in (FMI 2.0 §3.2.3 and §4.2.4). */
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
    double z_at_restart[ROD_NZ]; /* indicators when integration last (re)started */
    bool initial_event;          /* the event iteration right after initialization */
    double window_start;         /* of the current run of events without progress */
    int events_in_window;
    double tolerance;            /* from fmi2SetupExperiment; 0: the default */
    void *cosim;                 /* Co-Simulation's integrator (cosim.h), made on first use */
    bool solver_live;            /* CVODE holds this trajectory at `time`: the next step continues it */
    double last_successful_time;
} Instance;

const char *state_name(InstanceState s);
void log_event(Instance *in, const char *fmt, ...);

/* Logs "call: reason", enters the Error state, returns fmi2Error. */
fmi2Status fail(Instance *in, const char *call, const char *fmt, ...);

/* The model with derived values current (initial mode during initialization). */
Model *current(Instance *in);

/* The event iteration of MODEL.md §2 at the instance's time: new modes, states
 * moved off switching surfaces, the Zeno guard, the event log. */
fmi2Status handle_event(Instance *in, const char *call, bool *states_changed);

/* Records the indicators at which integration (re)starts, for the event log. */
void mark_restart(Instance *in);

/* Co-Simulation's share of the instance's life (fmi2_cs.c). */
void cs_free(Instance *in);

/* NULL-safe instance check: a call on a NULL instance cannot log anything. */
#define BEGIN(call, allowed)                                                              \
    Instance *in = (Instance *)c;                                                         \
    if (!in) return fmi2Error;                                                            \
    if (!(in->state & (allowed)))                                                         \
        return fail(in, call, "not allowed in state %s", state_name(in->state))

#define REQUIRE(call, cond, ...) \
    if (!(cond)) return fail(in, call, __VA_ARGS__)

/* For the calls of one interface only. */
#define INTERFACE(call, t, what) \
    REQUIRE(call, in->type == (t), "is a " what " call; this instance was instantiated for the other interface")

#endif
