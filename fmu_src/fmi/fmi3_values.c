/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 getters and setters. The model's Reals are Float64, its Integers
 * Int32, its Booleans Boolean (all scalars); the event indicators and time
 * are Float64 variables after them. No other type has a variable here:
 * its calls take no value reference. */
#include "fmi3_instance.h"

/* Array arguments shared by every getter and setter. */
static fmi3Status check_arrays(Instance *in, const char *call, const void *vr, size_t nvr, const void *values,
                               size_t nValues)
{
    REQUIRE(call, nvr == 0 || (vr && values), "valueReferences or values is NULL with nValueReferences = %zu", nvr);
    REQUIRE(call, nValues == nvr, "nValues = %zu, nValueReferences = %zu: every variable is a scalar", nValues, nvr);
    return fmi3OK;
}

/* Gets nvr values of `type` (the model gives doubles) into values. */
static fmi3Status get_values(fmi3Instance instance, const char *call, const fmi3ValueReference vr[], size_t nvr,
                             void *values, size_t nValues, VariableType type)
{
    BEGIN(call, READABLE);
    if (check_arrays(in, call, vr, nvr, values, nValues) != fmi3OK) return fmi3Error;
    double z[MODEL_NZ + 1]; /* + 1: a model without indicators (ShakerTable) has no zero-size array */
    for (size_t i = 0; i < nvr; ++i) {
        double v;
        if (type == TYPE_REAL && vr[i] >= VR_COUNT && vr[i] < VR_COUNT + MODEL_NZ) {
            model_get_indicators(instance_model(in), z);
            v = z[vr[i] - VR_COUNT];
        } else if (type == TYPE_REAL && vr[i] == VR_TIME) {
            v = in->time;
        } else if (instance_get(in, call, vr[i], type, &v) != STATUS_OK) {
            return fmi3Error;
        }
        switch (type) {
        case TYPE_REAL: ((fmi3Float64 *)values)[i] = v; break;
        case TYPE_INTEGER: ((fmi3Int32 *)values)[i] = (fmi3Int32)v; break;
        case TYPE_BOOLEAN: ((fmi3Boolean *)values)[i] = v != 0; break;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          fmi3Float64 values[], size_t nValues)
{
    return get_values(instance, "fmi3GetFloat64", valueReferences, nValueReferences, values, nValues, TYPE_REAL);
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                        fmi3Int32 values[], size_t nValues)
{
    return get_values(instance, "fmi3GetInt32", valueReferences, nValueReferences, values, nValues, TYPE_INTEGER);
}

fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          fmi3Boolean values[], size_t nValues)
{
    return get_values(instance, "fmi3GetBoolean", valueReferences, nValueReferences, values, nValues, TYPE_BOOLEAN);
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          const fmi3Float64 values[], size_t nValues)
{
    static const char call[] = "fmi3SetFloat64";
    BEGIN(call, Instantiated | InitializationMode | EventMode | ContinuousTimeMode | StepMode);
    if (check_arrays(in, call, valueReferences, nValueReferences, values, nValues) != fmi3OK) return fmi3Error;
    /* Check all, then set all: a rejected call changes nothing. */
    for (size_t i = 0; i < nValueReferences; ++i)
        if (instance_check_set(in, call, valueReferences[i], TYPE_REAL, values[i]) != STATUS_OK) return fmi3Error;
    for (size_t i = 0; i < nValueReferences; ++i) instance_set(in, valueReferences[i], values[i]);
    return fmi3OK;
}

#define SETTABLE (Instantiated | InitializationMode | EventMode | ContinuousTimeMode | StepMode)

/* A getter or setter of a type without (settable) variables: any value reference is wrong. */
static fmi3Status none_of(fmi3Instance instance, const char *call, InstanceState allowed, const fmi3ValueReference vr[],
                          size_t nvr, const void *values, size_t nValues, const char *type)
{
    BEGIN(call, allowed);
    if (check_arrays(in, call, vr, nvr, values, nValues) != fmi3OK) return fmi3Error;
    REQUIRE(call, nvr == 0, "value reference %u is not a %s%s variable of %s", vr[0],
            allowed == SETTABLE ? "settable " : "", type, MODEL_NAME);
    return fmi3OK;
}

/* The types with no variable at all, and Int32 and Boolean, which have no settable one. */
#define GETTER_OF_NONE(Type, CType)                                                                     \
    fmi3Status fmi3Get##Type(fmi3Instance instance, const fmi3ValueReference valueReferences[],          \
                             size_t nValueReferences, CType values[], size_t nValues)                   \
    {                                                                                                   \
        return none_of(instance, "fmi3Get" #Type, READABLE, valueReferences, nValueReferences, values,  \
                       nValues, #Type);                                                                 \
    }
#define SETTER_OF_NONE(Type, CType)                                                                     \
    fmi3Status fmi3Set##Type(fmi3Instance instance, const fmi3ValueReference valueReferences[],          \
                             size_t nValueReferences, const CType values[], size_t nValues)             \
    {                                                                                                   \
        return none_of(instance, "fmi3Set" #Type, SETTABLE, valueReferences, nValueReferences, values,  \
                       nValues, #Type);                                                                 \
    }

GETTER_OF_NONE(Float32, fmi3Float32)
GETTER_OF_NONE(Int8, fmi3Int8)
GETTER_OF_NONE(UInt8, fmi3UInt8)
GETTER_OF_NONE(Int16, fmi3Int16)
GETTER_OF_NONE(UInt16, fmi3UInt16)
GETTER_OF_NONE(UInt32, fmi3UInt32)
GETTER_OF_NONE(Int64, fmi3Int64)
GETTER_OF_NONE(UInt64, fmi3UInt64)
GETTER_OF_NONE(String, fmi3String)
SETTER_OF_NONE(Float32, fmi3Float32)
SETTER_OF_NONE(Int8, fmi3Int8)
SETTER_OF_NONE(UInt8, fmi3UInt8)
SETTER_OF_NONE(Int16, fmi3Int16)
SETTER_OF_NONE(UInt16, fmi3UInt16)
SETTER_OF_NONE(Int32, fmi3Int32)
SETTER_OF_NONE(UInt32, fmi3UInt32)
SETTER_OF_NONE(Int64, fmi3Int64)
SETTER_OF_NONE(UInt64, fmi3UInt64)
SETTER_OF_NONE(Boolean, fmi3Boolean)
SETTER_OF_NONE(String, fmi3String)

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                         size_t valueSizes[], fmi3Binary values[], size_t nValues)
{
    (void)valueSizes;
    return none_of(instance, "fmi3GetBinary", READABLE, valueReferences, nValueReferences, values, nValues, "Binary");
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                         const size_t valueSizes[], const fmi3Binary values[], size_t nValues)
{
    (void)valueSizes;
    return none_of(instance, "fmi3SetBinary", SETTABLE, valueReferences, nValueReferences, values, nValues, "Binary");
}

fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                        fmi3Clock values[])
{
    return none_of(instance, "fmi3GetClock", READABLE, valueReferences, nValueReferences, values, nValueReferences,
                   "Clock");
}

fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                        const fmi3Clock values[])
{
    return none_of(instance, "fmi3SetClock", SETTABLE, valueReferences, nValueReferences, values, nValueReferences,
                   "Clock");
}
