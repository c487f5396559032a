/* PainleveRod's FMI 3.0 layer through its C ABI, as an importer loads it
 * (dlopen): every fmi3 call in every state of both interfaces against FMI 3.0
 * (fmi3_conformance.c, fmi3_directional.c), and robustness: NULL pointers,
 * wrong array sizes (nValues != nValueReferences), unknown value references
 * and every getter and setter type, bad values (NaN, out of range: the
 * message names the variable and its range), Co-Simulation's early return
 * and Event Mode (a step while an event is pending is refused), serialized
 * FMU states cut short or changed, and what the FMU does not have (Scheduled
 * Execution, clocks, Configuration Mode, per-element dependencies).
 *
 * Built with AddressSanitizer + UBSan (fmi3_driver_asan) and plain for
 * valgrind (fmi3_driver); tests/test_c_robustness.py runs it.
 *
 *   fmi3_driver [--lib PATH] [--no-conformance | --conformance-only]
 *
 * Exit status 0 only if every check passed. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "driver3.h"

Fmi3Api api3;
static const Fmi3Api *const f = &api3;

/* Runs `expr` (which uses c) on a new instance in `state` and checks its status;
 * after fmi3Error, a message naming `call` and an instance that still works. */
#define EXPECT_IN(in_state, expected, call, expr)                                                                   \
    do {                                                                                                         \
        Inst3 in_;                                                                                               \
        if (!inst3_reach(&in_, (in_state), false)) break;                                                           \
        fmi3Instance c = in_.c;                                                                                  \
        const long errors_before_ = harness.error_messages;                                                      \
        const fmi3Status st_ = (expr);                                                                           \
        CHECK(st_ == (expected), "%s in %s: %s, expected %s (%s)", #expr, STATE3_NAME[in_state], status3_name(st_), \
              status3_name(expected), harness.last_message);                                                     \
        if (st_ == fmi3Error) {                                                                                  \
            check3_error_reported(#expr, call, errors_before_);                                                  \
            in_.state = state3_is_cs(in_state) ? C3_ERROR : M3_ERROR;                                               \
        }                                                                                                        \
        inst3_works(&in_, #expr);                                                                                \
        inst3_free(&in_);                                                                                        \
    } while (0)

/* ------------------------------------------------------ NULL arguments */

static void test_null_arguments(void)
{
    fmi3ValueReference vr[1] = { VR_EPSILON };
    double r[ROD_NX + ROD_NZ] = { 1e-3, 1, 0, 0, 1, 0.5 };
    fmi3Boolean b[2];
    fmi3Int32 i[1];
    size_t n;
    const fmi3String null_category[1] = { NULL };
    double t;

    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetDebugLogging", f->SetDebugLogging(c, fmi3True, 2, NULL));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetDebugLogging", f->SetDebugLogging(c, fmi3True, 1, null_category));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetFloat64", f->GetFloat64(c, NULL, 1, r, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetFloat64", f->GetFloat64(c, vr, 1, NULL, 1));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetFloat64", f->SetFloat64(c, NULL, 1, r, 1));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetFloat64", f->SetFloat64(c, vr, 1, NULL, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetInt32", f->GetInt32(c, NULL, 1, i, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetBoolean", f->GetBoolean(c, vr, 1, NULL, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetString", f->GetString(c, vr, 1, NULL, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetBinary", f->GetBinary(c, vr, 1, NULL, NULL, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetClock", f->GetClock(c, vr, 1, NULL));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetString", f->SetString(c, vr, 1, NULL, 1));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetBinary", f->SetBinary(c, NULL, 1, NULL, NULL, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3UpdateDiscreteStates", f->UpdateDiscreteStates(c, NULL, b, b, b, b, r));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3UpdateDiscreteStates", f->UpdateDiscreteStates(c, b, b, b, b, b, NULL));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3CompletedIntegratorStep", f->CompletedIntegratorStep(c, fmi3True, NULL, b));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3CompletedIntegratorStep", f->CompletedIntegratorStep(c, fmi3True, b, NULL));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3SetContinuousStates", f->SetContinuousStates(c, NULL, ROD_NX));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetContinuousStateDerivatives",
              f->GetContinuousStateDerivatives(c, NULL, ROD_NX));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetEventIndicators", f->GetEventIndicators(c, NULL, ROD_NZ));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetContinuousStates", f->GetContinuousStates(c, NULL, ROD_NX));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetNominalsOfContinuousStates",
              f->GetNominalsOfContinuousStates(c, NULL, ROD_NX));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3GetNumberOfContinuousStates", f->GetNumberOfContinuousStates(c, NULL));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3GetNumberOfEventIndicators", f->GetNumberOfEventIndicators(c, NULL));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetDirectionalDerivative",
              f->GetDirectionalDerivative(c, NULL, 1, vr, 1, r, 1, r, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetDirectionalDerivative",
              f->GetDirectionalDerivative(c, vr, 1, vr, 1, NULL, 1, r, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetAdjointDerivative", f->GetAdjointDerivative(c, vr, 1, NULL, 1, r, 1, r, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetAdjointDerivative", f->GetAdjointDerivative(c, vr, 1, vr, 1, r, 1, NULL, 1));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3DoStep", f->DoStep(c, 0.06, 0.01, fmi3True, NULL, b, b, &t));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3DoStep", f->DoStep(c, 0.06, 0.01, fmi3True, b, b, b, NULL));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3GetOutputDerivatives", f->GetOutputDerivatives(c, vr, 1, NULL, r, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetFMUState", f->GetFMUState(c, NULL));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3SetFMUState", f->SetFMUState(c, NULL));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3FreeFMUState", f->FreeFMUState(c, NULL));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3SerializedFMUStateSize", f->SerializedFMUStateSize(c, NULL, &n));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3SerializeFMUState", f->SerializeFMUState(c, NULL, NULL, 16));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3DeserializeFMUState", f->DeserializeFMUState(c, NULL, 16, NULL));
    /* A NULL FMU state to free is no error: there is nothing to free. */
    fmi3FMUState none = NULL;
    EXPECT_IN(M3_EVENT, fmi3OK, "fmi3FreeFMUState", f->FreeFMUState(c, &none));
}

