/* SPDX-License-Identifier: BSD-2-Clause */
/* libFuzzer target: every call returns, with a legal status, whatever the
 * tolerance, start time, step sizes, parameters, start states and inputs.
 * One input is one run of one instance (FMI 2.0: fuzz_bounded for
 * PainleveRod, fuzz_bounded_NAME for models/NAME; FMI 3.0: fuzz_bounded3),
 * Model Exchange (explicit Euler with event iterations) or Co-Simulation:
 *
 *   byte    flags: 1 Co-Simulation, 2 tolerance defined, 4 stop time defined, 8 logging on
 *   ...     the relative tolerance (an edge: 1e-14 ... 48.125 and past them, log-uniform in
 *           [1e-16, 100], or any double), the start time (an edge, a modest one, or any double)
 *   ...     for each Real parameter of modelDescription.xml (its order): keep the start value,
 *           start * 10^[-4, 4], min, max, log-uniform in [min, max], or any double
 *   ...     for each state and input: keep the start value, or start + [-1, 1] * 10^[-8, 3]
 *   ...     steps, one byte each: h = span * 10^-(byte % 64 / 8) (span: the profile's
 *           PROFILE_BOUNDED_SPAN, else PROFILE_FUZZ_SPAN), an input set anew before the
 *           step when the byte >= 192
 *
 * The integrated time of an input is bounded (one span) and its calls (8
 * doSteps, 200 Euler steps), not the work: a call's work is the FMU's to bound
 * (FUZZ_TRACE=1 prints each call with its time). Besides
 * AddressSanitizer and UBSan (and libFuzzer's -timeout: a call that does not
 * return is a finding), it aborts on:
 *   - a status that is not OK, Warning, Discard or Error (Fatal included);
 *   - fmi2Discard/fmi3Discard from any call but a doStep;
 *   - after a doStep's Discard, a getter of the outputs failing or giving NaN or infinity;
 *   - an Error without an error logged.
 * An Error ends the run (the standard's Error state), as does a Discard.
 *
 *   fuzz_bounded CORPUS_DIR... [-runs=N] [-seed=S] [-timeout=T]   fuzz
 *   fuzz_bounded FILE...                                            replay */
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef BOUNDED_FMI3
#define FUZZ_NAME "fuzz_bounded3"
#else
#define FUZZ_NAME "fuzz_bounded"
#endif
#include "fuzz_bytes.h"
#ifdef BOUNDED_FMI3
#include "fmi3_harness.h"
#else
#include "fmi_harness.h"
#endif
#include "model_structure.h"

#ifndef PROFILE_BOUNDED_SPAN
#define PROFILE_BOUNDED_SPAN PROFILE_FUZZ_SPAN
#endif

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { ST_OK, ST_WARNING, ST_DISCARD, ST_ERROR, ST_FATAL };

#ifdef BOUNDED_FMI3
static Fmi3Api api;
typedef fmi3Instance Instance;
#else
static FmiApi api;
typedef fmi2Component Instance;
#endif

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *lib = getenv("FUZZ_FMU_LIBRARY");
    char err[1024];
#ifdef BOUNDED_FMI3
    const bool loaded = fmi3_api_load(&api, lib ? lib : FMU_LIBRARY, err, sizeof err);
#else
    const bool loaded = fmi2_functions_load(&api, lib ? lib : FMU_LIBRARY, true, true, err, sizeof err);
#endif
    if (!loaded) {
        fprintf(stderr, "%s\n", err);
        exit(2);
    }
    return 0;
}

static Bytes in;

/* Every status: one of OK, Warning, Discard, Error; Discard only where `may_discard`; an Error logged. */
static int check(const char *call, int st, long errors_before, bool may_discard)
{
    INVARIANT(st >= ST_OK && st <= ST_ERROR, "%s returned %d", call, st);
    INVARIANT(st != ST_DISCARD || may_discard, "%s returned Discard (only a doStep may)", call);
    INVARIANT(st != ST_ERROR || harness.error_messages > errors_before,
              "%s returned Error without logging an error", call);
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
    if (getenv("FUZZ_TRACE")) { /* with the time since the previous call returned */
        static struct timespec last;
        struct timespec now;
        clock_gettime(CLOCK_MONOTONIC, &now);
        fprintf(stderr, "  %s -> %d (%.3f s)\n", call, st,
                (double)(now.tv_sec - last.tv_sec) + 1e-9 * (double)(now.tv_nsec - last.tv_nsec));
        last = now;
    }
    return st;
}

