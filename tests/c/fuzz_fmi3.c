/* SPDX-License-Identifier: BSD-2-Clause */
/* libFuzzer target for the FMI 3.0 layer: the input's bytes become a sequence
 * of fmi3 calls on up to three instances (Model Exchange, Co-Simulation with
 * and without Event Mode and early return), with the values, value
 * references, counts, array sizes and NULL pointers they carry. Besides
 * AddressSanitizer and UBSan it checks, and aborts on:
 *   - a status that is not an fmi3Status, an fmi3Error without an error logged
 *     (with a logger), a log message with a NULL field;
 *   - an fmi3OK output that is NaN or infinite;
 *   - a call that changes the instance succeeding after an fmi3Error without
 *     fmi3Reset or fmi3SetFMUState (§2.3.1: the instance is in Terminated);
 *   - fmi3DoStep returning fmi3OK with lastSuccessfulTime outside [t, t + h],
 *     an early return that was not allowed, or eventHandlingNeeded without
 *     eventModeUsed.
 *
 * Input format as fuzz_fmi.c's: an opcode byte (call = byte % N_OPS, instance
 * = byte / N_OPS % 3), then the call's arguments from the following bytes;
 * missing bytes read 0. Both targets replay tests/c/corpus (any bytes are an
 * input of either); seed3-* are this one's seeds, regress3-* inputs that once
 * broke an invariant (the first ones the target's own false alarms, since
 * fixed; regress3-*-hangs steps that never returned, from
 * tests/c/corpus_inputs.py).
 *
 *   fuzz_fmi3 CORPUS_DIR... [-runs=N] [-max_total_time=S]   fuzz (libFuzzer flags)
 *   fuzz_fmi3 FILE...                                         replay inputs */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FUZZ_NAME "fuzz_fmi3"
#include "fuzz_bytes.h"
#include "fmi3_harness.h"

static Fmi3Api api3;
static const Fmi3Api *const f = &api3;

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *lib = getenv("FUZZ_FMU_LIBRARY");
    char err[1024];
    if (!fmi3_api_load(&api3, lib ? lib : FMU_LIBRARY, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        exit(2);
    }
    return 0;
}

static Bytes in;

/* Mostly the model description's value references (event indicators and time too), sometimes far out. */
static fmi3ValueReference take_vr(void)
{
    static const fmi3ValueReference FAR[] = { VR_COUNT + CONTACT_NZ + 1, 255, 1000, 0x80000000u, UINT_MAX };
    const uint8_t sel = take(&in);
    return sel < 224 ? sel % (VR_COUNT + CONTACT_NZ + 3) : FAR[sel % (sizeof FAR / sizeof FAR[0])];
}

#define CAP 8 /* capacity of every array handed to the FMU */

/* A count of value references and of values (not always equal), and whether
 * the arrays are NULL: small counts with real arrays, or huge ones with NULL. */
static void take_counts(size_t *nvr, size_t *nvalues, bool *null_arrays)
{
    static const size_t HUGE_N[] = { SIZE_MAX, SIZE_MAX / 2 + 1, (size_t)1 << 40, CAP + 1 };
    const uint8_t sel = take(&in), other = take(&in);
    *null_arrays = sel >= 240;
    *nvr = sel < 240 ? sel % (CAP + 1) : HUGE_N[sel % (sizeof HUGE_N / sizeof HUGE_N[0])];
    *nvalues = other < 224 || *null_arrays ? *nvr : other % (CAP + 1);
}

/* ------------------------------------------------------- the instances */

typedef struct {
    fmi3Instance c;
    bool logs, cs, event_mode, early;
    double time;   /* where the next fmi3DoStep starts */
    bool in_error; /* an fmi3Error since the last instantiation, reset or restored state */
} Slot;

static Slot slots[3];
static double span_left; /* time fmi3DoStep may still integrate in this input */

static void free_slot(Slot *s)
{
    if (s->c) f->FreeInstance(s->c);
    memset(s, 0, sizeof *s);
}

/* Checks a status; `changes`: a call that changes the instance, which
 * Terminated (where an fmi3Error leaves it) must refuse. */
