/* SPDX-License-Identifier: BSD-2-Clause */
/* Every FMI 2.0 call in every state of both state machines, to the letter
 * of FMI 2.0.4: the tables of §3.2.3 (Model Exchange) and §4.2.4
 * (Co-Simulation), the status queries of §4.2.3 and the Error state of §2.1.3.
 *
 * A row is a call with legal arguments, the states the standard allows it
 * in, the status it must return there and where it leaves the instance.
 * Where it is not allowed it must return fmi2Error and log a message naming
 * it. Either way the instance must still work afterwards: inst_works runs an
 * integration step, a communication step or initialization from the state
 * the call left it in, and from the Error state checks that a refused call is
 * refused, a getter answers and fmi2Reset leads to a new run.
 *
 * The calls that read or set variables are checked variable by variable from
 * modelDescription.xml (test_conformance_variables, conformance_variables.c),
 * with the numbered conditions of the two tables. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conformance.h"

static const FmiApi *const f = &api;

/* ---------------------------------------------------------- the calls */

typedef fmi2Status RowFn(Inst *in);

static fmi2Status debug_logging_all(Inst *in) { return f->SetDebugLogging(in->c, fmi2True, 0, NULL); }
static fmi2Status debug_logging_one(Inst *in)
{
    const fmi2String cat[] = { "logEvents" };
    return f->SetDebugLogging(in->c, fmi2False, 1, cat);
}
static fmi2Status setup_experiment(Inst *in) { return f->SetupExperiment(in->c, fmi2True, 1e-6, 0, fmi2False, 0); }
/* fmi2SetupExperiment must come first (§2.1.6); where it is refused the
 * instance is in Error and fmi2EnterInitializationMode must be refused too. */
static fmi2Status enter_initialization(Inst *in)
{
    if (in->state == ME_INSTANTIATED || in->state == CS_INSTANTIATED) {
        const fmi2Status st = setup_experiment(in);
        if (st != fmi2OK) return st;
    }
    return f->EnterInitializationMode(in->c);
}
static fmi2Status exit_initialization(Inst *in) { return f->ExitInitializationMode(in->c); }
static fmi2Status terminate(Inst *in) { return f->Terminate(in->c); }
static fmi2Status reset(Inst *in) { return f->Reset(in->c); }
static fmi2Status get_real_none(Inst *in) { return f->GetReal(in->c, NULL, 0, NULL); }
static fmi2Status get_integer_none(Inst *in) { return f->GetInteger(in->c, NULL, 0, NULL); }
static fmi2Status get_boolean_none(Inst *in) { return f->GetBoolean(in->c, NULL, 0, NULL); }
static fmi2Status get_string_none(Inst *in) { return f->GetString(in->c, NULL, 0, NULL); }
static fmi2Status set_real_none(Inst *in) { return f->SetReal(in->c, NULL, 0, NULL); }
static fmi2Status set_integer_none(Inst *in) { return f->SetInteger(in->c, NULL, 0, NULL); }
static fmi2Status set_boolean_none(Inst *in) { return f->SetBoolean(in->c, NULL, 0, NULL); }
static fmi2Status set_string_none(Inst *in) { return f->SetString(in->c, NULL, 0, NULL); }

/* Worst of two statuses, for calls made in sequence. */
static fmi2Status worst(fmi2Status a, fmi2Status b) { return a > b ? a : b; }

static fmi2Status get_and_free_state(Inst *in)
{
    fmi2FMUstate s = NULL;
    const fmi2Status st = f->GetFMUstate(in->c, &s);
    if (st != fmi2OK) return st;
    return f->FreeFMUstate(in->c, &s);
}
static fmi2Status set_state_just_taken(Inst *in)
{
    fmi2FMUstate s = NULL;
    fmi2Status st = f->GetFMUstate(in->c, &s);
    if (st != fmi2OK) return st;
    st = f->SetFMUstate(in->c, s);
    return worst(st, f->FreeFMUstate(in->c, &s));
}
static fmi2Status serialize_round_trip(Inst *in)
{
    fmi2FMUstate s = NULL, t = NULL;
    size_t size = 0;
    fmi2Status st = f->GetFMUstate(in->c, &s);
    if (st != fmi2OK) return st;
    st = f->SerializedFMUstateSize(in->c, s, &size);
    fmi2Byte *bytes = st == fmi2OK ? malloc(size ? size : 1) : NULL;
    if (bytes) st = worst(st, f->SerializeFMUstate(in->c, s, bytes, size));
    if (bytes && st == fmi2OK) st = f->DeSerializeFMUstate(in->c, bytes, size, &t);
    if (st == fmi2OK) st = f->SetFMUstate(in->c, t);
    if (t) st = worst(st, f->FreeFMUstate(in->c, &t));
    free(bytes);
    return worst(st, f->FreeFMUstate(in->c, &s));
}
/* Derivatives by states: the first and last <Derivatives> by their states, in
 * every state that allows the call (states have initial = "exact": knowns of
 * Initialization Mode too). */
