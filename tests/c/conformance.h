/* SPDX-License-Identifier: BSD-2-Clause */
/* What the FMI 2.0 conformance table's files share (conformance_table.c,
 * conformance_variables.c): where a call leaves the instance, and the check of
 * a call's status against the table. */
#ifndef CONFORMANCE_H
#define CONFORMANCE_H

#include "driver.h"

/* Where a call leaves the instance, when it succeeds. */
typedef enum { SAME, TO_INSTANTIATED, TO_INIT, TO_INITIALIZED, TO_EVENT, TO_CONTINUOUS, TO_TERMINATED } Next;

/* The status of a call against the table (allowed: with status `expected`,
 * leaving the instance where `next` says; not allowed: fmi2Error and a message
 * naming `call`), then whether the instance works. */
void check_call(Inst *in, const char *call, const char *what, fmi2Status st, bool allowed,
                fmi2Status expected, Next next, long errors_before, long messages_before);

#endif
