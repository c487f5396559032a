/* A model's FMU (PainleveRod, or fmu_src/models/NAME as fmi_driver_NAME) through its
 * C ABI, as an importer loads it (dlopen): every FMI
 * function in every instance state of both interfaces against FMI 2.0.4
 * (conformance_table.c, conformance_directional.c), its inputs
 * (input_checks.c), NULL arguments, bad value references,
 * nvr = 0 and huge nvr, bad values, failing allocations, many live instances,
 * and instantiate/simulate/free cycles with a flat resident set.
 *
 * Built with AddressSanitizer + UBSan (fmi_driver_asan) and plain for
 * valgrind and the memory soak (fmi_driver); tests/test_c_robustness.py runs it.
 *
 *   fmi_driver [--lib PATH] [--cycles N] [--max-rss-growth-kb K] [--no-api]
 *              [--no-conformance | --conformance-only]
 *
 * Exit status 0 only if every check passed. */
#include <ctype.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "driver.h"

FmiApi api;
static const FmiApi *const f = &api;

/* ------------------------------------------------------ instance states */

/* A new instance brought to `state` (driver.h), logging off, or NULL. */
static fmi2Component instance_in(State state)
{
    Inst in;
    return inst_reach(&in, state, false) ? in.c : NULL;
}

static void free_instance(fmi2Component c)
{
    Inst in = { .c = c };
    inst_free(&in);
}

/* After an fmi2Error: a message naming a call, and the Error state (no
 * simulation call accepted, getters still are). */
static void check_error_handling(fmi2Component c, const char *what, long errors_before)
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
static void check_reset_recovers(fmi2Component c, const char *what)
{
    if (!CHECK(f->Reset(c) == fmi2OK, "%s: fmi2Reset failed", what)) return;
    EulerSim s = { .c = c };
    const fmi2Status st = harness_simulate(f, &s, 0.1, 5e-3, 20);
    CHECK(st == fmi2OK, "%s: simulation after fmi2Reset: %s (%s)", what, status_name(st), harness.last_message);
}

enum { MAX_VARS = 64 };

/* The value references of the Real variables of modelDescription.xml; their number. */
static size_t real_vrs(fmi2ValueReference vr[MAX_VARS])
{
    size_t n = 0;
    for (int k = 1; k <= MD_N_VARIABLES && n < MAX_VARS; ++k)
        if (md_var(k)->type == MD_REAL) vr[n++] = md_var(k)->vr;
    return n;
}

/* The first variable of `type`; VR_COUNT (no variable) if the model has none. */
static fmi2ValueReference first_of_type(MdType type)
{
    for (int k = 1; k <= MD_N_VARIABLES; ++k)
        if (md_var(k)->type == type) return md_var(k)->vr;
    return VR_COUNT;
}

/* Every Real read; each finite. */
static fmi2Status get_all_reals(fmi2Component c)
{
    fmi2ValueReference vr[MAX_VARS];
    double v[MAX_VARS];
    const size_t n = real_vrs(vr);
    const fmi2Status st = f->GetReal(c, vr, n, v);
    for (size_t i = 0; st == fmi2OK && i < n; ++i) CHECK(isfinite(v[i]), "Real %u = %g", vr[i], v[i]);
    return st;
}

/* ------------------------------------------------------ NULL arguments */

/* Runs `expr` (which uses c) on a new instance in `state` and checks its status. */
#define EXPECT_IN(state, expected, expr)                                                                   \
    do {                                                                                                   \
        fmi2Component c = instance_in(state);                                                              \
        if (!c) break;                                                                                     \
        const long errors_before_ = harness.error_messages;                                                \
        const fmi2Status st_ = (expr);                                                                     \
        CHECK(st_ == (expected), "%s in %s: %s, expected %s", #expr, STATE_NAME[state], status_name(st_), \
              status_name(expected));                                                                      \
        if (st_ == fmi2Error) check_error_handling(c, #expr, errors_before_);                              \
        free_instance(c);                                                                                  \
    } while (0)

static void test_null_arguments(void)
{
    fmi2ValueReference vr[1] = { PROFILE_KNOB };
    double r[MODEL_NX + 1] = { PROFILE_KNOB_VALUE(1e-3) };
    fmi2Integer i[1];
    fmi2Boolean b[1];
    fmi2String s[1] = { "x" };
    const fmi2String null_category[1] = { NULL };
    fmi2FMUstate state = NULL;
    size_t size;

    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetDebugLogging(c, fmi2True, 2, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetDebugLogging(c, fmi2True, 1, null_category));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetDebugLogging(c, fmi2True, SIZE_MAX, NULL));

    EXPECT_IN(ME_EVENT, fmi2Error, f->GetReal(c, NULL, 1, r));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetReal(c, vr, 1, NULL));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetInteger(c, NULL, 1, i));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetInteger(c, vr, 1, NULL));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetBoolean(c, NULL, 1, b));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetBoolean(c, vr, 1, NULL));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetString(c, NULL, 1, s));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetString(c, vr, 1, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, NULL, 1, r));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, vr, 1, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetInteger(c, NULL, 1, i));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetInteger(c, vr, 1, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetBoolean(c, NULL, 1, b));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetBoolean(c, vr, 1, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetString(c, NULL, 1, s));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetString(c, vr, 1, NULL));

    EXPECT_IN(ME_EVENT, fmi2Error, f->NewDiscreteStates(c, NULL));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->CompletedIntegratorStep(c, fmi2True, NULL, b));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->CompletedIntegratorStep(c, fmi2True, b, NULL));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->CompletedIntegratorStep(c, fmi2False, NULL, NULL));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->SetContinuousStates(c, NULL, MODEL_NX));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetDerivatives(c, NULL, MODEL_NX));
    if (MODEL_NZ > 0) EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetEventIndicators(c, NULL, MODEL_NZ));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetContinuousStates(c, NULL, MODEL_NX));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetNominalsOfContinuousStates(c, NULL, MODEL_NX));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->GetNominalsOfContinuousStates(c, NULL, MODEL_NX));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, NULL, 1, vr, 1, r, r));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, vr, 1, NULL, 1, r, r));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, vr, 1, vr, 1, NULL, r));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, vr, 1, vr, 1, r, NULL));

    /* Calls whose support is optional: any status, but no crash or read. */
    fmi2Status any;
    fmi2Component c = instance_in(ME_EVENT);
    if (c) {
        any = f->GetFMUstate(c, NULL);
        any = f->SetFMUstate(c, NULL);
        any = f->FreeFMUstate(c, NULL);
        any = f->FreeFMUstate(c, &state);
        any = f->SerializedFMUstateSize(c, NULL, &size);
        any = f->SerializedFMUstateSize(c, NULL, NULL);
        any = f->SerializeFMUstate(c, NULL, NULL, 16);
        any = f->DeSerializeFMUstate(c, NULL, 16, &state);
        any = f->DeSerializeFMUstate(c, (const fmi2Byte *)"garbage!", 8, &state);
        if (any <= fmi2Warning) any = f->FreeFMUstate(c, &state);
        any = f->DeSerializeFMUstate(c, (const fmi2Byte *)"garbage!", 8, NULL);
        any = f->SetRealInputDerivatives(c, NULL, 3, NULL, NULL);
        any = f->GetRealOutputDerivatives(c, NULL, 3, NULL, NULL);
        any = f->GetStatus(c, fmi2DoStepStatus, NULL);
        any = f->GetRealStatus(c, fmi2LastSuccessfulTime, NULL);
        any = f->GetIntegerStatus(c, fmi2DoStepStatus, NULL);
        any = f->GetBooleanStatus(c, fmi2Terminated, NULL);
        any = f->GetStringStatus(c, fmi2PendingStatus, NULL);
        (void)any;
        free_instance(c);
    }
}