static fmi2Status directional_derivative(Inst *in)
{
    const int last = MD_N_DERIVATIVES - 1;
    const fmi2ValueReference unknown[2] = { md_var(MD_DERIVATIVES[0].index)->vr,
                                            md_var(MD_DERIVATIVES[last].index)->vr },
                             known[2] = { md_var(md_state_index(0))->vr, md_var(md_state_index(last))->vr };
    const double seed[2] = { 1, -0.5 };
    double out[2] = { NAN, NAN };
    const fmi2Status st = f->GetDirectionalDerivative(in->c, unknown, 2, known, 2, seed, out);
    if (st == fmi2OK) CHECK(isfinite(out[0]) && isfinite(out[1]), "directional derivative %g, %g", out[0], out[1]);
    return st;
}
static fmi2Status enter_event_mode(Inst *in) { return f->EnterEventMode(in->c); }
static fmi2Status new_discrete_states(Inst *in)
{
    fmi2EventInfo info;
    return f->NewDiscreteStates(in->c, &info);
}
/* The event iteration first where it is allowed (§3.2.2: continuous-time
 * mode is entered once newDiscreteStatesNeeded is false). */
static fmi2Status enter_continuous_time_mode(Inst *in)
{
    if (in->state == ME_EVENT || in->state == ME_EVENT_AGAIN) {
        fmi2EventInfo info = { .newDiscreteStatesNeeded = fmi2True };
        for (int k = 0; k < 100 && info.newDiscreteStatesNeeded; ++k) {
            const fmi2Status st = f->NewDiscreteStates(in->c, &info);
            if (st != fmi2OK) return st;
        }
    }
    return f->EnterContinuousTimeMode(in->c);
}
static fmi2Status completed_integrator_step(Inst *in)
{
    fmi2Boolean enter = 7, terminate_ = 7;
    const fmi2Status st = f->CompletedIntegratorStep(in->c, fmi2True, &enter, &terminate_);
    if (st == fmi2OK) CHECK(enter == fmi2False || enter == fmi2True, "enterEventMode = %d", enter);
    return st;
}
static fmi2Status set_time(Inst *in)
{
    const fmi2Status st = f->SetTime(in->c, in->t + 1e-9);
    if (st == fmi2OK) in->t += 1e-9;
    return st;
}
/* The states' start values (modelDescription.xml). */
static void start_states(double x[MODEL_NX])
{
    for (int i = 0; i < MODEL_NX; ++i) x[i] = md_var(md_state_index(i))->start;
}
/* The current states where they can be set (Continuous-Time Mode), else the start values. */
static fmi2Status set_continuous_states(Inst *in)
{
    double x[MODEL_NX];
    start_states(x);
    if (in->state == ME_CONTINUOUS)
        CHECK(f->GetContinuousStates(in->c, x, MODEL_NX) == fmi2OK, "fmi2GetContinuousStates");
    return f->SetContinuousStates(in->c, x, MODEL_NX);
}
static fmi2Status get_array(Inst *in, fmi2GetDerivativesTYPE *get, size_t n)
{
    double v[MODEL_NX + HARNESS_NZ];
    for (size_t i = 0; i < n; ++i) v[i] = NAN;
    const fmi2Status st = get(in->c, v, n);
    for (size_t i = 0; st == fmi2OK && i < n; ++i) CHECK(isfinite(v[i]), "element %zu = %g", i, v[i]);
    return st;
}
static fmi2Status get_event_indicators(Inst *in) { return get_array(in, f->GetEventIndicators, MODEL_NZ); }
static fmi2Status get_continuous_states(Inst *in) { return get_array(in, f->GetContinuousStates, MODEL_NX); }
static fmi2Status get_derivatives(Inst *in) { return get_array(in, f->GetDerivatives, MODEL_NX); }
static fmi2Status get_nominals(Inst *in) { return get_array(in, f->GetNominalsOfContinuousStates, MODEL_NX); }
/* canInterpolateInputs is false and maxOutputDerivativeOrder = 0 in every
 * model: nvr = 0 is the call an importer may make. */
