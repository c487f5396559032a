/* SPDX-License-Identifier: BSD-2-Clause */
/* The driver's checks: counted, and reported with file and line; names in messages; exact copies of bytes. */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "driver.h"

long checks, failures;

bool check_(bool ok, const char *file, int line, const char *fmt, ...)
{
    ++checks;
    if (ok) return true;
    ++failures;
    fprintf(stderr, "FAIL %s:%d: ", file, line);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return false;
}

const char *status_name(fmi2Status s)
{
    static const char *const names[] = { "fmi2OK", "fmi2Warning", "fmi2Discard", "fmi2Error", "fmi2Fatal",
                                         "fmi2Pending" };
    return (unsigned)s < sizeof names / sizeof names[0] ? names[s] : "(not an fmi2Status)";
}

bool names_call(const char *message, const char *call)
{
    const size_t n = strlen(call);
    for (const char *p = strstr(message, call); p; p = strstr(p + 1, call)) {
        const char next = p[n];
        if (!isalnum((unsigned char)next) && next != '_') return true;
    }
    return false;
}

void *exact_copy(const void *bytes, size_t n)
{
    void *p = malloc(n ? n : 1);
    if (p && n) memcpy(p, bytes, n);
    return p;
}
