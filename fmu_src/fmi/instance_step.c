/* SPDX-License-Identifier: BSD-2-Clause */
/* A Co-Simulation step under any FMI version (instance.h). The explicit
 * Dormand-Prince pair of explicit_rk.c integrates the model (a flight the model
 * knows in closed form is evaluated: closed_flight.c), or, where a sustained
 * contact makes it stiff, the embedded CVODE of cosim.c; every event found
 * inside a step gets the same event update as in Model Exchange.
 *
 * The integrator carries on from one step to the next (a communication point
 * costs no restart) and restarts after events and wherever the trajectory may
 * have been replaced: initialization, reset, FMU state get and set; the FMU
 * state holds which integrator the trajectory is on. A trajectory handed to
 * CVODE stays with it, across events and restarts, until the instance is reset
 * or an event turns to a mode whose fast motion grows (the paradox's contact,
 * whose growth BDF's large steps would damp; instance_choose_integrator). In a
 * stiff contact the explicit pair's errors, within the tolerance in the states,
 * reach the contact force times the damping, and its force indicator would
 * chatter through spurious lift-offs, where CVODE stays on the slow motion; and
 * a model whose inputs restart the integrator at every step (a rod on the shaker
 * table) is not tested for stiffness again each time. An IWC never hands over:
 * the explicit pair runs it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "instance.h"
#include "cvode_build.h" /* HAVE_CVODE also where a source FMU carries CVODE */
#include "step_end.h"

#ifdef HAVE_CVODE
#include "cosim.h"
#include "closed_flight.h"
#include "explicit_rk.h"

typedef struct {
    Erk erk;
    CoSim *cvode; /* made when a trajectory is first handed over */
    long events;  /* event updates in steps (diagnostics) */
} Integrator;

/* The integrators' work so far (logStatistics): explicit steps and right-hand sides,
 * closed-form flight evaluations, CVODE's steps and right-hand sides, events. */
enum { COUNT_STEPS, COUNT_RHS, COUNT_FLIGHT, COUNT_CVODE_STEPS, COUNT_CVODE_RHS, COUNT_EVENTS, N_COUNTS };

static void counts(const Instance *in, long c[N_COUNTS])
{
    const Integrator *s = in->solver;
    for (int i = 0; i < N_COUNTS; ++i) c[i] = 0;
    if (!s) return;
    c[COUNT_STEPS] = s->erk.steps;
    c[COUNT_RHS] = s->erk.rhs;
    c[COUNT_FLIGHT] = s->erk.flight_samples;
    cosim_counts(s->cvode, &c[COUNT_CVODE_STEPS], &c[COUNT_CVODE_RHS]);
    c[COUNT_EVENTS] = s->events;
}

/* One line per step under logStatistics: the work between the counts before and now. */
static void log_statistics(Instance *in, const char *call, double t, const long before[N_COUNTS])
{
    long now[N_COUNTS];
    counts(in, now);
    instance_log_statistics(in, call, "t = %.17g to %.17g: explicit steps %ld, right-hand sides %ld, closed-form "
                            "flight evaluations %ld, CVODE steps %ld, CVODE right-hand sides %ld, events %ld",
                            t, in->time, now[COUNT_STEPS] - before[COUNT_STEPS], now[COUNT_RHS] - before[COUNT_RHS],
                            now[COUNT_FLIGHT] - before[COUNT_FLIGHT], now[COUNT_CVODE_STEPS] - before[COUNT_CVODE_STEPS],
                            now[COUNT_CVODE_RHS] - before[COUNT_CVODE_RHS], now[COUNT_EVENTS] - before[COUNT_EVENTS]);
}

void instance_free_solver(Instance *in)
{
    Integrator *s = in->solver;
    if (s) cosim_free(s->cvode);
    free(s);
    in->solver = NULL;
}

