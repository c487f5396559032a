/* SPDX-License-Identifier: BSD-2-Clause */
/* Serialized FMU states cut short or with a byte changed are refused, never read
 * past their end (fmi_driver's robustness tests). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robustness.h"

static const FmiApi *const f = &api;

/* ----------------------------------------------------- FMU state bytes */

/* Serialized states cut short or with a byte changed are refused, never
 * read past their end; an intact one round-trips. Skipped where the FMU does
 * not serialize its state. */
void test_serialized_state_bytes(State state)
{
    fmi2Component c = instance_in(state);
    if (!c) return;
    fmi2FMUstate s = NULL, t = NULL;
    size_t size = 0;
    fmi2Byte *bytes = NULL, *again = NULL;
    if (f->GetFMUstate(c, &s) != fmi2OK || f->SerializedFMUstateSize(c, s, &size) != fmi2OK) goto done;
    bytes = malloc(size ? size : 1);
    again = malloc(size ? size : 1);
    if (!CHECK(bytes && again, "out of memory")) goto done;
    if (!CHECK(f->SerializeFMUstate(c, s, bytes, size) == fmi2OK, "fmi2SerializeFMUstate: %s", harness.last_message))
        goto done;
    CHECK(f->DeSerializeFMUstate(c, bytes, size, &t) == fmi2OK, "intact state refused: %s", harness.last_message);
    CHECK(f->SerializeFMUstate(c, t, again, size) == fmi2OK && memcmp(bytes, again, size) == 0,
          "a deserialized state serializes differently");
    CHECK(f->SetFMUstate(c, t) == fmi2OK, "fmi2SetFMUstate of a deserialized state: %s", harness.last_message);
    f->FreeFMUstate(c, &t);

    fmi2Byte *small = exact_copy(bytes, size - 1);
    CHECK(f->SerializeFMUstate(c, s, small, size - 1) == fmi2Error, "a state serialized into %zu of %zu bytes",
          size - 1, size);
    CHECK(f->Reset(c) == fmi2OK, "fmi2Reset");
    free(small);
    for (size_t n = 0; n < size; ++n) {
        fmi2Byte *prefix = exact_copy(bytes, n);
        fmi2Status st = f->DeSerializeFMUstate(c, prefix, n, &t);
        CHECK(st != fmi2OK, "a state cut to %zu of %zu bytes was accepted", n, size);
        if (st == fmi2OK) f->FreeFMUstate(c, &t);
        if (st == fmi2Error) CHECK(f->Reset(c) == fmi2OK, "fmi2Reset");
        free(prefix);
    }
    /* Every byte set to values on the edges of lengths and counts. */
    static const unsigned char EDGES[] = { 0x00, 0x01, 0x3f, 0x40, 0x41, 0x7f, 0x80, 0xff };
    for (size_t n = 0; n < size; ++n) {
        for (size_t k = 0; k < sizeof EDGES; ++k) {
            if ((unsigned char)bytes[n] == EDGES[k]) continue;
            fmi2Byte *changed = exact_copy(bytes, size);
            changed[n] = (fmi2Byte)EDGES[k];
            fmi2Status st = f->DeSerializeFMUstate(c, changed, size, &t);
            CHECK(st != fmi2OK, "a state with byte %zu of %zu set to %#x was accepted", n, size, EDGES[k]);
            if (st == fmi2OK) f->FreeFMUstate(c, &t);
            if (st == fmi2Error) CHECK(f->Reset(c) == fmi2OK, "fmi2Reset");
            free(changed);
        }
    }
done:
    if (s) f->FreeFMUstate(c, &s);
    free(bytes);
    free(again);
    free_instance(c);
}
