/* SPDX-License-Identifier: BSD-2-Clause */
/* The event iteration of a rod model (PainleveRod, PainleveRodSI): the contact core's
 * record (contact_record.h) on the rod body, for the calls that need the rod's contact,
 * and the rod's state variables for a model's config.h list. (The record's variables,
 * its creation, description and check are the core's own: a model calls them by their
 * contact_record names.) */
#ifndef ROD_RECORD_H
#define ROD_RECORD_H

#include "contact_record.h"
#include "rod.h"

/* A rod model's continuous states (its Model's x, within +-BOUND) and their
 * derivatives (dx), for its config.h list, in the order of rod.h. */
#define ROD_STATE_VARIABLES(VARIABLE, BOUND)                                                       \
    VARIABLE(X, "x", REAL, STATE, x[ROD_X], -(BOUND), BOUND)                                       \
    VARIABLE(V, "v", REAL, STATE, x[ROD_V], -(BOUND), BOUND)                                       \
    VARIABLE(Y, "y", REAL, STATE, x[ROD_Y], -(BOUND), BOUND)                                       \
    VARIABLE(W, "w", REAL, STATE, x[ROD_W], -(BOUND), BOUND)                                       \
    VARIABLE(THETA, "theta", REAL, STATE, x[ROD_THETA], -(BOUND), BOUND)                           \
    VARIABLE(PHI, "phi", REAL, STATE, x[ROD_PHI], -(BOUND), BOUND)                                 \
    VARIABLE(DER_X, "der(x)", REAL, CALCULATED, dx[ROD_X], 0, 0)                                   \
    VARIABLE(DER_V, "der(v)", REAL, CALCULATED, dx[ROD_V], 0, 0)                                   \
    VARIABLE(DER_Y, "der(y)", REAL, CALCULATED, dx[ROD_Y], 0, 0)                                   \
    VARIABLE(DER_W, "der(w)", REAL, CALCULATED, dx[ROD_W], 0, 0)                                   \
    VARIABLE(DER_THETA, "der(theta)", REAL, CALCULATED, dx[ROD_THETA], 0, 0)                       \
    VARIABLE(DER_PHI, "der(phi)", REAL, CALCULATED, dx[ROD_PHI], 0, 0)

static inline RodMode rod_initial_mode(const RodParams *p, double x[ROD_NX])
{
    const Contact c = rod_contact(p);
    return contact_initial_mode(&c, x);
}

static inline void rod_record_start(ContactRecord *r, const RodParams *p, double x[ROD_NX], double time)
{
    const Contact c = rod_contact(p);
    contact_record_start(r, &c, x, time);
}

/* time_unit: the model's time per the rod's scaled time (1 for PainleveRod, sqrt(l/g) in SI). */
static inline bool rod_record_event(ContactRecord *r, const RodParams *p, double x[ROD_NX], const double z[ROD_NZ],
                                    double time, double time_unit, bool floor_jumped, ModelEvent *e)
{
    const Contact c = rod_contact(p);
    return contact_record_event(r, &c, x, z, time, time_unit, floor_jumped, e);
}

#endif
