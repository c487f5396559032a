/* SPDX-License-Identifier: BSD-2-Clause */
/* Instances brought to each state of FMI 2.0.4's state machines, and the
 * runs that show an instance still works after a call (see driver.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robustness.h"

static const FmiApi *const f = &api;

const char *const STATE_NAME[N_STATES] = {
    "ME Instantiated", "ME InitializationMode", "ME EventMode (initial)", "ME ContinuousTimeMode",
    "ME EventMode (after integration)", "ME Terminated", "ME Error",
    "CS Instantiated", "CS InitializationMode", "CS StepComplete", "CS Terminated", "CS Error",
};

bool state_is_cs(State s)
{
    return s >= CS_INSTANTIATED;
}

/* Co-Simulation runs with a compliant contact of epsilon 0.05 (the profile's
 * knob): CVODE's steps through the contact stay few, so that the many
 * instances remain cheap. */
#define CS_EPSILON 0.05
#define CS_STEP 0.02

#define TRY(call)                      \
    do {                               \
        if (st == fmi2OK) st = (call); \
    } while (0)

/* What inst_works is doing, as long as all went well. */
#define STAGE(text)                    \
    do {                               \
        if (st == fmi2OK) doing = text; \
    } while (0)

static fmi2Status cs_initialize(Inst *in)
{
    const fmi2ValueReference vr = PROFILE_KNOB;
    const double value = PROFILE_KNOB_VALUE(CS_EPSILON);
    fmi2Status st = f->SetupExperiment(in->c, fmi2False, 0, 0, fmi2False, 0);
    TRY(f->SetReal(in->c, &vr, 1, &value));
    TRY(f->EnterInitializationMode(in->c));
    in->t = 0;
    return st;
}

static fmi2Status euler_step_from(Inst *in, double h)
{
    double x[MODEL_NX], dx[MODEL_NX];
    fmi2Boolean enter_event = fmi2False, terminate = fmi2False;
    fmi2Status st = f->GetContinuousStates(in->c, x, MODEL_NX);
    TRY(f->GetDerivatives(in->c, dx, MODEL_NX));
    for (int i = 0; i < MODEL_NX; ++i) x[i] += h * dx[i];
    TRY(f->SetTime(in->c, in->t + h));
    TRY(f->SetContinuousStates(in->c, x, MODEL_NX));
    TRY(f->CompletedIntegratorStep(in->c, fmi2True, &enter_event, &terminate));
    if (st == fmi2OK) in->t += h;
    return st;
}

fmi2Status set_fixed_parameter(Inst *in)
{
    const MdVariable *p = md_var(md_first(MD_PARAMETER, MD_FIXED));
    if (!CHECK(p != NULL, "modelDescription.xml has no fixed Real parameter")) return fmi2Fatal;
    const fmi2ValueReference vr = p->vr;
    return f->SetReal(in->c, &vr, 1, &p->start);
}

bool inst_reach(Inst *in, State state, bool logging)
{
    const bool cs = state_is_cs(state);
    *in = (Inst){ .state = state };
    in->c = f->Instantiate(cs ? "cs rod" : "me rod", cs ? fmi2CoSimulation : fmi2ModelExchange, harness_guid,
                           "file:///nonexistent/resources", &harness_callbacks, fmi2False,
                           logging ? fmi2True : fmi2False);
    if (!CHECK(in->c != NULL, "fmi2Instantiate for %s failed: %s", STATE_NAME[state], harness.last_message))
        return false;
    fmi2Status st = fmi2OK;
    bool changed;
    if (cs) {
        if (state >= CS_INIT) st = cs_initialize(in);
        if (state >= CS_STEP_COMPLETE) TRY(f->ExitInitializationMode(in->c));
        for (int k = 0; k < 3 && state >= CS_STEP_COMPLETE; ++k) {
            TRY(f->DoStep(in->c, in->t, CS_STEP, fmi2True));
            if (st == fmi2OK) in->t += CS_STEP;
        }
        if (state == CS_TERMINATED) TRY(f->Terminate(in->c));
        /* A step of NaN is an error. */
        if (state == CS_ERROR && st == fmi2OK) st = f->DoStep(in->c, in->t, NAN, fmi2True) == fmi2Error ? fmi2OK : fmi2Fatal;
    } else {
        if (state >= ME_INIT) {
            st = f->SetupExperiment(in->c, fmi2True, 1e-6, 0, fmi2True, 1);
            TRY(f->EnterInitializationMode(in->c));
        }
        if (state >= ME_EVENT) TRY(f->ExitInitializationMode(in->c));
        if (state >= ME_CONTINUOUS && st == fmi2OK) st = harness_event_iteration(f, in->c, &changed);
        if (state >= ME_EVENT_AGAIN) {
            /* A short Euler step with the default epsilon, then an event. */
            TRY(euler_step_from(in, 1e-7));
            TRY(f->EnterEventMode(in->c));
        }
        if (state == ME_TERMINATED) TRY(f->Terminate(in->c));
        if (state == ME_ERROR && st == fmi2OK)
            st = set_fixed_parameter(in) == fmi2Error ? fmi2OK : fmi2Fatal;
    }
    if (!CHECK(st == fmi2OK, "reaching %s: %s (%s)", STATE_NAME[state], status_name(st), harness.last_message)) {
        f->FreeInstance(in->c);
        in->c = NULL;
        return false;
    }
    return true;
}

