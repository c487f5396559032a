/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 bad values: NaN and out of range, refused with a message that names
 * the variable and its range (fmi3_driver's robustness tests). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robustness3.h"

static const Fmi3Api *const f = &api3;

/* ------------------------------------------------------------- values */

/* After fmi3SetFloat64 of variable `index` to `value` was refused: the message
 * names the variable and the range [min, max] it must be in. */
static void check_range_message(int index, double value, double min, double max)
{
    Inst3 in;
    if (!inst3_reach(&in, M3_INSTANTIATED, false)) return;
    const MdVariable *v = md_var(index);
    const fmi3Status st = f->SetFloat64(in.c, &v->vr, 1, &value, 1);
    CHECK(st == fmi3Error, "fmi3SetFloat64(%s = %g): %s, expected fmi3Error", v->name, value, status3_name(st));
    char named[64], range[64];
    snprintf(named, sizeof named, "%s = ", v->name);
    snprintf(range, sizeof range, "[%g, %g]", min, max);
    CHECK(strstr(harness.last_error, named) && strstr(harness.last_error, range),
          "fmi3SetFloat64(%s = %g): the message does not name the variable and its range %s: '%s'", v->name, value,
          range, harness.last_error);
    in.state = M3_ERROR;
    inst3_works(&in, "a value out of range");
    inst3_free(&in);
}

/* A value below min (0 for a positive min, the smallest negative for 0) and above max. */
static double below(double min) { return min > 0 ? 0 : min == 0 ? -1e-300 : 2 * min; }
static double above(double max) { return max > 0 ? 2 * max : max == 0 ? 1e-300 : 0; }

void test3_bad_values(void)
{
    static const double BAD[] = { NAN, -NAN, INFINITY, -INFINITY, DBL_MAX, -DBL_MAX };
    for (int index = 1; index <= MD_N_VARIABLES; ++index) {
        const MdVariable *v = md_var(index);
        if (v->causality != MD_PARAMETER && !(v->state && v->initial != MD_INITIAL_CALCULATED)) continue;
        for (size_t k = 0; k < sizeof BAD / sizeof BAD[0]; ++k) {
            const fmi3ValueReference vr = v->vr;
            EXPECT_IN(M3_INSTANTIATED, fmi3Error, "fmi3SetFloat64", f->SetFloat64(c, &vr, 1, &BAD[k], 1));
        }
        /* The ranges: a parameter's of the model description (min, max), a state's the profile's bound. */
        const bool ranged = v->type == MD_REAL && (v->state || (v->has_min && v->has_max));
        if (!ranged) continue;
        const double min = v->state ? -PROFILE_STATE_BOUND : v->min, max = v->state ? PROFILE_STATE_BOUND : v->max;
        check_range_message(index, below(min), min, max);
        check_range_message(index, above(max), min, max);
        check_range_message(index, NAN, min, max);
    }
    /* A rejected fmi3SetFloat64 changes nothing (read back in Error, which is Terminated). */
    Inst3 in;
    if (inst3_reach(&in, M3_INIT, false)) {
        const fmi3ValueReference vrs[2] = { PROFILE_KNOB, PROFILE_KNOB };
        const double before = PROFILE_KNOB_VALUE(2e-3), values[2] = { PROFILE_KNOB_VALUE(0.5), NAN };
        double after = 0;
        CHECK(f->SetFloat64(in.c, vrs, 1, &before, 1) == fmi3OK, "the knob = %g refused", before);
        CHECK(f->SetFloat64(in.c, vrs, 2, values, 2) == fmi3Error, "the knob = NaN accepted");
        CHECK(f->GetFloat64(in.c, vrs, 1, &after, 1) == fmi3OK && after == before,
              "a rejected fmi3SetFloat64 changed the knob from %g to %g", before, after);
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
    double x[MODEL_NX];
    for (int i = 0; i < MODEL_NX; ++i) x[i] = md_var(md_state_index(i))->start;
    x[MODEL_NX - 1] = NAN;
    EXPECT_IN(M3_CONTINUOUS, fmi3Error, "fmi3SetContinuousStates", f->SetContinuousStates(c, x, MODEL_NX));
    const fmi3ValueReference u = derivative3_vr(MODEL_NX - 1), k = state3_vr(0);
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
