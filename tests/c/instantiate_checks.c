/* SPDX-License-Identifier: BSD-2-Clause */
/* fmi2Instantiate's arguments, allocations failing at each allocation of
 * fmi2Instantiate in turn, and logging (fmi_driver's robustness tests). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robustness.h"

static const FmiApi *const f = &api;

/* -------------------------------------------------- instantiate, logging */

void test_instantiate_arguments(void)
{
    const fmi2CallbackFunctions *cb = &harness_callbacks;
    fmi2CallbackFunctions no_alloc = *cb, no_free = *cb, no_logger = *cb;
    no_alloc.allocateMemory = NULL;
    no_free.freeMemory = NULL;
    no_logger.logger = NULL;
    const char *g = harness_guid;
    char *long_text = malloc(100001);
    if (!CHECK(long_text != NULL, "out of memory")) return;
    for (int k = 0; k < 100000; ++k) long_text[k] = "%s%n%d%%x"[k % 9];
    long_text[100000] = '\0';

    CHECK(f->Instantiate("rod", fmi2ModelExchange, g, "", NULL, fmi2False, fmi2False) == NULL, "functions NULL");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, g, "", &no_alloc, fmi2False, fmi2False) == NULL,
          "allocateMemory NULL");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, g, "", &no_free, fmi2False, fmi2False) == NULL, "freeMemory NULL");
    CHECK(f->Instantiate(NULL, fmi2ModelExchange, g, "", cb, fmi2False, fmi2False) == NULL, "instanceName NULL");
    CHECK(f->Instantiate("", fmi2ModelExchange, g, "", cb, fmi2False, fmi2False) == NULL, "instanceName empty");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, NULL, "", cb, fmi2False, fmi2False) == NULL, "GUID NULL");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, "{wrong}", "", cb, fmi2False, fmi2False) == NULL, "GUID wrong");
    CHECK(f->Instantiate("rod", fmi2ModelExchange, long_text, "", cb, fmi2False, fmi2False) == NULL, "GUID long");
    CHECK(f->Instantiate("rod", (fmi2Type)7, g, "", cb, fmi2False, fmi2False) == NULL, "fmuType 7");
    CHECK(f->Instantiate("rod", (fmi2Type)-1, g, "", cb, fmi2False, fmi2False) == NULL, "fmuType -1");
    CHECK(harness.live == 0, "a failed fmi2Instantiate left %ld blocks allocated", harness.live);

    /* Co-Simulation: this build may or may not offer it; either way nothing leaks. */
    fmi2Component c = f->Instantiate("rod", fmi2CoSimulation, g, "", cb, fmi2False, fmi2False);
    if (c) free_instance(c);
    CHECK(harness.live == 0, "fmi2Instantiate(fmi2CoSimulation) leaked %ld blocks", harness.live);

    /* Allowed oddities: no logger, no resource location, a long name full of '%'. */
    const struct { const char *name, *resources; const fmi2CallbackFunctions *cb; } OK_CASES[] = {
        { "rod", NULL, &no_logger }, { "rod", NULL, cb }, { long_text, long_text, cb }, { "%s%n", "%s", cb },
    };
    for (size_t k = 0; k < sizeof OK_CASES / sizeof OK_CASES[0]; ++k) {
        c = f->Instantiate(OK_CASES[k].name, fmi2ModelExchange, g, OK_CASES[k].resources, OK_CASES[k].cb, fmi2True,
                           fmi2True);
        if (!CHECK(c != NULL, "fmi2Instantiate case %zu failed", k)) continue;
        CHECK(set_one(c, PROFILE_KNOB, NAN) == fmi2Error, "the knob = NaN accepted");
        check_reset_recovers(c, "odd instantiate arguments");
        free_instance(c);
    }
    free(long_text);
}

/* allocateMemory returning NULL at each allocation of fmi2Instantiate in turn. */
void test_allocation_failure(void)
{
    for (long k = 1; k <= 16; ++k) {
        harness.fail_allocation_at = harness.allocations + k;
        fmi2Component c = harness_instantiate(f, "rod");
        const bool failed_inside = harness.allocations >= harness.fail_allocation_at;
        harness.fail_allocation_at = 0;
        if (failed_inside) {
            CHECK(c == NULL, "fmi2Instantiate succeeded although allocation %ld returned NULL", k);
            CHECK(harness.live == 0, "fmi2Instantiate that failed at allocation %ld leaked %ld blocks", k,
                  harness.live);
        } else {
            CHECK(c != NULL, "fmi2Instantiate failed without an allocation failure");
        }
        if (c) {
            check_reset_recovers(c, "after allocation failures");
            free_instance(c);
        }
        if (!failed_inside) break;
    }
}

void test_logging(void)
{
    char long_category[5000];
    memset(long_category, '%', sizeof long_category - 1);
    long_category[sizeof long_category - 1] = '\0';
    const fmi2String KNOWN[] = { "logEvents", "logStatusWarning", "logStatusError", "logAll" };
    const fmi2String UNKNOWN[] = { "logEvents", "logNothing" };
    const fmi2String LONG[] = { long_category };
    EXPECT_IN(ME_INSTANTIATED, fmi2OK, f->SetDebugLogging(c, fmi2True, 4, KNOWN));
    EXPECT_IN(ME_ERROR, fmi2OK, f->SetDebugLogging(c, fmi2False, 4, KNOWN));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetDebugLogging(c, fmi2True, 2, UNKNOWN));
    EXPECT_IN(ME_INSTANTIATED, fmi2Error, f->SetDebugLogging(c, fmi2True, 1, LONG));

    /* With every category on, a simulation logs its events, all well formed. */
    fmi2Component c = instance_in(ME_INSTANTIATED);
    if (c) {
        const long before = harness.messages;
        CHECK(f->SetDebugLogging(c, fmi2True, 0, NULL) == fmi2OK, "logging on");
        EulerSim s = { .c = c };
        CHECK(harness_simulate(f, &s, 0.1, 5e-3, 60) == fmi2OK, "simulation with logging: %s", harness.last_message);
        CHECK(harness.messages > before, "no message logged by a simulation with events and logging on");
        free_instance(c);
    }
}
