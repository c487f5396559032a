/* SPDX-License-Identifier: BSD-2-Clause */
/* Co-Simulation's flight in closed form (explicit_rk.h): where the model knows its free
 * flight exactly (model.h's MODEL_CLOSED_FLIGHT: a rigid body under gravity and constant
 * loads), a flight is evaluated, not integrated. It has no step error, so the velocity a
 * contact ends with reaches the horizon as it left the floor at any tolerance (the explicit
 * pair's error over a flight of O(1) time, 2.8e-5 at eps = 1e-2 and rtol 1e-6, is gone), and
 * it costs a few evaluations where the pair takes tens of steps. Events are found as the pair
 * finds them, with the same rule and resolution: the indicators sampled along the flight at
 * the intervals the model's physics bounds (model_flight_sample_step), and the first root of
 * the first interval where one changes sign located on the closed form by erk_locate_root.
 * Contact phases stay with the pair, and what it hands over with CVODE. */
#include "closed_flight.h"

ErkResult erk_or_flight_advance(Erk *e, Model *m, double *t, double t_end, long *steps_left)
{
#ifdef MODEL_CLOSED_FLIGHT
    ModelFlight flight;
    if (model_flight_begin(m, *t, e->y, &flight)) return erk_flight_advance(e, m, &flight, t, t_end, steps_left);
#endif
    return erk_advance(e, m, t, t_end, steps_left);
}

#ifdef MODEL_CLOSED_FLIGHT

#include <string.h>

#include "step_end.h"

/* One sampling interval (t, t + h] of the flight as an ErkStateAt. */
typedef struct {
    const ModelFlight *flight;
    double t, h;
    const double *x_end; /* the state at t + h, exactly the interval's end */
    long *evaluations;
} FlightPath;

static void flight_path_at(const void *path, double th, double x[MODEL_NX])
{
    const FlightPath *p = path;
    ++*p->evaluations;
    if (th >= 1) memcpy(x, p->x_end, sizeof(double) * MODEL_NX);
    else model_flight_at(p->flight, p->t + th * p->h, x);
}

/* From e->y and e->z (the state and indicators at *t); each sample spends one of *steps_left. */
ErkResult erk_flight_advance(Erk *e, Model *m, const ModelFlight *f, double *t, double t_end, long *steps_left)
{
    e->h = 0;   /* the pair, when it takes over after the next event, starts afresh there */
    double x[MODEL_NX], z[MODEL_NZ + 1];
    while (!step_end_reached(*t, t_end)) {
        if (*steps_left <= 0) {
            model_set_states(m, e->y);
            return ERK_BUDGET;
        }
        --*steps_left;
        ++e->flight_samples;
        const double dt = model_flight_sample_step(f, *t);
        const double t1 = dt < t_end - *t && !step_end_reached(*t + dt, t_end) ? *t + dt : t_end;
        /* a sample the time cannot resolve (a spin too fast for it) or a state not finite: CVODE decides */
        if (!(t1 > *t)) return erk_hand_over(e, m, "the flight's sampling fell below the time's resolution");
        model_flight_at(f, t1, x);
        if (!erk_all_finite(x, MODEL_NX)) return erk_hand_over(e, m, "a value is not finite");
        model_indicators_at(m, t1, x, z);
        if (erk_any_crossed(e->z, z)) {
            const FlightPath path = { f, *t, t1 - *t, x, &e->flight_samples };
            double root[MODEL_NX];
            erk_locate_root(m, *t, t1 - *t, e->z, z, flight_path_at, &path, t, root);
            model_set_states(m, root);
            return ERK_EVENT;
        }
        *t = t1;
        memcpy(e->y, x, sizeof e->y);
        memcpy(e->z, z, sizeof e->z);
    }
    model_set_states(m, e->y);
    return ERK_REACHED;
}

#else
typedef int closed_flight_needs_MODEL_CLOSED_FLIGHT; /* ISO C wants something in a translation unit */
#endif
