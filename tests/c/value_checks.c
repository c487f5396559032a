/* SPDX-License-Identifier: BSD-2-Clause */
/* Bad values: NaN, infinities and out-of-range values of every settable Real,
 * refused with an error that names the variable (fmi_driver's robustness tests). */
#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robustness.h"

static const FmiApi *const f = &api;

/* ------------------------------------------------------------- values */

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
void test_bad_values_of_variables(void)
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

void test_bad_values(void)
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
        if (md_var(md_state_index(k))->initial != MD_INITIAL_EXACT) continue;   /* calculated at initialization */
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
