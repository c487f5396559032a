/* SPDX-License-Identifier: BSD-2-Clause */
/* What the files of fmi3_driver's robustness tests share (FMI 3.0): a call
 * checked in a state, and the tests that fmi3_driver.c runs. */
#ifndef ROBUSTNESS3_H
#define ROBUSTNESS3_H

#include "driver3.h"

/* Runs `expr` (which uses c) on a new instance in `state` and checks its status;
 * after fmi3Error, a message naming `call` and an instance that still works. */
#define EXPECT_IN(in_state, expected, call, expr)                                                                   \
    do {                                                                                                         \
        Inst3 in_;                                                                                               \
        if (!inst3_reach(&in_, (in_state), false)) break;                                                           \
        fmi3Instance c = in_.c;                                                                                  \
        const long errors_before_ = harness.error_messages;                                                      \
        const fmi3Status st_ = (expr);                                                                           \
        CHECK(st_ == (expected), "%s in %s: %s, expected %s (%s)", #expr, STATE3_NAME[in_state], status3_name(st_), \
              status3_name(expected), harness.last_message);                                                     \
        if (st_ == fmi3Error) {                                                                                  \
            check3_error_reported(#expr, call, errors_before_);                                                  \
            in_.state = state3_is_cs(in_state) ? C3_ERROR : M3_ERROR;                                               \
        }                                                                                                        \
        inst3_works(&in_, #expr);                                                                                \
        inst3_free(&in_);                                                                                        \
    } while (0)


void test3_null_arguments(void);                   /* fmi3_argument_checks.c */
void test3_array_sizes(void);                      /* fmi3_argument_checks.c */
void test3_types_and_value_references(void);       /* fmi3_argument_checks.c */
void test3_bad_values(void);                       /* fmi3_value_checks.c */
void test3_early_return(void);                     /* fmi3_cosim_checks.c */
void test3_serialized_state_bytes(State3 state);   /* fmi3_fmu_state_checks.c */
void test3_instantiation_and_missing_features(void); /* fmi3_instantiate_checks.c */
void test3_log_messages_are_text(void);            /* fmi3_instantiate_checks.c */

#endif
