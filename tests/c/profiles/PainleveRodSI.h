/* SPDX-License-Identifier: BSD-2-Clause */
/* What the C drivers and fuzz targets need to know of PainleveRodSI beyond
 * its modelDescription.xml (see PainleveRod.h). */
#ifndef DRIVER_PROFILE_H
#define DRIVER_PROFILE_H

#include <math.h>

/* The contact's compliance is epsilon = sqrt(m g/(k l)): the stiffness k for
 * a given epsilon at the start values m = 1 kg, g = 9.81 m/s2, l = 0.5 m.
 * k's max (1e15 N/m) allows epsilon down to 1.4e-7. */
#define PROFILE_KNOB VR_K
#define PROFILE_KNOB_VALUE(epsilon) si_stiffness(epsilon)
static inline double si_stiffness(double epsilon)
{
    const double per_k = epsilon * epsilon * 0.5; /* 0 (or NaN) for the fuzzer's epsilon: no k */
    return per_k > 0 ? 1.0 * 9.81 / per_k : INFINITY;
}
#define PROFILE_STIFFEST 1e-6

/* The bound config.h puts on every state and input (the XML gives none). */
#define PROFILE_STATE_BOUND 1e9

/* A point inside one mode, away from its switching surfaces: the floor at
 * 1 mm rising at 1 cm/s under a belt at 0.1 m/s, the contact end 10 um into
 * it (F_N about 200 N + 4.5 N of damping), slipping forward at 0.4 m/s
 * relative to the belt, with a force and a torque applied. Every input is
 * away from 0, so that each partial by an input has something to show. */
#define PROFILE_DD_START                                                                                 \
    { { VR_MU, 1.0 },        { VR_Y_FLOOR, 1e-3 },     { VR_W_FLOOR, 1e-2 }, { VR_V_FLOOR, 0.1 },      \
      { VR_F_X, 0.5 },       { VR_F_Y, -1.0 },         { VR_TAU, 0.2 },      { VR_V, 0.5 },            \
      { VR_Y, 1e-3 - 1e-5 }, { VR_W, 1e-2 - 1e-3 },    { VR_THETA, 0.3 },    { VR_PHI, 0.4 } }

/* The fuzz target's budget of integrated time per input, and the longest
 * step it takes beyond it, in seconds: about a time unit sqrt(l/g) of the rod.
 * With a soft contact and heavy damping (k = 0.1 N/m: delta = 1.4e4) it
 * chatters between stick and slip at 2e6 events a second. */
#define PROFILE_FUZZ_SPAN 0.2
#define PROFILE_FUZZ_LONGEST_STEP 0.2

/* Mode-switch events (the FMI 3.0 driver's Co-Simulation checks): the run of
 * the start values over PROFILE_RUN_SPAN is an IWC (contact, one stick,
 * lift-off), which the event record's switches and sticks count (contact_record.h). */
#define PROFILE_MODE_SWITCHES 1
#define PROFILE_RUN_SPAN 0.05 /* s: the default experiment */

#endif
