/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 calls with bad arguments, each in every instance state: NULL
 * pointers, wrong array sizes (nValues != nValueReferences), unknown value
 * references and every getter and setter type (fmi3_driver's robustness tests). */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robustness3.h"

static const Fmi3Api *const f = &api3;

/* ------------------------------------------------------ NULL arguments */

void test3_null_arguments(void)
{
    fmi3ValueReference vr[1] = { PROFILE_KNOB };
    double r[MODEL_NX + HARNESS_NZ] = { PROFILE_KNOB_VALUE(1e-3) };
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
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3SetContinuousStates", f->SetContinuousStates(c, NULL, MODEL_NX));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetContinuousStateDerivatives",
              f->GetContinuousStateDerivatives(c, NULL, MODEL_NX));
    if (MODEL_NZ > 0)
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetEventIndicators", f->GetEventIndicators(c, NULL, MODEL_NZ));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetContinuousStates", f->GetContinuousStates(c, NULL, MODEL_NX));
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetNominalsOfContinuousStates",
              f->GetNominalsOfContinuousStates(c, NULL, MODEL_NX));
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

void test3_array_sizes(void)
{
    const fmi3ValueReference vr[2] = { PROFILE_KNOB, state3_vr(0) };
    double r[MODEL_NX + HARNESS_NZ + 2] = { PROFILE_KNOB_VALUE(1e-3) };
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
    static const size_t WRONG[] = { 0, MODEL_NX - 1, MODEL_NX + 1 };
    for (size_t k = 0; k < sizeof WRONG / sizeof WRONG[0]; ++k) {
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3SetContinuousStates", f->SetContinuousStates(c, r, WRONG[k]));
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetContinuousStates", f->GetContinuousStates(c, r, WRONG[k]));
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetContinuousStateDerivatives",
                  f->GetContinuousStateDerivatives(c, r, WRONG[k]));
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetNominalsOfContinuousStates",
                  f->GetNominalsOfContinuousStates(c, r, WRONG[k]));
    }
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetEventIndicators", f->GetEventIndicators(c, r, MODEL_NZ + 1));
    if (MODEL_NZ > 0)
        EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetEventIndicators", f->GetEventIndicators(c, r, (size_t)MODEL_NZ - 1));
    /* nSeed and nSensitivity: the knowns' and unknowns' counts (directional), swapped (adjoint):
     * the last state's derivative by every state (at least two). */
    const fmi3ValueReference u[1] = { derivative3_vr(MODEL_NX - 1) };
    fmi3ValueReference k[MODEL_NX];
    double seed[MODEL_NX], out[MODEL_NX];
    for (int j = 0; j < MODEL_NX; ++j) {
        k[j] = state3_vr(j);
        seed[j] = 1;
    }
    const size_t n = MODEL_NX;
    /* Right counts: answered, unless the model provides no derivatives (its description's flag). */
    const fmi3Status right = MD_PROVIDES_DIRECTIONAL_DERIVATIVE ? fmi3OK : fmi3Error;
    EXPECT_IN(M3_EVENT, right, right == fmi3OK ? "" : "fmi3GetDirectionalDerivative",
              f->GetDirectionalDerivative(c, u, 1, k, n, seed, n, out, 1));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetDirectionalDerivative",
              f->GetDirectionalDerivative(c, u, 1, k, n, seed, 1, out, n));
    EXPECT_IN(M3_EVENT, right, right == fmi3OK ? "" : "fmi3GetAdjointDerivative",
              f->GetAdjointDerivative(c, u, 1, k, n, seed, 1, out, n));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetAdjointDerivative", f->GetAdjointDerivative(c, u, 1, k, n, seed, n, out, 1));
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
 * only parameters, states (initial = "exact") and inputs are set in Instantiated, through fmi3SetFloat64. */
void test3_types_and_value_references(void)
{
    /* Beyond the model's variables, its event indicators and time (fmi3_instance.h). */
    static const fmi3ValueReference UNKNOWN[] = { VR_COUNT + MODEL_NZ + 1, 1000, 0x80000000u, UINT_MAX };
    for (int t = 0; t < N_TYPES; ++t) {
        char get_call[40], set_call[40];
        snprintf(get_call, sizeof get_call, "fmi3Get%s", TYPE_NAME[t]);
        snprintf(set_call, sizeof set_call, "fmi3Set%s", TYPE_NAME[t]);
        for (int index = 1; index <= MD_N_VARIABLES; ++index) {
            const MdVariable *v = md_var(index);
            const int own = v->type == MD_REAL ? 1 : v->type == MD_INTEGER ? 6 : 10;
            EXPECT_IN(M3_EVENT, t == own ? fmi3OK : fmi3Error, get_call, get_as(c, t, v->vr));
            /* initial = "exact", and inputs (which FMI 3.0 lets be set there) */
            const bool settable = t == 1 && (v->causality == MD_PARAMETER || v->causality == MD_INPUT ||
                                             (v->state && v->initial != MD_INITIAL_CALCULATED));
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
    for (unsigned k = 0; k < 64; ++k) vr[k] = k % (VR_COUNT + MODEL_NZ + 1);
    EXPECT_IN(M3_CONTINUOUS, fmi3OK, "", f->GetFloat64(c, vr, 0, v, 0));
    vr[63] = VR_COUNT + MODEL_NZ + 1;
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3GetFloat64", f->GetFloat64(c, vr, 64, v, 64));
}
