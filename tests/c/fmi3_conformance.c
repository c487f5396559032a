/* SPDX-License-Identifier: BSD-2-Clause */
/* Every FMI 3.0 call in every state of the Model Exchange and Co-Simulation
 * state machines, to the letter of FMI 3.0 (the release the model description
 * declares, fmiVersion="3.0"): the "Allowed Function Calls" of the common
 * states in §2.3 (FMU State Settable, Instantiated, Initialization Mode,
 * Initialized, Event Mode, Terminated), of Continuous-Time Mode in §3.2 and
 * of Step Mode in §4.2.
 *
 * A row is a call with legal arguments, the states the standard allows it
 * in, the status it must return there and where it leaves the instance.
 * Where it is not allowed it must return fmi3Error ("When detecting illegal
 * arguments or a function call not allowed in the current state according
 * to the respective state machine, the FMU must return fmi3Error", §2.2.3)
 * and log a message naming it. Either way the instance must still work
 * afterwards (inst3_works).
 *
 * The getters and setters are checked variable by variable from the FMI 3.0
 * modelDescription.xml (test3_conformance_variables, fmi3_conformance_variables.c).
 *
 * Where the FMU is not the letter, and why (the table encodes the letter; the
 * rows for what the FMU does not have encode its refusal):
 *   - After an fmi3Error its messages call the state "Error"; FMI 3.0 calls it
 *     Terminated (§2.3.1), and the FMU allows there exactly Terminated's calls.
 *   - Clock calls (fmi3GetClock, fmi3GetIntervalDecimal, ...) are refused with
 *     fmi3Error even with nValueReferences = 0 where the state machine lists
 *     them: there are no clocks, nothing to answer.
 *   - fmi3EnterConfigurationMode, fmi3GetNumberOfVariableDependencies: "must
 *     not be called" here (no structural parameters, providesPerElement-
 *     Dependencies = false); the FMU refuses them with a message.
 *   - More lenient: fmi3EvaluateDiscreteStates answers fmi3OK in Event Mode
 *     although providesEvaluateDiscreteStates is not declared (there is nothing
 *     to evaluate), and fmi3SetDebugLogging takes categories != NULL with
 *     nCategories = 0.
 * Not deviations: every variable may be read in Initialization Mode in FMI 3.0
 * (the FMI 2.0 layer's lenience is the letter here); continuous states are not
 * settable in Event Mode in FMI 3.0 (3.0.2 allows those with reinit = false). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conformance3.h"

static const Fmi3Api *const f = &api3;

typedef fmi3Status RowFn(Inst3 *in);

static fmi3Status worst(fmi3Status a, fmi3Status b) { return a > b ? a : b; }

static fmi3Status debug_logging_all(Inst3 *in) { return f->SetDebugLogging(in->c, fmi3True, 0, NULL); }
static fmi3Status debug_logging_one(Inst3 *in)
{
    const fmi3String cat[] = { "logEvents" };
    return f->SetDebugLogging(in->c, fmi3False, 1, cat);
}
static fmi3Status enter_initialization(Inst3 *in)
{
    return f->EnterInitializationMode(in->c, fmi3True, 1e-6, 0, fmi3False, 0);
}
static fmi3Status exit_initialization(Inst3 *in) { return f->ExitInitializationMode(in->c); }
static fmi3Status enter_event_mode(Inst3 *in) { return f->EnterEventMode(in->c); }
static fmi3Status terminate(Inst3 *in) { return f->Terminate(in->c); }
static fmi3Status reset(Inst3 *in) { return f->Reset(in->c); }

/* Every getter and setter with nValueReferences = 0: legal wherever the call is. */
#define NONE_GETTER(T) \
    static fmi3Status get_##T##_none(Inst3 *in) { return f->Get##T(in->c, NULL, 0, NULL, 0); }
#define NONE_SETTER(T) \
    static fmi3Status set_##T##_none(Inst3 *in) { return f->Set##T(in->c, NULL, 0, NULL, 0); }
#define EACH_TYPE(X) X(Float32) X(Float64) X(Int8) X(UInt8) X(Int16) X(UInt16) X(Int32) X(UInt32) X(Int64) \
    X(UInt64) X(Boolean) X(String)
EACH_TYPE(NONE_GETTER)
EACH_TYPE(NONE_SETTER)
static fmi3Status get_Binary_none(Inst3 *in) { return f->GetBinary(in->c, NULL, 0, NULL, NULL, 0); }
static fmi3Status set_Binary_none(Inst3 *in) { return f->SetBinary(in->c, NULL, 0, NULL, NULL, 0); }