/* -------------------------------------------- value references and nvr */

static void test_value_references(void)
{
    const fmi2ValueReference integer = first_of_type(MD_INTEGER), boolean = first_of_type(MD_BOOLEAN);
    const fmi2ValueReference NOT_REAL[] = { integer, boolean, VR_COUNT, 1000, 0x80000000u, UINT_MAX };
    double r[2] = { 0 };
    fmi2Integer i[2] = { 0 };
    fmi2Boolean b[2] = { 0 };
    fmi2String s[2] = { NULL, NULL };
    for (size_t k = 0; k < sizeof NOT_REAL / sizeof NOT_REAL[0]; ++k) {
        const fmi2ValueReference *vr = &NOT_REAL[k];
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetReal(c, vr, 1, r));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, vr, 1, r));
    }
    /* Integer and Boolean ones of the wrong type or out of range; none is settable. */
    const fmi2ValueReference NOT_INTEGER[] = { 0, PROFILE_KNOB, boolean, VR_COUNT, UINT_MAX };
    const fmi2ValueReference NOT_BOOLEAN[] = { 0, PROFILE_KNOB, integer, VR_COUNT, UINT_MAX };
    const fmi2ValueReference ANY[] = { 0, integer, boolean, VR_COUNT, UINT_MAX };
    for (size_t k = 0; k < sizeof ANY / sizeof ANY[0]; ++k) {
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetInteger(c, &NOT_INTEGER[k], 1, i));
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetBoolean(c, &NOT_BOOLEAN[k], 1, b));
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetString(c, &ANY[k], 1, s));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetInteger(c, &ANY[k], 1, i));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetBoolean(c, &ANY[k], 1, b));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetString(c, &ANY[k], 1, s));
    }
    /* Calculated variables are not settable. */
    for (int k = 1; k <= MD_N_VARIABLES; ++k)
        if (md_var(k)->type == MD_REAL && md_var(k)->initial == MD_INITIAL_CALCULATED)
            EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, &md_var(k)->vr, 1, r));
    /* Directional derivatives of anything but derivatives by states. */
    const fmi2ValueReference der = md_var(MD_DERIVATIVES[0].index)->vr, state = md_var(md_state_index(0))->vr,
                             bad = UINT_MAX, param = PROFILE_KNOB;
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, &bad, 1, &state, 1, r, r + 1));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, &der, 1, &bad, 1, r, r + 1));
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, &der, 1, &param, 1, r, r + 1));
    EXPECT_IN(ME_EVENT, fmi2OK, f->GetDirectionalDerivative(c, &der, 1, &state, 1, r, r + 1));
}

