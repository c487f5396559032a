/* SPDX-License-Identifier: BSD-2-Clause */
/* What the files of fmi_driver's robustness tests share (FMI 2.0): instances
 * in a state and the checks after an error (instance_states.c), Co-Simulation
 * runs (cosim_checks.c), and the tests that fmi_driver.c runs. */
#ifndef ROBUSTNESS_H
#define ROBUSTNESS_H

#include <stddef.h>

#include "driver.h"

/* A new instance brought to `state` (logging off), or NULL; freed with a check of its blocks. */
fmi2Component instance_in(State state);
void free_instance(fmi2Component c);

/* After an fmi2Error: a message naming a call, and the Error state (no
 * simulation call accepted, getters still are). */
void check_error_handling(fmi2Component c, const char *what, long errors_before);

/* fmi2Reset from any state gives an instance that simulates. */
void check_reset_recovers(fmi2Component c, const char *what);

/* The value references of the Real variables of modelDescription.xml; their number. */
size_t real_vrs(fmi2ValueReference vr[MAX_VARS]);

/* The first variable of `type`; VR_COUNT (no variable) if the model has none. */
fmi2ValueReference first_of_type(MdType type);

/* Every Real read; each finite. */
fmi2Status get_all_reals(fmi2Component c);

fmi2Status set_one(fmi2Component c, fmi2ValueReference vr, double value);

/* Runs `expr` (which uses c) on a new instance in `state` and checks its status. */
#define EXPECT_IN(state, expected, expr)                                                                   \
    do {                                                                                                   \
        fmi2Component c = instance_in(state);                                                              \
        if (!c) break;                                                                                     \
        const long errors_before_ = harness.error_messages;                                                \
        const fmi2Status st_ = (expr);                                                                     \
        CHECK(st_ == (expected), "%s in %s: %s, expected %s", #expr, STATE_NAME[state], status_name(st_), \
              status_name(expected));                                                                      \
        if (st_ == fmi2Error) check_error_handling(c, #expr, errors_before_);                              \
        free_instance(c);                                                                                  \
    } while (0)

/* Co-Simulation (cosim_checks.c): an instance; its set-up and initialization
 * (time 0); `steps` communication steps of h from *t (which follows); whether
 * this build steps (without SUNDIALS, fmi2DoStep always fails). */
fmi2Component cs_instance(void);
fmi2Status cs_start(fmi2Component c, double epsilon);
fmi2Status cs_run(fmi2Component c, double *t, double h, int steps);
bool cosimulation_available(void);

/* ----------------------------------------------------------- the tests */

void test_null_arguments(void);              /* argument_checks.c */
void test_value_references(void);            /* argument_checks.c */
void test_nvr_zero_and_huge(void);           /* argument_checks.c */
void test_large_arrays(void);                /* argument_checks.c */
void test_bad_values(void);                  /* value_checks.c */
void test_instantiate_arguments(void);       /* instantiate_checks.c */
void test_allocation_failure(void);          /* instantiate_checks.c */
void test_logging(void);                     /* instantiate_checks.c */
void test_serialized_state_bytes(State state); /* fmu_state_checks.c */
void test_interleaved_instances(void);       /* many_instances.c */
void test_cycles(long cycles, long max_growth_kb, bool cosimulation); /* many_instances.c */
void test_cosimulation_bad_steps(void);      /* cosim_checks.c */
void test_cosimulation_state_restores_the_run(void); /* cosim_checks.c */

#endif