/* ---------------------------------- array sizes, value references, types */

static void test_array_sizes(void)
{
    const fmi3ValueReference vr[2] = { VR_EPSILON, VR_ALPHA };
    double r[ROD_NX + ROD_NZ + 2] = { 1e-3, 3, 0, 0, 1, 0.5 };
    fmi3Int32 i[2];
    fmi3Boolean b[2];
    /* nValues != nValueReferences: every variable is a scalar. */
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetFloat64", f->GetFloat64(c, vr, 2, r, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetFloat64", f->GetFloat64(c, vr, 1, r, 2));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetFloat64", f->GetFloat64(c, vr, 0, r, 1));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetFloat64", f->SetFloat64(c, vr, 2, r, 1));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetFloat64", f->SetFloat64(c, vr, 1, r, 2));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetInt32", f->GetInt32(c, vr, 1, i, 2));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetBoolean", f->GetBoolean(c, vr, 2, b, 1));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetInt32", f->SetInt32(c, vr, 0, i, 1));
    /* Huge counts behind NULL: refused before any read. */
    static const size_t HUGE_N[] = { SIZE_MAX, SIZE_MAX / 2 + 1, (size_t)1 << 40 };
    for (size_t k = 0; k < sizeof HUGE_N / sizeof HUGE_N[0]; ++k) {
        const size_t n = HUGE_N[k];
        EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetFloat64", f->GetFloat64(c, NULL, n, NULL, n));
        EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetFloat64", f->SetFloat64(c, NULL, n, NULL, n));
        EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetFloat64", f->SetFloat64(c, vr, n, r, 1));
        EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetDirectionalDerivative",
                  f->GetDirectionalDerivative(c, NULL, n, NULL, n, NULL, n, NULL, n));
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3SetContinuousStates", f->SetContinuousStates(c, NULL, n));
    }
    /* The arrays of Model Exchange: a wrong size is an error, the array real. */
    static const size_t WRONG[] = { 0, ROD_NX - 1, ROD_NX + 1 };
    for (size_t k = 0; k < sizeof WRONG / sizeof WRONG[0]; ++k) {
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3SetContinuousStates", f->SetContinuousStates(c, r, WRONG[k]));
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetContinuousStates", f->GetContinuousStates(c, r, WRONG[k]));
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetContinuousStateDerivatives",
                  f->GetContinuousStateDerivatives(c, r, WRONG[k]));
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetNominalsOfContinuousStates",
                  f->GetNominalsOfContinuousStates(c, r, WRONG[k]));
    }
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetEventIndicators", f->GetEventIndicators(c, r, ROD_NZ + 1));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetEventIndicators", f->GetEventIndicators(c, r, ROD_NZ - 1));
    /* nSeed and nSensitivity: the knowns' and unknowns' counts (directional), swapped (adjoint). */
    const fmi3ValueReference u[2] = { VR_DER_V, VR_DER_W }, k3[3] = { VR_Y, VR_W, VR_THETA };
    EXPECT_IN(M3_EVENT, fmi3OK, "", f->GetDirectionalDerivative(c, u, 2, k3, 3, r, 3, r + 3, 2));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetDirectionalDerivative",
              f->GetDirectionalDerivative(c, u, 2, k3, 3, r, 2, r + 3, 3));
    EXPECT_IN(M3_EVENT, fmi3OK, "", f->GetAdjointDerivative(c, u, 2, k3, 3, r, 2, r + 3, 3));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetAdjointDerivative", f->GetAdjointDerivative(c, u, 2, k3, 3, r, 3, r + 3, 2));
}