static void test_nvr_zero_and_huge(void)
{
    /* nvr = 0: nothing is read, NULL arrays are fine. */
    EXPECT_IN(ME_EVENT, fmi2OK, f->GetReal(c, NULL, 0, NULL));
    EXPECT_IN(ME_EVENT, fmi2OK, f->GetInteger(c, NULL, 0, NULL));
    EXPECT_IN(ME_EVENT, fmi2OK, f->GetBoolean(c, NULL, 0, NULL));
    EXPECT_IN(ME_EVENT, fmi2OK, f->GetString(c, NULL, 0, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetReal(c, NULL, 0, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetInteger(c, NULL, 0, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetBoolean(c, NULL, 0, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetString(c, NULL, 0, NULL));
    EXPECT_IN(ME_EVENT, fmi2OK, f->GetDirectionalDerivative(c, NULL, 0, NULL, 0, NULL, NULL));
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetDebugLogging(c, fmi2False, 0, NULL));

    /* Huge nvr with NULL arrays: an error before any read. */
    static const size_t HUGE_N[] = { SIZE_MAX, SIZE_MAX / 2 + 1, (size_t)1 << 40, 1u << 31 };
    double one = 1;
    const fmi2ValueReference vr = PROFILE_KNOB;
    for (size_t k = 0; k < sizeof HUGE_N / sizeof HUGE_N[0]; ++k) {
        const size_t n = HUGE_N[k];
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetReal(c, NULL, n, NULL));
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetInteger(c, NULL, n, NULL));
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetBoolean(c, NULL, n, NULL));
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetString(c, NULL, n, NULL));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, NULL, n, NULL));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetInteger(c, NULL, n, NULL));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetBoolean(c, NULL, n, NULL));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetString(c, NULL, n, NULL));
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, NULL, n, NULL, n, NULL, NULL));
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->SetContinuousStates(c, NULL, n));
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetDerivatives(c, NULL, n));
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetEventIndicators(c, NULL, n));
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetContinuousStates(c, NULL, n));
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetNominalsOfContinuousStates(c, NULL, n));
        /* One real element behind a huge count must not be read past. */
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, NULL, n, &one));
        EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, &vr, n, NULL));
        EXPECT_IN(ME_EVENT, fmi2Error, f->GetDirectionalDerivative(c, NULL, n, &vr, 1, &one, &one));
    }

    /* Wrong sizes of the state and indicator arrays, each a real array. */
    double big[MODEL_NX + HARNESS_NZ + 2];
    for (int k = 0; k < MODEL_NX + HARNESS_NZ + 2; ++k) big[k] = k < MODEL_NX ? md_var(md_state_index(k))->start : 0;
    static const size_t WRONG[] = { 0, MODEL_NX - 1, MODEL_NX + 1 };
    for (size_t k = 0; k < sizeof WRONG / sizeof WRONG[0]; ++k) {
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->SetContinuousStates(c, big, WRONG[k]));
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetDerivatives(c, big, WRONG[k]));
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetContinuousStates(c, big, WRONG[k]));
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetNominalsOfContinuousStates(c, big, WRONG[k]));
    }
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetEventIndicators(c, big, MODEL_NZ + 1));
    if (MODEL_NZ > 0) EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetEventIndicators(c, big, (size_t)MODEL_NZ - 1));
}

/* Large but real arrays: a million value references. */
static void test_large_arrays(void)
{
    enum { N = 1 << 20 };
    fmi2ValueReference *vr = malloc(N * sizeof *vr);
    double *v = malloc(N * sizeof *v);
    fmi2Integer *iv = malloc(N * sizeof *iv);
    if (!CHECK(vr && v && iv, "out of memory")) goto done;

    for (size_t k = 0; k < N; ++k) vr[k] = UINT_MAX - (unsigned)(k % 7);
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetReal(c, vr, N, v));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, vr, N, v));

    fmi2ValueReference reals[MAX_VARS];
    const size_t n_reals = real_vrs(reals);
    for (size_t k = 0; k < N; ++k) vr[k] = reals[k % n_reals];
    EXPECT_IN(ME_EVENT, fmi2OK, f->GetReal(c, vr, N, v));
    bool finite = true;
    for (size_t k = 0; k < N; ++k) finite &= isfinite(v[k]) != 0;
    CHECK(finite, "fmi2GetReal of %d values gave a non-finite one", N);

    vr[N - 1] = VR_COUNT; /* the last one is out of range: every element is read */
    EXPECT_IN(ME_EVENT, fmi2Error, f->GetReal(c, vr, N, v));

    for (size_t k = 0; k < N; ++k) {
        vr[k] = PROFILE_KNOB;
        v[k] = PROFILE_KNOB_VALUE(1e-3 * (1 + (double)(k % 5)));
    }
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetReal(c, vr, N, v));
    v[N - 1] = NAN;
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetReal(c, vr, N, v));

    if (first_of_type(MD_INTEGER) != VR_COUNT) {
        for (size_t k = 0; k < N; ++k) vr[k] = first_of_type(MD_INTEGER);
        EXPECT_IN(ME_CONTINUOUS, fmi2OK, f->GetInteger(c, vr, N, iv));
        vr[N - 1] = first_of_type(MD_BOOLEAN);
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->GetInteger(c, vr, N, iv));
    }
done:
    free(vr);
    free(v);
    free(iv);
}

/* ------------------------------------------------------------- values */

static fmi2Status set_one(fmi2Component c, fmi2ValueReference vr, double value)
{
    return f->SetReal(c, &vr, 1, &value);
}

/* Whether `name` occurs in `message` as a whole word. */
static bool names_word(const char *message, const char *name)
{
    const size_t n = strlen(name);
    for (const char *p = strstr(message, name); p; p = strstr(p + 1, name)) {
        const bool starts = p == message || !(isalnum((unsigned char)p[-1]) || p[-1] == '_');
        if (starts && !(isalnum((unsigned char)p[n]) || p[n] == '_')) return true;
    }
    return false;
}

/* fmi2SetReal of variable `index` to `value` in `state`: fmi2Error, the Error
 * state, and a message that names the call and the variable. */
static void expect_refused(int index, State state, double value)
{
    const MdVariable *v = md_var(index);
    fmi2Component c = instance_in(state);
    if (!c) return;
    const long errors_before = harness.error_messages;
    const fmi2Status st = set_one(c, v->vr, value);
    CHECK(st == fmi2Error, "fmi2SetReal(%s = %g) in %s: %s, expected fmi2Error", v->name, value, STATE_NAME[state],
          status_name(st));
    if (st == fmi2Error) {
        CHECK(names_word(harness.last_error, v->name), "fmi2SetReal(%s = %g) in %s: the message does not name %s: '%s'",
              v->name, value, STATE_NAME[state], v->name, harness.last_error);
        if (state_is_cs(state)) { /* the Error state of Co-Simulation: no step, getters still */
            double value_now;
            CHECK(f->DoStep(c, 0.06, 1e-3, fmi2True) == fmi2Error, "fmi2DoStep accepted in the Error state");
            CHECK(f->GetReal(c, &v->vr, 1, &value_now) == fmi2OK, "fmi2GetReal refused in the Error state");
        } else {
            check_error_handling(c, "fmi2SetReal", errors_before);
        }
    }
    free_instance(c);
}

