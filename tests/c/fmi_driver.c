/* SPDX-License-Identifier: BSD-2-Clause */
/* A model's FMU (PainleveRod, or fmu_src/models/NAME as fmi_driver_NAME) through its
 * C ABI, as an importer loads it (dlopen): every FMI
 * function in every instance state of both interfaces against FMI 2.0.4
 * (conformance_table.c, conformance_directional.c), its inputs
 * (input_checks.c), NULL arguments, bad value references,
 * nvr = 0 and huge nvr, bad values, failing allocations, many live instances,
 * and instantiate/simulate/free cycles with a flat resident set.
 *
 * Built with AddressSanitizer + UBSan (fmi_driver_asan) and plain for
 * valgrind and the memory soak (fmi_driver); tests/fmu/test_c_robustness.py runs it.
 *
 *   fmi_driver [--lib PATH] [--cycles N] [--max-rss-growth-kb K] [--no-api]
 *              [--no-conformance | --conformance-only]
 *
 * This file: the options and the order of the tests; the tests are in
 * argument_checks.c, value_checks.c, instantiate_checks.c, fmu_state_checks.c,
 * cosim_checks.c and many_instances.c, what they share in instance_states.c.
 *
 * Exit status 0 only if every check passed. */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robustness.h"

FmiApi api;
static const FmiApi *const f = &api;

/* ----------------------------------------------------------------- main */

static void test_platform_and_version(void)
{
    CHECK(strcmp(f->GetTypesPlatform(), "default") == 0, "types platform '%s'", f->GetTypesPlatform());
    CHECK(strcmp(f->GetVersion(), "2.0") == 0, "version '%s'", f->GetVersion());
}

/* The FMI 2.0.4 conformance table of both interfaces (conformance_*.c). */
static void test_conformance(bool cosimulation)
{
    test_platform_and_version(); /* the two calls without an instance, allowed everywhere */
    if (!CHECK(cosimulation, "Co-Simulation is not in this build: the conformance table needs both interfaces"))
        return;
    test_conformance_null_instance();
    test_conformance_table();
    test_conformance_variables();
    test_error_state_recovery();
    test_directional_derivatives();
    test_inputs();
}

int main(int argc, char **argv)
{
    const char *lib = FMU_LIBRARY;
    long cycles = 1000, max_growth_kb = -1;
    bool api_tests = true, conformance = true, robustness = true;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--lib") && k + 1 < argc) lib = argv[++k];
        else if (!strcmp(argv[k], "--cycles") && k + 1 < argc) cycles = atol(argv[++k]);
        else if (!strcmp(argv[k], "--max-rss-growth-kb") && k + 1 < argc) max_growth_kb = atol(argv[++k]);
        else if (!strcmp(argv[k], "--no-api")) api_tests = false;
        else if (!strcmp(argv[k], "--no-conformance")) conformance = false;
        else if (!strcmp(argv[k], "--conformance-only")) robustness = false;
        else {
            fprintf(stderr, "usage: %s [--lib PATH] [--cycles N] [--max-rss-growth-kb K] [--no-api] "
                            "[--no-conformance | --conformance-only]\n", argv[0]);
            return 2;
        }
    }
    char err[1024];
    if (!fmi2_functions_load(&api, lib, true, true, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    harness_reset();
    const bool cosimulation = cosimulation_available();
    printf("Co-Simulation %s\n", cosimulation ? "tested" : "not in this build: Model Exchange only");
    if (api_tests && conformance) test_conformance(cosimulation);
    if (api_tests && robustness) {
        test_null_arguments();
        test_value_references();
        test_nvr_zero_and_huge();
        test_large_arrays();
        test_bad_values();
        for (int state = ME_INSTANTIATED; state <= ME_TERMINATED; ++state) test_serialized_state_bytes((State)state);
        test_instantiate_arguments();
        test_allocation_failure();
        test_logging();
        test_interleaved_instances();
        if (cosimulation) {
            test_cosimulation_bad_steps();
            test_cosimulation_state_restores_the_run();
        }
    }
    if (robustness) test_cycles(cycles, max_growth_kb, cosimulation);
    CHECK(harness.bad_messages == 0, "%ld malformed log messages, the last: %s", harness.bad_messages,
          harness.last_bad);
    CHECK(harness.live == 0, "%ld blocks allocated through allocateMemory never freed", harness.live);
    fmi2_functions_unload(&api);
    printf("fmi_driver: %ld checks, %ld failed (%ld allocations, %ld log messages)\n", checks, failures,
           harness.allocations, harness.messages);
    return failures ? 1 : 0;
}
