/* SPDX-License-Identifier: BSD-2-Clause */
/* Instances brought to each state of FMI 3.0's state machines, and the runs
 * that show an instance still works after a call (see driver3.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "driver3.h"

static const Fmi3Api *const f = &api3;

const char *const STATE3_NAME[N3_STATES] = {
    "ME Instantiated", "ME InitializationMode", "ME EventMode (initial)", "ME ContinuousTimeMode",
    "ME EventMode (after integration)", "ME Terminated", "ME Error (Terminated)",
    "CS Instantiated", "CS InitializationMode", "CS EventMode (initial, eventModeUsed)", "CS StepMode",
    "CS StepMode (eventModeUsed)", "CS EventMode (after steps, eventModeUsed)", "CS Terminated",
    "CS Error (Terminated)",
};

const char *status3_name(fmi3Status s)
{
    static const char *const names[] = { "fmi3OK", "fmi3Warning", "fmi3Discard", "fmi3Error", "fmi3Fatal" };
    return (unsigned)s < sizeof names / sizeof names[0] ? names[s] : "(not an fmi3Status)";
}

fmi3ValueReference state3_vr(int i) { return md_var(md_state_index(i))->vr; }
fmi3ValueReference derivative3_vr(int i) { return md_var(MD_DERIVATIVES[i].index)->vr; }

bool state3_is_cs(State3 s)
{
    return s >= C3_INSTANTIATED;
}

bool state3_event_mode_used(State3 s)
{
    return s == C3_EVENT || s == C3_STEP_EM || s == C3_EVENT_AGAIN;
}

/* Co-Simulation with a compliant contact of epsilon 0.05 (the profile's knob)
 * keeps CVODE's steps few. */
#define CS_EPSILON 0.05
#define CS_STEP 0.02

#define TRY(call)                      \
    do {                               \
        if (st == fmi3OK) st = (call); \
    } while (0)

static fmi3Status cs_initialize(Inst3 *in)
{
    const fmi3ValueReference vr = PROFILE_KNOB;
    const double value = PROFILE_KNOB_VALUE(CS_EPSILON);
    fmi3Status st = f->SetFloat64(in->c, &vr, 1, &value, 1);
    TRY(f->EnterInitializationMode(in->c, fmi3False, 0, 0, fmi3False, 0));
    in->t = 0;
    return st;
}

/* fmi3ExitInitializationMode, and with Event Mode the initial event update
 * and fmi3EnterStepMode. */
static fmi3Status cs_exit_initialization(Inst3 *in, bool to_step_mode)
{
    bool changed;
    fmi3Status st = f->ExitInitializationMode(in->c);
    if (in->event_mode && to_step_mode) {
        TRY(harness3_update_discrete_states(f, in->c, &changed));
        TRY(f->EnterStepMode(in->c));
    }
    return st;
}

static fmi3Status euler_step_from(Inst3 *in, double h)
{
    double x[MODEL_NX], dx[MODEL_NX];
    fmi3Boolean enter_event = fmi3False, terminate = fmi3False;
    fmi3Status st = f->GetContinuousStates(in->c, x, MODEL_NX);
    TRY(f->GetContinuousStateDerivatives(in->c, dx, MODEL_NX));
    for (int i = 0; i < MODEL_NX; ++i) x[i] += h * dx[i];
    TRY(f->SetTime(in->c, in->t + h));
    TRY(f->SetContinuousStates(in->c, x, MODEL_NX));
    TRY(f->CompletedIntegratorStep(in->c, fmi3True, &enter_event, &terminate));
    if (st == fmi3OK) in->t += h;
    return st;
}

static fmi3Status me_initialize(Inst3 *in)
{
    in->t = 0;
    return f->EnterInitializationMode(in->c, fmi3True, 1e-6, 0, fmi3True, 1);
}

static fmi3Status me_event_update_then_continuous(Inst3 *in)
{
    bool changed;
    fmi3Status st = harness3_update_discrete_states(f, in->c, &changed);
    TRY(f->EnterContinuousTimeMode(in->c));
    return st;
}

/* The first fixed Float64 parameter of the model description set to its start value. */
static fmi3Status set_fixed_parameter3(Inst3 *in)
{
    const MdVariable *p = md_var(md_first(MD_PARAMETER, MD_FIXED));
    if (!CHECK(p != NULL, "the model description has no fixed Float64 parameter")) return fmi3Fatal;
    return f->SetFloat64(in->c, &p->vr, 1, &p->start, 1);
}