/* Where a settable variable is first settable (FMI 2.0.4 §3.2.3): parameters
 * and states before initialization (condition 1), inputs from Initialization
 * Mode on (condition 3); false if it is not settable. */
static bool first_settable(const MdVariable *v, State *state)
{
    if (v->type != MD_REAL) return false;
    *state = v->causality == MD_INPUT ? ME_INIT : ME_INSTANTIATED;
    return v->causality == MD_INPUT || (v->variability != MD_CONSTANT && v->initial == MD_INITIAL_EXACT);
}

/* Every settable Real of modelDescription.xml: NaN, infinities and the
 * largest doubles refused, so are values just past its min and max (its
 * bounds themselves are accepted); inputs refuse NaN and infinities in every
 * state they may be set in. Each refusal names the variable. */
static void test_bad_values_of_variables(void)
{
    static const double BAD_EVERYWHERE[] = { NAN, -NAN, INFINITY, -INFINITY, DBL_MAX, -DBL_MAX };
    static const State INPUT_STATES[] = { ME_INSTANTIATED, ME_EVENT, ME_CONTINUOUS, CS_INSTANTIATED, CS_INIT,
                                          CS_STEP_COMPLETE };
    for (int index = 1; index <= MD_N_VARIABLES; ++index) {
        const MdVariable *v = md_var(index);
        State state;
        if (!first_settable(v, &state)) continue;
        for (size_t k = 0; k < sizeof BAD_EVERYWHERE / sizeof BAD_EVERYWHERE[0]; ++k)
            expect_refused(index, state, BAD_EVERYWHERE[k]);
        if (v->causality == MD_INPUT)
            for (size_t s = 0; s < sizeof INPUT_STATES / sizeof INPUT_STATES[0]; ++s)
                for (size_t k = 0; k < 4; ++k) expect_refused(index, INPUT_STATES[s], BAD_EVERYWHERE[k]);
        if (v->has_min) {
            /* Just below, further below; for a positive min also zero, -0, a denormal, a tenth. */
            expect_refused(index, state, nextafter(v->min, -INFINITY));
            expect_refused(index, state, v->min - fmax(1, fabs(v->min)) * 1e-3);
            if (v->min > 0) {
                static const double NOT_POSITIVE_ENOUGH[] = { 0.0, -0.0, 4.9e-324 };
                for (size_t k = 0; k < 3; ++k)
                    if (NOT_POSITIVE_ENOUGH[k] < v->min) expect_refused(index, state, NOT_POSITIVE_ENOUGH[k]);
                expect_refused(index, state, v->min / 10);
            }
            EXPECT_IN(state, fmi2OK, set_one(c, v->vr, v->min));
        }
        if (v->has_max) {
            expect_refused(index, state, nextafter(v->max, INFINITY));
            expect_refused(index, state, v->max * (1 + 1e-7) + 1e-300);
            if (v->max < 1e300) expect_refused(index, state, 1e300);
            EXPECT_IN(state, fmi2OK, set_one(c, v->vr, v->max));
        }
    }
}

static void test_bad_values(void)
{
    test_bad_values_of_variables();

    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetupExperiment(c, fmi2True, NAN, 0, fmi2False, 0));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetupExperiment(c, fmi2True, -1, 0, fmi2False, 0));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetupExperiment(c, fmi2False, 0, INFINITY, fmi2False, 0));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetupExperiment(c, fmi2False, 0, 1, fmi2True, 0));
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetupExperiment(c, fmi2False, NAN, 0, fmi2False, NAN));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->SetTime(c, NAN));
    EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->SetTime(c, -INFINITY));

    double x[MODEL_NX];
    for (int k = 0; k < MODEL_NX; ++k) x[k] = md_var(md_state_index(k))->start;
    for (int k = 0; k < MODEL_NX; ++k) {
        const double keep = x[k];
        x[k] = k % 2 ? NAN : INFINITY;
        EXPECT_IN(ME_CONTINUOUS, fmi2Error, f->SetContinuousStates(c, x, MODEL_NX));
        x[k] = keep;
    }
    /* Extreme but allowed values of each state, with the stiffest contact:
     * every output stays finite or the call says why. */
    for (int k = 0; k < MODEL_NX; ++k) {
        fmi2Component c = instance_in(ME_INIT);
        if (!c) continue;
        const fmi2ValueReference vr = md_var(md_state_index(k))->vr;
        set_one(c, PROFILE_KNOB, PROFILE_KNOB_VALUE(PROFILE_STIFFEST));
        CHECK(set_one(c, vr, k % 2 ? -PROFILE_STATE_BOUND : PROFILE_STATE_BOUND) == fmi2OK,
              "setting Real %u to its bound", vr);
        bool changed;
        if (f->ExitInitializationMode(c) == fmi2OK && harness_event_iteration(f, c, &changed) == fmi2OK)
            get_all_reals(c);
        free_instance(c);
    }

    /* A rejected fmi2SetReal changes nothing: the knob keeps the value set
     * before (read in the Error state: parameters need not be readable in
     * InitializationMode, FMI 2.0.4 §3.2.3 condition 2). */
    fmi2Component c = instance_in(ME_INIT);
    if (c) {
        const fmi2ValueReference vrs[2] = { PROFILE_KNOB, PROFILE_KNOB };
        const double before = PROFILE_KNOB_VALUE(2e-3), values[2] = { PROFILE_KNOB_VALUE(0.5), NAN };
        double after = 0;
        CHECK(f->SetReal(c, vrs, 1, &before) == fmi2OK, "the knob = %g refused", before);
        CHECK(f->SetReal(c, vrs, 2, values) == fmi2Error, "the knob = NaN accepted");
        CHECK(f->GetReal(c, vrs, 1, &after) == fmi2OK, "reading the knob in the Error state");
        CHECK(before == after, "a rejected fmi2SetReal changed the knob from %g to %g", before, after);
        free_instance(c);
    }
}