void inst_free(Inst *in)
{
    f->FreeInstance(in->c);
    in->c = NULL;
    CHECK(harness.live == 0, "%ld blocks allocated through allocateMemory are not freed after fmi2FreeInstance",
          harness.live);
}

void check_error_reported(const char *what, const char *call, long errors_before)
{
    CHECK(harness.error_messages > errors_before, "%s returned fmi2Error without logging an error", what);
    CHECK(names_call(harness.last_error, call), "%s: the error message does not name %s: '%s'", what, call,
          harness.last_error);
}

/* Every Real variable read, each finite. */
static fmi2Status read_reals(Inst *in)
{
    fmi2ValueReference vr[64];
    double v[64];
    size_t n = 0;
    for (int k = 1; k <= MD_N_VARIABLES && n < 64; ++k)
        if (md_var(k)->type == MD_REAL) vr[n++] = md_var(k)->vr;
    const fmi2Status st = f->GetReal(in->c, vr, n, v);
    for (size_t i = 0; st == fmi2OK && i < n; ++i)
        CHECK(isfinite(v[i]), "Real with value reference %u = %g", vr[i], v[i]);
    return st;
}

/* A call that the Error state refuses, then a getter that it allows, then
 * fmi2Reset (FMI 2.0.4 §2.1.3: "fmi2FreeInstance or fmi2Reset must be called"). */
static fmi2Status error_state_rules(Inst *in, const char *what)
{
    const long errors_before = harness.error_messages;
    fmi2Status st;
    const char *refused;
    if (state_is_cs(in->state)) {
        refused = "fmi2DoStep";
        st = f->DoStep(in->c, in->t, CS_STEP, fmi2True);
    } else {
        refused = "fmi2SetTime";
        st = f->SetTime(in->c, in->t + 1e-9);
    }
    CHECK(st == fmi2Error, "%s: %s accepted in the Error state (%s)", what, refused, status_name(st));
    if (st == fmi2Error) check_error_reported(what, refused, errors_before);
    st = read_reals(in);
    CHECK(st == fmi2OK, "%s: fmi2GetReal refused in the Error state: %s (%s)", what, status_name(st),
          harness.last_message);
    return f->Reset(in->c);
}

void inst_works(Inst *in, const char *what)
{
    fmi2Status st = fmi2OK;
    bool changed;
    const char *doing = "";
    switch (in->state) {
    case ME_ERROR:
        STAGE("the Error state's rules and fmi2Reset");
        st = error_state_rules(in, what);
        in->t = 0;
        goto instantiated;
    case ME_TERMINATED:
        STAGE("reading, fmi2Reset");
        st = read_reals(in);
        TRY(f->Reset(in->c));
        in->t = 0;
        /* fall through */
    case ME_INSTANTIATED:
    instantiated:
        STAGE("initialization");
        TRY(f->SetupExperiment(in->c, fmi2True, 1e-6, in->t, fmi2False, 0));
        TRY(f->EnterInitializationMode(in->c));
        /* fall through */
    case ME_INIT:
        STAGE("fmi2ExitInitializationMode");
        TRY(f->ExitInitializationMode(in->c));
        /* fall through */
    case ME_EVENT:
    case ME_EVENT_AGAIN:
        STAGE("the event iteration");
        if (st == fmi2OK) st = harness_event_iteration(f, in->c, &changed);
        /* fall through */
    case ME_CONTINUOUS:
        STAGE("an integration step and reading");
        TRY(euler_step_from(in, 1e-6));
        TRY(read_reals(in));
        break;
    case CS_ERROR:
        STAGE("the Error state's rules and fmi2Reset");
        st = error_state_rules(in, what);
        goto cs_instantiated;
    case CS_TERMINATED:
        STAGE("reading, fmi2Reset");
        st = read_reals(in);
        TRY(f->Reset(in->c));
        /* fall through */
    case CS_INSTANTIATED:
    cs_instantiated:
        STAGE("initialization");
        TRY(cs_initialize(in));
        /* fall through */
    case CS_INIT:
        STAGE("fmi2ExitInitializationMode");
        TRY(f->ExitInitializationMode(in->c));
        /* fall through */
    case CS_STEP_COMPLETE:
        STAGE("a communication step and reading");
        TRY(f->DoStep(in->c, in->t, CS_STEP, fmi2True));
        if (st == fmi2OK) in->t += CS_STEP;
        TRY(read_reals(in));
        break;
    default: break;
    }
    CHECK(st == fmi2OK, "%s: the instance (%s) no longer works: %s: %s (%s)", what, STATE_NAME[in->state], doing,
          status_name(st), harness.last_message);
}