/* Reads `vr` with the getter of type `t` (0..13: Float32 .. Binary) into scratch. */
static fmi3Status get_as(fmi3Instance c, int t, fmi3ValueReference vr)
{
    union {
        double d[2];
        fmi3Int64 i[2];
        fmi3String s[2];
        fmi3Binary bin[2];
    } u;
    size_t sizes[2];
    fmi3Float32 f32;
    fmi3Int8 i8;
    fmi3UInt8 u8;
    fmi3Int16 i16;
    fmi3UInt16 u16;
    fmi3Int32 i32;
    fmi3UInt32 u32;
    fmi3UInt64 u64;
    fmi3Boolean b;
    switch (t) {
    case 0: return f->GetFloat32(c, &vr, 1, &f32, 1);
    case 1: return f->GetFloat64(c, &vr, 1, u.d, 1);
    case 2: return f->GetInt8(c, &vr, 1, &i8, 1);
    case 3: return f->GetUInt8(c, &vr, 1, &u8, 1);
    case 4: return f->GetInt16(c, &vr, 1, &i16, 1);
    case 5: return f->GetUInt16(c, &vr, 1, &u16, 1);
    case 6: return f->GetInt32(c, &vr, 1, &i32, 1);
    case 7: return f->GetUInt32(c, &vr, 1, &u32, 1);
    case 8: return f->GetInt64(c, &vr, 1, u.i, 1);
    case 9: return f->GetUInt64(c, &vr, 1, &u64, 1);
    case 10: return f->GetBoolean(c, &vr, 1, &b, 1);
    case 11: return f->GetString(c, &vr, 1, u.s, 1);
    default: return f->GetBinary(c, &vr, 1, sizes, u.bin, 1);
    }
}

static fmi3Status set_as(fmi3Instance c, int t, fmi3ValueReference vr)
{
    const fmi3Float32 f32 = 1;
    const double d = 1e-3;
    const fmi3Int8 i8 = 0;
    const fmi3UInt8 u8 = 0;
    const fmi3Int16 i16 = 0;
    const fmi3UInt16 u16 = 0;
    const fmi3Int32 i32 = 0;
    const fmi3UInt32 u32 = 0;
    const fmi3Int64 i64 = 0;
    const fmi3UInt64 u64 = 0;
    const fmi3Boolean b = fmi3False;
    const fmi3String s = "";
    const fmi3Byte byte = 0;
    const fmi3Binary bin = &byte;
    const size_t size = 1;
    switch (t) {
    case 0: return f->SetFloat32(c, &vr, 1, &f32, 1);
    case 1: return f->SetFloat64(c, &vr, 1, &d, 1);
    case 2: return f->SetInt8(c, &vr, 1, &i8, 1);
    case 3: return f->SetUInt8(c, &vr, 1, &u8, 1);
    case 4: return f->SetInt16(c, &vr, 1, &i16, 1);
    case 5: return f->SetUInt16(c, &vr, 1, &u16, 1);
    case 6: return f->SetInt32(c, &vr, 1, &i32, 1);
    case 7: return f->SetUInt32(c, &vr, 1, &u32, 1);
    case 8: return f->SetInt64(c, &vr, 1, &i64, 1);
    case 9: return f->SetUInt64(c, &vr, 1, &u64, 1);
    case 10: return f->SetBoolean(c, &vr, 1, &b, 1);
    case 11: return f->SetString(c, &vr, 1, &s, 1);
    default: return f->SetBinary(c, &vr, 1, &size, &bin, 1);
    }
}