static fmi3Status get_and_free_state(Inst3 *in)
{
    fmi3FMUState s = NULL;
    const fmi3Status st = f->GetFMUState(in->c, &s);
    if (st != fmi3OK) return st;
    return f->FreeFMUState(in->c, &s);
}
static fmi3Status set_state_just_taken(Inst3 *in)
{
    fmi3FMUState s = NULL;
    fmi3Status st = f->GetFMUState(in->c, &s);
    if (st != fmi3OK) return st;
    st = f->SetFMUState(in->c, s);
    return worst(st, f->FreeFMUState(in->c, &s));
}
static fmi3Status serialize_round_trip(Inst3 *in)
{
    fmi3FMUState s = NULL, t = NULL;
    size_t size = 0;
    fmi3Status st = f->GetFMUState(in->c, &s);
    if (st != fmi3OK) return st;
    st = f->SerializedFMUStateSize(in->c, s, &size);
    fmi3Byte *bytes = st == fmi3OK ? malloc(size ? size : 1) : NULL;
    if (bytes) st = worst(st, f->SerializeFMUState(in->c, s, bytes, size));
    if (bytes && st == fmi3OK) st = f->DeserializeFMUState(in->c, bytes, size, &t);
    if (st == fmi3OK) st = f->SetFMUState(in->c, t);
    if (t) st = worst(st, f->FreeFMUState(in->c, &t));
    free(bytes);
    return worst(st, f->FreeFMUState(in->c, &s));
}
/* Every state derivative by every state: pairs of every mode that has
 * derivatives (states have initial = "exact": knowns of Initialization Mode too). */
static fmi3Status jacobian_product(Inst3 *in, bool adjoint)
{
    fmi3ValueReference unknown[MODEL_NX], known[MODEL_NX];
    double seed[MODEL_NX], out[MODEL_NX];
    for (int i = 0; i < MODEL_NX; ++i) {
        unknown[i] = derivative3_vr(i);
        known[i] = state3_vr(i);
        seed[i] = i % 2 ? -0.5 : 1;
        out[i] = NAN;
    }
    const fmi3Status st = adjoint ? f->GetAdjointDerivative(in->c, unknown, MODEL_NX, known, MODEL_NX, seed,
                                                            MODEL_NX, out, MODEL_NX)
                                  : f->GetDirectionalDerivative(in->c, unknown, MODEL_NX, known, MODEL_NX, seed,
                                                                MODEL_NX, out, MODEL_NX);
    for (int i = 0; st == fmi3OK && i < MODEL_NX; ++i)
        CHECK(isfinite(out[i]), "%s derivative %d: %g", adjoint ? "adjoint" : "directional", i, out[i]);
    return st;
}
static fmi3Status directional_derivative(Inst3 *in) { return jacobian_product(in, false); }
static fmi3Status adjoint_derivative(Inst3 *in) { return jacobian_product(in, true); }
static fmi3Status update_discrete_states(Inst3 *in)
{
    fmi3Boolean a, b, c, d, e;
    double t;
    return f->UpdateDiscreteStates(in->c, &a, &b, &c, &d, &e, &t);
}
static fmi3Status evaluate_discrete_states(Inst3 *in) { return f->EvaluateDiscreteStates(in->c); }
/* The event update first where it is allowed: Continuous-Time and Step Mode
 * are entered once the discrete states need no update. */