/* CVODE from the model's state at the instance's time; false with a message. */
static bool start_cvode(Instance *in, char *err, size_t n)
{
    Integrator *s = in->solver;
    if (!s->cvode) s->cvode = cosim_new();
    if (!s->cvode) {
        snprintf(err, n, "out of memory for the integrator");
        return false;
    }
    return cosim_start(s->cvode, &in->model, in->time, in->tolerance, err, n);
}

static Status restart(Instance *in, const char *call)
{
    Integrator *s = in->solver;
    char err[512];
    if (in->solver_implicit) {
        if (!start_cvode(in, err, sizeof err)) return instance_fail(in, call, "%s", err);
        model_begin_integration(&in->model);
    } else {   /* the pair's indicators and the derived values at its start: one anchor (model.h) */
        double x[MODEL_NX];
        model_get_states(&in->model, x);
        model_anchor(&in->model, x, true);
        erk_start(&s->erk, &in->model, in->time, in->tolerance);
        model_begin_integration(&in->model);
        model_anchor(&in->model, x, false);
    }
    in->solver_live = true;
    return STATUS_OK;
}

/* What one Co-Simulation call may spend: room for hundreds of IWCs (a few
 * events and a few hundred solver steps each) and for the fastest contacts the
 * parameter ranges allow, while every call returns within seconds
 * (docs/bounded_calls.md has the figures). A master whose step needs more gets
 * fmi2Discard / fmi3Discard at the time reached (its last successful time) and
 * goes on from there with smaller steps. */
#define MAX_SOLVER_STEPS_PER_CALL 200000L
#define MAX_EVENTS_PER_CALL 20000L

/* The state where a budget ran out, by the states' names, for the log line. */
static void describe_states(const Instance *in, char *text, size_t size)
{
    double x[MODEL_NX];
    size_t n = 0;
    model_get_states(&in->model, x);
    text[0] = '\0';
    for (size_t i = 0; i < MODEL_NX && n < size; ++i)
        n += (size_t)snprintf(text + n, size - n, "%s%s = %.6g", i ? ", " : "",
                              model_variable(model_state_vr(i))->name, x[i]);
}

static Status out_of_budget(Instance *in, const char *call, long budget, const char *what, double t_end)
{
    char states[384];
    describe_states(in, states, sizeof states);
    return instance_discard(in, call, "the budget of %ld %s per call is spent at t = %.17g, before the step's end "
                            "%.17g (%s): the step stops there; go on from that last successful time, or with "
                            "smaller steps", budget, what, in->time, t_end, states);
}

/* One advance of the trajectory's integrator; the explicit pair hands a
 * trajectory it cannot take on to CVODE at the time it reached (logged). */
static CoSimResult advance(Instance *in, double t_end, long *steps_left, char *err, size_t n)
{
    Integrator *s = in->solver;
    if (!in->solver_implicit) {
        switch (erk_or_flight_advance(&s->erk, &in->model, &in->time, t_end, steps_left)) {
        case ERK_REACHED: return COSIM_REACHED;
        case ERK_EVENT: return COSIM_EVENT;
        case ERK_BUDGET: return COSIM_BUDGET;
        case ERK_HAND_OVER: break;
        }
        instance_log_event(in, "t = %.17g: %s: CVODE integrates on", in->time, s->erk.why);
        in->solver_implicit = true;
        if (!start_cvode(in, err, n)) return COSIM_FAILED;
    }
    return cosim_advance(s->cvode, &in->model, &in->time, t_end, steps_left, err, n);
}

void instance_choose_integrator(Instance *in)
{
    const Integrator *s = in->solver;
    if (!s) return;
    if (in->solver_implicit && in->fast_growth) {   /* CVODE's large steps would damp the growth */
        instance_log_event(in, "t = %.17g: the contact's fast motion grows: the explicit pair integrates on", in->time);
        in->solver_implicit = false;
    }
}