static fmi2Status set_input_derivatives(Inst *in) { return f->SetRealInputDerivatives(in->c, NULL, 0, NULL, NULL); }
static fmi2Status get_output_derivatives(Inst *in) { return f->GetRealOutputDerivatives(in->c, NULL, 0, NULL, NULL); }
static fmi2Status do_step(Inst *in)
{
    const fmi2Status st = f->DoStep(in->c, in->t, 0.01, fmi2True);
    if (st == fmi2OK) in->t += 0.01;
    return st;
}
static fmi2Status cancel_step(Inst *in) { return f->CancelStep(in->c); }

static fmi2Status status_do_step(Inst *in)
{
    fmi2Status v;
    return f->GetStatus(in->c, fmi2DoStepStatus, &v);
}
static fmi2Status status_pending(Inst *in)
{
    fmi2Status v;
    return f->GetStatus(in->c, fmi2PendingStatus, &v);
}
/* The end of the last communication step, the time the instance is at. */
static fmi2Status real_status_last_time(Inst *in)
{
    fmi2Real v = NAN;
    const fmi2Status st = f->GetRealStatus(in->c, fmi2LastSuccessfulTime, &v);
    if (st == fmi2OK && state_is_cs(in->state))
        CHECK(v == in->t, "fmi2LastSuccessfulTime = %.17g, the last step ended at %.17g", v, in->t);
    return st;
}
static fmi2Status real_status_other(Inst *in)
{
    fmi2Real v;
    return f->GetRealStatus(in->c, fmi2DoStepStatus, &v);
}
static fmi2Status integer_status(Inst *in)
{
    fmi2Integer v;
    return f->GetIntegerStatus(in->c, fmi2DoStepStatus, &v);
}
/* Every step returned fmi2OK: the slave never asked to terminate. */
static fmi2Status boolean_status_terminated(Inst *in)
{
    fmi2Boolean v = 7;
    const fmi2Status st = f->GetBooleanStatus(in->c, fmi2Terminated, &v);
    if (st == fmi2OK && state_is_cs(in->state))
        CHECK(v == fmi2False, "fmi2Terminated = %d after steps that all returned fmi2OK", v);
    return st;
}
static fmi2Status boolean_status_other(Inst *in)
{
    fmi2Boolean v;
    return f->GetBooleanStatus(in->c, fmi2PendingStatus, &v);
}
static fmi2Status string_status(Inst *in)
{
    fmi2String v;
    return f->GetStringStatus(in->c, fmi2PendingStatus, &v);
}
static fmi2Status string_status_other(Inst *in)
{
    fmi2String v;
    return f->GetStringStatus(in->c, fmi2LastSuccessfulTime, &v);
}

/* ---------------------------------------------------------- the table */

typedef struct {
    const char *call; /* the function, which an error message must name */
    const char *args;
    RowFn *run;
    unsigned allowed;    /* the states in which the standard allows it */
    fmi2Status expected; /* its status there */
    Next next;
} Row;

/* The columns (driver.h): ME Instantiated, InitializationMode, EventMode (two
 * ways in), ContinuousTimeMode, Terminated, Error; CS Instantiated,
 * InitializationMode, StepComplete, Terminated, Error. */
