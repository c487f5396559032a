/* SPDX-License-Identifier: BSD-2-Clause */
/* What the FMI 2.0 files share: the instance (instance.h) with the
 * importer's callbacks, the call guards. The model is reached only through
 * instance.h and model.h. */
#ifndef FMI2_INSTANCE_H
#define FMI2_INSTANCE_H

#include "fmi2Functions.h"
#include "instance.h"

/* The standard's fmi2Functions.h prefixes the fmi2 names with
 * FMI2_FUNCTION_PREFIX; fmpy's copy, which the build uses, adds none. Either
 * way the exported names get the prefix, as our own do. */
#ifdef FMI2_FUNCTION_PREFIX
#undef fmi2FullName
#define fmi2FullName(name) NAMESPACED(name)
#endif

typedef struct {
    Instance base; /* first: an Fmi2Instance is an Instance */
    fmi2CallbackFunctions cb;
} Fmi2Instance;

/* States each call is allowed in (FMI 2.0.4 §3.2.3 and §4.2.4). */
#define READABLE (InitializationMode | EventMode | ContinuousTimeMode | StepMode | Terminated | Error)
#define SIMULATING (EventMode | ContinuousTimeMode)

/* NULL-safe instance check: a call on a NULL instance cannot log anything. */
#define BEGIN(call, allowed)                                                                         \
    Instance *in = (Instance *)c;                                                                    \
    if (!in) return fmi2Error;                                                                       \
    if (!(in->state & (allowed)))                                                                    \
        return (fmi2Status)instance_fail(in, call, "not allowed in state %s", instance_state_name(in->state))

#define REQUIRE(call, cond, ...) \
    if (!(cond)) return (fmi2Status)instance_fail(in, call, __VA_ARGS__)

/* For the calls of one interface only. */
#define INTERFACE(call, t, what) \
    REQUIRE(call, in->interface == (t), "is a " what " call; this instance was instantiated for the other interface")

/* The importer's memory functions of an instance. */
#define CALLBACKS(in) (((Fmi2Instance *)(in))->cb)

#endif