static const char *const TYPE_NAME[] = { "Float32", "Float64", "Int8", "UInt8", "Int16", "UInt16", "Int32",
                                         "UInt32", "Int64", "UInt64", "Boolean", "String", "Binary" };
#define N_TYPES 13

/* Every getter and setter type with every value reference of the model
 * description and some beyond: only the variable's own type reads it, and
 * only parameters and states (initial = "exact") are set in Instantiated, through fmi3SetFloat64. */
static void test_types_and_value_references(void)
{
    /* Beyond the model's variables, its event indicators and time (fmi3_instance.h). */
    static const fmi3ValueReference UNKNOWN[] = { VR_COUNT + ROD_NZ + 1, 1000, 0x80000000u, UINT_MAX };
    for (int t = 0; t < N_TYPES; ++t) {
        char get_call[40], set_call[40];
        snprintf(get_call, sizeof get_call, "fmi3Get%s", TYPE_NAME[t]);
        snprintf(set_call, sizeof set_call, "fmi3Set%s", TYPE_NAME[t]);
        for (int index = 1; index <= MD_N_VARIABLES; ++index) {
            const MdVariable *v = md_var(index);
            const int own = v->type == MD_REAL ? 1 : v->type == MD_INTEGER ? 6 : 10;
            EXPECT_IN(M3_EVENT, t == own ? fmi3OK : fmi3Error, get_call, get_as(c, t, v->vr));
            const bool settable = t == 1 && (v->causality == MD_PARAMETER || v->state); /* initial = "exact" */
            EXPECT_IN(M3_INSTANTIATED, settable ? fmi3OK : fmi3Error, set_call, set_as(c, t, v->vr));
        }
        for (size_t k = 0; k < sizeof UNKNOWN / sizeof UNKNOWN[0]; ++k) {
            EXPECT_IN(C3_STEP, fmi3Error, get_call, get_as(c, t, UNKNOWN[k]));
            EXPECT_IN(C3_INSTANTIATED, fmi3Error, set_call, set_as(c, t, UNKNOWN[k]));
        }
    }
    /* The last of many value references is unknown: every element is checked. */
    fmi3ValueReference vr[64];
    double v[64];
    for (unsigned k = 0; k < 64; ++k) vr[k] = k % (VR_COUNT + ROD_NZ + 1);
    EXPECT_IN(M3_CONTINUOUS, fmi3OK, "", f->GetFloat64(c, vr, 0, v, 0));
    vr[63] = VR_COUNT + ROD_NZ + 1;
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetFloat64", f->GetFloat64(c, vr, 64, v, 64));
}

/* ------------------------------------------------------------- values */

/* After fmi3SetFloat64(name = value) was refused: the message names the
 * variable and the range it must be in. */
static void check_range_message(const char *name, double value, const char *range)
{
    Inst3 in;
    if (!inst3_reach(&in, M3_INSTANTIATED, false)) return;
    fmi3ValueReference vr = 0;
    for (int k = 1; k <= MD_N_VARIABLES; ++k)
        if (!strcmp(md_var(k)->name, name)) vr = md_var(k)->vr;
    const fmi3Status st = f->SetFloat64(in.c, &vr, 1, &value, 1);
    CHECK(st == fmi3Error, "fmi3SetFloat64(%s = %g): %s, expected fmi3Error", name, value, status3_name(st));
    char named[64];
    snprintf(named, sizeof named, "%s = ", name);
    CHECK(strstr(harness.last_error, named) && strstr(harness.last_error, range),
          "fmi3SetFloat64(%s = %g): the message does not name the variable and its range %s: '%s'", name, value,
          range, harness.last_error);
    in.state = M3_ERROR;
    inst3_works(&in, "a value out of range");
    inst3_free(&in);
}

