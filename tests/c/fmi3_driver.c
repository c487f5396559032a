/* SPDX-License-Identifier: BSD-2-Clause */
/* A model's FMI 3.0 layer (PainleveRod, or fmu_src/models/NAME as fmi3_driver_NAME,
 * with what its profile, profiles/NAME.h, says of it) through its C ABI, as an
 * importer loads it (dlopen): every fmi3 call in every state of both interfaces against FMI 3.0
 * (fmi3_conformance.c, fmi3_directional.c), and robustness: NULL pointers,
 * wrong array sizes (nValues != nValueReferences), unknown value references
 * and every getter and setter type, bad values (NaN, out of range: the
 * message names the variable and its range), Co-Simulation's early return
 * and Event Mode (a step while an event is pending is refused), serialized
 * FMU states cut short or changed, and what the FMU does not have (Scheduled
 * Execution, clocks, Configuration Mode, per-element dependencies).
 *
 * Built with AddressSanitizer + UBSan (fmi3_driver_asan) and plain for
 * valgrind (fmi3_driver); tests/fmu/test_c_robustness.py runs it.
 *
 *   fmi3_driver [--lib PATH] [--no-conformance | --conformance-only]
 *
 * This file: the options and the order of the tests; the robustness tests are
 * in fmi3_argument_checks.c, fmi3_value_checks.c, fmi3_cosim_checks.c,
 * fmi3_fmu_state_checks.c and fmi3_instantiate_checks.c.
 *
 * Exit status 0 only if every check passed. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robustness3.h"

Fmi3Api api3;

int main(int argc, char **argv)
{
    const char *lib = FMU_LIBRARY;
    bool conformance = true, robustness = true;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--lib") && k + 1 < argc) lib = argv[++k];
        else if (!strcmp(argv[k], "--no-conformance")) conformance = false;
        else if (!strcmp(argv[k], "--conformance-only")) robustness = false;
        else {
            fprintf(stderr, "usage: %s [--lib PATH] [--no-conformance | --conformance-only]\n", argv[0]);
            return 2;
        }
    }
    char err[1024];
    if (!fmi3_api_load(&api3, lib, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    harness_reset();
    if (conformance) {
        test3_conformance_table();
        test3_conformance_variables();
        test3_null_instance();
        test3_derivatives();
    }
    if (robustness) {
        test3_null_arguments();
        test3_array_sizes();
        test3_types_and_value_references();
        test3_bad_values();
        test3_early_return();
        static const State3 SERIALIZED[] = { M3_INSTANTIATED, M3_CONTINUOUS, M3_ERROR, C3_STEP_EM, C3_EVENT_AGAIN };
        for (size_t k = 0; k < sizeof SERIALIZED / sizeof SERIALIZED[0]; ++k) test3_serialized_state_bytes(SERIALIZED[k]);
        test3_instantiation_and_missing_features();
        test3_log_messages_are_text();
    }
    CHECK(harness.bad_messages == 0, "%ld malformed log messages, the last: %s", harness.bad_messages,
          harness.last_bad);
    fmi3_api_unload(&api3);
    printf("fmi3_driver: %ld checks, %ld failed (%ld log messages)\n", checks, failures, harness.messages);
    return failures ? 1 : 0;
}
