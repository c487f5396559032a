/* The event iteration of a rod model (PainleveRod, PainleveRodSI): the contact core's
 * record (contact_record.h) on the rod body, under the rod's names, and the rod's
 * state variables for a model's config.h list. */
#ifndef ROD_RECORD_H
#define ROD_RECORD_H

#include "contact_record.h"
#include "rod.h"

typedef ContactRecord RodRecord;

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

/* The record's and the coefficients' variables (contact_record.h). */
#define ROD_COEFFICIENT_VARIABLES CONTACT_COEFFICIENT_VARIABLES
#define ROD_RECORD_TIMES CONTACT_RECORD_TIMES
#define ROD_RECORD_MODES CONTACT_RECORD_MODES
#define ROD_RECORD_INTERNALS CONTACT_RECORD_INTERNALS

static inline RodRecord rod_record_new(void) { return contact_record_new(); }

static inline RodMode rod_initial_mode(const RodParams *p, double x[ROD_NX])
{
    const Contact c = rod_contact(p);
    return contact_initial_mode(&c, x);
}

static inline void rod_record_start(RodRecord *r, const RodParams *p, double x[ROD_NX], double time)
{
    const Contact c = rod_contact(p);
    contact_record_start(r, &c, x, time);
}

static inline void rod_record_describe_start(const RodRecord *r, char *text, size_t size)
{
    contact_record_describe_start(r, text, size);
}

static inline bool rod_record_event(RodRecord *r, const RodParams *p, double x[ROD_NX], const double z[ROD_NZ],
                                    double time, bool floor_jumped, ModelEvent *e)
{
    const Contact c = rod_contact(p);
    return contact_record_event(r, &c, x, z, time, floor_jumped, e);
}

static inline const char *rod_record_implausible(const RodRecord *r) { return contact_record_implausible(r); }

#endif