static fmi3Status checked(Slot *s, const char *call, fmi3Status st, long errors_before, bool changes)
{
    INVARIANT(st >= fmi3OK && st <= fmi3Fatal, "%s returned %d", call, (int)st);
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
    if (!s->c) {
        INVARIANT(st == fmi3Error || st == fmi3Fatal, "%s on a NULL instance returned %d", call, (int)st);
        return st;
    }
    if (st >= fmi3Error) {
        INVARIANT(!s->logs || harness.error_messages > errors_before, "%s returned %d without logging an error", call,
                  (int)st);
        s->in_error = true;
    } else if (s->in_error) {
        INVARIANT(!changes || st > fmi3Warning, "%s succeeded after an fmi3Error", call);
    }
    return st;
}

#define CALL(slot, changes, expr) checked((slot), #expr, (expr), errors_before, (changes))

static void require_finite(const char *what, const double *v, size_t n)
{
    for (size_t k = 0; k < n && k < CAP; ++k) INVARIANT(isfinite(v[k]), "%s[%zu] = %g with fmi3OK", what, k, v[k]);
}

enum {
    OP_INSTANTIATE_ME, OP_INSTANTIATE_CS, OP_FREE, OP_RESET, OP_ENTER_INIT, OP_EXIT_INIT, OP_SET_FLOAT64,
    OP_GET_FLOAT64, OP_GET_OTHER, OP_SET_OTHER, OP_UPDATE, OP_ENTER_CT, OP_ENTER_STEP, OP_ENTER_EVENT, OP_SET_TIME,
    OP_SET_STATES, OP_GET_ARRAYS, OP_COMPLETED, OP_DO_STEP, OP_FMU_STATE, OP_SERIALIZED, OP_DERIVATIVES,
    OP_TERMINATE, OP_LOGGING, OP_NOT_THERE, N_OPS
};

static void op_instantiate(Slot *s, bool cs)
{
    static const char *const NAMES[] = { "rod", "%s%n%d", "", NULL };
    const uint8_t name = take(&in), token = take(&in), flags = take(&in);
    const char *t = token < 224 ? harness_guid : token < 240 ? "{b1036d9e-0000}" : NULL;
    fmi3LogMessageCallback logger = flags & 4 ? NULL : harness3_logger;
    free_slot(s);
    const char *n = NAMES[name % 4];
    s->c = cs ? f->InstantiateCoSimulation(n, t, flags & 8 ? NULL : "file:///tmp", fmi3False, flags & 1, flags & 16,
                                           flags & 32, NULL, 0, NULL, logger, NULL)
              : f->InstantiateModelExchange(n, t, flags & 8 ? NULL : "file:///tmp", fmi3False, flags & 1, NULL,
                                            logger);
    s->logs = logger != NULL;
    s->cs = cs;
    s->event_mode = (flags & 16) != 0;
    s->early = (flags & 32) != 0;
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
}

