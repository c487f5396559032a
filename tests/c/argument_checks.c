/* SPDX-License-Identifier: BSD-2-Clause */
/* Calls with bad arguments, each in every instance state: NULL pointers, value
 * references that are not the type's or not the model's, nvr = 0 and huge nvr,
 * a million value references (fmi_driver's robustness tests). */
#include <math.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robustness.h"

static const FmiApi *const f = &api;

/* ------------------------------------------------------ NULL arguments */

void test_null_arguments(void)
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

void test_value_references(void)
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
    /* A defined pair: answered, unless the model provides none (its description's flag). */
    EXPECT_IN(ME_EVENT, MD_PROVIDES_DIRECTIONAL_DERIVATIVE ? fmi2OK : fmi2Error,
              f->GetDirectionalDerivative(c, &der, 1, &state, 1, r, r + 1));
}

void test_nvr_zero_and_huge(void)
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
void test_large_arrays(void)
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