/* The count of errors logged before the call (the comma operator reads it first). */
static long errors_before;
#define CALL(expr) (errors_before = harness.error_messages, check(#expr, (int)(expr), errors_before, false))

/* ------------------------------------------------------------- the values */

static double take_tolerance(void)
{
    static const double EDGES[] = { 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2, 0.1, 0.5, 1.0, 10.0, 48.125,
                                    DBL_MIN, 1e-300, 1e-16, 1e3, 1e300, 0.0 };
    const uint8_t sel = take(&in);
    if (sel < 128) return EDGES[sel % (sizeof EDGES / sizeof EDGES[0])];
    if (sel < 250) return pow(10.0, -16.0 + 18.0 * take(&in) / 255.0);
    return take_double(&in);
}

static double take_start_time(void)
{
    static const double EDGES[] = { 0.0, 48.125, -1e4, 1e6, 1e9, 1e-300, -0.0, 100.5, -48.125, 1e15 };
    const uint8_t sel = take(&in);
    if (sel < 128) return EDGES[sel % (sizeof EDGES / sizeof EDGES[0])];
    if (sel < 250) return (double)(int16_t)(take(&in) << 8 | take(&in)) / 16.0;
    return take_double(&in);
}

/* A parameter's value, or NAN to keep its start value. */
static double take_parameter(const MdVariable *v)
{
    const double lo = v->has_min ? v->min : -DBL_MAX, hi = v->has_max ? v->max : DBL_MAX;
    const double start = v->has_start ? v->start : 0.0;
    const uint8_t sel = take(&in);
    if (sel < 96) return NAN;
    if (sel < 160) {
        const double x = (start != 0 ? start : 1.0) * pow(10.0, (double)(int8_t)take(&in) / 32.0);
        return fmin(fmax(x, lo), hi);
    }
    if (sel < 176) return v->has_min ? lo : start;
    if (sel < 192) return v->has_max ? hi : start;
    if (sel < 240) {
        const double a = lo > 0 ? lo : hi > 0 && hi < DBL_MAX ? hi * 1e-12 : 1e-6, b = hi < DBL_MAX ? hi : 1e6;
        return a < b ? a * pow(b / a, take(&in) / 255.0) : start;
    }
    return take_double(&in);
}

/* A state's or input's value, or NAN to keep its start value. */
static double take_excursion(const MdVariable *v)
{
    const uint8_t sel = take(&in);
    if (sel < 128) return NAN;
    const double scale = pow(10.0, (double)(take(&in) % 12) - 8.0);
    return (v->has_start ? v->start : 0.0) + (double)(int8_t)take(&in) / 128.0 * scale;
}

/* ---------------------------------------------------------- the FMI layer */

static Instance instantiate(bool cs, bool logging)
{
#ifdef BOUNDED_FMI3
    return cs ? harness3_instantiate_cs(&api, "rod", logging, false, false)
              : harness3_instantiate_me(&api, "rod", logging);
#else
    return api.Instantiate("rod", cs ? fmi2CoSimulation : fmi2ModelExchange, harness_guid, "file:///tmp",
                           &harness_callbacks, fmi2False, logging);
#endif
}

static int set_real(Instance c, unsigned vr, double value)
{
#ifdef BOUNDED_FMI3
    const fmi3ValueReference r = vr;
    return CALL(api.SetFloat64(c, &r, 1, &value, 1));
#else
    const fmi2ValueReference r = vr;
    return CALL(api.SetReal(c, &r, 1, &value));
#endif
}

