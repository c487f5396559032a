/* SPDX-License-Identifier: BSD-2-Clause */
/* libFuzzer target: the input's bytes become a sequence of FMI calls on up to
 * three instances of a model (one target per model: fuzz_fmi for PainleveRod,
 * fuzz_fmi_NAME for fmu_src/models/NAME), with the values, value references, counts
 * and NULL pointers they carry (NaN, infinities, denormals, range limits,
 * epsilon huge and tiny, raw bit patterns). Besides AddressSanitizer and
 * UBSan it checks, and aborts on:
 *   - a status that is not an fmi2Status, an fmi2Error without an error logged;
 *   - a log message with a lone '%' (the FMU passes its text unformatted);
 *   - an fmi2OK output that is NaN or infinite, a mode outside {-1, 0, 1};
 *   - a simulation call succeeding in the Error state without fmi2Reset;
 *   - a status query (§4.2.3) answering fmi2OK where there is nothing to
 *     report, or an fmi2Discard that changed the instance's state;
 *   - memory from allocateMemory still held after the instances are freed.
 *
 * Input format, one call at a time: an opcode byte (call = byte % N_OPS,
 * instance = byte / N_OPS % 3), then the call's arguments, each taken from the
 * following bytes (see take_double, take_vr, take_count); missing bytes read 0.
 *
 * tests/c/corpus holds the seeds (seed-*: a simulation with events, FMU
 * state round trips, two instances, logging, Co-Simulation, an error and a
 * reset) and the inputs that once broke an invariant (regress-*), kept as
 * regression cases: the first ones the target's own false alarms, since fixed;
 * regress-*-hangs calls that never returned, written from
 * readable call sequences by tests/c/corpus_inputs.py. The CI runs are
 * deterministic: -runs=N -seed=S over the corpus, -timeout per input.
 *
 *   fuzz_fmi CORPUS_DIR... [-runs=N] [-max_total_time=S]   fuzz (libFuzzer flags)
 *   fuzz_fmi FILE...                                         replay inputs
 *
 * This file: the opcodes and the loop that decodes them; the calls are in
 * fuzz_fmi_instances.c, fuzz_fmi_values.c, fuzz_fmi_modes.c,
 * fuzz_fmi_fmu_state.c and fuzz_fmi_steps.c (fuzz_fmi.h). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_fmi.h"

FmiApi api;

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *lib = getenv("FUZZ_FMU_LIBRARY");
    char err[1024];
    if (!fmi2_functions_load(&api, lib ? lib : FMU_LIBRARY, true, true, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        exit(2);
    }
    return 0;
}

enum {
    OP_INSTANTIATE, OP_FREE,
    OP_GET, OP_GET_END = OP_GET + 3,
    OP_SET, OP_SET_END = OP_SET + 3,
    OP_ARRAYS, OP_ARRAYS_END = OP_ARRAYS + 4,
    OP_EVENT, OP_EVENT_END = OP_EVENT + 5,
    OP_LIFECYCLE, OP_LIFECYCLE_END = OP_LIFECYCLE + 4,
    OP_DEBUG_LOGGING, OP_DIRECTIONAL,
    OP_OPTIONAL, OP_OPTIONAL_END = OP_OPTIONAL + 5,
    OP_SIMULATE, OP_SIMULATE_END = OP_SIMULATE + 1,
    N_OPS
};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    harness_reset();
    fuzz_input = (Bytes){ data, size };
    span_left = PROFILE_FUZZ_SPAN;
    for (int calls = 0; fuzz_input.n > 0 && calls < 256; ++calls) {
        const uint8_t op = take(&fuzz_input);
        Slot *s = &slots[op / N_OPS % 3];
        const int code = op % N_OPS;
        if (code == OP_INSTANTIATE) op_instantiate(s);
        else if (code == OP_FREE) free_slot(s);
        else if (code <= OP_GET_END) op_get(s, (uint8_t)(code - OP_GET));
        else if (code <= OP_SET_END) op_set(s, (uint8_t)(code - OP_SET));
        else if (code <= OP_ARRAYS_END) op_arrays(s, (uint8_t)(code - OP_ARRAYS));
        else if (code <= OP_EVENT_END) op_event(s, (uint8_t)(code - OP_EVENT));
        else if (code <= OP_LIFECYCLE_END) op_lifecycle(s, (uint8_t)(code - OP_LIFECYCLE));
        else if (code == OP_DEBUG_LOGGING) op_debug_logging(s);
        else if (code == OP_DIRECTIONAL) op_directional_derivative(s);
        else if (code <= OP_OPTIONAL_END) op_optional(s, (uint8_t)(code - OP_OPTIONAL));
        else op_simulate(s, (uint8_t)(code - OP_SIMULATE));
    }
    for (int k = 0; k < 3; ++k) free_slot(&slots[k]);
    INVARIANT(harness.live == 0, "%ld blocks from allocateMemory outlive every instance", harness.live);
    INVARIANT(harness.bad_messages == 0, "malformed log message: %s", harness.last_bad);
    return 0;
}