bool inst3_reach(Inst3 *in, State3 state, bool logging)
{
    const bool cs = state3_is_cs(state);
    *in = (Inst3){ .state = state, .event_mode = state3_event_mode_used(state) };
    in->c = cs ? harness3_instantiate_cs(f, "cs rod", logging, in->event_mode, in->event_mode)
               : harness3_instantiate_me(f, "me rod", logging);
    if (!CHECK(in->c != NULL, "fmi3Instantiate for %s failed: %s", STATE3_NAME[state], harness.last_message))
        return false;
    fmi3Status st = fmi3OK;
    switch (state) {
    case M3_INSTANTIATED: case C3_INSTANTIATED: break;
    case M3_INIT: st = me_initialize(in); break;
    case M3_EVENT:
        st = me_initialize(in);
        TRY(f->ExitInitializationMode(in->c));
        break;
    case M3_CONTINUOUS: case M3_EVENT_AGAIN: case M3_TERMINATED: case M3_ERROR:
        st = me_initialize(in);
        TRY(f->ExitInitializationMode(in->c));
        TRY(me_event_update_then_continuous(in));
        if (state == M3_CONTINUOUS) break;
        /* A short Euler step, then an event. */
        TRY(euler_step_from(in, 1e-7));
        TRY(f->EnterEventMode(in->c));
        if (state == M3_TERMINATED) TRY(f->Terminate(in->c));
        /* A fixed parameter set after initialization is an error. */
        if (state == M3_ERROR && st == fmi3OK) st = set_fixed_parameter3(in) == fmi3Error ? fmi3OK : fmi3Fatal;
        break;
    case C3_INIT: st = cs_initialize(in); break;
    case C3_EVENT:
        st = cs_initialize(in);
        TRY(cs_exit_initialization(in, false));
        break;
    default: /* Step Mode, after it Event Mode, Terminated, Error */
        st = cs_initialize(in);
        TRY(cs_exit_initialization(in, true));
        for (int k = 0; k < 3; ++k) TRY(harness3_do_step(f, in->c, &in->t, CS_STEP, NULL));
        if (state == C3_EVENT_AGAIN) TRY(f->EnterEventMode(in->c));
        if (state == C3_TERMINATED) TRY(f->Terminate(in->c));
        if (state == C3_ERROR && st == fmi3OK) { /* a step of NaN is an error */
            fmi3Boolean e, t, r;
            double last;
            st = f->DoStep(in->c, in->t, NAN, fmi3True, &e, &t, &r, &last) == fmi3Error ? fmi3OK : fmi3Fatal;
        }
        break;
    }
    if (!CHECK(st == fmi3OK, "reaching %s: %s (%s)", STATE3_NAME[state], status3_name(st), harness.last_message)) {
        f->FreeInstance(in->c);
        in->c = NULL;
        return false;
    }
    return true;
}

void inst3_free(Inst3 *in)
{
    f->FreeInstance(in->c);
    in->c = NULL;
}

void check3_error_reported(const char *what, const char *call, long errors_before)
{
    CHECK(harness.error_messages > errors_before, "%s returned fmi3Error without logging an error", what);
    CHECK(names_call(harness.last_error, call), "%s: the error message does not name %s: '%s'", what, call,
          harness.last_error);
}

/* Every Float64 variable read (the event indicators and time too), each finite. */
static fmi3Status read_floats(Inst3 *in)
{
    fmi3ValueReference vr[64];
    double v[64];
    size_t n = 0;
    for (int k = 1; k <= MD_N_VARIABLES && n < 64; ++k)
        if (md_var(k)->type == MD_REAL) vr[n++] = md_var(k)->vr;
    const fmi3Status st = f->GetFloat64(in->c, vr, n, v, n);
    for (size_t i = 0; st == fmi3OK && i < n; ++i)
        CHECK(isfinite(v[i]), "Float64 with value reference %u = %g", vr[i], v[i]);
    return st;
}

/* Terminated (and Error, which is Terminated): a simulation call refused, a
 * getter allowed, then fmi3Reset (§2.3.1: "Otherwise fmi3FreeInstance or
 * fmi3Reset must be called"). */
static fmi3Status terminated_rules(Inst3 *in, const char *what)
{
    const long errors_before = harness.error_messages;
    fmi3Status st;
    const char *refused;
    if (state3_is_cs(in->state)) {
        fmi3Boolean e, t, r;
        double last;
        refused = "fmi3DoStep";
        st = f->DoStep(in->c, in->t, CS_STEP, fmi3True, &e, &t, &r, &last);
    } else {
        refused = "fmi3SetTime";
        st = f->SetTime(in->c, in->t + 1e-9);
    }
    CHECK(st == fmi3Error, "%s: %s accepted in %s (%s)", what, refused, STATE3_NAME[in->state], status3_name(st));
    if (st == fmi3Error) check3_error_reported(what, refused, errors_before);
    st = read_floats(in);
    CHECK(st == fmi3OK, "%s: fmi3GetFloat64 refused in %s: %s (%s)", what, STATE3_NAME[in->state],
          status3_name(st), harness.last_message);
    in->t = 0;
    return f->Reset(in->c);
}

void inst3_works(Inst3 *in, const char *what)
{
    fmi3Status st = fmi3OK;
    switch (in->state) {
    case M3_TERMINATED: case M3_ERROR:
        st = terminated_rules(in, what);
        /* fall through */
    case M3_INSTANTIATED:
        TRY(me_initialize(in));
        /* fall through */
    case M3_INIT:
        TRY(f->ExitInitializationMode(in->c));
        /* fall through */
    case M3_EVENT: case M3_EVENT_AGAIN:
        TRY(me_event_update_then_continuous(in));
        /* fall through */
    case M3_CONTINUOUS:
        TRY(euler_step_from(in, 1e-6));
        TRY(read_floats(in));
        break;
    case C3_TERMINATED: case C3_ERROR:
        st = terminated_rules(in, what);
        /* fall through */
    case C3_INSTANTIATED:
        TRY(cs_initialize(in));
        /* fall through */
    case C3_INIT:
        TRY(cs_exit_initialization(in, true));
        goto step;
    case C3_EVENT: case C3_EVENT_AGAIN: {
        bool changed;
        TRY(harness3_update_discrete_states(f, in->c, &changed));
        TRY(f->EnterStepMode(in->c));
    }
        /* fall through */
    case C3_STEP: case C3_STEP_EM:
    step:
        TRY(harness3_do_step(f, in->c, &in->t, CS_STEP, NULL));
        TRY(read_floats(in));
        break;
    default: break;
    }
    CHECK(st == fmi3OK, "%s: the instance (%s) no longer works: %s (%s)", what, STATE3_NAME[in->state],
          status3_name(st), harness.last_message);
}
