/* FMI 2.0 Co-Simulation: fmi2DoStep integrates the same model and the same
 * event iteration as Model Exchange with the embedded CVODE of cosim.c.
 * Built without SUNDIALS (no HAVE_CVODE), every step says so and fails. */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "fmi2_instance.h"

#ifdef HAVE_CVODE
#include "cosim.h"
#endif

/* Communication points closer than this (relative) are the same point. */
#define SAME_TIME 1e-12

void cs_free(Instance *in)
{
#ifdef HAVE_CVODE
    cosim_free(in->cosim);
#endif
    in->cosim = NULL;
}

#ifdef HAVE_CVODE
/* The default tolerance keeps the solver's error well below the model's own
 * O(eps ln 1/eps): measured, eps/1000 does with a restart at every
 * communication point (Model Exchange under fmpy needs eps/100); it is kept
 * for masters that restore FMU states often (each restore restarts). */
static double tolerance_of(const Instance *in)
{
    const double eps = in->model.params.epsilon;
    return in->tolerance > 0 ? in->tolerance : fmin(1e-6, eps / 1000);
}

static fmi2Status restart(Instance *in, const char *call)
{
    char err[512];
    REQUIRE(call, cosim_start(in->cosim, &in->model, in->time, tolerance_of(in), err, sizeof err), "%s", err);
    mark_restart(in);
    return fmi2OK;
}

/* Integrates to t_end; events on the way are located by CVODE and handled
 * by the same event iteration as Model Exchange, unseen by the master.
 * CVODE continues from one step to the next (its history is the trajectory's:
 * a communication point costs no restart) and restarts after events and
 * wherever the trajectory may have been replaced: initialization, reset,
 * FMU state get and set. So the FMU state is still just the model's. */
static fmi2Status integrate(Instance *in, double t_end)
{
    static const char call[] = "fmi2DoStep";
    if (!in->cosim) in->cosim = cosim_new();
    REQUIRE(call, in->cosim, "out of memory for the integrator");
    if (!in->solver_live && restart(in, call) != fmi2OK) return fmi2Error;
    in->solver_live = true;
    /* A remainder CVODE cannot resolve (a few ulps after an event) is reached. */
    while (t_end - in->time > 4 * DBL_EPSILON * fmax(1, fabs(t_end))) {
        char err[512];
        const CoSimResult r = cosim_advance(in->cosim, &in->model, &in->time, t_end, err, sizeof err);
        REQUIRE(call, r != COSIM_FAILED, "%s", err);
        if (r == COSIM_REACHED) break;
        bool changed;
        in->solver_live = false;
        if (handle_event(in, call, &changed) != fmi2OK) return fmi2Error;
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
    return fail(in, call, "this binary was built without SUNDIALS CVODE: Co-Simulation is not available "
                          "(rebuild with libsundials-dev installed, or use Model Exchange)");
#endif
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    BEGIN("fmi2CancelStep", StepComplete);
    return fail(in, "fmi2CancelStep", "steps are never asynchronous (canRunAsynchronuously is false)");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr, (void)order, (void)value;
    BEGIN("fmi2SetRealInputDerivatives", BEFORE_INIT_ENDS | StepComplete);
    REQUIRE("fmi2SetRealInputDerivatives", nvr == 0, "PainleveRod has no inputs");
    return fmi2OK;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)order, (void)value;
    BEGIN("fmi2GetRealOutputDerivatives", StepComplete | Terminated | Error);
    REQUIRE("fmi2GetRealOutputDerivatives", nvr == 0, "output derivatives are not provided (maxOutputDerivativeOrder = 0)");
    return fmi2OK;
}

static const char *const STATUS_STATES = "StepComplete, Terminated, Error";

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    (void)s, (void)value;
    BEGIN("fmi2GetStatus", StepComplete | Terminated | Error);
    return fail(in, "fmi2GetStatus", "no step is pending (steps are synchronous); status kinds available: "
                "fmi2LastSuccessfulTime (Real), fmi2Terminated (Boolean) in %s", STATUS_STATES);
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    BEGIN("fmi2GetRealStatus", StepComplete | Terminated | Error);
    REQUIRE("fmi2GetRealStatus", value, "value is NULL");
    REQUIRE("fmi2GetRealStatus", s == fmi2LastSuccessfulTime, "only fmi2LastSuccessfulTime is a Real status");
    *value = in->last_successful_time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)s, (void)value;
    BEGIN("fmi2GetIntegerStatus", StepComplete | Terminated | Error);
    return fail(in, "fmi2GetIntegerStatus", "there is no Integer status");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    BEGIN("fmi2GetBooleanStatus", StepComplete | Terminated | Error);
    REQUIRE("fmi2GetBooleanStatus", value, "value is NULL");
    REQUIRE("fmi2GetBooleanStatus", s == fmi2Terminated, "only fmi2Terminated is a Boolean status");
    *value = fmi2False; /* the rod never asks to end a simulation */
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)s, (void)value;
    BEGIN("fmi2GetStringStatus", StepComplete | Terminated | Error);
    return fail(in, "fmi2GetStringStatus", "there is no String status");
}
