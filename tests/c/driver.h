/* SPDX-License-Identifier: BSD-2-Clause */
/* What the files of the C driver (fmi_driver) share: the loaded FMU, the
 * check counter, and the instance states of FMI 2.0.4 with the calls that
 * reach them and the runs that show an instance still works. */
#ifndef DRIVER_H
#define DRIVER_H

#include <stdbool.h>

#include "fmi_harness.h"
#include "model_structure.h"

extern FmiApi api; /* loaded by main */

/* ------------------------------------------------------------- checks */

bool check_(bool ok, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
#define CHECK(cond, ...) check_((cond), __FILE__, __LINE__, __VA_ARGS__)

extern long checks, failures;

const char *status_name(fmi2Status s);

/* Whether `message` names function `call` (a whole name: "fmi2GetReal" is
 * not named by "fmi2GetRealStatus: ..."). */
bool names_call(const char *message, const char *call);

/* A copy of n bytes (an FMU state serialized) in a block of exactly n, so that
 * any read past the end is caught; freed with free. */
void *exact_copy(const void *bytes, size_t n);

/* Arrays of the model's variables. */
enum { MAX_VARS = 64 };

/* ----------------------------------------------------- instance states */

/* The states of the Model Exchange state machine (FMI 2.0.4 §3.2.3) and of
 * the Co-Simulation one (§4.2.4) that an instance of the model can be in:
 * stepInProgress, stepFailed and stepCanceled need asynchronous or failing
 * steps, which it does not have. Event Mode is reached two ways: right after
 * initialization, and from Continuous-Time Mode after an integration step. */
typedef enum {
    ME_INSTANTIATED, ME_INIT, ME_EVENT, ME_CONTINUOUS, ME_EVENT_AGAIN, ME_TERMINATED, ME_ERROR,
    CS_INSTANTIATED, CS_INIT, CS_STEP_COMPLETE, CS_TERMINATED, CS_ERROR,
    N_STATES
} State;

extern const char *const STATE_NAME[N_STATES];

#define B(s) (1u << (s))
#define ME_ALL (B(ME_INSTANTIATED) | B(ME_INIT) | B(ME_EVENT) | B(ME_CONTINUOUS) | B(ME_EVENT_AGAIN) | \
                B(ME_TERMINATED) | B(ME_ERROR))
#define CS_ALL (B(CS_INSTANTIATED) | B(CS_INIT) | B(CS_STEP_COMPLETE) | B(CS_TERMINATED) | B(CS_ERROR))
#define ME_EVENT_MODE (B(ME_EVENT) | B(ME_EVENT_AGAIN))

bool state_is_cs(State s);

/* An instance and what the test knows of it. */
typedef struct {
    fmi2Component c;
    State state;
    double t; /* its time: where the next step starts */
} Inst;

/* A new instance (logging on or off) brought to `state` by the calls an
 * importer makes; false (with a failed check) if that did not work. */
bool inst_reach(Inst *in, State state, bool logging);

/* The first fixed Real parameter of modelDescription.xml set to its start
 * value: an error once initialization has ended (FMI 2.0.4 §3.2.3). */
fmi2Status set_fixed_parameter(Inst *in);

/* fmi2FreeInstance, and a check that every block it allocated is freed. */
void inst_free(Inst *in);

/* Runs something real from the state the instance is believed to be in:
 * initialization, an integration step or a communication step, outputs read;
 * from Terminated and Error the Error state's rules, fmi2Reset and a new run.
 * Each call is checked; `what` says which test this follows. */
void inst_works(Inst *in, const char *what);

/* After a call that returned fmi2Error: an error message naming `call` was
 * logged since `errors_before`, and the instance is in the Error state. */
void check_error_reported(const char *what, const char *call, long errors_before);

/* ----------------------------------------------------------- the tests */

void test_conformance_table(void);           /* conformance_table.c */
void test_conformance_variables(void);       /* conformance_variables.c */
void test_conformance_null_instance(void);   /* conformance_table.c */
void test_error_state_recovery(void);        /* conformance_table.c */
void test_directional_derivatives(void);     /* conformance_directional.c */
void test_inputs(void);                      /* input_checks.c */
#endif
