/* SPDX-License-Identifier: BSD-2-Clause */
/* What the C driver and the fuzz target share: the FMU's functions (looked up
 * by importer/fmi2_functions.c, as the benchmark's native driver does), callbacks that count allocations and
 * check every log message, and an explicit-Euler simulation through FMI calls. */
#ifndef FMI_HARNESS_H
#define FMI_HARNESS_H

#include <stdbool.h>
#include <stddef.h>

#include "fmi2FunctionTypes.h"
#include "fmi2_functions.h"
#include "model.h" /* the FMU's metadata: value references, MODEL_NX, MODEL_NZ */
/* What the driver needs to know of this model beyond its modelDescription.xml
 * (tests/c/profiles/NAME.h, chosen by CMake's add_model_checks). */
#include DRIVER_PROFILE

/* Arrays of event indicators, which a model may not have. */
#define HARNESS_NZ (MODEL_NZ > 0 ? MODEL_NZ : 1)

/* The FMU's functions: the shared loader of importer/ (all of them required). */
typedef Fmi2Functions FmiApi;

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
    double t, x[MODEL_NX], z[HARNESS_NZ];
    int events; /* event iterations after initialization */
} EulerSim;

/* Set-up with the contact's compliance epsilon (the profile's knob), initialization, the initial event
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
