/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 FMU state: get, set, free, serialize, deserialize, over the
 * snapshots of instance_state.c (FMI 3.0 has no memory callbacks: malloc). */
#include <stdlib.h>

#include "fmi3_instance.h"
#include "instance_state.h"

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    BEGIN("fmi3GetFMUState", ANY_STATE);
    REQUIRE("fmi3GetFMUState", FMUState, "FMUState pointer is NULL");
    void *s = *FMUState ? *FMUState : malloc(instance_snapshot_size());
    REQUIRE("fmi3GetFMUState", s, "out of memory");
    instance_snapshot_take(in, s);
    *FMUState = s;
    return fmi3OK;
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    BEGIN("fmi3SetFMUState", ANY_STATE);
    REQUIRE("fmi3SetFMUState", FMUState, "FMUState is NULL");
    return (fmi3Status)instance_snapshot_restore(in, "fmi3SetFMUState", FMUState);
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    BEGIN("fmi3FreeFMUState", ANY_STATE);
    REQUIRE("fmi3FreeFMUState", FMUState, "FMUState pointer is NULL");
    free(*FMUState);
    *FMUState = NULL;
    return fmi3OK;
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t *size)
{
    BEGIN("fmi3SerializedFMUStateSize", ANY_STATE);
    REQUIRE("fmi3SerializedFMUStateSize", FMUState && size, "FMUState or size is NULL");
    *size = instance_snapshot_serialize(FMUState, NULL);
    return fmi3OK;
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState, fmi3Byte serializedState[],
                                 size_t size)
{
    BEGIN("fmi3SerializeFMUState", ANY_STATE);
    REQUIRE("fmi3SerializeFMUState", FMUState && serializedState, "FMUState or serializedState is NULL");
    const size_t needed = instance_snapshot_serialize(FMUState, NULL);
    REQUIRE("fmi3SerializeFMUState", size >= needed, "%zu bytes given, the state needs %zu", size, needed);
    instance_snapshot_serialize(FMUState, serializedState);
    return fmi3OK;
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[], size_t size,
                                   fmi3FMUState *FMUState)
{
    static const char call[] = "fmi3DeserializeFMUState";
    BEGIN(call, ANY_STATE);
    REQUIRE(call, serializedState && FMUState, "serializedState or FMUState pointer is NULL");
    void *s = *FMUState ? *FMUState : malloc(instance_snapshot_size());
    REQUIRE(call, s, "out of memory");
    if (instance_snapshot_deserialize(in, call, serializedState, size, s) != STATUS_OK) {
        if (!*FMUState) free(s);
        return fmi3Error;
    }
    *FMUState = s;
    return fmi3OK;
}
