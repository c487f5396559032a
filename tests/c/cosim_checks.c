/* SPDX-License-Identifier: BSD-2-Clause */
/* Co-Simulation: instances started and stepped, bad communication steps refused,
 * an FMU state taken mid-run restoring the run (fmi_driver's robustness tests). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robustness.h"

static const FmiApi *const f = &api;

/* ------------------------------------------------------- Co-Simulation */

fmi2Component cs_instance(void)
{
    return f->Instantiate("cs rod", fmi2CoSimulation, harness_guid, "", &harness_callbacks, fmi2False, fmi2False);
}

/* Set-up and initialization of a Co-Simulation instance; time 0. */
fmi2Status cs_start(fmi2Component c, double epsilon)
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
fmi2Status cs_run(fmi2Component c, double *t, double h, int steps)
{
    for (int k = 0; k < steps; ++k) {
        const fmi2Status st = f->DoStep(c, *t, h, fmi2True);
        if (st != fmi2OK) return st;
        *t += h;
    }
    return fmi2OK;
}

/* Whether this build steps: without SUNDIALS, fmi2DoStep always fails. */
bool cosimulation_available(void)
{
    fmi2Component c = cs_instance();
    if (!c) return false;
    double t = 0;
    fmi2Status st = cs_start(c, 0.05);
    if (st == fmi2OK) st = cs_run(c, &t, 1e-3, 1);
    free_instance(c);
    return st == fmi2OK;
}

void test_cosimulation_bad_steps(void)
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
void test_cosimulation_state_restores_the_run(void)
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