/* ------------------------------------- what the robustness tests share */

/* A new instance brought to `state` (driver.h), logging off, or NULL. */
fmi2Component instance_in(State state)
{
    Inst in;
    return inst_reach(&in, state, false) ? in.c : NULL;
}

void free_instance(fmi2Component c)
{
    Inst in = { .c = c };
    inst_free(&in);
}

/* After an fmi2Error: a message naming a call, and the Error state (no
 * simulation call accepted, getters still are). */
void check_error_handling(fmi2Component c, const char *what, long errors_before)
{
    CHECK(harness.error_messages > errors_before, "%s returned fmi2Error without logging an error", what);
    CHECK(strstr(harness.last_error, "fmi2") != NULL, "%s: error message names no call: '%s'", what,
          harness.last_error);
    double x[MODEL_NX];
    CHECK(f->SetTime(c, 0) == fmi2Error, "%s: fmi2SetTime accepted in the Error state", what);
    CHECK(f->EnterContinuousTimeMode(c) == fmi2Error, "%s: fmi2EnterContinuousTimeMode accepted in the Error state",
          what);
    CHECK(f->SetReal(c, NULL, 0, NULL) == fmi2Error, "%s: fmi2SetReal accepted in the Error state", what);
    CHECK(f->GetContinuousStates(c, x, MODEL_NX) == fmi2OK, "%s: fmi2GetContinuousStates refused in the Error state",
          what);
}

/* fmi2Reset from any state gives an instance that simulates. */
void check_reset_recovers(fmi2Component c, const char *what)
{
    if (!CHECK(f->Reset(c) == fmi2OK, "%s: fmi2Reset failed", what)) return;
    EulerSim s = { .c = c };
    const fmi2Status st = harness_simulate(f, &s, 0.1, 5e-3, 20);
    CHECK(st == fmi2OK, "%s: simulation after fmi2Reset: %s (%s)", what, status_name(st), harness.last_message);
}

/* The value references of the Real variables of modelDescription.xml; their number. */
size_t real_vrs(fmi2ValueReference vr[MAX_VARS])
{
    size_t n = 0;
    for (int k = 1; k <= MD_N_VARIABLES && n < MAX_VARS; ++k)
        if (md_var(k)->type == MD_REAL) vr[n++] = md_var(k)->vr;
    return n;
}

/* The first variable of `type`; VR_COUNT (no variable) if the model has none. */
fmi2ValueReference first_of_type(MdType type)
{
    for (int k = 1; k <= MD_N_VARIABLES; ++k)
        if (md_var(k)->type == type) return md_var(k)->vr;
    return VR_COUNT;
}

/* Every Real read; each finite. */
fmi2Status get_all_reals(fmi2Component c)
{
    fmi2ValueReference vr[MAX_VARS];
    double v[MAX_VARS];
    const size_t n = real_vrs(vr);
    const fmi2Status st = f->GetReal(c, vr, n, v);
    for (size_t i = 0; st == fmi2OK && i < n; ++i) CHECK(isfinite(v[i]), "Real %u = %g", vr[i], v[i]);
    return st;
}

fmi2Status set_one(fmi2Component c, fmi2ValueReference vr, double value)
{
    return f->SetReal(c, &vr, 1, &value);
}
