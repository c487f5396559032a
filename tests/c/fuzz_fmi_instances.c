/* SPDX-License-Identifier: BSD-2-Clause */
/* fuzz_fmi's instances: the bytes that become a value reference or a count, the
 * three slots, the invariants every call's status must hold, fmi2Instantiate. */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_fmi.h"

static const FmiApi *const f = &api;

/* ------------------------------------------------------------ the bytes */

/* A value reference: mostly near the valid ones, sometimes far out. */
fmi2ValueReference take_vr(Bytes *b)
{
    static const fmi2ValueReference FAR[] = { VR_COUNT, 255, 1000, 0x7fffffffu, 0x80000000u, UINT_MAX - 1,
                                              UINT_MAX };
    const uint8_t sel = take(b);
    return sel < 224 ? sel % (VR_COUNT + 4) : FAR[sel % (sizeof FAR / sizeof FAR[0])];
}

/* A count and whether the arrays are passed: small counts with real arrays,
 * or huge counts (and sometimes small ones) with NULL arrays. */
size_t take_count(Bytes *b, bool *null_arrays)
{
    static const size_t HUGE_N[] = { SIZE_MAX, SIZE_MAX / 2 + 1, (size_t)1 << 40, (size_t)1 << 31, CAP + 1 };
    const uint8_t sel = take(b);
    *null_arrays = sel >= 240;
    if (sel < 240) return sel % (CAP + 1);
    return sel < 248 ? (size_t)(sel % 3) : HUGE_N[sel % (sizeof HUGE_N / sizeof HUGE_N[0])];
}

/* ------------------------------------------------------- the instances */

Slot slots[3];
Bytes fuzz_input;
double span_left;

void free_slot(Slot *s)
{
    if (s->sim.c) f->FreeInstance(s->sim.c);
    memset(s, 0, sizeof *s);
}

/* Checks a status and the Error state's rules. `may_pass_in_error`: calls the
 * Error state allows (getters, logging, FMU state, status queries). */
fmi2Status checked(Slot *s, const char *call, fmi2Status st, long errors_before, bool may_pass_in_error)
{
    INVARIANT(st >= fmi2OK && st <= fmi2Pending, "%s returned %d", call, (int)st);
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
    if (!s->sim.c) {
        INVARIANT(st == fmi2Error || st == fmi2Fatal, "%s on a NULL instance returned %d", call, (int)st);
        return st;
    }
    if (st == fmi2Error || st == fmi2Fatal) {
        INVARIANT(!s->logs || harness.error_messages > errors_before, "%s returned %d without logging an error",
                  call, (int)st);
        s->in_error = true;
    } else if (s->in_error) {
        INVARIANT(may_pass_in_error || st > fmi2Warning, "%s succeeded in the Error state", call);
    }
    return st;
}

void require_finite(const char *what, const double *v, size_t n)
{
    for (size_t k = 0; k < n; ++k) INVARIANT(isfinite(v[k]), "%s[%zu] = %g returned with fmi2OK", what, k, v[k]);
}

/* ------------------------------------------------------- fmi2Instantiate */

static const char *take_name(Bytes *b)
{
    static const char *const NAMES[] = { "rod", "rod", "%s%n%d", "", NULL,
                                         "a rod with a long name, a long long name, a long long long name" };
    return NAMES[take(b) % 6];
}

void op_instantiate(Slot *s)
{
    static const fmi2Type TYPES[] = { fmi2ModelExchange, fmi2ModelExchange, fmi2ModelExchange, fmi2CoSimulation,
                                      (fmi2Type)2, (fmi2Type)-1 };
    fmi2CallbackFunctions no_logger = harness_callbacks;
    no_logger.logger = NULL;
    const char *name = take_name(&fuzz_input);
    const uint8_t g = take(&fuzz_input), t = take(&fuzz_input), flags = take(&fuzz_input);
    const char *guid = g < 224 ? harness_guid : g < 240 ? "{aeb84f4e-0000}" : g < 248 ? NULL : "%s%s%s%n";
    free_slot(s);
    harness.fail_allocation_at = flags & 0x30 ? harness.allocations + (flags >> 4 & 3) : 0;
    s->sim.c = f->Instantiate(name, TYPES[t % 6], guid, flags & 8 ? NULL : "file:///tmp",
                              flags & 4 ? &no_logger : &harness_callbacks, flags & 1, flags & 2);
    harness.fail_allocation_at = 0;
    s->logs = !(flags & 4);
    s->cs = TYPES[t % 6] == fmi2CoSimulation;
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
}
