/* SPDX-License-Identifier: BSD-2-Clause */
/* The cases the native driver runs, one a line of stdin, "theta0 phi0 v0
 * delta epsilon w10 alpha mu", and what a case implies for a run: its horizon. */
#ifndef CASES_H
#define CASES_H

#include <stddef.h>

enum { THETA0, PHI0, V0, DELTA, EPSILON, W10, ALPHA, MU, N_FIELDS };
extern const char *const FIELD[N_FIELDS];

typedef struct {
    double value[N_FIELDS];
    long line; /* in stdin, for messages */
} Case;

/* Every case of stdin (blank lines and lines starting with '#' skipped), or 0
 * with a message; *cases is the caller's to free either way. */
int read_cases(Case **cases, size_t *count, char *err, size_t n);

/* Experiment._solver_settings's horizon of case k; NaN outside the Painleve wedge. */
double horizon_of(const Case *k);

#endif
