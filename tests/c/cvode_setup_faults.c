/* SPDX-License-Identifier: BSD-2-Clause */
/* Co-Simulation's CVODE failing at each SUNDIALS call of its set-up and
 * restarts in turn (the FMU built with fail_sundials_call.c, which makes the
 * chosen call return its documented failure): every failure must end the step
 * with fmi2Error and a message naming the call, free what the set-up had made
 * (valgrind checks), and leave an instance that, after fmi2Reset, simulates
 * exactly as one that never failed.
 *
 *   cvode_setup_faults [--lib PATH]      exit status 0 only if every check passed */
#include <dlfcn.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi_harness.h"
#include "unit_check.h"

static FmiApi api;
static const FmiApi *const f = &api;

/* The calls of the set-up and of each advance (the step budget), each named by the message when it fails. */
static const char *const SETUP[] = { "SUNContext_Create", "CVodeCreate", "N_VNew_Serial", "SUNDenseMatrix",
                                     "SUNLinSol_Dense", "CVodeInit", "CVodeSetUserData", "CVodeRootInit",
                                     "CVodeSetLinearSolver", "CVodeSetJacFn", "CVodeSetNoInactiveRootWarn",
                                     "CVodeSetMaxNumSteps", "CVodeGetNumSteps" };
#define N_SETUP (sizeof SETUP / sizeof SETUP[0])

static const fmi2ValueReference STATES[ROD_NX] = { VR_X, VR_V, VR_Y, VR_W, VR_THETA, VR_PHI };

/* A sustained contact in one step, the case Co-Simulation hands to CVODE: the rod put down
 * at rest at theta = 1 (mu = 3: it sticks and tips over on the floor), eps = 1e-6, t = 0 ... 0.01.
 * (An IWC's contact is short: the explicit pair integrates it and CVODE is not set up.) */
static fmi2Status start_and_step(fmi2Component c)
{
    static const fmi2ValueReference vr[] = { VR_EPSILON, VR_V, VR_W, VR_THETA, VR_PHI };
    static const fmi2Real at_rest[] = { 1e-6, 0, 0, 1, 0 };
    if (f->SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0) != fmi2OK ||
        f->SetReal(c, vr, sizeof vr / sizeof vr[0], at_rest) != fmi2OK || f->EnterInitializationMode(c) != fmi2OK ||
        f->ExitInitializationMode(c) != fmi2OK)
        return fmi2Fatal;
    return f->DoStep(c, 0, 0.01, fmi2True);
}

int main(int argc, char **argv)
{
    const char *lib = argc == 3 && !strcmp(argv[1], "--lib") ? argv[2] : FMU_LIBRARY;
    char err[512];
    if (!fmi2_functions_load(&api, lib, true, true, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    long (*fail_call)(long);
    void *sym = dlsym(api.handle, "fault_fail_sundials_call");
    if (!sym) {
        fprintf(stderr, "%s is not the fault-injection build (no fault_fail_sundials_call)\n", lib);
        return 2;
    }
    memcpy(&fail_call, &sym, sizeof sym);
    harness_reset();

    /* A run that never fails: its result, and how many wrapped calls its step makes. */
    fmi2Component c = f->Instantiate("clean", fmi2CoSimulation, harness_guid, "", &harness_callbacks, fmi2False,
                                     fmi2False);
    CHECK(c, "fmi2Instantiate failed: %s", harness.last_message);
    if (!c) return 1;
    fail_call(0);
    CHECK(start_and_step(c) == fmi2OK, "the clean step failed: %s", harness.last_message);
    const long made = fail_call(0);
    double clean[ROD_NX];
    CHECK(f->GetReal(c, STATES, ROD_NX, clean) == fmi2OK, "fmi2GetReal failed");
    f->FreeInstance(c);
    CHECK(made > (long)N_SETUP, "the step made %ld wrapped calls: the set-up alone makes %zu (are they wrapped?)",
          made, N_SETUP);
    bool named[N_SETUP] = { false };

    for (long k = 1; k <= made; ++k) {
        c = f->Instantiate("faulty", fmi2CoSimulation, harness_guid, "", &harness_callbacks, fmi2False, fmi2False);
        if (!c) break;
        fail_call(k);
        const fmi2Status st = start_and_step(c);
        fail_call(0);
        CHECK(st == fmi2Error, "call %ld of %ld failing: fmi2DoStep returned %d, not fmi2Error", k, made, st);
        CHECK(strstr(harness.last_message, "fmi2DoStep") &&
                  (strstr(harness.last_message, "CVODE could not be set up") ||
                   strstr(harness.last_message, "CVODE could not restart") ||
                   strstr(harness.last_message, "CVODE refused the stop time") ||
                   strstr(harness.last_message, "CVODE refused its step budget") ||
                   strstr(harness.last_message, "CVODE could not count its steps")),
              "call %ld failing: the message says no CVODE failure: '%s'", k, harness.last_message);
        for (size_t i = 0; i < N_SETUP; ++i)
            if (strstr(harness.last_message, SETUP[i]) && strstr(harness.last_message, "failed")) named[i] = true;
        CHECK(f->Reset(c) == fmi2OK, "call %ld failing: fmi2Reset failed", k);
        CHECK(start_and_step(c) == fmi2OK, "call %ld failing: the step after fmi2Reset failed: %s", k,
              harness.last_message);
        double x[ROD_NX];
        CHECK(f->GetReal(c, STATES, ROD_NX, x) == fmi2OK, "fmi2GetReal failed");
        CHECK(!memcmp(x, clean, sizeof x), "call %ld failing: after fmi2Reset the step gives w = %.17g, "
              "not the clean run's %.17g", k, x[3], clean[3]);
        f->FreeInstance(c);
    }
    for (size_t i = 0; i < N_SETUP; ++i) CHECK(named[i], "no message named %s as the call that failed", SETUP[i]);
    fmi2_functions_unload(&api);
    printf("CVODE failing at each of its %ld SUNDIALS calls: %d checks, %d failed\n", made, checks, failures);
    return failures ? 1 : 0;
}
