/* SPDX-License-Identifier: BSD-2-Clause */
/* fuzz_fmi's steps: Co-Simulation's fmi2DoStep and status queries, the optional
 * calls, and whole stretches of a simulation. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_fmi.h"

static const FmiApi *const f = &api;

/* One communication step from t, mostly the instance's time. CVODE's cost
 * grows with the span (PainleveRod: up to ~0.5 s for 1000), so each input gets
 * a budget of integrated time (the profile's), and one step of any size
 * (huge, infinite, NaN) besides, finite ones up to the profile's longest (the
 * rod in SI units, with a soft contact and heavy damping, can chatter between
 * stick and slip at a million events a second). */
static fmi2Status do_step(Slot *s, double t, double h, fmi2Boolean no_set_prior)
{
    const long errors_before = harness.error_messages;
    if (fabs(h) <= span_left) span_left -= fabs(h);
    else if (span_left >= 0 && !(isfinite(h) && fabs(h) > PROFILE_FUZZ_LONGEST_STEP)) span_left = -1;
    else h = 1e-3;
    const fmi2Status st = CALL(s, false, f->DoStep(s->sim.c, t, h, no_set_prior));
    if (st == fmi2OK) s->time = t + h;
    return st;
}

/* The status queries of FMI 2.0.4 §4.2.3. Steps are synchronous, so only
 * fmi2LastSuccessfulTime (Real) and fmi2Terminated (Boolean) have an answer;
 * any other query "cannot be retrieved by the slave" and returns fmi2Discard
 * where the call is allowed (stepComplete, terminated), fmi2Error elsewhere
 * (the Error state included). A query answered with fmi2Discard leaves the
 * instance as it was: asked again, it answers fmi2Discard again. */
static void op_status_query(Slot *s, uint8_t arg)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const fmi2StatusKind kind = (fmi2StatusKind)(arg % 4);
    const int which = arg >> 2 & 7;
    fmi2Status value;
    fmi2Real r;
    fmi2Integer i;
    fmi2Boolean b;
    fmi2String str;
    fmi2Status st;
    bool has_answer = false;
    switch (which) {
    case 0: st = CALL(s, false, f->GetStatus(c, kind, &value)); break;
    case 1:
        st = CALL(s, false, f->GetRealStatus(c, kind, &r));
        has_answer = kind == fmi2LastSuccessfulTime;
        if (st == fmi2OK) INVARIANT(isfinite(r), "fmi2LastSuccessfulTime = %g", r);
        break;
    case 2: st = CALL(s, false, f->GetIntegerStatus(c, kind, &i)); break;
    case 3:
        st = CALL(s, false, f->GetBooleanStatus(c, kind, &b));
        has_answer = kind == fmi2Terminated;
        if (st == fmi2OK) INVARIANT(b == fmi2False || b == fmi2True, "fmi2Terminated = %d", b);
        break;
    case 4: st = CALL(s, false, f->GetStringStatus(c, kind, &str)); break;
    default: CALL(s, false, f->GetStatus(c, kind, NULL)); return;
    }
    if (!c) return;
    INVARIANT(s->cs || st == fmi2Error, "status query %d on a Model Exchange instance returned %d", which, (int)st);
    INVARIANT(has_answer || st != fmi2OK, "status query %d of kind %d answered fmi2OK: there is nothing to report",
              which, (int)kind);
    if (st == fmi2Discard) {
        const fmi2Status again = which == 0 ? f->GetStatus(c, kind, &value)
                                 : which == 1 ? f->GetRealStatus(c, kind, &r)
                                 : which == 2 ? f->GetIntegerStatus(c, kind, &i)
                                 : which == 3 ? f->GetBooleanStatus(c, kind, &b)
                                              : f->GetStringStatus(c, kind, &str);
        INVARIANT(again == fmi2Discard, "a status query answered fmi2Discard, then %d: the first moved the instance",
                  (int)again);
    }
}

/* FMU state and Co-Simulation calls: optional, they must not crash or leak. */
void op_optional(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const uint8_t arg = take(&fuzz_input);
    switch (which % 6) {
    case 0: op_fmu_state(s); break;
    case 1: op_deserialize_raw(s); break;
    case 2: {
        const double t = arg & 2 ? take_double(&fuzz_input) : s->time;
        do_step(s, t, take_double(&fuzz_input), arg & 1);
        break;
    }
    case 3: CALL(s, false, f->CancelStep(c)); break;
    case 4: op_status_query(s, arg); break;
    default: {
        const fmi2ValueReference vr = take_vr(&fuzz_input);
        const fmi2Integer order = (int8_t)take(&fuzz_input);
        double v = take_double(&fuzz_input);
        if (arg & 1) CALL(s, false, f->SetRealInputDerivatives(c, &vr, arg >> 1 & 1, &order, &v));
        else CALL(s, true, f->GetRealOutputDerivatives(c, &vr, arg >> 1 & 1, &order, &v));
    }
    }
}

/* Whole stretches of a simulation: start with a fuzzed knob (Co-Simulation:
 * its value; Model Exchange: the profile's value for a fuzzed epsilon), Euler steps. */
void op_simulate(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    if (which % 2 == 0 && s->cs) {
        const fmi2ValueReference vr = PROFILE_KNOB;
        const double eps = take_double(&fuzz_input);
        fmi2Status st = CALL(s, false, f->SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0));
        s->time = 0;
        if (st == fmi2OK) st = CALL(s, false, f->SetReal(c, &vr, 1, &eps));
        if (st == fmi2OK) st = CALL(s, false, f->EnterInitializationMode(c));
        if (st == fmi2OK) CALL(s, false, f->ExitInitializationMode(c));
        return;
    }
    if (which % 2 == 0) {
        CALL(s, false, euler_start(f, &s->sim, take_double(&fuzz_input)));
        return;
    }
    const int steps = take(&fuzz_input) % 33;
    const double h = take_double(&fuzz_input);
    for (int k = 0; k < steps; ++k) {
        const fmi2Status st = s->cs ? do_step(s, s->time, h, fmi2True) : CALL(s, false, euler_step(f, &s->sim, h));
        if (st != fmi2OK) break;
    }
}