/* -------------------------------------------------- instantiate, logging */

static void test_instantiate_arguments(void)
{
    const fmi2CallbackFunctions *cb = &harness_callbacks;
    fmi2CallbackFunctions no_alloc = *cb, no_free = *cb, no_logger = *cb;
    no_alloc.allocateMemory = NULL;
    no_free.freeMemory = NULL;
    no_logger.logger = NULL;
    const char *g = harness_guid;
    char *long_text = malloc(100001);
    if (!CHECK(long_text != NULL, "out of memory")) return;
    for (int k = 0; k < 100000; ++k) long_text[k] = "%s%n%d%%x"[k % 9];
    long_text[100000] = '\0';

    CHECK(f->Instantiate("rod", fmi2ModelExchange, g, "", NULL, fmi2False, fmi2False) == NULL, "functions NULL");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, g, "", &no_alloc, fmi2False, fmi2False) == NULL,
          "allocateMemory NULL");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, g, "", &no_free, fmi2False, fmi2False) == NULL, "freeMemory NULL");
    CHECK(f->Instantiate(NULL, fmi2ModelExchange, g, "", cb, fmi2False, fmi2False) == NULL, "instanceName NULL");
    CHECK(f->Instantiate("", fmi2ModelExchange, g, "", cb, fmi2False, fmi2False) == NULL, "instanceName empty");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, NULL, "", cb, fmi2False, fmi2False) == NULL, "GUID NULL");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, "{wrong}", "", cb, fmi2False, fmi2False) == NULL, "GUID wrong");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, long_text, "", cb, fmi2False, fmi2False) == NULL, "GUID long");
    CHECK(f->Instantiate("rod", (fmi2Type)7, g, "", cb, fmi2False, fmi2False) == NULL, "fmuType 7");
    CHECK(f->Instantiate("rod", (fmi2Type)-1, g, "", cb, fmi2False, fmi2False) == NULL, "fmuType -1");
    CHECK(harness.live == 0, "a failed fmi2Instantiate left %ld blocks allocated", harness.live);

    /* Co-Simulation: this build may or may not offer it; either way nothing leaks. */
    fmi2Component c = f->Instantiate("rod", fmi2CoSimulation, g, "", cb, fmi2False, fmi2False);
    if (c) free_instance(c);
    CHECK(harness.live == 0, "fmi2Instantiate(fmi2CoSimulation) leaked %ld blocks", harness.live);

    /* Allowed oddities: no logger, no resource location, a long name full of '%'. */
    const struct { const char *name, *resources; const fmi2CallbackFunctions *cb; } OK_CASES[] = {
        { "rod", NULL, &no_logger }, { "rod", NULL, cb }, { long_text, long_text, cb }, { "%s%n", "%s", cb },
    };
    for (size_t k = 0; k < sizeof OK_CASES / sizeof OK_CASES[0]; ++k) {
        c = f->Instantiate(OK_CASES[k].name, fmi2ModelExchange, g, OK_CASES[k].resources, OK_CASES[k].cb, fmi2True,
                           fmi2True);
        if (!CHECK(c != NULL, "fmi2Instantiate case %zu failed", k)) continue;
        CHECK(set_one(c, PROFILE_KNOB, NAN) == fmi2Error, "the knob = NaN accepted");
        check_reset_recovers(c, "odd instantiate arguments");
        free_instance(c);
    }
    free(long_text);
}

/* allocateMemory returning NULL at each allocation of fmi2Instantiate in turn. */
static void test_allocation_failure(void)
{
    for (long k = 1; k <= 16; ++k) {
        harness.fail_allocation_at = harness.allocations + k;
        fmi2Component c = harness_instantiate(f, "rod");
        const bool failed_inside = harness.allocations >= harness.fail_allocation_at;
        harness.fail_allocation_at = 0;
        if (failed_inside) {
            CHECK(c == NULL, "fmi2Instantiate succeeded although allocation %ld returned NULL", k);
            CHECK(harness.live == 0, "fmi2Instantiate that failed at allocation %ld leaked %ld blocks", k,
                  harness.live);
        } else {
            CHECK(c != NULL, "fmi2Instantiate failed without an allocation failure");
        }
        if (c) {
            check_reset_recovers(c, "after allocation failures");
            free_instance(c);
        }
        if (!failed_inside) break;
    }
}

static void test_logging(void)
{
    char long_category[5000];
    memset(long_category, '%', sizeof long_category - 1);
    long_category[sizeof long_category - 1] = '\0';
    const fmi2String KNOWN[] = { "logEvents", "logStatusWarning", "logStatusError", "logAll" };
    const fmi2String UNKNOWN[] = { "logEvents", "logNothing" };
    const fmi2String LONG[] = { long_category };
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetDebugLogging(c, fmi2True, 4, KNOWN));
    EXPECT_IN(ME_ERROR, fmi2OK, f->SetDebugLogging(c, fmi2False, 4, KNOWN));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetDebugLogging(c, fmi2True, 2, UNKNOWN));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetDebugLogging(c, fmi2True, 1, LONG));

    /* With every category on, a simulation logs its events, all well formed. */
    fmi2Component c = instance_in(ME_INSTANTIATED);
    if (c) {
        const long before = harness.messages;
        CHECK(f->SetDebugLogging(c, fmi2True, 0, NULL) == fmi2OK, "logging on");
        EulerSim s = { .c = c };
        CHECK(harness_simulate(f, &s, 0.1, 5e-3, 60) == fmi2OK, "simulation with logging: %s", harness.last_message);
        CHECK(harness.messages > before, "no message logged by a simulation with events and logging on");
        free_instance(c);
    }
}

