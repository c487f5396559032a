/* SPDX-License-Identifier: BSD-2-Clause */
/* Co-Simulation's implicit integrator: SUNDIALS CVODE (Adams, Newton with a
 * dense linear solver and the rod's analytic Jacobian, root finding on the
 * rod's event indicators) over the model of model.h, for what the explicit
 * pair (explicit_rk.h) hands over: a sustained contact. Knows CVODE and the
 * model, not FMI. */
#ifndef COSIM_H
#define COSIM_H

#include <stdbool.h>
#include <stddef.h>

#include "model.h"

typedef struct CoSim CoSim;

/* COSIM_BUDGET: the internal steps allowed ran out before t_end or a root
 * (the state is CVODE's at the time reached, and integration can go on). */
typedef enum { COSIM_REACHED, COSIM_EVENT, COSIM_BUDGET, COSIM_FAILED } CoSimResult;

CoSim *cosim_new(void);
void cosim_free(CoSim *cs);

/* (Re)starts the integration at time t from the model's state and mode, with
 * absolute tolerances rtol * nominal. False, with a message, on failure. */
bool cosim_start(CoSim *cs, Model *m, double t, double rtol, char *err, size_t n);

/* Integrates from *t towards t_end, stopping exactly there, at the first
 * root of an event indicator, or after *steps_left internal steps; the
 * model's state and *t follow, and *steps_left loses the steps taken. An end
 * that *t or CVODE's own time has reached (step_end.h) is reached at once,
 * CVODE not called. */
CoSimResult cosim_advance(CoSim *cs, Model *m, double *t, double t_end, long *steps_left, char *err, size_t n);

/* CVODE's steps and right-hand sides since cs was made (diagnostics: restarts reset
 * CVODE's own counters, not these). */
void cosim_counts(const CoSim *cs, long *steps, long *rhs);

#endif
