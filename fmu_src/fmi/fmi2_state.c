/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 2.0 FMU state: get, set, free, serialize, deserialize, over the
 * snapshots of instance_state.c, in the importer's memory. */
#include "fmi2_instance.h"
#include "instance_state.h"

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    BEGIN("fmi2GetFMUstate", ANY_STATE);
    REQUIRE("fmi2GetFMUstate", state, "FMUstate pointer is NULL");
    void *s = *state ? *state : CALLBACKS(in).allocateMemory(1, instance_snapshot_size());
    REQUIRE("fmi2GetFMUstate", s, "out of memory");
    instance_snapshot_take(in, s);
    *state = s;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state)
{
    BEGIN("fmi2SetFMUstate", ANY_STATE);
    REQUIRE("fmi2SetFMUstate", state, "FMUstate is NULL");
    return (fmi2Status)instance_snapshot_restore(in, "fmi2SetFMUstate", state);
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    BEGIN("fmi2FreeFMUstate", ANY_STATE);
    REQUIRE("fmi2FreeFMUstate", state, "FMUstate pointer is NULL");
    if (*state) CALLBACKS(in).freeMemory(*state);
    *state = NULL;
    return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *size)
{
    BEGIN("fmi2SerializedFMUstateSize", ANY_STATE);
    REQUIRE("fmi2SerializedFMUstateSize", state && size, "FMUstate or size is NULL");
    *size = instance_snapshot_serialize(state, NULL);
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size)
{
    BEGIN("fmi2SerializeFMUstate", ANY_STATE);
    REQUIRE("fmi2SerializeFMUstate", state && bytes, "FMUstate or bytes is NULL");
    const size_t needed = instance_snapshot_serialize(state, NULL);
    REQUIRE("fmi2SerializeFMUstate", size >= needed, "%zu bytes given, the state needs %zu", size, needed);
    instance_snapshot_serialize(state, (unsigned char *)bytes);
    return fmi2OK;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size, fmi2FMUstate *state)
{
    static const char call[] = "fmi2DeSerializeFMUstate";
    BEGIN(call, ANY_STATE);
    REQUIRE(call, bytes && state, "bytes or FMUstate pointer is NULL");
    void *s = *state ? *state : CALLBACKS(in).allocateMemory(1, instance_snapshot_size());
    REQUIRE(call, s, "out of memory");
    if (instance_snapshot_deserialize(in, call, (const unsigned char *)bytes, size, s) != STATUS_OK) {
        if (!*state) CALLBACKS(in).freeMemory(s);
        return fmi2Error;
    }
    *state = s;
    return fmi2OK;
}
