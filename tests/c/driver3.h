/* SPDX-License-Identifier: BSD-2-Clause */
/* What the files of the FMI 3.0 driver (fmi3_driver) share: the loaded FMU,
 * the instance states of FMI 3.0's state machines (§3.2 Model Exchange, §4.2
 * Co-Simulation, the common states of §2.3) with the calls that reach them
 * and the runs that show an instance still works. The checks (check_,
 * names_call) are driver_checks.c's, shared with the FMI 2.0 driver. */
#ifndef DRIVER3_H
#define DRIVER3_H

#include <stdbool.h>

#include "driver.h" /* CHECK, checks, failures, names_call */
#include "fmi3_harness.h"

extern Fmi3Api api3; /* loaded by main */

const char *status3_name(fmi3Status s);

/* The value references of continuous state i (0-based) and of its derivative
 * (the model description's <ContinuousStateDerivative>s, in order). */
fmi3ValueReference state3_vr(int i);
fmi3ValueReference derivative3_vr(int i);

/* The states of FMI 3.0's state machines an instance of a model can be in
 * (no Configuration Mode: the FMUs have no structural parameters; no clocks, no
 * Intermediate Update Mode). Event Mode is reached two ways in each
 * interface: right after initialization, and from Continuous-Time Mode or
 * Step Mode. Co-Simulation's Event Mode needs eventModeUsed; Step Mode is
 * reached with and without it. "Error" is where a call that returned
 * fmi3Error leaves the instance: FMI 3.0 §2.3.1 calls it Terminated ("If any
 * function called in super state FMU State Settable returns fmi3Error, the
 * FMU enters state Terminated"), so the table gives it Terminated's calls. */
typedef enum {
    M3_INSTANTIATED, M3_INIT, M3_EVENT, M3_CONTINUOUS, M3_EVENT_AGAIN, M3_TERMINATED, M3_ERROR,
    C3_INSTANTIATED, C3_INIT, C3_EVENT, C3_STEP, C3_STEP_EM, C3_EVENT_AGAIN, C3_TERMINATED, C3_ERROR,
    N3_STATES
} State3;

extern const char *const STATE3_NAME[N3_STATES];

bool state3_is_cs(State3 s);
/* Whether instances in `s` are made with eventModeUsed (and earlyReturnAllowed). */
bool state3_event_mode_used(State3 s);

typedef struct {
    fmi3Instance c;
    State3 state;
    bool event_mode; /* Co-Simulation: instantiated with eventModeUsed and earlyReturnAllowed */
    double t;        /* its time: where the next step starts */
} Inst3;

/* A new instance (logging on or off) brought to `state` by an importer's calls. */
bool inst3_reach(Inst3 *in, State3 state, bool logging);
void inst3_free(Inst3 *in);

/* Runs something real from the state the instance is believed to be in:
 * initialization, an integration step or a communication step, values read;
 * from Terminated and Error a refused call, reading, fmi3Reset and a new run. */
void inst3_works(Inst3 *in, const char *what);

/* After fmi3Error: an error logged since `errors_before`, naming `call`. */
void check3_error_reported(const char *what, const char *call, long errors_before);

void test3_conformance_table(void);      /* fmi3_conformance.c */
void test3_conformance_variables(void);  /* fmi3_conformance_variables.c */
void test3_null_instance(void);          /* fmi3_conformance.c */
void test3_derivatives(void);            /* fmi3_directional.c */

#endif
