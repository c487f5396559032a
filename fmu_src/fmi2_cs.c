/* FMI 2.0 Co-Simulation: fmi2DoStep integrates the model with the embedded
 * CVODE of cosim.c and runs the same event update as Model Exchange at every
 * event inside a step. Built without SUNDIALS (no HAVE_CVODE), every step
 * says so and fails. */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "fmi2_instance.h"

#ifdef HAVE_CVODE
#include "cosim.h"
#endif

/* Communication points closer than this (relative) are the same point. */
#define SAME_TIME 1e-12

#ifdef HAVE_CVODE
static void free_solver(void *solver)
{
    cosim_free(solver);
}

static fmi2Status restart(Instance *in, const char *call)
{
    char err[512];
    REQUIRE(call, cosim_start(in->solver, &in->model, in->time, in->tolerance, err, sizeof err), "%s", err);
    model_begin_integration(&in->model);
    return fmi2OK;
}

/* Integrates to t_end; events on the way are located by CVODE and handled
 * by the same event update as Model Exchange, unseen by the master.
 * CVODE continues from one step to the next (its history is the trajectory's:
 * a communication point costs no restart) and restarts after events and
 * wherever the trajectory may have been replaced: initialization, reset,
 * FMU state get and set. So the FMU state is still just the model's. */
static fmi2Status integrate(Instance *in, double t_end)
{
    static const char call[] = "fmi2DoStep";
    if (!in->solver) {
        in->solver = cosim_new();
        in->free_solver = free_solver;
    }
    REQUIRE(call, in->solver, "out of memory for the integrator");
    if (!in->solver_live && restart(in, call) != fmi2OK) return fmi2Error;
    in->solver_live = true;
    /* A remainder CVODE cannot resolve (a few ulps after an event) is reached. */
    while (t_end - in->time > 4 * DBL_EPSILON * fmax(1, fabs(t_end))) {
        char err[512];
        const CoSimResult r = cosim_advance(in->solver, &in->model, &in->time, t_end, err, sizeof err);
        if (r == COSIM_FAILED) in->solver_live = false;
        REQUIRE(call, r != COSIM_FAILED, "%s", err);
        if (r == COSIM_REACHED) break;
        bool changed;
        in->solver_live = false;
        if (instance_event_update(in, call, &changed) != fmi2OK) return fmi2Error;
        if (restart(in, call) != fmi2OK) return fmi2Error;
        in->solver_live = true;
    }
    in->time = t_end;
    return fmi2OK;
}
#endif

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    static const char call[] = "fmi2DoStep";
    BEGIN(call, StepComplete);
    INTERFACE(call, fmi2CoSimulation, "Co-Simulation");
    REQUIRE(call, isfinite(t) && fabs(t - in->time) <= SAME_TIME * fmax(1, fabs(t)),
            "currentCommunicationPoint = %.17g is not the instance's time %.17g", t, in->time);
    REQUIRE(call, isfinite(h) && h > 0, "communicationStepSize = %g must be finite and > 0", h);
#ifdef HAVE_CVODE
    if (integrate(in, t + h) != fmi2OK) return fmi2Error;
    in->last_successful_time = in->time;
    return fmi2OK;
#else
    return instance_fail(in, call, "this binary was built without SUNDIALS CVODE: Co-Simulation is not available "
                                   "(rebuild with libsundials-dev installed, or use Model Exchange)");
#endif
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    BEGIN("fmi2CancelStep", StepComplete);
    INTERFACE("fmi2CancelStep", fmi2CoSimulation, "Co-Simulation");
    return instance_fail(in, "fmi2CancelStep", "steps are never asynchronous (canRunAsynchronuously is false)");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr, (void)order, (void)value;
    BEGIN("fmi2SetRealInputDerivatives", BEFORE_INIT_ENDS | StepComplete);
    INTERFACE("fmi2SetRealInputDerivatives", fmi2CoSimulation, "Co-Simulation");
    REQUIRE("fmi2SetRealInputDerivatives", nvr == 0, "%s has no inputs (canInterpolateInputs is false)", MODEL_NAME);
    return fmi2OK;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)order, (void)value;
    BEGIN("fmi2GetRealOutputDerivatives", StepComplete | Terminated | Error);
    INTERFACE("fmi2GetRealOutputDerivatives", fmi2CoSimulation, "Co-Simulation");
    REQUIRE("fmi2GetRealOutputDerivatives", nvr == 0,
            "output derivatives are not provided (maxOutputDerivativeOrder = 0)");
    return fmi2OK;
}

/* Status queries (FMI 2.0.4 §4.2.3): steps are synchronous, so a status that
 * exists only for asynchronous steps is a legal question with no answer. */
#define STATUS_STATES (StepComplete | Terminated | Error)
#define STATUS_BEGIN(call)                                                 \
    BEGIN(call, STATUS_STATES);                                            \
    INTERFACE(call, fmi2CoSimulation, "Co-Simulation");                    \
    REQUIRE(call, value, "value is NULL")

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    STATUS_BEGIN("fmi2GetStatus");
    return instance_discard(in, "fmi2GetStatus", "status kind %d: no step is pending (steps are synchronous)", (int)s);
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    STATUS_BEGIN("fmi2GetRealStatus");
    if (s != fmi2LastSuccessfulTime)
        return instance_discard(in, "fmi2GetRealStatus", "status kind %d: only fmi2LastSuccessfulTime is a Real status",
                                (int)s);
    *value = in->last_successful_time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    STATUS_BEGIN("fmi2GetIntegerStatus");
    return instance_discard(in, "fmi2GetIntegerStatus", "status kind %d: there is no Integer status", (int)s);
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    STATUS_BEGIN("fmi2GetBooleanStatus");
    if (s != fmi2Terminated)
        return instance_discard(in, "fmi2GetBooleanStatus", "status kind %d: only fmi2Terminated is a Boolean status",
                                (int)s);
    *value = fmi2False; /* the rod never asks to end a simulation */
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    STATUS_BEGIN("fmi2GetStringStatus");
    return instance_discard(in, "fmi2GetStringStatus", "status kind %d: no step is pending (steps are synchronous)",
                            (int)s);
}