static void test_bad_values(void)
{
    static const double BAD[] = { NAN, -NAN, INFINITY, -INFINITY, DBL_MAX, -DBL_MAX };
    for (int index = 1; index <= MD_N_VARIABLES; ++index) {
        const MdVariable *v = md_var(index);
        if (v->causality != MD_PARAMETER && !v->state) continue;
        for (size_t k = 0; k < sizeof BAD / sizeof BAD[0]; ++k) {
            const fmi3ValueReference vr = v->vr;
            EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetFloat64", f->SetFloat64(c, &vr, 1, &BAD[k], 1));
        }
    }
    /* The ranges of modelDescription.xml (min, max). */
    check_range_message("epsilon", 0, "[1e-08, 1]");
    check_range_message("epsilon", 2, "[1e-08, 1]");
    check_range_message("epsilon", NAN, "[1e-08, 1]");
    check_range_message("alpha", 0, "[1e-06, 1e+06]");
    check_range_message("mu", -1e-300, "[0, 1e+06]");
    check_range_message("delta", -1, "[0, 1e+06]");
    check_range_message("y", 2e6, "[-1e+06, 1e+06]");
    /* A rejected fmi3SetFloat64 changes nothing (read back in Error, which is Terminated). */
    Inst3 in;
    if (inst3_reach(&in, M3_INIT, false)) {
        const fmi3ValueReference vrs[2] = { VR_EPSILON, VR_ALPHA };
        const double before = 2e-3, values[2] = { 0.5, -1 };
        double after = 0;
        CHECK(f->SetFloat64(in.c, vrs, 1, &before, 1) == fmi3OK, "epsilon = %g refused", before);
        CHECK(f->SetFloat64(in.c, vrs, 2, values, 2) == fmi3Error, "alpha = -1 accepted");
        CHECK(f->GetFloat64(in.c, vrs, 1, &after, 1) == fmi3OK && after == before,
              "a rejected fmi3SetFloat64 changed epsilon from %g to %g", before, after);
        inst3_free(&in);
    }
    /* Bad arguments of the mode changes and steps. */
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3EnterInitializationMode",
              f->EnterInitializationMode(c, fmi3True, NAN, 0, fmi3False, 0));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3EnterInitializationMode",
              f->EnterInitializationMode(c, fmi3True, -1, 0, fmi3False, 0));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3EnterInitializationMode",
              f->EnterInitializationMode(c, fmi3False, 0, INFINITY, fmi3False, 0));
    EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3EnterInitializationMode",
              f->EnterInitializationMode(c, fmi3False, 0, 1, fmi3True, 0));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3SetTime", f->SetTime(c, NAN));
    double x[ROD_NX] = { 0, 1, 0, 0, 1, 0.5 };
    x[3] = NAN;
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3SetContinuousStates", f->SetContinuousStates(c, x, ROD_NX));
    const fmi3ValueReference u = VR_DER_W, k = VR_Y;
    const double nan_seed = NAN;
    double out;
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetDirectionalDerivative",
              f->GetDirectionalDerivative(c, &u, 1, &k, 1, &nan_seed, 1, &out, 1));
    fmi3Boolean e, t, r;
    double last;
    /* The step starts where the last one ended (t = 0.06 after three steps of 0.02). */
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3DoStep", f->DoStep(c, 0.5, 0.01, fmi3True, &e, &t, &r, &last));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3DoStep", f->DoStep(c, 0.06, 0, fmi3True, &e, &t, &r, &last));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3DoStep", f->DoStep(c, 0.06, -0.01, fmi3True, &e, &t, &r, &last));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3DoStep", f->DoStep(c, 0.06, INFINITY, fmi3True, &e, &t, &r, &last));
}

/* ------------------------------------- Co-Simulation: early return, events */