static fmi3Status enter_continuous_time_mode(Inst3 *in)
{
    bool changed;
    if (in->state == M3_EVENT || in->state == M3_EVENT_AGAIN) {
        const fmi3Status st = harness3_update_discrete_states(f, in->c, &changed);
        if (st != fmi3OK) return st;
    }
    return f->EnterContinuousTimeMode(in->c);
}
static fmi3Status enter_step_mode(Inst3 *in)
{
    bool changed;
    if (in->state == C3_EVENT || in->state == C3_EVENT_AGAIN) {
        const fmi3Status st = harness3_update_discrete_states(f, in->c, &changed);
        if (st != fmi3OK) return st;
    }
    return f->EnterStepMode(in->c);
}
static fmi3Status completed_integrator_step(Inst3 *in)
{
    fmi3Boolean enter = 7, terminate_ = 7;
    const fmi3Status st = f->CompletedIntegratorStep(in->c, fmi3True, &enter, &terminate_);
    if (st == fmi3OK) CHECK(enter == fmi3False || enter == fmi3True, "enterEventMode = %d", enter);
    return st;
}
static fmi3Status set_time(Inst3 *in)
{
    const fmi3Status st = f->SetTime(in->c, in->t + 1e-9);
    if (st == fmi3OK) in->t += 1e-9;
    return st;
}
static fmi3Status set_continuous_states(Inst3 *in)
{
    double x[MODEL_NX];
    for (int i = 0; i < MODEL_NX; ++i) x[i] = md_var(md_state_index(i))->start;
    if (in->state == M3_CONTINUOUS) f->GetContinuousStates(in->c, x, MODEL_NX);
    return f->SetContinuousStates(in->c, x, MODEL_NX);
}
static fmi3Status get_array(Inst3 *in, fmi3GetEventIndicatorsTYPE *get, size_t n)
{
    double v[MODEL_NX + HARNESS_NZ];
    for (size_t i = 0; i < n; ++i) v[i] = NAN;
    const fmi3Status st = get(in->c, v, n);
    for (size_t i = 0; st == fmi3OK && i < n; ++i) CHECK(isfinite(v[i]), "element %zu = %g", i, v[i]);
    return st;
}
static fmi3Status get_event_indicators(Inst3 *in) { return get_array(in, f->GetEventIndicators, MODEL_NZ); }
static fmi3Status get_continuous_states(Inst3 *in) { return get_array(in, f->GetContinuousStates, MODEL_NX); }
static fmi3Status get_derivatives(Inst3 *in) { return get_array(in, f->GetContinuousStateDerivatives, MODEL_NX); }
static fmi3Status get_nominals(Inst3 *in) { return get_array(in, f->GetNominalsOfContinuousStates, MODEL_NX); }
static fmi3Status number_of_states(Inst3 *in)
{
    size_t n = 0;
    const fmi3Status st = f->GetNumberOfContinuousStates(in->c, &n);
    if (st == fmi3OK) CHECK(n == MODEL_NX, "fmi3GetNumberOfContinuousStates: %zu", n);
    return st;
}
static fmi3Status number_of_indicators(Inst3 *in)
{
    size_t n = 0;
    const fmi3Status st = f->GetNumberOfEventIndicators(in->c, &n);
    if (st == fmi3OK) CHECK(n == (size_t)MD_N_EVENTINDICATORS, "fmi3GetNumberOfEventIndicators: %zu", n);
    return st;
}
/* maxOutputDerivativeOrder = 0: nValueReferences = 0 is the call an importer may make. */
static fmi3Status get_output_derivatives(Inst3 *in) { return f->GetOutputDerivatives(in->c, NULL, 0, NULL, NULL, 0); }
/* Where the step ends at an event (eventModeUsed), the master's Event Mode follows. */
static fmi3Status do_step(Inst3 *in) { return harness3_do_step(f, in->c, &in->t, 0.01, NULL); }
/* No tunable structural parameters: "must not be called" (§2.3.4, §4.2.1). */
static fmi3Status enter_configuration_mode(Inst3 *in) { return f->EnterConfigurationMode(in->c); }
static fmi3Status exit_configuration_mode(Inst3 *in) { return f->ExitConfigurationMode(in->c); }
/* providesPerElementDependencies = false. */
static fmi3Status number_of_dependencies(Inst3 *in)
{
    size_t n;
    return f->GetNumberOfVariableDependencies(in->c, derivative3_vr(0), &n);
}

/* ---------------------------------------------------------- the table */

typedef struct {
    const char *call, *args;
    RowFn *run;
    unsigned allowed;
    fmi3Status expected;
    Next next;
} Row;

#define MI B(M3_INSTANTIATED)
#define MN B(M3_INIT)
#define ME (B(M3_EVENT) | B(M3_EVENT_AGAIN))
#define MC B(M3_CONTINUOUS)
#define CI B(C3_INSTANTIATED)
#define CN B(C3_INIT)
#define CE (B(C3_EVENT) | B(C3_EVENT_AGAIN))
#define CS (B(C3_STEP) | B(C3_STEP_EM))
/* Terminated, which a call returning fmi3Error also leads to (§2.3.1). */
#define MT (B(M3_TERMINATED) | B(M3_ERROR))
#define CT (B(C3_TERMINATED) | B(C3_ERROR))
#define ALL ((1u << N3_STATES) - 1)
/* fmi3Get{VariableType}: Initialization, Event, Continuous-Time, Step Mode, Terminated (§2.3.3-2.3.7, 3.2.1, 4.2.1). */
#define GETTERS (MN | ME | MC | MT | CN | CE | CS | CT)
/* fmi3Set{VariableType}: Instantiated, Initialization, Event, Continuous-Time, Step Mode (each with its variables). */
#define SETTERS (MI | MN | ME | MC | CI | CN | CE | CS)
/* Model Exchange's arrays: Initialization, Event, Continuous-Time Mode, Terminated; "Not allowed in Co-Simulation". */
#define ME_ARRAYS (MN | ME | MC | MT)