#define M_I B(ME_INSTANTIATED)
#define M_N B(ME_INIT)
#define M_E ME_EVENT_MODE
#define M_C B(ME_CONTINUOUS)
#define M_T B(ME_TERMINATED)
#define M_X B(ME_ERROR)
#define C_I B(CS_INSTANTIATED)
#define C_N B(CS_INIT)
#define C_S B(CS_STEP_COMPLETE)
#define C_T B(CS_TERMINATED)
#define C_X B(CS_ERROR)
/* Getters: "2" in InitializationMode (with nvr = 0 nothing breaks the
 * condition), "x" in Event, Continuous-Time, StepComplete and Terminated,
 * "7" (always, values for debugging) in Error. */
#define GETTERS (M_N | M_E | M_C | M_T | M_X | C_N | C_S | C_T | C_X)

static const Row ROWS[] = {
    /* §2.1.4-2.1.6, both tables */
    { "fmi2SetDebugLogging", "(on, all categories)", debug_logging_all, ME_ALL | CS_ALL, fmi2OK, SAME },
    { "fmi2SetDebugLogging", "(off, logEvents)", debug_logging_one, ME_ALL | CS_ALL, fmi2OK, SAME },
    { "fmi2SetupExperiment", "", setup_experiment, M_I | C_I, fmi2OK, SAME },
    { "fmi2EnterInitializationMode", "", enter_initialization, M_I | C_I, fmi2OK, TO_INIT },
    { "fmi2ExitInitializationMode", "", exit_initialization, M_N | C_N, fmi2OK, TO_INITIALIZED },
    /* CS: stepComplete and stepFailed; ME: Event and Continuous-Time Mode. */
    { "fmi2Terminate", "", terminate, M_E | M_C | C_S, fmi2OK, TO_TERMINATED },
    { "fmi2Reset", "", reset, ME_ALL | CS_ALL, fmi2OK, TO_INSTANTIATED },
    /* §2.1.7 */
    { "fmi2GetReal", "(nvr = 0)", get_real_none, GETTERS, fmi2OK, SAME },
    { "fmi2GetInteger", "(nvr = 0)", get_integer_none, GETTERS, fmi2OK, SAME },
    { "fmi2GetBoolean", "(nvr = 0)", get_boolean_none, GETTERS, fmi2OK, SAME },
    { "fmi2GetString", "(nvr = 0)", get_string_none, GETTERS, fmi2OK, SAME },
    /* ME: 1, 3, 4, 5 (Real only in Continuous-Time Mode); CS: 1, 3, 6. */
    { "fmi2SetReal", "(nvr = 0)", set_real_none, M_I | M_N | M_E | M_C | C_I | C_N | C_S, fmi2OK, SAME },
    { "fmi2SetInteger", "(nvr = 0)", set_integer_none, M_I | M_N | M_E | C_I | C_N | C_S, fmi2OK, SAME },
    { "fmi2SetBoolean", "(nvr = 0)", set_boolean_none, M_I | M_N | M_E | C_I | C_N | C_S, fmi2OK, SAME },
    { "fmi2SetString", "(nvr = 0)", set_string_none, M_I | M_N | M_E | C_I | C_N | C_S, fmi2OK, SAME },
    /* §2.1.8: everywhere but start and fatal; fmi2GetFMUstate "7" in Error. */
    { "fmi2GetFMUstate", "(then fmi2FreeFMUstate)", get_and_free_state, ME_ALL | CS_ALL, fmi2OK, SAME },
    { "fmi2SetFMUstate", "(of the state just taken)", set_state_just_taken, ME_ALL | CS_ALL, fmi2OK, SAME },
    { "fmi2SerializeFMUstate", "(size, serialize, deserialize, set, free)", serialize_round_trip, ME_ALL | CS_ALL,
      fmi2OK, SAME },
    /* §2.1.9 */
    { "fmi2GetDirectionalDerivative", "(der(v), der(w) by y, theta)", directional_derivative, GETTERS, fmi2OK,
      SAME },
    /* §3.2, Model Exchange only: "8" (a pure discrete-time FMU) does not
     * apply to fmi2SetTime in Event Mode, every model has continuous states. */
    { "fmi2EnterEventMode", "", enter_event_mode, M_E | M_C, fmi2OK, TO_EVENT },
    { "fmi2NewDiscreteStates", "", new_discrete_states, M_E, fmi2OK, SAME },
    { "fmi2EnterContinuousTimeMode", "(after the event iteration)", enter_continuous_time_mode, M_E, fmi2OK,
      TO_CONTINUOUS },
    { "fmi2CompletedIntegratorStep", "", completed_integrator_step, M_C, fmi2OK, SAME },
    { "fmi2SetTime", "(t + 1e-9)", set_time, M_C, fmi2OK, SAME },
    { "fmi2SetContinuousStates", "(the current states)", set_continuous_states, M_C, fmi2OK, SAME },
    { "fmi2GetEventIndicators", "", get_event_indicators, M_N | M_E | M_C | M_T | M_X, fmi2OK, SAME },
    { "fmi2GetContinuousStates", "", get_continuous_states, M_N | M_E | M_C | M_T | M_X, fmi2OK, SAME },
    { "fmi2GetDerivatives", "", get_derivatives, M_N | M_E | M_C | M_T | M_X, fmi2OK, SAME },
    { "fmi2GetNominalsOfContinuousStates", "", get_nominals, M_I | M_N | M_E | M_C | M_T | M_X, fmi2OK, SAME },
    /* §4.2, Co-Simulation only. */
    { "fmi2SetRealInputDerivatives", "(nvr = 0)", set_input_derivatives, C_I | C_N | C_S, fmi2OK, SAME },
    { "fmi2GetRealOutputDerivatives", "(nvr = 0)", get_output_derivatives, C_S | C_T | C_X, fmi2OK, SAME },
    { "fmi2DoStep", "(t, 0.01)", do_step, C_S, fmi2OK, SAME },
    /* Only in stepInProgress, which synchronous steps never enter. */
    { "fmi2CancelStep", "", cancel_step, 0, fmi2OK, SAME },
    /* §4.2.3: stepComplete, stepInProgress, stepFailed, terminated; nothing
     * is asynchronous, so only fmi2LastSuccessfulTime and fmi2Terminated have
     * an answer: "If a status is required which cannot be retrieved by the
     * slave it returns fmi2Discard." */
    { "fmi2GetStatus", "(fmi2DoStepStatus)", status_do_step, C_S | C_T, fmi2Discard, SAME },
    { "fmi2GetStatus", "(fmi2PendingStatus)", status_pending, C_S | C_T, fmi2Discard, SAME },
    { "fmi2GetRealStatus", "(fmi2LastSuccessfulTime)", real_status_last_time, C_S | C_T, fmi2OK, SAME },
    { "fmi2GetRealStatus", "(fmi2DoStepStatus)", real_status_other, C_S | C_T, fmi2Discard, SAME },
    { "fmi2GetIntegerStatus", "(fmi2DoStepStatus)", integer_status, C_S | C_T, fmi2Discard, SAME },
    { "fmi2GetBooleanStatus", "(fmi2Terminated)", boolean_status_terminated, C_S | C_T, fmi2OK, SAME },
    { "fmi2GetBooleanStatus", "(fmi2PendingStatus)", boolean_status_other, C_S | C_T, fmi2Discard, SAME },
    { "fmi2GetStringStatus", "(fmi2PendingStatus)", string_status, C_S | C_T, fmi2Discard, SAME },
    { "fmi2GetStringStatus", "(fmi2LastSuccessfulTime)", string_status_other, C_S | C_T, fmi2Discard, SAME },
};
#define N_ROWS (sizeof ROWS / sizeof ROWS[0])

