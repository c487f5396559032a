/* SPDX-License-Identifier: BSD-2-Clause */
/* CHECK(cond, format, ...) for the C tests (rod_unit.c, arm_unit.c, cvode_setup_faults.c): counts the checks and
 * the failures, and prints each failure with its place and the message. */
#ifndef UNIT_CHECK_H
#define UNIT_CHECK_H

#include <stdio.h>

static int failures, checks;

#define CHECK(cond, ...)                                                 \
    do {                                                                 \
        ++checks;                                                        \
        if (!(cond)) {                                                   \
            ++failures;                                                  \
            fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);         \
            fprintf(stderr, __VA_ARGS__);                                \
            fputc('\n', stderr);                                         \
        }                                                                \
    } while (0)

#endif
