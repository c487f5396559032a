/* SPDX-License-Identifier: BSD-2-Clause */
/* What the FMI 3.0 files share: the instance (instance.h) with the
 * importer's callbacks and Co-Simulation's choices, the call guards. The
 * model is reached only through instance.h and model.h. */
#ifndef FMI3_INSTANCE_H
#define FMI3_INSTANCE_H

#include "fmi3Functions.h"
#include "instance.h"

typedef struct {
    Instance base; /* first: an Fmi3Instance is an Instance */
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback log_message;
    bool event_mode_used;      /* Co-Simulation: the master handles events in Event Mode */
    bool early_return_allowed; /* Co-Simulation: a step may end at an event */
    bool event_pending;        /* a step ended at an event the master has yet to handle in Event Mode */
} Fmi3Instance;

#define FMI3(in) ((Fmi3Instance *)(in))

/* States each call is allowed in (FMI 3.0 §3.2 and §4.2; this FMU has no
 * Configuration Mode and no clocks). */
#define READABLE (InitializationMode | EventMode | ContinuousTimeMode | StepMode | Terminated | Error)

/* Event indicators and time are variables in FMI 3.0: value references
 * VR_COUNT .. VR_COUNT + MODEL_NZ - 1 and VR_COUNT + MODEL_NZ follow the
 * model's (cmake/fmi3_model_description.py). */
#define VR_TIME (VR_COUNT + MODEL_NZ)

#define BEGIN(call, allowed)                                                                         \
    Instance *in = (Instance *)instance;                                                             \
    if (!in) return fmi3Error;                                                                       \
    if (!(in->state & (allowed)))                                                                    \
        return (fmi3Status)instance_fail(in, call, "not allowed in state %s", instance_state_name(in->state))

#define REQUIRE(call, cond, ...) \
    if (!(cond)) return (fmi3Status)instance_fail(in, call, __VA_ARGS__)

#define INTERFACE(call, t, what) \
    REQUIRE(call, in->interface == (t), "is a " what " call; this instance was instantiated for the other interface")

#endif
