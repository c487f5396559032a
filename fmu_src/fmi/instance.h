/* SPDX-License-Identifier: BSD-2-Clause */
/* What an instance is under any FMI version: its state in the state machine,
 * its log, its time, the model, and Co-Simulation's integrator. The FMI 2.0
 * and 3.0 layers wrap it with their own callbacks and types; it knows the
 * model interface (model.h) and no FMI header. Status codes are those both
 * standards share (OK 0, Warning 1, Discard 2, Error 3). */
#ifndef INSTANCE_H
#define INSTANCE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>

#include "model.h"

typedef enum { STATUS_OK, STATUS_WARNING, STATUS_DISCARD, STATUS_ERROR } Status;

typedef enum {
    Instantiated = 1 << 0,
    InitializationMode = 1 << 1,
    EventMode = 1 << 2,
    ContinuousTimeMode = 1 << 3, /* Model Exchange */
    StepMode = 1 << 4,           /* Co-Simulation, initialized (FMI 2.0: slaveInitialized) */
    Terminated = 1 << 5,
    Error = 1 << 6,
} InstanceState;

#define ANY_STATE (Instantiated | InitializationMode | EventMode | ContinuousTimeMode | StepMode | Terminated | Error)
#define BEFORE_INIT_ENDS (Instantiated | InitializationMode)

typedef enum { MODEL_EXCHANGE, CO_SIMULATION } Interface;

/* LOG_STATISTICS: the integrators' work over each Co-Simulation step (instance_step). */
enum { LOG_EVENTS, LOG_WARNING, LOG_ERROR, LOG_STATISTICS, LOG_ALL, N_LOG_CATEGORIES };

typedef struct Instance Instance;

/* The FMI layer's adapter to the importer's logger; `message` has no '%'
 * that the importer could take for a format. */
typedef void (*InstanceLogger)(const Instance *in, Status status, const char *category, const char *message);

struct Instance {
    char *name;
    Interface interface;
    InstanceState state;
    InstanceLogger logger;
    bool log_on[N_LOG_CATEGORIES];
    double time;
    Model model;
    double tolerance;            /* the master's, else the DefaultExperiment's */
    void *solver;                /* Co-Simulation's integrator, made on the first step */
    bool solver_live;            /* the solver holds this trajectory at `time`: a step continues it */
    bool solver_implicit;        /* CVODE, not the explicit pair, integrates (a sustained stiff phase) */
    bool fast_growth;            /* the last event update's mode grows fast (model_event.h) */
    double last_successful_time;
    bool inputs_jumped;          /* an input changed since the last Co-Simulation step */
};

extern const char *const instance_log_categories[N_LOG_CATEGORIES];

const char *instance_state_name(InstanceState s);

/* A new instance's values: start values, Instantiated, time 0. */
void instance_reset(Instance *in);

/* Frees the integrator (the instance's memory is the FMI layer's). */
void instance_free_solver(Instance *in);

/* Sets the categories named (all if n is 0) on or off; STATUS_ERROR naming
 * an unknown one. */
Status instance_set_logging(Instance *in, const char *call, bool on, size_t n, const char *const categories[]);

void instance_log_event(Instance *in, const char *fmt, ...);

/* True if the statistics category (or logAll) is on: only then is anything counted up for it. */
bool instance_logs_statistics(const Instance *in);

/* Logs "call: text" under logStatistics (when instance_logs_statistics). */
void instance_log_statistics(Instance *in, const char *call, const char *fmt, ...);

/* Logs "call: reason", enters the Error state, returns STATUS_ERROR. */
Status instance_fail(Instance *in, const char *call, const char *fmt, ...);

/* Logs "call: reason" as a warning and returns STATUS_DISCARD: a legal call
 * the FMU cannot answer; the instance stays as it was. */
Status instance_discard(Instance *in, const char *call, const char *fmt, ...);

/* The relative tolerances for which Co-Simulation's answers are right
 * (docs/bounded_calls.md): above the range the solver's error reaches the
 * contact's own scales and the mode sequence can change; below it CVODE asks
 * for more digits than a double has. */
#define INSTANCE_TOLERANCE_MIN 1e-12
#define INSTANCE_TOLERANCE_MAX 1e-3

/* The master's tolerance (the DefaultExperiment's if not defined), clamped
 * to the range above: in Co-Simulation a clamp is logged and answers
 * STATUS_WARNING; in Model Exchange the importer's solver uses the tolerance,
 * not the FMU, so it is kept quietly. */
Status instance_set_tolerance(Instance *in, const char *call, bool defined, double tolerance);

/* The model, with the initial mode decided while initializing. */
Model *instance_model(Instance *in);

/* Initialization ends: the initial mode and the event record (model_start). */
void instance_start(Instance *in);

/* Co-Simulation after a located event: CVODE hands a mode whose fast motion grows back to the
 * explicit pair; otherwise the trajectory keeps its integrator. */
void instance_choose_integrator(Instance *in);

/* The event update at the instance's time, logged; `located`: a state event an integrator located. */
Status instance_event_update(Instance *in, const char *call, bool located, bool *states_changed);

/* ----------------------------------------------------------- variables */

/* The value of variable vr if it has `type`; STATUS_ERROR naming it if not,
 * or if its value is not finite. */
Status instance_get(Instance *in, const char *call, unsigned int vr, VariableType type, double *value);

/* Checks that vr is a settable variable of `type`, settable now, and that
 * value is in its range (nothing is set). */
Status instance_check_set(Instance *in, const char *call, unsigned int vr, VariableType type, double value);

/* Sets vr (checked by instance_check_set): an input that changes makes the
 * next Co-Simulation step start with an event update and a fresh integrator. */
void instance_set(Instance *in, unsigned int vr, double value);

/* The model's vectors that Model Exchange reads. */
typedef enum { ARRAY_STATES, ARRAY_DERIVATIVES, ARRAY_EVENT_INDICATORS, ARRAY_NOMINALS } ModelArray;

/* Reads vector `which` into out[n]; STATUS_ERROR if out is NULL, n is not its
 * size, or a value is not finite. */
Status instance_read_array(Instance *in, const char *call, ModelArray which, double out[], size_t n);

/* Sets the continuous states to x[n], all checked first (size, each range). */
Status instance_set_states(Instance *in, const char *call, const double x[], size_t n);

/* sum_j d unknown_i / d known_j * seed_j for each i (directional), or, if
 * adjoint, sum_i seed_i * d unknown_i / d known_j for each j; knowns are the
 * states, and while initializing the parameters too. */
Status instance_derivatives(Instance *in, const char *call, const unsigned int unknowns[], size_t n_unknowns,
                            const unsigned int knowns[], size_t n_knowns, const double seed[], double out[],
                            bool adjoint);

/* ------------------------------------------------------ Co-Simulation */

typedef enum {
    THROUGH_EVENTS,     /* update at each event and go on to t_end */
    RETURN_AFTER_EVENT, /* update at the first event and return there (early return) */
    RETURN_AT_EVENT,    /* return at the first event, its update left to the master (event mode) */
} StepPolicy;

typedef enum { STEP_REACHED, STEP_EVENT } StepEnd;

/* One Co-Simulation step from the master's communication point t (the
 * instance's time to 1e-12) over h > 0, with the embedded CVODE, events as the
 * policy says (where the step ends at one, the instance's time is the
 * event's); the last successful time follows. STATUS_ERROR with a message if
 * t or h is wrong, or the solver fails or was not built in. */
Status instance_step(Instance *in, const char *call, double t, double h, StepPolicy policy, StepEnd *end);

#endif
