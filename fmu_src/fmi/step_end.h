/* SPDX-License-Identifier: BSD-2-Clause */
/* When an integration has reached the end of its interval: the one rule that every path of a
 * Co-Simulation step asks (the step's loop over events and hand-overs, the explicit pair, the
 * closed-form flight, CVODE), so that none of them starts an integration towards an end it has
 * already reached. What remains of the interval is nothing when it is within a few units in
 * the last place of the times (absolute below 1): CVODE refuses a stop time at or behind its
 * own time and cannot start an interval shorter than 2 ulps of it, a root located to 100 ulps
 * may leave such a remainder, and so may a master's own arithmetic. The state reached is the
 * state at the end. */
#ifndef STEP_END_H
#define STEP_END_H

#include <float.h>
#include <math.h>
#include <stdbool.h>

#define STEP_END_ULPS 4

static inline bool step_end_reached(double t, double t_end)
{
    return !(t_end - t > STEP_END_ULPS * DBL_EPSILON * fmax(1, fmax(fabs(t), fabs(t_end))));
}

#endif
