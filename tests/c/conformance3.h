/* SPDX-License-Identifier: BSD-2-Clause */
/* What the FMI 3.0 conformance table's files share (fmi3_conformance.c,
 * fmi3_conformance_variables.c): where a call leaves the instance, and the
 * check of a call's status against the table. */
#ifndef CONFORMANCE3_H
#define CONFORMANCE3_H

#include "driver3.h"

/* Where a call leaves the instance, when it succeeds. */
typedef enum { SAME, TO_INSTANTIATED, TO_INIT, TO_INITIALIZED, TO_EVENT, TO_CONTINUOUS, TO_STEP, TO_TERMINATED } Next;

/* The status of a call against the table (allowed: with status `expected`,
 * leaving the instance where `next` says; not allowed: fmi3Error and a message
 * naming `call`), then whether the instance works. */
void check_call(Inst3 *in, const char *call, const char *what, fmi3Status st, bool allowed,
                fmi3Status expected, Next next, long errors_before);

#endif