/* Every Real output: its getter answers, with finite values. */
static void outputs_answer(Instance c, const char *after)
{
    for (int k = 1; k <= MD_N_VARIABLES; ++k) {
        const MdVariable *v = md_var(k);
        if (v->type != MD_REAL || v->causality != MD_OUTPUT) continue;
        double x = NAN;
#ifdef BOUNDED_FMI3
        const fmi3ValueReference r = v->vr;
        const int st = CALL(api.GetFloat64(c, &r, 1, &x, 1));
#else
        const fmi2ValueReference r = v->vr;
        const int st = CALL(api.GetReal(c, &r, 1, &x));
#endif
        INVARIANT(st <= ST_WARNING && isfinite(x), "after %s, %s = %g with status %d", after, v->name, x, st);
    }
}

/* The set-up: tolerance, start and stop time, parameters, states and inputs; initialization. */
static int initialize(Instance c, uint8_t flags, double *t, double span)
{
    const double tol = take_tolerance(), start = take_start_time();
    const bool tol_defined = flags & 2, stop_defined = flags & 4;
    if (getenv("FUZZ_TRACE")) fprintf(stderr, "tolerance %.17g (%d), start %.17g\n", tol, tol_defined, start);
    *t = start;
    int st;
#ifdef BOUNDED_FMI3
    st = CALL(api.EnterInitializationMode(c, tol_defined, tol, start, stop_defined, start + 2 * span));
#else
    st = CALL(api.SetupExperiment(c, tol_defined, tol, start, stop_defined, start + 2 * span));
    if (st <= ST_WARNING) st = CALL(api.EnterInitializationMode(c));
#endif
    for (int k = 1; st <= ST_WARNING && k <= MD_N_VARIABLES; ++k) {
        const MdVariable *v = md_var(k);
        if (v->type != MD_REAL) continue;
        double x = NAN;
        if (v->causality == MD_PARAMETER && (v->variability == MD_FIXED || v->variability == MD_TUNABLE))
            x = take_parameter(v);
        else if (v->causality == MD_INPUT || (v->state && v->initial == MD_INITIAL_EXACT))
            x = take_excursion(v);
        if (isnan(x)) continue;
        if (getenv("FUZZ_TRACE")) fprintf(stderr, "set %s = %.17g\n", v->name, x);
        st = set_real(c, v->vr, x);
    }
    if (st <= ST_WARNING) st = CALL(api.ExitInitializationMode(c));
    return st;
}

/* An input (if the model has any) set anew between steps. */
static int set_an_input(Instance c, uint8_t which)
{
    int inputs[64], n = 0;
    for (int k = 1; k <= MD_N_VARIABLES && n < 64; ++k)
        if (md_var(k)->type == MD_REAL && md_var(k)->causality == MD_INPUT) inputs[n++] = k;
    if (!n) return ST_OK;
    const MdVariable *v = md_var(inputs[which % n]);
    const double x = take_excursion(v);
    return isnan(x) ? ST_OK : set_real(c, v->vr, x);
}

/* Model Exchange: the event iteration, then Continuous-Time Mode. */
static int event_iteration(Instance c)
{
    bool changed;
#ifdef BOUNDED_FMI3
    int st = CALL(harness3_update_discrete_states(&api, c, &changed));
    if (st <= ST_WARNING) st = CALL(api.EnterContinuousTimeMode(c));
    return st;
#else
    return CALL(harness_event_iteration(&api, c, &changed));
#endif
}