static const Row ROWS[] = {
    /* §2.3.1 FMU State Settable: every state */
    { "fmi3SetDebugLogging", "(on, all categories)", debug_logging_all, ALL, fmi3OK, SAME },
    { "fmi3SetDebugLogging", "(off, logEvents)", debug_logging_one, ALL, fmi3OK, SAME },
    { "fmi3Reset", "", reset, ALL, fmi3OK, TO_INSTANTIATED },
    { "fmi3GetFMUState", "(then fmi3FreeFMUState)", get_and_free_state, ALL, fmi3OK, SAME },
    { "fmi3SetFMUState", "(of the state just taken)", set_state_just_taken, ALL, fmi3OK, SAME },
    { "fmi3SerializeFMUState", "(size, serialize, deserialize, set, free)", serialize_round_trip, ALL, fmi3OK, SAME },
    /* §2.3.2 Instantiated: Model Exchange only for the numbers (also in Event Mode, §2.3.5) */
    { "fmi3EnterInitializationMode", "", enter_initialization, MI | CI, fmi3OK, TO_INIT },
    { "fmi3GetNumberOfContinuousStates", "", number_of_states, MI | ME, fmi3OK, SAME },
    { "fmi3GetNumberOfEventIndicators", "", number_of_indicators, MI | ME, fmi3OK, SAME },
    /* §2.3.3 Initialization Mode */
    { "fmi3ExitInitializationMode", "", exit_initialization, MN | CN, fmi3OK, TO_INITIALIZED },
    /* §2.3.4 Initialized: Event, Continuous-Time, Step Mode; nominals Model Exchange only (also Initialization
     * Mode, Terminated) */
    { "fmi3Terminate", "", terminate, ME | MC | CE | CS, fmi3OK, TO_TERMINATED },
    { "fmi3GetNominalsOfContinuousStates", "", get_nominals, ME_ARRAYS, fmi3OK, SAME },
    /* Getters and setters of every type with nValueReferences = 0 */
#define GETTER_ROW(T) { "fmi3Get" #T, "(nValueReferences = 0)", get_##T##_none, GETTERS, fmi3OK, SAME },
#define SETTER_ROW(T) { "fmi3Set" #T, "(nValueReferences = 0)", set_##T##_none, SETTERS, fmi3OK, SAME },
    EACH_TYPE(GETTER_ROW) EACH_TYPE(SETTER_ROW)
    GETTER_ROW(Binary) SETTER_ROW(Binary)
    /* Partial derivatives: Initialization, Event, Continuous-Time, Step Mode, Terminated */
    { "fmi3GetDirectionalDerivative", "(every derivative by every state)", directional_derivative, GETTERS, fmi3OK, SAME },
    { "fmi3GetAdjointDerivative", "(every derivative by every state)", adjoint_derivative, GETTERS, fmi3OK, SAME },
    /* §2.3.5 Event Mode */
    { "fmi3UpdateDiscreteStates", "", update_discrete_states, ME | CE, fmi3OK, SAME },
    { "fmi3EvaluateDiscreteStates", "", evaluate_discrete_states, ME | CE, fmi3OK, SAME },
    { "fmi3EnterContinuousTimeMode", "(after the event update)", enter_continuous_time_mode, ME, fmi3OK,
      TO_CONTINUOUS },
    { "fmi3EnterStepMode", "(after the event update)", enter_step_mode, CE, fmi3OK, TO_STEP },
    { "fmi3GetContinuousStates", "", get_continuous_states, ME_ARRAYS, fmi3OK, SAME },
    { "fmi3GetContinuousStateDerivatives", "", get_derivatives, ME_ARRAYS, fmi3OK, SAME },
    { "fmi3GetEventIndicators", "", get_event_indicators, ME_ARRAYS, fmi3OK, SAME },
    /* §3.2.1 Continuous-Time Mode */
    { "fmi3EnterEventMode", "", enter_event_mode, MC | B(C3_STEP_EM), fmi3OK, TO_EVENT },
    { "fmi3CompletedIntegratorStep", "", completed_integrator_step, MC, fmi3OK, SAME },
    { "fmi3SetTime", "(t + 1e-9)", set_time, MC, fmi3OK, SAME },
    { "fmi3SetContinuousStates", "(the current states)", set_continuous_states, MC, fmi3OK, SAME },
    /* §4.2.1 Step Mode (fmi3EnterEventMode there only with eventModeUsed, above); output derivatives also
     * in Terminated */
    { "fmi3DoStep", "(t, 0.01)", do_step, CS, fmi3OK, SAME },
    { "fmi3GetOutputDerivatives", "(nValueReferences = 0)", get_output_derivatives, CS | CT, fmi3OK, SAME },
    /* Calls the importer must not make to this FMU: no structural parameters, no per-element dependencies. */
    { "fmi3EnterConfigurationMode", "", enter_configuration_mode, 0, fmi3OK, SAME },
    { "fmi3ExitConfigurationMode", "", exit_configuration_mode, 0, fmi3OK, SAME },
    { "fmi3GetNumberOfVariableDependencies", "(a derivative)", number_of_dependencies, 0, fmi3OK, SAME },
};
#define N_ROWS (sizeof ROWS / sizeof ROWS[0])

