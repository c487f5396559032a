/* A Co-Simulation step under any FMI version (instance.h): the embedded CVODE
 * of cosim.c integrates the model, and each event it locates gets the same
 * event update as in Model Exchange.
 *
 * CVODE continues from one step to the next (its history is the trajectory's:
 * a communication point costs no restart) and restarts after events and
 * wherever the trajectory may have been replaced: initialization, reset, FMU
 * state get and set. So the FMU state is still just the model's. */
#include <float.h>
#include <math.h>

#include "instance.h"

#ifdef HAVE_CVODE
#include "cosim.h"

void instance_free_solver(Instance *in)
{
    cosim_free(in->solver);
    in->solver = NULL;
}

static Status restart(Instance *in, const char *call)
{
    char err[512];
    if (!cosim_start(in->solver, &in->model, in->time, in->tolerance, err, sizeof err))
        return instance_fail(in, call, "%s", err);
    model_begin_integration(&in->model);
    in->solver_live = true;
    return STATUS_OK;
}

static Status integrate(Instance *in, const char *call, double t_end, StepPolicy policy, StepEnd *end)
{
    if (!in->solver) in->solver = cosim_new();
    if (!in->solver) return instance_fail(in, call, "out of memory for the integrator");
    if (in->inputs_jumped) {   /* the master's new inputs: the mode may change (a stick may end) */
        bool changed;
        in->inputs_jumped = false;
        in->solver_live = false;
        if (instance_event_update(in, call, &changed) != STATUS_OK) return STATUS_ERROR;
    }
    if (!in->solver_live && restart(in, call) != STATUS_OK) return STATUS_ERROR;
    const double t_start = in->time;
    /* A remainder CVODE cannot resolve (a few ulps after an event) is reached. */
    while (t_end - in->time > 4 * DBL_EPSILON * fmax(1, fabs(t_end))) {
        char err[512];
        const CoSimResult r = cosim_advance(in->solver, &in->model, &in->time, t_end, err, sizeof err);
        if (r == COSIM_FAILED) {
            in->solver_live = false;
            return instance_fail(in, call, "%s", err);
        }
        if (r == COSIM_REACHED) break;
        /* CVODE continues from its own last time, which a master's communication point may pass
         * by rounding errors: a root it locates before the step's start is at the start. */
        in->time = fmax(in->time, t_start);
        in->solver_live = false;
        if (policy == RETURN_AT_EVENT) {
            *end = STEP_EVENT;
            return STATUS_OK;
        }
        bool changed;
        if (instance_event_update(in, call, &changed) != STATUS_OK || restart(in, call) != STATUS_OK)
            return STATUS_ERROR;
        if (policy == RETURN_AFTER_EVENT) {
            *end = STEP_EVENT;
            return STATUS_OK;
        }
    }
    in->time = t_end;
    return STATUS_OK;
}
#else
void instance_free_solver(Instance *in)
{
    in->solver = NULL;
}

static Status integrate(Instance *in, const char *call, double t_end, StepPolicy policy, StepEnd *end)
{
    (void)t_end, (void)policy, (void)end;
    return instance_fail(in, call, "this binary was built without SUNDIALS CVODE: Co-Simulation is not available "
                                   "(rebuild with libsundials-dev installed, or use Model Exchange)");
}
#endif

/* Communication points closer than this (relative) are the same point. */
#define SAME_TIME 1e-12

Status instance_step(Instance *in, const char *call, double t, double h, StepPolicy policy, StepEnd *end)
{
    *end = STEP_REACHED;
    if (!(isfinite(t) && fabs(t - in->time) <= SAME_TIME * fmax(1, fabs(t))))
        return instance_fail(in, call, "currentCommunicationPoint = %.17g is not the instance's time %.17g", t,
                             in->time);
    if (!(isfinite(h) && h > 0))
        return instance_fail(in, call, "communicationStepSize = %g must be finite and > 0", h);
    in->time = t;    /* the master's point: where the step starts, and nothing it reports comes before */
    model_step_begin(&in->model, t);
    if (integrate(in, call, t + h, policy, end) != STATUS_OK) return STATUS_ERROR;
    in->last_successful_time = in->time;
    return STATUS_OK;
}