static void run_op(int op, Slot *s)
{
    const long errors_before = harness.error_messages;
    fmi3ValueReference vr[CAP], vr2[CAP];
    double v[CAP + ROD_NX + CONTACT_NZ], w[CAP];
    size_t nvr, nvalues;
    bool null_arrays;
    fmi3Boolean b1 = 7, b2 = 7, b3 = 7, b4 = 7, b5 = 7;
    fmi3Status st;
    switch (op) {
    case OP_INSTANTIATE_ME: op_instantiate(s, false); break;
    case OP_INSTANTIATE_CS: op_instantiate(s, true); break;
    case OP_FREE: free_slot(s); break;
    case OP_RESET:
        if (CALL(s, false, f->Reset(s->c)) == fmi3OK) s->in_error = false, s->time = 0;
        break;
    case OP_ENTER_INIT: {
        const uint8_t flags = take(&in);
        const double tol = take_double(&in), start = take_double(&in), stop = take_double(&in);
        if (CALL(s, true, f->EnterInitializationMode(s->c, flags & 1, tol, start, flags & 2, stop)) == fmi3OK)
            s->time = start;
        break;
    }
    case OP_EXIT_INIT: CALL(s, true, f->ExitInitializationMode(s->c)); break;
    case OP_SET_FLOAT64:
        take_counts(&nvr, &nvalues, &null_arrays);
        for (size_t k = 0; k < CAP; ++k) vr[k] = take_vr(), v[k] = take_double(&in);
        for (size_t k = 0; getenv("FUZZ_TRACE") && !null_arrays && k < nvr && k < CAP; ++k)
            fprintf(stderr, "  set %u = %.17g\n", vr[k], v[k]);
        CALL(s, true, f->SetFloat64(s->c, null_arrays ? NULL : vr, nvr, null_arrays ? NULL : v, nvalues));
        break;
    case OP_GET_FLOAT64:
        take_counts(&nvr, &nvalues, &null_arrays);
        for (size_t k = 0; k < CAP; ++k) vr[k] = take_vr();
        st = CALL(s, false, f->GetFloat64(s->c, null_arrays ? NULL : vr, nvr, null_arrays ? NULL : v, nvalues));
        if (st == fmi3OK) require_finite("fmi3GetFloat64", v, nvr);
        break;
    case OP_GET_OTHER: {
        fmi3Int32 i32[CAP];
        fmi3Boolean bb[CAP];
        fmi3String str[CAP];
        fmi3UInt64 u64[CAP];
        const uint8_t type = take(&in);
        take_counts(&nvr, &nvalues, &null_arrays);
        for (size_t k = 0; k < CAP; ++k) vr[k] = take_vr();
        const fmi3ValueReference *p = null_arrays ? NULL : vr;
        switch (type % 4) {
        case 0:
            st = CALL(s, false, f->GetInt32(s->c, p, nvr, null_arrays ? NULL : i32, nvalues));
            for (size_t k = 0; st == fmi3OK && k < nvr && k < CAP; ++k)
                INVARIANT(vr[k] != VR_MODE || (i32[k] >= -1 && i32[k] <= 1), "mode = %d", (int)i32[k]);
            break;
        case 1:
            st = CALL(s, false, f->GetBoolean(s->c, p, nvr, null_arrays ? NULL : bb, nvalues));
            for (size_t k = 0; st == fmi3OK && k < nvr && k < CAP; ++k)
                INVARIANT(bb[k] == fmi3True || bb[k] == fmi3False, "Boolean %d", (int)bb[k]);
            break;
        case 2: CALL(s, false, f->GetString(s->c, p, nvr, null_arrays ? NULL : str, nvalues)); break;
        default: CALL(s, false, f->GetUInt64(s->c, p, nvr, null_arrays ? NULL : u64, nvalues));
        }
        break;
    }
    case OP_SET_OTHER: {
        fmi3Int32 i32[CAP];
        fmi3Boolean bb[CAP];
        const fmi3String str[CAP] = { "", "x", "%s", NULL, "", "", "", "" };
        const uint8_t type = take(&in);
        take_counts(&nvr, &nvalues, &null_arrays);
        for (size_t k = 0; k < CAP; ++k) vr[k] = take_vr(), i32[k] = (fmi3Int32)(int8_t)take(&in), bb[k] = take(&in) & 1;
        const fmi3ValueReference *p = null_arrays ? NULL : vr;
        switch (type % 3) {
        case 0: CALL(s, true, f->SetInt32(s->c, p, nvr, null_arrays ? NULL : i32, nvalues)); break;
        case 1: CALL(s, true, f->SetBoolean(s->c, p, nvr, null_arrays ? NULL : bb, nvalues)); break;
        default: CALL(s, true, f->SetString(s->c, p, nvr, null_arrays ? NULL : str, nvalues));
        }
        break;
    }
    case OP_UPDATE: {
        const uint8_t nulls = take(&in);
        double next = NAN;
        st = CALL(s, true, f->UpdateDiscreteStates(s->c, nulls == 1 ? NULL : &b1, &b2, &b3, &b4, &b5,
                                                     nulls == 2 ? NULL : &next));
        if (st == fmi3OK) INVARIANT(b1 <= 1 && b2 <= 1 && b3 <= 1 && b4 <= 1 && b5 <= 1, "flags not Booleans");
        break;
    }
    case OP_ENTER_CT: CALL(s, true, f->EnterContinuousTimeMode(s->c)); break;
    case OP_ENTER_STEP: CALL(s, true, f->EnterStepMode(s->c)); break;
    case OP_ENTER_EVENT: CALL(s, true, f->EnterEventMode(s->c)); break;
    case OP_SET_TIME: {
        const double t = take(&in) & 1 ? take_double(&in) : s->time + 1e-4 * take(&in);
        if (CALL(s, true, f->SetTime(s->c, t)) == fmi3OK) s->time = t;
        break;
    }
    case OP_SET_STATES: {
        const size_t n = take(&in) < 200 ? ROD_NX : take(&in) % (ROD_NX + 2);
        for (size_t k = 0; k < ROD_NX + 2; ++k) v[k] = take_double(&in);
        CALL(s, true, f->SetContinuousStates(s->c, take(&in) == 255 ? NULL : v, n));
        break;
    }
    case OP_GET_ARRAYS: {
        const uint8_t which = take(&in), sel = take(&in);
        const size_t n = (which % 4 == 1 ? CONTACT_NZ : ROD_NX) + (sel < 200 ? 0 : (size_t)(sel % 3) - 1);
        fmi3Float64 *out = sel == 255 ? NULL : v;
        switch (which % 4) {
        case 0: st = CALL(s, false, f->GetContinuousStateDerivatives(s->c, out, n)); break;
        case 1: st = CALL(s, false, f->GetEventIndicators(s->c, out, n)); break;
        case 2: st = CALL(s, false, f->GetContinuousStates(s->c, out, n)); break;
        default: st = CALL(s, false, f->GetNominalsOfContinuousStates(s->c, out, n));
        }
        if (st == fmi3OK) require_finite("array", v, n);
        break;
    }
    case OP_COMPLETED: {
        const uint8_t nulls = take(&in);
        CALL(s, true, f->CompletedIntegratorStep(s->c, nulls & 1, nulls == 2 ? NULL : &b1, nulls == 4 ? NULL : &b2));
        break;
    }
    case OP_DO_STEP: {
        const uint8_t sel = take(&in);
        const double t = sel < 224 ? s->time : take_double(&in);
        double h = sel % 2 ? take_double(&in) : 1e-3 * (1 + take(&in));
        /* Bounded integration per input (a step of hundreds of time units is a long
         * run of bounces, not a finding): a legal step past the bound is cut to 1e-3;
         * bad ones (NaN, infinite, <= 0) go through, for the FMU to refuse. */
        if (isfinite(h) && h > 0) {
            if (h <= span_left) span_left -= h;
            else h = 1e-3;
        }
        double last = NAN;
        if (getenv("FUZZ_TRACE")) fprintf(stderr, "fmi3DoStep(%.17g, %.17g)\n", t, h);
        st = CALL(s, true, f->DoStep(s->c, t, h, fmi3True, &b1, &b2, &b3, &last));
        if (st == fmi3OK) {
            /* [t, t + h]: a step smaller than an ulp of t ends where it began (t + h == t). */
            INVARIANT(last >= t && last <= t + h, "lastSuccessfulTime %.17g outside [%.17g, %.17g]", last, t, t + h);
            INVARIANT(s->early || !b3, "an early return without earlyReturnAllowed");
            INVARIANT(s->event_mode || !b1, "eventHandlingNeeded without eventModeUsed");
            INVARIANT(b3 || last == t + h, "lastSuccessfulTime %.17g without an early return", last);
            s->time = last;
        }
        break;
    }
    case OP_FMU_STATE: {
        fmi3FMUState state = NULL;
        const uint8_t sel = take(&in);
        st = CALL(s, false, f->GetFMUState(s->c, sel == 1 ? NULL : &state));
        if (st == fmi3OK && state) {
            const double time = s->time;
            if (sel & 2) run_op(OP_DO_STEP, s);
            if (CALL(s, false, f->SetFMUState(s->c, state)) == fmi3OK) s->in_error = false, s->time = time;
            CALL(s, false, f->FreeFMUState(s->c, &state));
        }
        break;
    }
    case OP_SERIALIZED: {
        fmi3Byte bytes[512];
        fmi3FMUState state = NULL;
        size_t size = 0;
        const uint8_t len = take(&in);
        const size_t n = len < 200 ? len : (size_t)len * 2;
        for (size_t k = 0; k < n && k < sizeof bytes; ++k) bytes[k] = (fmi3Byte)take(&in);
        fmi3Byte *copy = malloc(n ? n : 1); /* exactly n bytes: a read past them is caught */
        if (!copy) break;
        memcpy(copy, bytes, n < sizeof bytes ? n : sizeof bytes);
        st = CALL(s, false, f->DeserializeFMUState(s->c, copy, n, &state));
        if (st == fmi3OK) {
            if (CALL(s, false, f->SerializedFMUStateSize(s->c, state, &size)) == fmi3OK && size <= sizeof bytes)
                CALL(s, false, f->SerializeFMUState(s->c, state, bytes, size));
            if (CALL(s, false, f->SetFMUState(s->c, state)) == fmi3OK) s->in_error = false;
            CALL(s, false, f->FreeFMUState(s->c, &state));
        }
        free(copy);
        break;
    }
    case OP_DERIVATIVES: {
        const uint8_t sel = take(&in);
        size_t nu, nk, nseed, nsens;
        take_counts(&nu, &nseed, &null_arrays);
        nk = take(&in) % (CAP + 1);
        nsens = sel & 2 ? (sel & 1 ? nk : nu) : take(&in) % (CAP + 1);
        if (!(sel & 2)) nseed = sel & 1 ? nu : nk;
        for (size_t k = 0; k < CAP; ++k) vr[k] = take_vr(), vr2[k] = take_vr(), w[k] = take_double(&in);
        if (nseed > CAP || nsens > CAP) null_arrays = true;
        const fmi3ValueReference *u = null_arrays ? NULL : vr, *kn = null_arrays ? NULL : vr2;
        st = sel & 1 ? CALL(s, false, f->GetAdjointDerivative(s->c, u, nu, kn, nk, null_arrays ? NULL : w, nseed,
                                                                null_arrays ? NULL : v, nsens))
                     : CALL(s, false, f->GetDirectionalDerivative(s->c, u, nu, kn, nk, null_arrays ? NULL : w, nseed,
                                                                    null_arrays ? NULL : v, nsens));
        if (st == fmi3OK) require_finite("sensitivity", v, nsens);
        break;
    }
    case OP_TERMINATE: CALL(s, true, f->Terminate(s->c)); break;
    case OP_LOGGING: {
        const fmi3String cats[] = { "logEvents", "logAll", "logNothing", NULL, "%s%n" };
        const uint8_t on = take(&in), n = take(&in) % 4, first = take(&in);
        fmi3String chosen[3];
        for (size_t k = 0; k < 3; ++k) chosen[k] = cats[(first + k) % 5];
        CALL(s, false, f->SetDebugLogging(s->c, on & 1, n, take(&in) == 255 ? NULL : chosen));
        break;
    }
    default: { /* what this FMU does not have */
        size_t n;
        fmi3Clock clocks[CAP];
        vr[0] = take_vr();
        switch (take(&in) % 5) {
        case 0: CALL(s, true, f->GetNumberOfVariableDependencies(s->c, vr[0], &n)); break;
        case 1: CALL(s, true, f->EnterConfigurationMode(s->c)); break;
        case 2: CALL(s, true, f->GetClock(s->c, vr, 1, clocks)); break;
        case 3: CALL(s, true, f->EvaluateDiscreteStates(s->c)); break;
        default: CALL(s, false, f->GetNumberOfContinuousStates(s->c, take(&in) == 255 ? NULL : &n));
        }
    }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    harness_reset();
    in = (Bytes){ data, size };
    span_left = 0.2; /* twice the default experiment */
    for (int calls = 0; in.n > 0 && calls < 256; ++calls) {
        const uint8_t op = take(&in);
        if (getenv("FUZZ_TRACE")) fprintf(stderr, "op %d on instance %d\n", op % N_OPS, op / N_OPS % 3);
        run_op(op % N_OPS, &slots[op / N_OPS % 3]);
    }
    for (int k = 0; k < 3; ++k) free_slot(&slots[k]);
    return 0;
}
