/* SPDX-License-Identifier: BSD-2-Clause */
/* The cases of stdin and their horizons (cases.h). */
#include "cases.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "native_fail.h"

const char *const FIELD[N_FIELDS] = { "theta0", "phi0", "v0", "delta", "epsilon", "w10", "alpha", "mu" };

/* lambda_+ of eq lambdapm with p = p_+(theta0); NaN unless p_+ < 0. */
static double lambda_plus(const Case *k)
{
    const double *x = k->value, s = sin(x[THETA0]), c = cos(x[THETA0]);
    const double p = 1 + x[ALPHA] * c * c - x[MU] * x[ALPHA] * s * c, delta = x[DELTA];
    if (!(p < 0)) return NAN;
    return -delta * p / 2 + sqrt(delta * delta * p * p - 4 * p) / 2;
}

/* Experiment._solver_settings: fast time 10 ln(1/eps)/lambda_+ + 50 (1 + delta), times eps. */
double horizon_of(const Case *k)
{
    const double eps = k->value[EPSILON];
    return eps * (10 * log(1 / eps) / lambda_plus(k) + 50 * (1 + k->value[DELTA]));
}

static int parse_case(const char *text, long line, Case *k, char *err, size_t n)
{
    const char *p = text;
    k->line = line;
    for (int i = 0; i < N_FIELDS; ++i) {
        while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
        if (*p == '\0' || *p == '\n')
            FAIL("line %ld: %d numbers given, 8 needed: theta0 phi0 v0 delta epsilon w10 alpha mu", line, i);
        char *end;
        errno = 0;
        k->value[i] = strtod(p, &end);
        if (end == p || (*end && !strchr(" \t\r\n", *end))) {
            const size_t len = strcspn(p, " \t\r\n");
            FAIL("line %ld: %s = '%.*s' is not a number", line, FIELD[i], (int)(len < 40 ? len : 40), p);
        }
        if (!isfinite(k->value[i]) || errno == ERANGE)
            FAIL("line %ld: %s = '%.*s' is not a finite double", line, FIELD[i], (int)(end - p < 40 ? end - p : 40), p);
        p = end;
    }
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') ++p;
    if (*p) FAIL("line %ld: more than 8 fields (theta0 phi0 v0 delta epsilon w10 alpha mu)", line);
    return 1;
}

/* Every case of stdin, or 0 with a message. */
int read_cases(Case **cases, size_t *count, char *err, size_t n)
{
    char *line = NULL;
    size_t cap = 0, size = 0;
    long number = 0;
    int ok = 1;
    *cases = NULL;
    *count = 0;
    while (ok && getline(&line, &cap, stdin) != -1) {
        ++number;
        const char *p = line + strspn(line, " \t\r\n");
        if (*p == '\0' || *p == '#') continue;
        if (*count == size) {
            size = 2 * size + 16;
            Case *bigger = realloc(*cases, size * sizeof **cases);
            if (!bigger) {
                snprintf(err, n, "out of memory reading the cases");
                ok = 0;
                break;
            }
            *cases = bigger;
        }
        ok = parse_case(line, number, &(*cases)[*count], err, n);
        *count += (size_t)ok;
    }
    if (ok && ferror(stdin)) {
        snprintf(err, n, "reading stdin: %s", strerror(errno));
        ok = 0;
    }
    free(line);
    if (ok && *count == 0) {
        snprintf(err, n, "no cases on stdin: give lines 'theta0 phi0 v0 delta epsilon w10 alpha mu'");
        ok = 0;
    }
    return ok;
}