/* ----------------------------------------------------- FMU state bytes */

/* A copy of n bytes in a block of exactly n, so that any read past the end is caught. */
static fmi2Byte *exact_copy(const fmi2Byte *bytes, size_t n)
{
    fmi2Byte *p = malloc(n ? n : 1);
    if (p && n) memcpy(p, bytes, n);
    return p;
}

/* Serialized states cut short or with a byte changed are refused, never
 * read past their end; an intact one round-trips. Skipped where the FMU does
 * not serialize its state. */
static void test_serialized_state_bytes(State state)
{
    fmi2Component c = instance_in(state);
    if (!c) return;
    fmi2FMUstate s = NULL, t = NULL;
    size_t size = 0;
    fmi2Byte *bytes = NULL, *again = NULL;
    if (f->GetFMUstate(c, &s) != fmi2OK || f->SerializedFMUstateSize(c, s, &size) != fmi2OK) goto done;
    bytes = malloc(size ? size : 1);
    again = malloc(size ? size : 1);
    if (!CHECK(bytes && again, "out of memory")) goto done;
    if (!CHECK(f->SerializeFMUstate(c, s, bytes, size) == fmi2OK, "fmi2SerializeFMUstate: %s", harness.last_message))
        goto done;
    CHECK(f->DeSerializeFMUstate(c, bytes, size, &t) == fmi2OK, "intact state refused: %s", harness.last_message);
    CHECK(f->SerializeFMUstate(c, t, again, size) == fmi2OK && memcmp(bytes, again, size) == 0,
          "a deserialized state serializes differently");
    CHECK(f->SetFMUstate(c, t) == fmi2OK, "fmi2SetFMUstate of a deserialized state: %s", harness.last_message);
    f->FreeFMUstate(c, &t);

    fmi2Byte *small = exact_copy(bytes, size - 1);
    CHECK(f->SerializeFMUstate(c, s, small, size - 1) == fmi2Error, "a state serialized into %zu of %zu bytes",
          size - 1, size);
    CHECK(f->Reset(c) == fmi2OK, "fmi2Reset");
    free(small);
    for (size_t n = 0; n < size; ++n) {
        fmi2Byte *prefix = exact_copy(bytes, n);
        fmi2Status st = f->DeSerializeFMUstate(c, prefix, n, &t);
        CHECK(st != fmi2OK, "a state cut to %zu of %zu bytes was accepted", n, size);
        if (st == fmi2OK) f->FreeFMUstate(c, &t);
        if (st == fmi2Error) CHECK(f->Reset(c) == fmi2OK, "fmi2Reset");
        free(prefix);
    }
    /* Every byte set to values on the edges of lengths and counts. */
    static const unsigned char EDGES[] = { 0x00, 0x01, 0x3f, 0x40, 0x41, 0x7f, 0x80, 0xff };
    for (size_t n = 0; n < size; ++n) {
        for (size_t k = 0; k < sizeof EDGES; ++k) {
            if ((unsigned char)bytes[n] == EDGES[k]) continue;
            fmi2Byte *changed = exact_copy(bytes, size);
            changed[n] = (fmi2Byte)EDGES[k];
            fmi2Status st = f->DeSerializeFMUstate(c, changed, size, &t);
            CHECK(st != fmi2OK, "a state with byte %zu of %zu set to %#x was accepted", n, size, EDGES[k]);
            if (st == fmi2OK) f->FreeFMUstate(c, &t);
            if (st == fmi2Error) CHECK(f->Reset(c) == fmi2OK, "fmi2Reset");
            free(changed);
        }
    }
done:
    if (s) f->FreeFMUstate(c, &s);
    free(bytes);
    free(again);
    free_instance(c);
}

/* --------------------------------------------------- instances together */

static bool same_state(const EulerSim *a, const EulerSim *b)
{
    return memcmp(a->x, b->x, sizeof a->x) == 0 && a->events == b->events;
}

/* Instances stepped in turn are independent: equal set-ups give equal runs. */
static void test_interleaved_instances(void)
{
    enum { N = 32, STEPS = 60 };
    EulerSim s[N];
    char name[32];
    for (int k = 0; k < N; ++k) {
        snprintf(name, sizeof name, "rod%d", k);
        s[k] = (EulerSim){ .c = harness_instantiate(f, name) };
        if (!CHECK(s[k].c != NULL, "instance %d", k)) return;
        CHECK(euler_start(f, &s[k], k % 2 ? 0.1 : 0.05) == fmi2OK, "start %d", k);
    }
    for (int step = 0; step < STEPS; ++step)
        for (int k = 0; k < N; ++k) {
            if (!s[k].c) continue;
            CHECK(euler_step(f, &s[k], 5e-3) == fmi2OK, "instance %d step %d: %s", k, step, harness.last_message);
            /* Some instances leave early, in various states. */
            if (k % 5 == 4 && step == STEPS / 2 + k) {
                f->FreeInstance(s[k].c);
                s[k].c = NULL;
            }
        }
    for (int k = 2; k < N; ++k)
        if (s[k].c && s[k % 2].c)
            CHECK(same_state(&s[k], &s[k % 2]), "instance %d ended unlike instance %d", k, k % 2);
    if (MODEL_NZ > 0)
        CHECK(s[0].events > 0 && s[1].events > 0, "the runs crossed no event (%d, %d)", s[0].events, s[1].events);
    for (int k = N - 1; k >= 0; k -= 2)
        if (s[k].c) f->FreeInstance(s[k].c);
    for (int k = 0; k < N; k += 2)
        if (s[k].c) f->FreeInstance(s[k].c);
    CHECK(harness.live == 0, "%ld blocks left after freeing every instance", harness.live);
}

