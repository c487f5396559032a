/* SPDX-License-Identifier: BSD-2-Clause */
/* Co-Simulation's flight in closed form (closed_flight.c), beside the explicit pair whose
 * state, stops and root finding it shares (explicit_rk.h). */
#ifndef CLOSED_FLIGHT_H
#define CLOSED_FLIGHT_H

#include "explicit_rk.h"

#ifdef MODEL_CLOSED_FLIGHT
/* erk_advance over a flight in closed form (f: model_flight_begin's): the same stops, events
 * and budget, the state exact. */
ErkResult erk_flight_advance(Erk *e, Model *m, const ModelFlight *f, double *t, double t_end, long *steps_left);
#endif

/* erk_advance, or erk_flight_advance where the model is in a flight it knows in closed form. */
ErkResult erk_or_flight_advance(Erk *e, Model *m, double *t, double t_end, long *steps_left);

#endif
