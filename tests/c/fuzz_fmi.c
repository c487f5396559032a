/* libFuzzer target: the input's bytes become a sequence of FMI calls on up to
 * three instances of a model (one target per model: fuzz_fmi for PainleveRod,
 * fuzz_fmi_NAME for fmu_src/models/NAME), with the values, value references, counts
 * and NULL pointers they carry (NaN, infinities, denormals, range limits,
 * epsilon huge and tiny, raw bit patterns). Besides AddressSanitizer and
 * UBSan it checks, and aborts on:
 *   - a status that is not an fmi2Status, an fmi2Error without an error logged;
 *   - a log message with a lone '%' (the FMU passes its text unformatted);
 *   - an fmi2OK output that is NaN or infinite, a mode outside {-1, 0, 1};
 *   - a simulation call succeeding in the Error state without fmi2Reset;
 *   - a status query (§4.2.3) answering fmi2OK where there is nothing to
 *     report, or an fmi2Discard that changed the instance's state;
 *   - memory from allocateMemory still held after the instances are freed.
 *
 * Input format, one call at a time: an opcode byte (call = byte % N_OPS,
 * instance = byte / N_OPS % 3), then the call's arguments, each taken from the
 * following bytes (see take_double, take_vr, take_count); missing bytes read 0.
 *
 * tests/c/corpus holds the seeds (seed-*: a simulation with events, FMU
 * state round trips, two instances, logging, Co-Simulation, an error and a
 * reset) and the inputs that once broke an invariant (regress-*), kept as
 * regression cases: the first ones the target's own false alarms, since fixed;
 * regress-*issue23-* calls that never returned (issue 23), written from
 * readable call sequences by tests/c/corpus_inputs.py. The CI runs are
 * deterministic: -runs=N -seed=S over the corpus, -timeout per input.
 *
 *   fuzz_fmi CORPUS_DIR... [-runs=N] [-max_total_time=S]   fuzz (libFuzzer flags)
 *   fuzz_fmi FILE...                                         replay inputs */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FUZZ_NAME "fuzz_fmi"
#include "fuzz_bytes.h"
#include "fmi_harness.h"
#include "model_structure.h"

static FmiApi api;
static const FmiApi *const f = &api;

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *lib = getenv("FUZZ_FMU_LIBRARY");
    char err[1024];
    if (!fmi2_functions_load(&api, lib ? lib : FMU_LIBRARY, true, true, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        exit(2);
    }
    return 0;
}

/* ------------------------------------------------------------ the bytes */

/* A value reference: mostly near the valid ones, sometimes far out. */
static fmi2ValueReference take_vr(Bytes *b)
{
    static const fmi2ValueReference FAR[] = { VR_COUNT, 255, 1000, 0x7fffffffu, 0x80000000u, UINT_MAX - 1,
                                              UINT_MAX };
    const uint8_t sel = take(b);
    return sel < 224 ? sel % (VR_COUNT + 4) : FAR[sel % (sizeof FAR / sizeof FAR[0])];
}

#define CAP 8 /* capacity of every array handed to the FMU */

/* A count and whether the arrays are passed: small counts with real arrays,
 * or huge counts (and sometimes small ones) with NULL arrays. */
static size_t take_count(Bytes *b, bool *null_arrays)
{
    static const size_t HUGE_N[] = { SIZE_MAX, SIZE_MAX / 2 + 1, (size_t)1 << 40, (size_t)1 << 31, CAP + 1 };
    const uint8_t sel = take(b);
    *null_arrays = sel >= 240;
    if (sel < 240) return sel % (CAP + 1);
    return sel < 248 ? (size_t)(sel % 3) : HUGE_N[sel % (sizeof HUGE_N / sizeof HUGE_N[0])];
}

/* ------------------------------------------------------- the instances */

typedef struct {
    EulerSim sim;  /* sim.c is the instance, NULL if none */
    bool logs;     /* instantiated with a logger */
    bool cs;       /* instantiated for Co-Simulation */
    double time;   /* where the next fmi2DoStep starts */
    bool in_error; /* an fmi2Error since the last instantiate or reset */
} Slot;