static State error_state(State s) { return state_is_cs(s) ? CS_ERROR : ME_ERROR; }

static State next_state(Next next, State s)
{
    const bool cs = state_is_cs(s);
    switch (next) {
    case TO_INSTANTIATED: return cs ? CS_INSTANTIATED : ME_INSTANTIATED;
    case TO_INIT: return cs ? CS_INIT : ME_INIT;
    case TO_INITIALIZED: return cs ? CS_STEP_COMPLETE : ME_EVENT;
    case TO_EVENT: return s == ME_CONTINUOUS ? ME_EVENT_AGAIN : s;
    case TO_CONTINUOUS: return ME_CONTINUOUS;
    case TO_TERMINATED: return cs ? CS_TERMINATED : ME_TERMINATED;
    default: return s;
    }
}

/* The status of a call against the table, then whether the instance works. */
void check_call(Inst *in, const char *call, const char *what, fmi2Status st, bool allowed,
                       fmi2Status expected, Next next, long errors_before, long messages_before)
{
    const State s = in->state;
    if (allowed) {
        CHECK(st == expected, "%s: %s, expected %s (%s)", what, status_name(st), status_name(expected),
              st >= fmi2Error ? harness.last_error : harness.last_message);
        if (expected == fmi2Discard && st == fmi2Discard) {
            CHECK(harness.messages > messages_before, "%s returned fmi2Discard without logging why", what);
            CHECK(harness.error_messages == errors_before, "%s returned fmi2Discard but logged an error: %s", what,
                  harness.last_error);
        }
    } else {
        CHECK(st == fmi2Error, "%s: %s, expected fmi2Error: the standard does not allow it there", what,
              status_name(st));
        if (st == fmi2Error) check_error_reported(what, call, errors_before);
    }
    in->state = st >= fmi2Error ? error_state(s) : next_state(next, s);
    if (in->state == ME_INSTANTIATED || in->state == CS_INSTANTIATED) in->t = 0;
    inst_works(in, what);
}