static State3 next_state(Next next, const Inst3 *in)
{
    const State3 s = in->state;
    const bool cs = state3_is_cs(s);
    switch (next) {
    case TO_INSTANTIATED: return cs ? C3_INSTANTIATED : M3_INSTANTIATED;
    case TO_INIT: return cs ? C3_INIT : M3_INIT;
    case TO_INITIALIZED: return !cs ? M3_EVENT : in->event_mode ? C3_EVENT : C3_STEP;
    case TO_EVENT: return s == M3_CONTINUOUS ? M3_EVENT_AGAIN : s == C3_STEP_EM ? C3_EVENT_AGAIN : s;
    case TO_CONTINUOUS: return M3_CONTINUOUS;
    case TO_STEP: return C3_STEP_EM;
    case TO_TERMINATED: return cs ? C3_TERMINATED : M3_TERMINATED;
    default: return s;
    }
}

void check_call(Inst3 *in, const char *call, const char *what, fmi3Status st, bool allowed,
                fmi3Status expected, Next next, long errors_before)
{
    if (allowed) {
        CHECK(st == expected, "%s: %s, expected %s (%s)", what, status3_name(st), status3_name(expected),
              st >= fmi3Error ? harness.last_error : harness.last_message);
    } else {
        CHECK(st == fmi3Error, "%s: %s, expected fmi3Error: the standard does not allow it there", what,
              status3_name(st));
        if (st == fmi3Error) check3_error_reported(what, call, errors_before);
    }
    CHECK(harness.bad_messages == 0, "%s: a malformed log message: %s", what, harness.last_bad);
    in->state = st >= fmi3Error ? (state3_is_cs(in->state) ? C3_ERROR : M3_ERROR) : next_state(next, in);
    if (in->state == M3_INSTANTIATED || in->state == C3_INSTANTIATED) in->t = 0;
    inst3_works(in, what);
}

void test3_conformance_table(void)
{
    for (int s = 0; s < N3_STATES; ++s) {
        Inst3 in;
        if (inst3_reach(&in, (State3)s, true)) inst3_free(&in); /* fmi3FreeInstance straight from each state */
        for (size_t k = 0; k < N_ROWS; ++k) {
            const Row *r = &ROWS[k];
            if (!inst3_reach(&in, (State3)s, true)) continue;
            char what[200];
            snprintf(what, sizeof what, "%s%s%s in %s", r->call, *r->args ? " " : "", r->args, STATE3_NAME[s]);
            const long errors_before = harness.error_messages;
            const fmi3Status st = r->run(&in);
            /* A model whose description says providesDirectionalDerivatives="false" answers both kinds with
             * an error wherever the standard allows the calls (fmi3_directional.c checks the messages). */
            const bool derivative = r->run == directional_derivative || r->run == adjoint_derivative;
            const fmi3Status expected = derivative && !MD_PROVIDES_DIRECTIONAL_DERIVATIVE ? fmi3Error : r->expected;
            check_call(&in, r->call, what, st, (r->allowed & B(s)) != 0, expected, r->next, errors_before);
            inst3_free(&in);
        }
    }
}

/* Every call with instance NULL fails, and fmi3FreeInstance(NULL) does nothing. */
void test3_null_instance(void)
{
    Inst3 in = { .c = NULL, .state = M3_INSTANTIATED };
    for (size_t k = 0; k < N_ROWS; ++k) {
        const fmi3Status st = ROWS[k].run(&in);
        CHECK(st == fmi3Error || st == fmi3Fatal, "%s on a NULL instance: %s", ROWS[k].call, status3_name(st));
    }
    f->FreeInstance(NULL);
}
