/* SPDX-License-Identifier: BSD-2-Clause */
/* fuzz_fmi's FMU states: got, serialized, changed, cut or extended, deserialized
 * and set; and bytes that never were a state. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_fmi.h"

static const FmiApi *const f = &api;

/* FNV-1a, the checksum that ends a serialized state of fmi2_state.c: fixing
 * it up after a mutation lets the fuzzer reach the field parser behind it. */
static void fix_checksum(fmi2Byte *bytes, size_t n)
{
    if (n < 4) return;
    uint32_t h = 2166136261u;
    for (size_t k = 0; k < n - 4; ++k) h = (h ^ (uint8_t)bytes[k]) * 16777619u;
    for (size_t k = 0; k < 4; ++k) bytes[n - 4 + k] = (fmi2Byte)(h >> 8 * k);
}

/* A byte for a serialized state: a length or count on an edge, or any byte. */
static uint8_t take_byte_value(Bytes *b)
{
    static const uint8_t EDGES[] = { 0, 1, 2, 7, 8, 15, 16, 31, 32, 63, 64, 65, 127, 128, 255 };
    const uint8_t sel = take(b);
    return sel < 128 ? EDGES[sel % sizeof EDGES] : take(b);
}

/* Get an FMU state, serialize it, change some bytes, cut or extend it,
 * deserialize and set it into this instance or another. Every buffer is
 * allocated to its exact size, so a read past its end is caught. */
void op_fmu_state(Slot *s)
{
    const long errors_before = harness.error_messages;
    fmi2Component c = s->sim.c;
    const uint8_t flags = take(&fuzz_input);
    fmi2FMUstate state = NULL, restored = NULL;
    size_t size = 0;
    if (CALL(s, true, f->GetFMUstate(c, &state)) > fmi2Warning) return;
    if (flags & 1 && CALL(s, true, f->SetFMUstate(c, state)) <= fmi2Warning) s->in_error = false;
    if (CALL(s, true, f->SerializedFMUstateSize(c, state, &size)) <= fmi2Warning && size < 1u << 16) {
        fmi2Byte *bytes = malloc(size + 1);
        if (CALL(s, true, f->SerializeFMUstate(c, state, bytes, size - (flags >> 1 & 1))) <= fmi2Warning) {
            for (int k = take(&fuzz_input) % 8; k > 0; --k) {
                const size_t at = (size_t)take(&fuzz_input) << 8 | take(&fuzz_input);
                bytes[size ? at % size : 0] = (fmi2Byte)take_byte_value(&fuzz_input);
            }
            /* Cut to a length of n, or keep it whole (bytes past size stay out). */
            const uint8_t cut = take(&fuzz_input);
            const size_t n = cut < 192 ? size : cut % (size + 1);
            if (flags & 4) fix_checksum(bytes, n);
            fmi2Byte *exact = malloc(n ? n : 1);
            if (n) memcpy(exact, bytes, n);
            Slot *target = &slots[flags >> 3 & 1 ? (s - slots + 1) % 3 : s - slots];
            if (CALL(s, true, f->DeSerializeFMUstate(c, exact, n, &restored)) <= fmi2Warning) {
                const long before_target = harness.error_messages;
                if (target->sim.c && checked(target, "fmi2SetFMUstate(deserialized)",
                                             f->SetFMUstate(target->sim.c, restored), before_target, true) <= fmi2Warning)
                    target->in_error = false;
                CALL(s, true, f->FreeFMUstate(c, &restored));
            }
            free(exact);
        }
        free(bytes);
    }
    CALL(s, true, f->FreeFMUstate(c, &state));
}

/* Deserialization of bytes that never were a state. */
void op_deserialize_raw(Slot *s)
{
    const long errors_before = harness.error_messages;
    const size_t n = take(&fuzz_input) % 200;
    fmi2Byte *bytes = malloc(n ? n : 1);
    for (size_t k = 0; k < n; ++k) bytes[k] = (fmi2Byte)take(&fuzz_input);
    if (n > 8 && bytes[0] == 'P') memcpy(bytes, "PRODSTAT", 8); /* past the magic now and then */
    fmi2FMUstate state = NULL;
    if (CALL(s, true, f->DeSerializeFMUstate(s->sim.c, bytes, n, &state)) <= fmi2Warning)
        CALL(s, true, f->FreeFMUstate(s->sim.c, &state));
    free(bytes);
}