/* One fmi3DoStep over the whole IWC (t = 0 .. 0.1, epsilon 1e-3) with the flags given. */
static void test_early_return(void)
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
        fmi3Status st = f->EnterInitializationMode(c, fmi3True, 1e-8, 0, fmi3True, 0.1);
        if (st == fmi3OK) st = f->ExitInitializationMode(c);
        if (em && st == fmi3OK) st = harness3_update_discrete_states(f, c, &changed);
        if (em && st == fmi3OK) st = f->EnterStepMode(c);
        double t = 0;
        int returns = 0, events = 0;
        while (st == fmi3OK && t < 0.1 && returns < 100) {
            fmi3Boolean event = 7, terminate = 7, early_return = 7;
            double last = NAN;
            st = f->DoStep(c, t, 0.1 - t, fmi3True, &event, &terminate, &early_return, &last);
            if (st != fmi3OK) break;
            CHECK(terminate == fmi3False, "terminateSimulation = %d", terminate);
            CHECK(early_return == fmi3False || early_return == fmi3True, "earlyReturn = %d", early_return);
            CHECK(event == (em && early_return), "eventHandlingNeeded = %d, earlyReturn = %d, eventModeUsed = %d",
                  event, early_return, em);
            CHECK(early || !early_return, "an early return that earlyReturnAllowed = false does not allow");
            CHECK(t < last && last <= 0.1, "lastSuccessfulTime %.17g not in (%.17g, 0.1]", last, t);
            CHECK(early_return || last == 0.1, "lastSuccessfulTime %.17g without an early return", last);
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
        CHECK(st == fmi3OK && t == 0.1, "eventModeUsed %d, earlyReturnAllowed %d: %s at t = %.17g (%s)", em, early,
              status3_name(st), t, harness.last_error);
        fmi3ValueReference vr[2] = { VR_SWITCHES, VR_STICKS };
        fmi3Int32 counts[2] = { -1, -1 };
        CHECK(f->GetInt32(c, vr, 2, counts, 2) == fmi3OK, "fmi3GetInt32(switches, sticks)");
        /* An IWC: contact, stick, lift-off; an early return at each event (each
         * mode switch, and an indicator's crossing that switches nothing, such as
         * y = 0 after a damped lift-off). */
        CHECK(counts[0] >= 2 && counts[1] == 1, "switches %d, sticks %d", counts[0], counts[1]);
        if (early) CHECK(returns >= counts[0], "%d early returns for %d mode switches", returns, counts[0]);
        else CHECK(returns == 0, "%d early returns without earlyReturnAllowed", returns);
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

/* ----------------------------------------------------- FMU state bytes */

static fmi3Byte *exact_copy(const fmi3Byte *bytes, size_t n)
{
    fmi3Byte *p = malloc(n ? n : 1);
    if (p && n) memcpy(p, bytes, n);
    return p;
}

/* Serialized states cut short or with a byte changed are refused, never read past their end. */
static void test_serialized_state_bytes(State3 state)
{
    Inst3 in;
    if (!inst3_reach(&in, state, false)) return;
    fmi3FMUState s = NULL, t = NULL;
    size_t size = 0;
    fmi3Byte *bytes = NULL;
    if (!CHECK(f->GetFMUState(in.c, &s) == fmi3OK && f->SerializedFMUStateSize(in.c, s, &size) == fmi3OK && size > 0,
               "FMU state in %s", STATE3_NAME[state]))
        goto done;
    bytes = malloc(size);
    if (!CHECK(bytes && f->SerializeFMUState(in.c, s, bytes, size) == fmi3OK, "fmi3SerializeFMUState")) goto done;
    CHECK(f->SerializeFMUState(in.c, s, bytes, size - 1) == fmi3Error, "a state serialized into %zu of %zu bytes",
          size - 1, size);
    CHECK(f->Reset(in.c) == fmi3OK, "fmi3Reset");
    for (size_t n = 0; n < size; n += 1 + n / 16) {
        fmi3Byte *prefix = exact_copy(bytes, n);
        const fmi3Status st = f->DeserializeFMUState(in.c, prefix, n, &t);
        CHECK(st != fmi3OK, "a state cut to %zu of %zu bytes was accepted", n, size);
        if (st == fmi3OK) f->FreeFMUState(in.c, &t);
        if (st == fmi3Error) CHECK(f->Reset(in.c) == fmi3OK, "fmi3Reset");
        free(prefix);
    }
    static const unsigned char EDGES[] = { 0x00, 0x7f, 0x80, 0xff };
    for (size_t n = 0; n < size; n += 1 + n / 32) {
        for (size_t k = 0; k < sizeof EDGES; ++k) {
            if ((unsigned char)bytes[n] == EDGES[k]) continue;
            fmi3Byte *changed = exact_copy(bytes, size);
            changed[n] = (fmi3Byte)EDGES[k];
            const fmi3Status st = f->DeserializeFMUState(in.c, changed, size, &t);
            /* A changed value byte can make another legal state: then it must set. */
            if (st == fmi3OK) {
                CHECK(f->SetFMUState(in.c, t) <= fmi3Error, "fmi3SetFMUState");
                f->FreeFMUState(in.c, &t);
            }
            CHECK(f->Reset(in.c) == fmi3OK, "fmi3Reset");
            free(changed);
        }
    }
    /* The intact bytes still make the state, and it still runs. */
    CHECK(f->DeserializeFMUState(in.c, bytes, size, &t) == fmi3OK, "intact state refused: %s", harness.last_error);
    CHECK(f->SetFMUState(in.c, t) == fmi3OK, "fmi3SetFMUState of a deserialized state: %s", harness.last_error);
    f->FreeFMUState(in.c, &t);
    inst3_works(&in, "a deserialized FMU state");
done:
    if (s) f->FreeFMUState(in.c, &s);
    free(bytes);
    inst3_free(&in);
}

/* ------------------------------------ instantiation, what is not there */

static void test_instantiation_and_missing_features(void)
{
    const char *g = harness_guid;
    long errors_before = harness.error_messages;
    CHECK(f->InstantiateModelExchange(NULL, g, "", fmi3False, fmi3False, NULL, harness3_logger) == NULL,
          "instanceName NULL");
    CHECK(f->InstantiateModelExchange("", g, "", fmi3False, fmi3False, NULL, harness3_logger) == NULL,
          "instanceName empty");
    CHECK(f->InstantiateModelExchange("rod", NULL, "", fmi3False, fmi3False, NULL, harness3_logger) == NULL,
          "instantiationToken NULL");
    CHECK(f->InstantiateModelExchange("rod", "{wrong}", "", fmi3False, fmi3False, NULL, harness3_logger) == NULL,
          "instantiationToken wrong");
    const fmi3ValueReference vr = VR_W;
    CHECK(f->InstantiateCoSimulation("rod", g, "", fmi3False, fmi3False, fmi3False, fmi3False, &vr, 1, NULL,
                                     harness3_logger, NULL) == NULL,
          "required intermediate variables, which the FMU does not provide");
    CHECK(f->InstantiateScheduledExecution("rod", g, "", fmi3False, fmi3False, NULL, harness3_logger, NULL, NULL,
                                           NULL) == NULL,
          "Scheduled Execution, which the model description does not declare");
    CHECK(harness.error_messages == errors_before + 6, "%ld of 6 failed instantiations logged why",
          harness.error_messages - errors_before);
    /* No logger: allowed (each callback may be NULL), and errors are silent. */
    fmi3Instance silent = f->InstantiateModelExchange("rod", g, NULL, fmi3False, fmi3True, NULL, NULL);
    if (CHECK(silent != NULL, "fmi3InstantiateModelExchange without a logger")) {
        const double nan = NAN;
        const fmi3ValueReference eps = VR_EPSILON;
        CHECK(f->SetFloat64(silent, &eps, 1, &nan, 1) == fmi3Error, "epsilon = NaN accepted");
        CHECK(f->Reset(silent) == fmi3OK, "fmi3Reset");
        f->FreeInstance(silent);
    }
    CHECK(strcmp(f->GetVersion(), "3.0") == 0, "fmi3GetVersion: %s", f->GetVersion());
    /* Clocks, Configuration Mode and per-element dependencies: fmi3Error with a message. */
    fmi3Clock clock;
    double interval;
    fmi3IntervalQualifier qualifier;
    fmi3UInt64 counter, resolution;
    size_t element, n;
    fmi3ValueReference independent;
    fmi3DependencyKind kind;
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetClock", f->GetClock(c, &vr, 1, &clock));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3SetClock", f->SetClock(c, &vr, 1, &clock));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetIntervalDecimal", f->GetIntervalDecimal(c, &vr, 1, &interval, &qualifier));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetIntervalFraction",
              f->GetIntervalFraction(c, &vr, 1, &counter, &resolution, &qualifier));
    EXPECT_IN(M3_INIT, fmi3Error, "fmi3GetShiftDecimal", f->GetShiftDecimal(c, &vr, 1, &interval));
    EXPECT_IN(M3_INIT, fmi3Error, "fmi3GetShiftFraction", f->GetShiftFraction(c, &vr, 1, &counter, &resolution));
    EXPECT_IN(M3_INIT, fmi3Error, "fmi3SetIntervalDecimal", f->SetIntervalDecimal(c, &vr, 1, &interval));
    EXPECT_IN(M3_INIT, fmi3Error, "fmi3SetIntervalFraction", f->SetIntervalFraction(c, &vr, 1, &counter, &resolution));
    EXPECT_IN(M3_INIT, fmi3Error, "fmi3SetShiftDecimal", f->SetShiftDecimal(c, &vr, 1, &interval));
    EXPECT_IN(M3_INIT, fmi3Error, "fmi3SetShiftFraction", f->SetShiftFraction(c, &vr, 1, &counter, &resolution));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3ActivateModelPartition", f->ActivateModelPartition(c, 0, 0.06));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetNumberOfVariableDependencies",
              f->GetNumberOfVariableDependencies(c, VR_DER_W, &n));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetVariableDependencies",
              f->GetVariableDependencies(c, VR_DER_W, &element, &independent, &element, &kind, 1));
    /* The wrong interface's calls. */
    double x[ROD_NX];
    fmi3Boolean e, t, r;
    double last;
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3GetContinuousStates", f->GetContinuousStates(c, x, ROD_NX));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3GetNominalsOfContinuousStates", f->GetNominalsOfContinuousStates(c, x, ROD_NX));
    EXPECT_IN(C3_EVENT, fmi3Error, "fmi3EnterContinuousTimeMode", f->EnterContinuousTimeMode(c));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3EnterStepMode", f->EnterStepMode(c));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3DoStep", f->DoStep(c, 0, 0.01, fmi3True, &e, &t, &r, &last));
}

