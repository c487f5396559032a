/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 serialized FMU states cut short or with a byte changed are refused,
 * never read past their end (fmi3_driver's robustness tests). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "robustness3.h"

static const Fmi3Api *const f = &api3;

/* ----------------------------------------------------- FMU state bytes */

/* Serialized states cut short or with a byte changed are refused, never read past their end. */
void test3_serialized_state_bytes(State3 state)
{
    Inst3 in;
    if (!inst3_reach(&in, state, false)) return;
    fmi3FMUState s = NULL, t = NULL;
    size_t size = 0;
    fmi3Byte *bytes = NULL;
    if (!CHECK(f->GetFMUState(in.c, &s) == fmi3OK && f->SerializedFMUStateSize(in.c, s, &size) == fmi3OK && size > 0,
               "FMU state in %s", STATE3_NAME[state]))
        goto done;
    bytes = malloc(size);
    if (!CHECK(bytes && f->SerializeFMUState(in.c, s, bytes, size) == fmi3OK, "fmi3SerializeFMUState")) goto done;
    CHECK(f->SerializeFMUState(in.c, s, bytes, size - 1) == fmi3Error, "a state serialized into %zu of %zu bytes",
          size - 1, size);
    CHECK(f->Reset(in.c) == fmi3OK, "fmi3Reset");
    for (size_t n = 0; n < size; n += 1 + n / 16) {
        fmi3Byte *prefix = exact_copy(bytes, n);
        const fmi3Status st = f->DeserializeFMUState(in.c, prefix, n, &t);
        CHECK(st != fmi3OK, "a state cut to %zu of %zu bytes was accepted", n, size);
        if (st == fmi3OK) f->FreeFMUState(in.c, &t);
        if (st == fmi3Error) CHECK(f->Reset(in.c) == fmi3OK, "fmi3Reset");
        free(prefix);
    }
    static const unsigned char EDGES[] = { 0x00, 0x7f, 0x80, 0xff };
    for (size_t n = 0; n < size; n += 1 + n / 32) {
        for (size_t k = 0; k < sizeof EDGES; ++k) {
            if ((unsigned char)bytes[n] == EDGES[k]) continue;
            fmi3Byte *changed = exact_copy(bytes, size);
            changed[n] = (fmi3Byte)EDGES[k];
            const fmi3Status st = f->DeserializeFMUState(in.c, changed, size, &t);
            /* A changed value byte can make another legal state: then it must set. */
            if (st == fmi3OK) {
                CHECK(f->SetFMUState(in.c, t) <= fmi3Error, "fmi3SetFMUState");
                f->FreeFMUState(in.c, &t);
            }
            CHECK(f->Reset(in.c) == fmi3OK, "fmi3Reset");
            free(changed);
        }
    }
    /* The intact bytes still make the state, and it still runs. */
    CHECK(f->DeserializeFMUState(in.c, bytes, size, &t) == fmi3OK, "intact state refused: %s", harness.last_error);
    CHECK(f->SetFMUState(in.c, t) == fmi3OK, "fmi3SetFMUState of a deserialized state: %s", harness.last_error);
    f->FreeFMUState(in.c, &t);
    inst3_works(&in, "a deserialized FMU state");
done:
    if (s) f->FreeFMUState(in.c, &s);
    free(bytes);
    inst3_free(&in);
}