/* ------------------------------------------------------- Co-Simulation */

static fmi2Component cs_instance(void)
{
    return f->Instantiate("cs rod", fmi2CoSimulation, harness_guid, "", &harness_callbacks, fmi2False, fmi2False);
}

/* Set-up and initialization of a Co-Simulation instance; time 0. */
static fmi2Status cs_start(fmi2Component c, double epsilon)
{
    const fmi2ValueReference vr = PROFILE_KNOB;
    const double value = PROFILE_KNOB_VALUE(epsilon);
    fmi2Status st = f->SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0);
    if (st == fmi2OK) st = f->SetReal(c, &vr, 1, &value);
    if (st == fmi2OK) st = f->EnterInitializationMode(c);
    if (st == fmi2OK) st = f->ExitInitializationMode(c);
    return st;
}

/* `steps` communication steps of h from *t (which follows). */
static fmi2Status cs_run(fmi2Component c, double *t, double h, int steps)
{
    for (int k = 0; k < steps; ++k) {
        const fmi2Status st = f->DoStep(c, *t, h, fmi2True);
        if (st != fmi2OK) return st;
        *t += h;
    }
    return fmi2OK;
}

/* Whether this build steps: without SUNDIALS, fmi2DoStep always fails. */
static bool cosimulation_available(void)
{
    fmi2Component c = cs_instance();
    if (!c) return false;
    double t = 0;
    fmi2Status st = cs_start(c, 0.05);
    if (st == fmi2OK) st = cs_run(c, &t, 1e-3, 1);
    free_instance(c);
    return st == fmi2OK;
}

static void test_cosimulation_bad_steps(void)
{
    static const double BAD_H[] = { 0.0, -0.0, -1e-3, NAN, INFINITY, -INFINITY, -DBL_MAX };
    for (size_t k = 0; k < sizeof BAD_H / sizeof BAD_H[0]; ++k) {
        fmi2Component c = instance_in(CS_STEP_COMPLETE);
        if (!c) continue;
        CHECK(f->DoStep(c, 0.06, BAD_H[k], fmi2True) == fmi2Error, "fmi2DoStep with step size %g accepted", BAD_H[k]);
        free_instance(c);
    }
    static const double BAD_T[] = { 0.0, 0.07, NAN, INFINITY, -1.0 };
    for (size_t k = 0; k < sizeof BAD_T / sizeof BAD_T[0]; ++k) {
        fmi2Component c = instance_in(CS_STEP_COMPLETE); /* at t = 0.06 */
        if (!c) continue;
        CHECK(f->DoStep(c, BAD_T[k], 1e-3, fmi2True) == fmi2Error, "fmi2DoStep from t = %g accepted at 0.06",
              BAD_T[k]);
        free_instance(c);
    }
    fmi2Component c = instance_in(CS_INIT);
    if (c) {
        CHECK(f->DoStep(c, 0, 1e-3, fmi2True) == fmi2Error, "fmi2DoStep accepted during initialization");
        free_instance(c);
    }
}

/* An FMU state taken mid-run and set again gives the same steps. */
static void test_cosimulation_state_restores_the_run(void)
{
    fmi2Component c = instance_in(CS_STEP_COMPLETE);
    if (!c) return;
    fmi2ValueReference vr[MODEL_NX];
    double first[MODEL_NX], second[MODEL_NX], t = 0.06, t_saved;
    for (int i = 0; i < MODEL_NX; ++i) vr[i] = md_var(md_state_index(i))->vr;
    fmi2FMUstate s = NULL;
    if (!CHECK(f->GetFMUstate(c, &s) == fmi2OK, "fmi2GetFMUstate: %s", harness.last_message)) goto done;
    t_saved = t;
    CHECK(cs_run(c, &t, 0.02, 10) == fmi2OK && f->GetReal(c, vr, MODEL_NX, first) == fmi2OK, "first run: %s",
          harness.last_message);
    CHECK(f->SetFMUstate(c, s) == fmi2OK, "fmi2SetFMUstate: %s", harness.last_message);
    t = t_saved;
    CHECK(cs_run(c, &t, 0.02, 10) == fmi2OK && f->GetReal(c, vr, MODEL_NX, second) == fmi2OK, "second run: %s",
          harness.last_message);
    CHECK(memcmp(first, second, sizeof first) == 0, "the run after fmi2SetFMUstate differs (%s %.17g vs %.17g)",
          md_var(md_state_index(0))->name, first[0], second[0]);
done:
    if (s) f->FreeFMUstate(c, &s);
    free_instance(c);
}

/* --------------------------------------------------------- memory soak */

static long resident_kb(void)
{
    long size = 0, resident = 0;
    FILE *fp = fopen("/proc/self/statm", "r");
    if (!fp) return -1;
    if (fscanf(fp, "%ld %ld", &size, &resident) != 2) resident = -1;
    fclose(fp);
    return resident < 0 ? -1 : resident * (sysconf(_SC_PAGESIZE) / 1024);
}

/* Instantiate, simulate (Model Exchange with events, or Co-Simulation every
 * fourth cycle), sometimes reset and simulate again or stop half-way, free:
 * `cycles` times, with the resident set measured after a warm-up and at the end. */