/* FMI 3.0's logMessage takes text ("a string that contains the message to log",
 * §2.3.1), not a printf format as FMI 2.0's logger: a '%' reaches it as it is. */
static void test_log_messages_are_text(void)
{
    Inst3 in;
    if (!inst3_reach(&in, M3_INSTANTIATED, true)) return;
    const fmi3String category[1] = { "50% of %s" };
    CHECK(f->SetDebugLogging(in.c, fmi3True, 1, category) == fmi3Error, "unknown category accepted");
    CHECK(strstr(harness.last_error, "'50% of %s'") != NULL, "the category reaches the logger changed: %s",
          harness.last_error);
    in.state = M3_ERROR;
    inst3_works(&in, "a '%' in a log message");
    inst3_free(&in);
}

int main(int argc, char **argv)
{
    const char *lib = FMU_LIBRARY;
    bool conformance = true, robustness = true;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--lib") && k + 1 < argc) lib = argv[++k];
        else if (!strcmp(argv[k], "--no-conformance")) conformance = false;
        else if (!strcmp(argv[k], "--conformance-only")) robustness = false;
        else {
            fprintf(stderr, "usage: %s [--lib PATH] [--no-conformance | --conformance-only]\n", argv[0]);
            return 2;
        }
    }
    char err[1024];
    if (!fmi3_api_load(&api3, lib, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    harness_reset();
    if (conformance) {
        test3_conformance_table();
        test3_conformance_variables();
        test3_null_instance();
        test3_derivatives();
    }
    if (robustness) {
        test_null_arguments();
        test_array_sizes();
        test_types_and_value_references();
        test_bad_values();
        test_early_return();
        static const State3 SERIALIZED[] = { M3_INSTANTIATED, M3_CONTINUOUS, M3_ERROR, C3_STEP_EM, C3_EVENT_AGAIN };
        for (size_t k = 0; k < sizeof SERIALIZED / sizeof SERIALIZED[0]; ++k) test_serialized_state_bytes(SERIALIZED[k]);
        test_instantiation_and_missing_features();
        test_log_messages_are_text();
    }
    CHECK(harness.bad_messages == 0, "%ld malformed log messages, the last: %s", harness.bad_messages,
          harness.last_bad);
    fmi3_api_unload(&api3);
    printf("fmi3_driver: %ld checks, %ld failed (%ld log messages)\n", checks, failures, harness.messages);
    return failures ? 1 : 0;
}
