/* SPDX-License-Identifier: BSD-2-Clause */
/* Two copies of PainleveRod's sources, compiled with FMI2_FUNCTION_PREFIX A_
 * and B_ and linked statically into this one program, run side by side: the
 * default experiment through Co-Simulation, steps interleaved. They must not
 * share anything, so both must end exactly where one run alone ends.
 * Built and run by tests/fmu/test_source_fmu.py; prints "w_A w_B w_alone". */
#include <stdio.h>
#include <stdlib.h>

#include "fmi2FunctionTypes.h"
#include "model_description.h"

#define DECLARE(prefix)                                           \
    extern fmi2InstantiateTYPE prefix##fmi2Instantiate;           \
    extern fmi2SetupExperimentTYPE prefix##fmi2SetupExperiment;   \
    extern fmi2EnterInitializationModeTYPE prefix##fmi2EnterInitializationMode; \
    extern fmi2ExitInitializationModeTYPE prefix##fmi2ExitInitializationMode;   \
    extern fmi2DoStepTYPE prefix##fmi2DoStep;                     \
    extern fmi2GetRealTYPE prefix##fmi2GetReal;                   \
    extern fmi2FreeInstanceTYPE prefix##fmi2FreeInstance;
DECLARE(A_)
DECLARE(B_)

typedef struct {
    fmi2InstantiateTYPE *instantiate;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *exit;
    fmi2DoStepTYPE *step;
    fmi2GetRealTYPE *get;
    fmi2FreeInstanceTYPE *free;
} Api;

#define API(prefix)                                                                         \
    { prefix##fmi2Instantiate, prefix##fmi2SetupExperiment, prefix##fmi2EnterInitializationMode, \
      prefix##fmi2ExitInitializationMode, prefix##fmi2DoStep, prefix##fmi2GetReal, prefix##fmi2FreeInstance }

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status, fmi2String category,
                   fmi2String message, ...)
{
    (void)env, (void)status;
    fprintf(stderr, "%s [%s] %s\n", name, category, message);
}

static const fmi2CallbackFunctions CALLBACKS = { logger, calloc, free, NULL, NULL };
enum { STEPS = 100 };
static const double STOP = 0.1;
static const fmi2ValueReference W = 7; /* w, as in modelDescription.xml */

static fmi2Component start(const Api *api, const char *name)
{
    fmi2Component c = api->instantiate(name, fmi2CoSimulation, MODEL_GUID, "", &CALLBACKS, fmi2False, fmi2False);
    if (!c || api->setup(c, fmi2False, 0, 0, fmi2True, STOP) != fmi2OK || api->enter(c) != fmi2OK ||
        api->exit(c) != fmi2OK) {
        fprintf(stderr, "%s: set-up failed\n", name);
        exit(1);
    }
    return c;
}

static double w_of(const Api *api, fmi2Component c)
{
    double w;
    if (api->get(c, &W, 1, &w) != fmi2OK) exit(1);
    return w;
}

int main(void)
{
    const Api a = API(A_), b = API(B_);
    fmi2Component ca = start(&a, "A"), cb = start(&b, "B");
    for (int i = 0; i < STEPS; ++i) {
        const double t = STOP * i / STEPS, h = STOP / STEPS;
        if (a.step(ca, t, h, fmi2True) != fmi2OK || b.step(cb, t, h, fmi2True) != fmi2OK) return 1;
    }
    fmi2Component alone = start(&a, "alone");
    for (int i = 0; i < STEPS; ++i)
        if (a.step(alone, STOP * i / STEPS, STOP / STEPS, fmi2True) != fmi2OK) return 1;
    printf("%.17g %.17g %.17g\n", w_of(&a, ca), w_of(&b, cb), w_of(&a, alone));
    a.free(ca);
    b.free(cb);
    a.free(alone);
    return 0;
}