void test_conformance_table(void)
{
    for (int s = 0; s < N_STATES; ++s) {
        Inst in;
        if (inst_reach(&in, (State)s, true)) inst_free(&in); /* fmi2FreeInstance straight from each state */
        for (size_t k = 0; k < N_ROWS; ++k) {
            const Row *r = &ROWS[k];
            if (!inst_reach(&in, (State)s, true)) continue;
            char what[200];
            snprintf(what, sizeof what, "%s%s%s in %s", r->call, *r->args ? " " : "", r->args, STATE_NAME[s]);
            const long errors_before = harness.error_messages, messages_before = harness.messages;
            const fmi2Status st = r->run(&in);
            /* A model whose description says providesDirectionalDerivative="false" answers them with
             * an error wherever the standard allows the call (conformance_directional.c checks the message). */
            const fmi2Status expected =
                r->run == directional_derivative && !MD_PROVIDES_DIRECTIONAL_DERIVATIVE ? fmi2Error : r->expected;
            check_call(&in, r->call, what, st, (r->allowed & B(s)) != 0, expected, r->next, errors_before,
                       messages_before);
            inst_free(&in);
        }
    }
}

/* Every call with instance NULL fails and touches nothing. */
void test_conformance_null_instance(void)
{
    Inst in = { .c = NULL, .state = ME_INSTANTIATED };
    for (size_t k = 0; k < N_ROWS; ++k) {
        const fmi2Status st = ROWS[k].run(&in);
        CHECK(st == fmi2Error || st == fmi2Fatal, "%s on a NULL instance: %s", ROWS[k].call, status_name(st));
    }
    f->FreeInstance(NULL);
}


/* §2.1.3: after fmi2Error "it can be tried to restart the simulation from a
 * formerly stored FMU state by calling fmi2SetFMUstate". A state taken in
 * Continuous-Time Mode (or StepComplete), an error, the state set: the
 * instance integrates on from there. */
void test_error_state_recovery(void)
{
    static const State FROM[] = { ME_CONTINUOUS, CS_STEP_COMPLETE };
    for (size_t k = 0; k < sizeof FROM / sizeof FROM[0]; ++k) {
        Inst in;
        if (!inst_reach(&in, FROM[k], true)) continue;
        char what[120];
        snprintf(what, sizeof what, "fmi2SetFMUstate in Error (a state of %s)", STATE_NAME[FROM[k]]);
        fmi2FMUstate saved = NULL;
        const double t_saved = in.t;
        if (CHECK(f->GetFMUstate(in.c, &saved) == fmi2OK, "%s: fmi2GetFMUstate: %s", what, harness.last_message)) {
            CHECK(set_fixed_parameter(&in) == fmi2Error, "%s: a fixed parameter set after initialization", what);
            CHECK(f->SetFMUstate(in.c, saved) == fmi2OK, "%s: %s", what, harness.last_message);
            in.t = t_saved;
            inst_works(&in, what); /* still in FROM[k] */
            CHECK(f->FreeFMUstate(in.c, &saved) == fmi2OK, "%s: fmi2FreeFMUstate", what);
        }
        inst_free(&in);
    }
}
