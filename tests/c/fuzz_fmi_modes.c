/* SPDX-License-Identifier: BSD-2-Clause */
/* fuzz_fmi's calls that move an instance between modes: event handling, the
 * lifecycle (initialization, termination, reset), and logging. */
#include <math.h>
#include <stdint.h>

#include "fuzz_fmi.h"

static const FmiApi *const f = &api;

void op_event(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const uint8_t arg = take(&fuzz_input);
    fmi2EventInfo info;
    fmi2Boolean enter, terminate;
    switch (which % 6) {
    case 0: CALL(s, false, f->EnterEventMode(c)); break;
    case 1: CALL(s, false, f->NewDiscreteStates(c, arg == 255 ? NULL : &info)); break;
    case 2: CALL(s, false, f->EnterContinuousTimeMode(c)); break;
    case 3:
        CALL(s, false, f->CompletedIntegratorStep(c, arg & 1, arg & 2 ? NULL : &enter, arg & 4 ? NULL : &terminate));
        break;
    case 4: CALL(s, false, f->SetTime(c, take_double(&fuzz_input))); break;
    default: {
        bool changed;
        CALL(s, false, harness_event_iteration(f, c, &changed));
    }
    }
}

void op_lifecycle(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const uint8_t flags = take(&fuzz_input);
    switch (which % 5) {
    case 0: {
        const double tol = take_double(&fuzz_input), start = take_double(&fuzz_input), stop = take_double(&fuzz_input);
        if (CALL(s, false, f->SetupExperiment(c, flags & 1, tol, start, flags & 2, stop)) == fmi2OK) s->time = start;
        break;
    }
    case 1: CALL(s, false, f->EnterInitializationMode(c)); break;
    case 2: CALL(s, false, f->ExitInitializationMode(c)); break;
    case 3: CALL(s, false, f->Terminate(c)); break;
    default:
        if (CALL(s, true, f->Reset(c)) == fmi2OK) {
            s->in_error = false;
            s->time = 0;
        }
    }
}

void op_debug_logging(Slot *s)
{
    const long errors_before = harness.error_messages;
    static const fmi2String CATEGORIES[] = { "logEvents", "logStatusWarning", "logStatusError", "logAll",
                                             "logNothing", NULL, "%s%n", "" };
    fmi2String cats[CAP];
    bool null_arrays;
    const size_t n = take_count(&fuzz_input, &null_arrays);
    for (size_t k = 0; k < CAP; ++k) cats[k] = CATEGORIES[take(&fuzz_input) % 8];
    CALL(s, true, f->SetDebugLogging(s->sim.c, take(&fuzz_input) & 1, n, null_arrays ? NULL : cats));
}