/* Model Exchange: one explicit Euler step of h, then the event iteration where an indicator changed sign. */
static int me_step(Instance c, double *t, double h)
{
    double x[MODEL_NX > 0 ? MODEL_NX : 1], dx[MODEL_NX > 0 ? MODEL_NX : 1];
    double z[HARNESS_NZ] = { 0 }, z2[HARNESS_NZ] = { 0 };
    const size_t nx = MODEL_NX, nz = MODEL_NZ;
    int st;
#ifdef BOUNDED_FMI3
    fmi3Boolean enter = fmi3False, terminate = fmi3False;
    st = CALL(api.GetContinuousStates(c, x, nx));
    if (st <= ST_WARNING) st = CALL(api.GetContinuousStateDerivatives(c, dx, nx));
    if (st <= ST_WARNING) st = CALL(api.GetEventIndicators(c, z, nz));
    for (size_t k = 0; k < nx; ++k) x[k] += h * dx[k];
    *t += h;
    if (st <= ST_WARNING) st = CALL(api.SetTime(c, *t));
    if (st <= ST_WARNING) st = CALL(api.SetContinuousStates(c, x, nx));
    if (st <= ST_WARNING) st = CALL(api.GetEventIndicators(c, z2, nz));
    if (st <= ST_WARNING) st = CALL(api.CompletedIntegratorStep(c, fmi3True, &enter, &terminate));
#else
    fmi2Boolean enter = fmi2False, terminate = fmi2False;
    st = CALL(api.GetContinuousStates(c, x, nx));
    if (st <= ST_WARNING) st = CALL(api.GetDerivatives(c, dx, nx));
    if (st <= ST_WARNING) st = CALL(api.GetEventIndicators(c, z, nz));
    for (size_t k = 0; k < nx; ++k) x[k] += h * dx[k];
    *t += h;
    if (st <= ST_WARNING) st = CALL(api.SetTime(c, *t));
    if (st <= ST_WARNING) st = CALL(api.SetContinuousStates(c, x, nx));
    if (st <= ST_WARNING) st = CALL(api.GetEventIndicators(c, z2, nz));
    if (st <= ST_WARNING) st = CALL(api.CompletedIntegratorStep(c, fmi2True, &enter, &terminate));
#endif
    bool crossed = enter;
    for (size_t k = 0; k < nz; ++k) crossed |= (z[k] > 0) != (z2[k] > 0);
    if (st <= ST_WARNING && crossed) {
        st = CALL(api.EnterEventMode(c));
        if (st <= ST_WARNING) st = event_iteration(c);
    }
    return st;
}

static int do_step(Instance c, double *t, double h)
{
    int st;
#ifdef BOUNDED_FMI3
    fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
    double last = NAN;
    errors_before = harness.error_messages;
    st = check("fmi3DoStep", (int)api.DoStep(c, *t, h, fmi3True, &event, &terminate, &early, &last), errors_before,
               true);
    if (st == ST_OK) *t = last;
#else
    errors_before = harness.error_messages;
    st = check("fmi2DoStep", (int)api.DoStep(c, *t, h, fmi2True), errors_before, true);
    if (st == ST_OK) *t += h;
#endif
    return st;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    harness_reset();
    in = (Bytes){ data, size };
    const uint8_t flags = take(&in);
    const bool cs = flags & 1;
    const double span = PROFILE_BOUNDED_SPAN;
    Instance c = instantiate(cs, flags & 8);
    INVARIANT(c != NULL, "instantiation failed");
    double t;
    int st = initialize(c, flags, &t, span);
    if (!cs && st <= ST_WARNING) st = event_iteration(c);
    double left = span; /* integrated time */
    /* The calls of an input are bounded too, so that -timeout bounds one call's work: 8 doSteps (each
     * may use the FMU's whole budget: up to a second under the sanitizers) or 200 Euler steps (each a
     * few cheap calls and at most one event iteration). */
    const int max_steps = cs ? 8 : 200;
    for (int steps = 0; st <= ST_WARNING && in.n > 0 && steps < max_steps; ++steps) {
        const uint8_t sel = take(&in);
        const double h = span * pow(10.0, -(double)(sel % 64) / 8.0);
        if (h > left) break;
        left -= h;
        if (sel >= 192) st = set_an_input(c, take(&in));
        if (st > ST_WARNING) break;
        if (getenv("FUZZ_TRACE")) fprintf(stderr, "%s t = %.17g, h = %.17g\n", cs ? "doStep" : "Euler", t, h);
        st = cs ? do_step(c, &t, h) : me_step(c, &t, h);
        if (st == ST_DISCARD) outputs_answer(c, "a doStep's Discard");
    }
    if (st <= ST_DISCARD) CALL(api.Terminate(c));
    api.FreeInstance(c);
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
    return 0;
}