static Status integrate(Instance *in, const char *call, double t_end, StepPolicy policy, StepEnd *end)
{
    if (!in->solver) in->solver = calloc(1, sizeof(Integrator));
    if (!in->solver) return instance_fail(in, call, "out of memory for the integrator");
    if (in->inputs_jumped) {   /* the master's new inputs: the mode may change (a stick may end) */
        bool changed;
        in->inputs_jumped = false;
        in->solver_live = false;
        if (instance_event_update(in, call, false, &changed) != STATUS_OK) return STATUS_ERROR;
    }
    if (!in->solver_live && restart(in, call) != STATUS_OK) return STATUS_ERROR;
    const double t_start = in->time;
    long steps_left = MAX_SOLVER_STEPS_PER_CALL;
    long events = 0;
    while (!step_end_reached(in->time, t_end)) {
        char err[512];
        const CoSimResult r = advance(in, t_end, &steps_left, err, sizeof err);
        if (r == COSIM_FAILED) {
            in->solver_live = false;
            return instance_fail(in, call, "%s", err);
        }
        if (r == COSIM_REACHED) break;
        if (r == COSIM_BUDGET) return out_of_budget(in, call, MAX_SOLVER_STEPS_PER_CALL, "solver steps", t_end);
        /* CVODE continues from its own last time, which a master's communication point may pass
         * by rounding errors: a root it locates before the step's start is at the start. */
        in->time = fmax(in->time, t_start);
        in->solver_live = false;
        if (policy == RETURN_AT_EVENT) {
            *end = STEP_EVENT;
            return STATUS_OK;
        }
        bool changed;
        ++((Integrator *)in->solver)->events;
        if (instance_event_update(in, call, true, &changed) != STATUS_OK) return STATUS_ERROR;
        instance_choose_integrator(in);
        if (restart(in, call) != STATUS_OK) return STATUS_ERROR;
        if (policy == RETURN_AFTER_EVENT) {
            *end = STEP_EVENT;
            return STATUS_OK;
        }
        if (++events >= MAX_EVENTS_PER_CALL) return out_of_budget(in, call, MAX_EVENTS_PER_CALL, "events", t_end);
    }
    in->time = t_end;
    return STATUS_OK;
}
#else
enum { N_COUNTS = 1 };

static void counts(const Instance *in, long c[N_COUNTS])
{
    (void)in;
    c[0] = 0;
}

static void log_statistics(Instance *in, const char *call, double t, const long before[N_COUNTS])
{
    (void)in, (void)call, (void)t, (void)before;
}

void instance_free_solver(Instance *in)
{
    in->solver = NULL;
}

void instance_choose_integrator(Instance *in)
{
    (void)in;
}

static Status integrate(Instance *in, const char *call, double t_end, StepPolicy policy, StepEnd *end)
{
    (void)t_end, (void)policy, (void)end;
    return instance_fail(in, call, "this binary was built without SUNDIALS CVODE: Co-Simulation is not available "
                                   "(rebuild with libsundials-dev installed, or use Model Exchange)");
}
#endif

/* Communication points closer than this (relative) are the same point. It forgives a master's
 * own arithmetic (t += h rounds by up to half an ulp a step; 1e-12 is 4500 ulps of t, thousands
 * of steps' drift), the same number of ulps at every t. It is no instant of the physics (the
 * contact record's is, contact_record.h): the state is not moved, only labelled with the
 * master's time, and an autonomous body does not see the label. */
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
    const bool statistics = instance_logs_statistics(in);
    long before[N_COUNTS];
    if (statistics) counts(in, before);
    const Status s = integrate(in, call, t + h, policy, end);
    if (statistics) log_statistics(in, call, t, before);
    if (s == STATUS_ERROR) return s;
    in->last_successful_time = in->time;   /* a Discard's too: the state is valid there */
    model_step_end(&in->model, fmax(in->time - t, 0));   /* the part it completed: to an event, a spent budget */
    return s;
}