static Slot slots[3];
static Bytes in;
static double span_left; /* time that fmi2DoStep may still integrate in this input */

static void free_slot(Slot *s)
{
    if (s->sim.c) f->FreeInstance(s->sim.c);
    memset(s, 0, sizeof *s);
}

/* Checks a status and the Error state's rules. `may_pass_in_error`: calls the
 * Error state allows (getters, logging, FMU state, status queries). */
static fmi2Status checked(Slot *s, const char *call, fmi2Status st, long errors_before, bool may_pass_in_error)
{
    INVARIANT(st >= fmi2OK && st <= fmi2Pending, "%s returned %d", call, (int)st);
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
    if (!s->sim.c) {
        INVARIANT(st == fmi2Error || st == fmi2Fatal, "%s on a NULL instance returned %d", call, (int)st);
        return st;
    }
    if (st == fmi2Error || st == fmi2Fatal) {
        INVARIANT(!s->logs || harness.error_messages > errors_before, "%s returned %d without logging an error",
                  call, (int)st);
        s->in_error = true;
    } else if (s->in_error) {
        INVARIANT(may_pass_in_error || st > fmi2Warning, "%s succeeded in the Error state", call);
    }
    return st;
}

#define CALL(slot, may_pass_in_error, expr) \
    checked((slot), #expr, (expr), errors_before, (may_pass_in_error))

static void require_finite(const char *what, const double *v, size_t n)
{
    for (size_t k = 0; k < n; ++k) INVARIANT(isfinite(v[k]), "%s[%zu] = %g returned with fmi2OK", what, k, v[k]);
}

/* ----------------------------------------------------------- the calls */

static const char *take_name(Bytes *b)
{
    static const char *const NAMES[] = { "rod", "rod", "%s%n%d", "", NULL,
                                         "a rod with a long name, a long long name, a long long long name" };
    return NAMES[take(b) % 6];
}

static void op_instantiate(Slot *s)
{
    static const fmi2Type TYPES[] = { fmi2ModelExchange, fmi2ModelExchange, fmi2ModelExchange, fmi2CoSimulation,
                                      (fmi2Type)2, (fmi2Type)-1 };
    fmi2CallbackFunctions no_logger = harness_callbacks;
    no_logger.logger = NULL;
    const char *name = take_name(&in);
    const uint8_t g = take(&in), t = take(&in), flags = take(&in);
    const char *guid = g < 224 ? harness_guid : g < 240 ? "{aeb84f4e-0000}" : g < 248 ? NULL : "%s%s%s%n";
    free_slot(s);
    harness.fail_allocation_at = flags & 0x30 ? harness.allocations + (flags >> 4 & 3) : 0;
    s->sim.c = f->Instantiate(name, TYPES[t % 6], guid, flags & 8 ? NULL : "file:///tmp",
                              flags & 4 ? &no_logger : &harness_callbacks, flags & 1, flags & 2);
    harness.fail_allocation_at = 0;
    s->logs = !(flags & 4);
    s->cs = TYPES[t % 6] == fmi2CoSimulation;
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
}

/* The arguments of a fmi2Get/fmi2Set call, read from the input: a count (or NULL arrays),
 * CAP value references and, for a Set, CAP values of each type. */
typedef struct {
    fmi2ValueReference vr[CAP];
    double r[CAP];
    fmi2Integer iv[CAP];
    fmi2Boolean bv[CAP];
    fmi2String sv[CAP];
    bool null_arrays;
    size_t n;
} ValueArgs;

static void take_value_args(ValueArgs *a, bool values)
{
    memset(a, 0, sizeof *a);
    a->n = take_count(&in, &a->null_arrays);
    for (size_t k = 0; k < CAP; ++k) {
        a->vr[k] = take_vr(&in);
        if (!values) continue;
        a->r[k] = take_double(&in);
        a->iv[k] = (int8_t)take(&in);
        a->bv[k] = a->iv[k] & 1;
        a->sv[k] = a->iv[k] & 2 ? "%s" : NULL;
    }
}

/* Whether an Integer value lies within its variable's min and max (modelDescription.xml). */
static bool within_bounds(fmi2ValueReference vr, fmi2Integer value)
{
    for (int k = 1; k <= MD_N_VARIABLES; ++k) {
        const MdVariable *v = md_var(k);
        if (v->vr != vr || v->type != MD_INTEGER) continue;
        return (!v->has_min || value >= v->min) && (!v->has_max || value <= v->max);
    }
    return false;
}

static void op_get(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    ValueArgs a;
    take_value_args(&a, false);
    const bool null_arrays = a.null_arrays;
    const size_t n = a.n;
    const fmi2ValueReference *v = null_arrays ? NULL : a.vr;
    fmi2Component c = s->sim.c;
    switch (which % 4) {
    case 0:
        if (CALL(s, true, f->GetReal(c, v, n, null_arrays ? NULL : a.r)) == fmi2OK && !null_arrays)
            require_finite("fmi2GetReal", a.r, n);
        break;
    case 1:
        if (CALL(s, true, f->GetInteger(c, v, n, null_arrays ? NULL : a.iv)) == fmi2OK && !null_arrays)
            for (size_t k = 0; k < n; ++k)   /* within the min and max of modelDescription.xml */
                INVARIANT(within_bounds(a.vr[k], a.iv[k]), "Integer %u = %d", a.vr[k], a.iv[k]);
        break;
    case 2:
        if (CALL(s, true, f->GetBoolean(c, v, n, null_arrays ? NULL : a.bv)) == fmi2OK && !null_arrays)
            for (size_t k = 0; k < n; ++k) INVARIANT(a.bv[k] == 0 || a.bv[k] == 1, "contact = %d", a.bv[k]);
        break;
    default:
        CALL(s, true, f->GetString(c, v, n, null_arrays ? NULL : a.sv));
    }
}

static void op_set(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    ValueArgs a;
    take_value_args(&a, true);
    const bool null_arrays = a.null_arrays;
    const size_t n = a.n;
    const fmi2ValueReference *v = null_arrays ? NULL : a.vr;
    fmi2Component c = s->sim.c;
    switch (which % 4) {
    case 0: CALL(s, false, f->SetReal(c, v, n, null_arrays ? NULL : a.r)); break;
    case 1: CALL(s, false, f->SetInteger(c, v, n, null_arrays ? NULL : a.iv)); break;
    case 2: CALL(s, false, f->SetBoolean(c, v, n, null_arrays ? NULL : a.bv)); break;
    default: CALL(s, false, f->SetString(c, v, n, null_arrays ? NULL : a.sv));
    }
}

/* fmi2GetDerivatives, GetEventIndicators, GetContinuousStates, GetNominals,
 * SetContinuousStates, with right, wrong and huge sizes. */
static void op_arrays(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    double v[CAP];
    bool null_arrays;
    const uint8_t size_sel = take(&in);
    size_t n = size_sel < 200 ? (which % 5 == 1 ? MODEL_NZ : MODEL_NX) : take_count(&in, &null_arrays);
    null_arrays = n > CAP || size_sel == 255;
    for (size_t k = 0; k < CAP; ++k) v[k] = take_double(&in);
    double *a = null_arrays ? NULL : v;
    fmi2Component c = s->sim.c;
    fmi2Status st;
    switch (which % 5) {
    case 0: st = CALL(s, true, f->GetDerivatives(c, a, n)); break;
    case 1: st = CALL(s, true, f->GetEventIndicators(c, a, n)); break;
    case 2: st = CALL(s, true, f->GetContinuousStates(c, a, n)); break;
    case 3: st = CALL(s, true, f->GetNominalsOfContinuousStates(c, a, n)); break;
    default: CALL(s, false, f->SetContinuousStates(c, a, n)); return;
    }
    if (st == fmi2OK && a) require_finite("array getter", a, n);
}

static void op_event(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const uint8_t arg = take(&in);
    fmi2EventInfo info;
    fmi2Boolean enter, terminate;
    switch (which % 6) {
    case 0: CALL(s, false, f->EnterEventMode(c)); break;
    case 1: CALL(s, false, f->NewDiscreteStates(c, arg == 255 ? NULL : &info)); break;
    case 2: CALL(s, false, f->EnterContinuousTimeMode(c)); break;
    case 3:
        CALL(s, false, f->CompletedIntegratorStep(c, arg & 1, arg & 2 ? NULL : &enter, arg & 4 ? NULL : &terminate));
        break;
    case 4: CALL(s, false, f->SetTime(c, take_double(&in))); break;
    default: {
        bool changed;
        CALL(s, false, harness_event_iteration(f, c, &changed));
    }
    }
}

static void op_lifecycle(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const uint8_t flags = take(&in);
    switch (which % 5) {
    case 0: {
        const double tol = take_double(&in), start = take_double(&in), stop = take_double(&in);
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

static void op_debug_logging(Slot *s)
{
    const long errors_before = harness.error_messages;
    static const fmi2String CATEGORIES[] = { "logEvents", "logStatusWarning", "logStatusError", "logAll",
                                             "logNothing", NULL, "%s%n", "" };
    fmi2String cats[CAP];
    bool null_arrays;
    const size_t n = take_count(&in, &null_arrays);
    for (size_t k = 0; k < CAP; ++k) cats[k] = CATEGORIES[take(&in) % 8];
    CALL(s, true, f->SetDebugLogging(s->sim.c, take(&in) & 1, n, null_arrays ? NULL : cats));
}

/* A value reference for a directional derivative, from modelDescription.xml:
 * mostly an unknown (an output, a derivative, an initial unknown) or a known
 * (a state, a variable with initial = "exact") that some mode defines, often
 * a pair that the current mode does not, sometimes an Integer or Boolean
 * variable, sometimes far out. */
static fmi2ValueReference take_dd_vr(Bytes *b, bool unknown)
{
    const uint8_t sel = take(b);
    if (sel >= 224) return take_vr(b);
    int candidates[64], n = 0;
    for (int index = 1; index <= MD_N_VARIABLES && n < 64; ++index) {
        bool defined = false;
        for (int mode = MD_MODE_INIT; mode <= MD_MODE_STEP; ++mode)
            defined |= unknown ? md_unknown_of_mode((MdMode)mode, index) != NULL : md_known_of_mode((MdMode)mode, index);
        if (defined || sel >= 160) candidates[n++] = index;
    }
    return n ? md_var(candidates[sel % n])->vr : take_vr(b);
}

static void op_directional_derivative(Slot *s)
{
    const long errors_before = harness.error_messages;
    fmi2ValueReference unknown[CAP], known[CAP];
    double dv_known[CAP], dv_unknown[CAP];
    bool null_u, null_k;
    const size_t nu = take_count(&in, &null_u), nk = take_count(&in, &null_k);
    for (size_t k = 0; k < CAP; ++k) {
        unknown[k] = take_dd_vr(&in, true);
        known[k] = take_dd_vr(&in, false);
        dv_known[k] = take_double(&in);
    }
    /* Allowed in the Error state ("7" in both tables). */
    const fmi2Status st = CALL(s, true,
                               f->GetDirectionalDerivative(s->sim.c, null_u ? NULL : unknown, nu, null_k ? NULL : known,
                                                           nk, null_k ? NULL : dv_known, null_u ? NULL : dv_unknown));
    (void)st; /* the product of finite Jacobian entries and any seed may be anything */
}

/* FNV-1a, the checksum that ends a serialized state of fmi2_state.c: fixing
 * it up after a mutation lets the fuzzer reach the field parser behind it. */
static void fix_checksum(fmi2Byte *bytes, size_t n)
{
    if (n < 4) return;
    uint32_t h = 2166136261u;
    for (size_t k = 0; k < n - 4; ++k) h = (h ^ (uint8_t)bytes[k]) * 16777619u;
    for (size_t k = 0; k < 4; ++k) bytes[n - 4 + k] = (fmi2Byte)(h >> 8 * k);
}

/* A byte for a serialized state: a length or count on an edge, or any byte. */
static uint8_t take_byte_value(Bytes *b)
{
    static const uint8_t EDGES[] = { 0, 1, 2, 7, 8, 15, 16, 31, 32, 63, 64, 65, 127, 128, 255 };
    const uint8_t sel = take(b);
    return sel < 128 ? EDGES[sel % sizeof EDGES] : take(b);
}

/* Get an FMU state, serialize it, change some bytes, cut or extend it,
 * deserialize and set it into this instance or another. Every buffer is
 * allocated to its exact size, so a read past its end is caught. */
static void op_fmu_state(Slot *s)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const uint8_t flags = take(&in);
    fmi2FMUstate state = NULL, restored = NULL;
    size_t size = 0;
    if (CALL(s, true, f->GetFMUstate(c, &state)) > fmi2Warning) return;
    if (flags & 1 && CALL(s, true, f->SetFMUstate(c, state)) <= fmi2Warning) s->in_error = false;
    if (CALL(s, true, f->SerializedFMUstateSize(c, state, &size)) <= fmi2Warning && size < 1u << 16) {
        fmi2Byte *bytes = malloc(size + 1);
        if (CALL(s, true, f->SerializeFMUstate(c, state, bytes, size - (flags >> 1 & 1))) <= fmi2Warning) {
            for (int k = take(&in) % 8; k > 0; --k) {
                const size_t at = (size_t)take(&in) << 8 | take(&in);
                bytes[size ? at % size : 0] = (fmi2Byte)take_byte_value(&in);
            }
            /* Cut to a length of n, or keep it whole (bytes past size stay out). */
            const uint8_t cut = take(&in);
            const size_t n = cut < 192 ? size : cut % (size + 1);
            if (flags & 4) fix_checksum(bytes, n);
            fmi2Byte *exact = malloc(n ? n : 1);
            if (n) memcpy(exact, bytes, n);
            Slot *target = &slots[flags >> 3 & 1 ? (s - slots + 1) % 3 : s - slots];
            if (CALL(s, true, f->DeSerializeFMUstate(c, exact, n, &restored)) <= fmi2Warning) {
                const long before_target = harness.error_messages;
                if (target->sim.c && checked(target, "fmi2SetFMUstate(deserialized)",
                                             f->SetFMUstate(target->sim.c, restored), before_target, true) <= fmi2Warning)
                    target->in_error = false;
                CALL(s, true, f->FreeFMUstate(c, &restored));
            }
            free(exact);
        }
        free(bytes);
    }
    CALL(s, true, f->FreeFMUstate(c, &state));
}

/* Deserialization of bytes that never were a state. */
static void op_deserialize_raw(Slot *s)
{
    const long errors_before = harness.error_messages;
    const size_t n = take(&in) % 200;
    fmi2Byte *bytes = malloc(n ? n : 1);
    for (size_t k = 0; k < n; ++k) bytes[k] = (fmi2Byte)take(&in);
    if (n > 8 && bytes[0] == 'P') memcpy(bytes, "PRODSTAT", 8); /* past the magic now and then */
    fmi2FMUstate state = NULL;
    if (CALL(s, true, f->DeSerializeFMUstate(s->sim.c, bytes, n, &state)) <= fmi2Warning)
        CALL(s, true, f->FreeFMUstate(s->sim.c, &state));
    free(bytes);
}

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
static void op_optional(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const uint8_t arg = take(&in);
    switch (which % 6) {
    case 0: op_fmu_state(s); break;
    case 1: op_deserialize_raw(s); break;
    case 2: {
        const double t = arg & 2 ? take_double(&in) : s->time;
        do_step(s, t, take_double(&in), arg & 1);
        break;
    }
    case 3: CALL(s, false, f->CancelStep(c)); break;
    case 4: op_status_query(s, arg); break;
    default: {
        const fmi2ValueReference vr = take_vr(&in);
        const fmi2Integer order = (int8_t)take(&in);
        double v = take_double(&in);
        if (arg & 1) CALL(s, false, f->SetRealInputDerivatives(c, &vr, arg >> 1 & 1, &order, &v));
        else CALL(s, true, f->GetRealOutputDerivatives(c, &vr, arg >> 1 & 1, &order, &v));
    }
    }
}

/* Whole stretches of a simulation: start with a fuzzed knob (Co-Simulation:
 * its value; Model Exchange: the profile's value for a fuzzed epsilon), Euler steps. */
static void op_simulate(Slot *s, uint8_t which)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    if (which % 2 == 0 && s->cs) {
        const fmi2ValueReference vr = PROFILE_KNOB;
        const double eps = take_double(&in);
        fmi2Status st = CALL(s, false, f->SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0));
        s->time = 0;
        if (st == fmi2OK) st = CALL(s, false, f->SetReal(c, &vr, 1, &eps));
        if (st == fmi2OK) st = CALL(s, false, f->EnterInitializationMode(c));
        if (st == fmi2OK) CALL(s, false, f->ExitInitializationMode(c));
        return;
    }
    if (which % 2 == 0) {
        CALL(s, false, euler_start(f, &s->sim, take_double(&in)));
        return;
    }
    const int steps = take(&in) % 33;
    const double h = take_double(&in);
    for (int k = 0; k < steps; ++k) {
        const fmi2Status st = s->cs ? do_step(s, s->time, h, fmi2True) : CALL(s, false, euler_step(f, &s->sim, h));
        if (st != fmi2OK) break;
    }
}

enum {
    OP_INSTANTIATE, OP_FREE,
    OP_GET, OP_GET_END = OP_GET + 3,
    OP_SET, OP_SET_END = OP_SET + 3,
    OP_ARRAYS, OP_ARRAYS_END = OP_ARRAYS + 4,
    OP_EVENT, OP_EVENT_END = OP_EVENT + 5,
    OP_LIFECYCLE, OP_LIFECYCLE_END = OP_LIFECYCLE + 4,
    OP_DEBUG_LOGGING, OP_DIRECTIONAL,
    OP_OPTIONAL, OP_OPTIONAL_END = OP_OPTIONAL + 5,
    OP_SIMULATE, OP_SIMULATE_END = OP_SIMULATE + 1,
    N_OPS
};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    harness_reset();
    in = (Bytes){ data, size };
    span_left = PROFILE_FUZZ_SPAN;
    for (int calls = 0; in.n > 0 && calls < 256; ++calls) {
        const uint8_t op = take(&in);
        Slot *s = &slots[op / N_OPS % 3];
        const int code = op % N_OPS;
        if (code == OP_INSTANTIATE) op_instantiate(s);
        else if (code == OP_FREE) free_slot(s);
        else if (code <= OP_GET_END) op_get(s, (uint8_t)(code - OP_GET));
        else if (code <= OP_SET_END) op_set(s, (uint8_t)(code - OP_SET));
        else if (code <= OP_ARRAYS_END) op_arrays(s, (uint8_t)(code - OP_ARRAYS));
        else if (code <= OP_EVENT_END) op_event(s, (uint8_t)(code - OP_EVENT));
        else if (code <= OP_LIFECYCLE_END) op_lifecycle(s, (uint8_t)(code - OP_LIFECYCLE));
        else if (code == OP_DEBUG_LOGGING) op_debug_logging(s);
        else if (code == OP_DIRECTIONAL) op_directional_derivative(s);
        else if (code <= OP_OPTIONAL_END) op_optional(s, (uint8_t)(code - OP_OPTIONAL));
        else op_simulate(s, (uint8_t)(code - OP_SIMULATE));
    }
    for (int k = 0; k < 3; ++k) free_slot(&slots[k]);
    INVARIANT(harness.live == 0, "%ld blocks from allocateMemory outlive every instance", harness.live);
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
    return 0;
}
