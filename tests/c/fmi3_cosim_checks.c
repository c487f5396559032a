/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 Co-Simulation: early return and Event Mode (a step while an event is
 * pending is refused) (fmi3_driver's robustness tests). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robustness3.h"

static const Fmi3Api *const f = &api3;

/* ------------------------------------- Co-Simulation: early return, events */

#if !defined(PROFILE_MODE_SWITCHES) || !defined(PROFILE_RUN_SPAN)
#error "the model's profiles/NAME.h: PROFILE_MODE_SWITCHES (1: an IWC's switches, as the rods) and PROFILE_RUN_SPAN"
#endif
#define SPAN PROFILE_RUN_SPAN

/* One fmi3DoStep over the profile's run of the start values (PainleveRod: the
 * whole IWC, t = 0 .. 0.1, epsilon 1e-3) with the flags given. */
void test3_early_return(void)
{
    static const struct {
        bool event_mode, early;
    } CASES[] = { { false, false }, { false, true }, { true, true } };
    enum { MAX_RETURNS = 32 };
    double return_times[2][MAX_RETURNS];
    int n_returns[2] = { 0, 0 };
    for (size_t k = 0; k < sizeof CASES / sizeof CASES[0]; ++k) {
        const bool em = CASES[k].event_mode, early = CASES[k].early;
        fmi3Instance c = harness3_instantiate_cs(f, "rod", false, em, early);
        if (!CHECK(c != NULL, "fmi3InstantiateCoSimulation")) continue;
        bool changed;
        fmi3Status st = f->EnterInitializationMode(c, fmi3True, 1e-8, 0, fmi3True, SPAN);
        if (st == fmi3OK) st = f->ExitInitializationMode(c);
        if (em && st == fmi3OK) st = harness3_update_discrete_states(f, c, &changed);
        if (em && st == fmi3OK) st = f->EnterStepMode(c);
        double t = 0;
        int returns = 0, events = 0;
        while (st == fmi3OK && t < SPAN && returns < 100) {
            fmi3Boolean event = 7, terminate = 7, early_return = 7;
            double last = NAN;
            st = f->DoStep(c, t, SPAN - t, fmi3True, &event, &terminate, &early_return, &last);
            if (st != fmi3OK) break;
            CHECK(terminate == fmi3False, "terminateSimulation = %d", terminate);
            CHECK(early_return == fmi3False || early_return == fmi3True, "earlyReturn = %d", early_return);
            CHECK(event == (em && early_return), "eventHandlingNeeded = %d, earlyReturn = %d, eventModeUsed = %d",
                  event, early_return, em);
            CHECK(early || !early_return, "an early return that earlyReturnAllowed = false does not allow");
            CHECK(t < last && last <= SPAN, "lastSuccessfulTime %.17g not in (%.17g, %g]", last, t, SPAN);
            CHECK(early_return || last == SPAN, "lastSuccessfulTime %.17g without an early return", last);
            t = last;
            if (early_return && early && returns < MAX_RETURNS) return_times[em][returns] = t;
            returns += early_return != 0;
            if (event) {
                /* A step while the event is pending is refused; the instance is then
                 * in Error (Terminated), and the FMU state taken at the event restores it. */
                fmi3FMUState saved = NULL;
                CHECK(f->GetFMUState(c, &saved) == fmi3OK, "fmi3GetFMUState at the event");
                fmi3Boolean e2, t2, r2;
                double last2;
                const long errors_before = harness.error_messages;
                CHECK(f->DoStep(c, t, 0.01, fmi3True, &e2, &t2, &r2, &last2) == fmi3Error,
                      "fmi3DoStep accepted while an event is pending at t = %.17g", t);
                check3_error_reported("fmi3DoStep with an event pending", "fmi3DoStep", errors_before);
                /* §2.2.3: "it is possible to restore a previously retrieved FMU state". */
                CHECK(f->SetFMUState(c, saved) == fmi3OK, "fmi3SetFMUState after the refused step: %s",
                      harness.last_error);
                CHECK(f->FreeFMUState(c, &saved) == fmi3OK, "fmi3FreeFMUState");
                st = f->EnterEventMode(c);
                if (st == fmi3OK) st = harness3_update_discrete_states(f, c, &changed);
                if (st == fmi3OK) st = f->EnterStepMode(c);
                ++events;
            }
        }
        CHECK(st == fmi3OK && t == SPAN, "eventModeUsed %d, earlyReturnAllowed %d: %s at t = %.17g (%s)", em, early,
              status3_name(st), t, harness.last_error);
#if PROFILE_MODE_SWITCHES
        fmi3ValueReference vr[2] = { VR_SWITCHES, VR_STICKS };
        fmi3Int32 counts[2] = { -1, -1 };
        CHECK(f->GetInt32(c, vr, 2, counts, 2) == fmi3OK, "fmi3GetInt32(switches, sticks)");
        /* An IWC: contact, stick, lift-off; an early return at each event (each
         * mode switch, and an indicator's crossing that switches nothing, such as
         * y = 0 after a damped lift-off). */
        CHECK(counts[0] >= 2 && counts[1] == 1, "switches %d, sticks %d", counts[0], counts[1]);
        if (early) CHECK(returns >= counts[0], "%d early returns for %d mode switches", returns, counts[0]);
#else
        if (early && MODEL_NZ == 0) CHECK(returns == 0, "%d early returns without event indicators", returns);
#endif
        if (!early) CHECK(returns == 0, "%d early returns without earlyReturnAllowed", returns);
        if (em) CHECK(events == returns, "%d Event Modes for %d early returns", events, returns);
        if (early) n_returns[em] = returns;
        f->FreeInstance(c);
    }
    /* Returning after the event's update or at it, for the master's Event Mode: the same events. */
    CHECK(n_returns[0] == n_returns[1], "%d early returns without Event Mode, %d with", n_returns[0], n_returns[1]);
    for (int k = 0; k < n_returns[0] && k < n_returns[1] && k < MAX_RETURNS; ++k)
        CHECK(fabs(return_times[0][k] - return_times[1][k]) <= 1e-12, "early return %d at %.17g and %.17g", k,
              return_times[0][k], return_times[1][k]);
}