static void test_cycles(long cycles, long max_growth_kb, bool cosimulation)
{
    const long warmup = cycles / 10 < 1000 ? cycles / 10 : 1000;
    long rss_before = -1, events = 0;
    for (long k = 0; k < cycles; ++k) {
        if (k == warmup) rss_before = resident_kb();
        fmi2Status st;
        fmi2Component c;
        if (cosimulation && k % 4 == 1) {
            /* Co-Simulation: CVODE's memory, made on the first step, freed with the instance. */
            c = cs_instance();
            if (!CHECK(c != NULL, "cycle %ld: fmi2Instantiate(fmi2CoSimulation) failed", k)) return;
            double t = 0;
            st = cs_start(c, 0.05);
            if (st == fmi2OK) st = cs_run(c, &t, 0.02, k % 8 == 5 ? 3 : 12);
            if (k % 3 == 0 && st == fmi2OK) st = f->Reset(c);
        } else {
            c = harness_instantiate(f, "cycling rod");
            if (!CHECK(c != NULL, "cycle %ld: fmi2Instantiate failed", k)) return;
            EulerSim s = { .c = c };
            /* 24 steps cross about three events (stick, slip, lift-off); some runs stop early. */
            st = harness_simulate(f, &s, 0.05, 1e-2, k % 7 == 3 ? 6 : 24);
            events += s.events;
            if (k % 10 == 5 && st == fmi2OK) {
                st = f->Reset(c);
                if (st == fmi2OK) st = harness_simulate(f, &s, 0.05, 5e-3, 6);
            }
        }
        if (k % 13 == 7) (void)set_one(c, PROFILE_KNOB, NAN); /* leave through the Error state */
        f->FreeInstance(c);
        if (!CHECK(st == fmi2OK, "cycle %ld: %s (%s)", k, status_name(st), harness.last_message)) return;
        if (!CHECK(harness.live == 0, "cycle %ld left %ld blocks allocated", k, harness.live)) return;
    }
    const long rss_after = resident_kb();
    printf("cycles: %ld instantiate/simulate/free cycles, %ld events, %ld allocations; resident set %ld kB "
           "after %ld warm-up cycles, %ld kB at the end\n",
           cycles, events, harness.allocations, rss_before, warmup, rss_after);
    if (MODEL_NZ > 0) CHECK(cycles == 0 || events > cycles / 2, "the cycles crossed too few events (%ld)", events);
    if (max_growth_kb >= 0 && cycles > 0)
        CHECK(rss_after - rss_before <= max_growth_kb, "resident set grew by %ld kB over %ld cycles (bound %ld kB)",
              rss_after - rss_before, cycles - warmup, max_growth_kb);
}

/* ----------------------------------------------------------------- main */

static void test_platform_and_version(void)
{
    CHECK(strcmp(f->GetTypesPlatform(), "default") == 0, "types platform '%s'", f->GetTypesPlatform());
    CHECK(strcmp(f->GetVersion(), "2.0") == 0, "version '%s'", f->GetVersion());
}

/* The FMI 2.0.4 conformance table of both interfaces (conformance_*.c). */
static void test_conformance(bool cosimulation)
{
    test_platform_and_version(); /* the two calls without an instance, allowed everywhere */
    if (!CHECK(cosimulation, "Co-Simulation is not in this build: the conformance table needs both interfaces"))
        return;
    test_conformance_null_instance();
    test_conformance_table();
    test_conformance_variables();
    test_error_state_recovery();
    test_directional_derivatives();
    test_inputs();
}

int main(int argc, char **argv)
{
    const char *lib = FMU_LIBRARY;
    long cycles = 1000, max_growth_kb = -1;
    bool api_tests = true, conformance = true, robustness = true;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--lib") && k + 1 < argc) lib = argv[++k];
        else if (!strcmp(argv[k], "--cycles") && k + 1 < argc) cycles = atol(argv[++k]);
        else if (!strcmp(argv[k], "--max-rss-growth-kb") && k + 1 < argc) max_growth_kb = atol(argv[++k]);
        else if (!strcmp(argv[k], "--no-api")) api_tests = false;
        else if (!strcmp(argv[k], "--no-conformance")) conformance = false;
        else if (!strcmp(argv[k], "--conformance-only")) robustness = false;
        else {
            fprintf(stderr, "usage: %s [--lib PATH] [--cycles N] [--max-rss-growth-kb K] [--no-api] "
                            "[--no-conformance | --conformance-only]\n", argv[0]);
            return 2;
        }
    }
    char err[1024];
    if (!fmi2_functions_load(&api, lib, true, true, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    harness_reset();
    const bool cosimulation = cosimulation_available();
    printf("Co-Simulation %s\n", cosimulation ? "tested" : "not in this build: Model Exchange only");
    if (api_tests && conformance) test_conformance(cosimulation);
    if (api_tests && robustness) {
        test_null_arguments();
        test_value_references();
        test_nvr_zero_and_huge();
        test_large_arrays();
        test_bad_values();
        for (int state = ME_INSTANTIATED; state <= ME_TERMINATED; ++state) test_serialized_state_bytes((State)state);
        test_instantiate_arguments();
        test_allocation_failure();
        test_logging();
        test_interleaved_instances();
        if (cosimulation) {
            test_cosimulation_bad_steps();
            test_cosimulation_state_restores_the_run();
        }
    }
    if (robustness) test_cycles(cycles, max_growth_kb, cosimulation);
    CHECK(harness.bad_messages == 0, "%ld malformed log messages, the last: %s", harness.bad_messages,
          harness.last_bad);
    CHECK(harness.live == 0, "%ld blocks allocated through allocateMemory never freed", harness.live);
    fmi2_functions_unload(&api);
    printf("fmi_driver: %ld checks, %ld failed (%ld allocations, %ld log messages)\n", checks, failures,
           harness.allocations, harness.messages);
    return failures ? 1 : 0;
}
