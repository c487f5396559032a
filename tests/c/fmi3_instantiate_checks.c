/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 instantiation, what the FMU does not have (Scheduled Execution,
 * clocks, Configuration Mode, per-element dependencies), and log messages that
 * are text (fmi3_driver's robustness tests). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robustness3.h"

static const Fmi3Api *const f = &api3;

/* ------------------------------------ instantiation, what is not there */

void test3_instantiation_and_missing_features(void)
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
    const fmi3ValueReference vr = state3_vr(0);
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
        const fmi3ValueReference knob = PROFILE_KNOB;
        CHECK(f->SetFloat64(silent, &knob, 1, &nan, 1) == fmi3Error, "the knob = NaN accepted");
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
              f->GetNumberOfVariableDependencies(c, derivative3_vr(0), &n));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3GetVariableDependencies",
              f->GetVariableDependencies(c, derivative3_vr(0), &element, &independent, &element, &kind, 1));
    /* The wrong interface's calls. */
    double x[MODEL_NX];
    fmi3Boolean e, t, r;
    double last;
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3GetContinuousStates", f->GetContinuousStates(c, x, MODEL_NX));
    EXPECT_IN(C3_STEP, fmi3Error, "fmi3GetNominalsOfContinuousStates", f->GetNominalsOfContinuousStates(c, x, MODEL_NX));
    EXPECT_IN(C3_EVENT, fmi3Error, "fmi3EnterContinuousTimeMode", f->EnterContinuousTimeMode(c));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3EnterStepMode", f->EnterStepMode(c));
    EXPECT_IN(M3_EVENT, fmi3Error, "fmi3DoStep", f->DoStep(c, 0, 0.01, fmi3True, &e, &t, &r, &last));
}

/* FMI 3.0's logMessage takes text ("a string that contains the message to log",
 * §2.3.1), not a printf format as FMI 2.0's logger: a '%' reaches it as it is. */
void test3_log_messages_are_text(void)
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
