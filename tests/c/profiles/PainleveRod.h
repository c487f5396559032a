/* SPDX-License-Identifier: BSD-2-Clause */
/* What the C drivers (FMI 2.0 and 3.0) and fuzz targets need to know of PainleveRod beyond
 * its modelDescription.xml (which gives them the variables, their ranges and
 * the ModelStructure): the CMake functions add_model_checks and add_fmi3_checks include it as
 * DRIVER_PROFILE. */
#ifndef DRIVER_PROFILE_H
#define DRIVER_PROFILE_H

#include <math.h>

/* The knob the runs turn: the parameter that sets the contact's compliance,
 * and its value for the paper's epsilon (runs at 0.05 or 0.1 cross a few
 * events cheaply); the stiffest contact it allows. */
#define PROFILE_KNOB VR_EPSILON
#define PROFILE_KNOB_VALUE(epsilon) (epsilon)
#define PROFILE_STIFFEST 1e-8

/* The bound config.h puts on every state (the XML gives none). */
#define PROFILE_STATE_BOUND 1e6

/* A point inside one mode, away from its switching surfaces (in contact,
 * slipping forward), so that central differences stay in it; a nonlinear
 * compliance law (kappa, beta > 0: differences in them may step both ways). */
#define PROFILE_DD_START                                                                                 \
    { { VR_MU, 1.0 },    { VR_V, 0.2 },   { VR_Y, -2e-7 },   { VR_W, -1e-4 },                            \
      { VR_THETA, 0.3 }, { VR_PHI, 0.4 }, { VR_KAPPA, 0.5 }, { VR_BETA, 0.5 } }

/* The fuzz target's budget of integrated time per input, and the longest
 * step it takes beyond it (it comes to rest: a step of any size). */
#define PROFILE_FUZZ_SPAN 2.0
/* fuzz_bounded's run: at most this span (twice the default experiment), in steps of it down to 1e-8 of it. */
#define PROFILE_BOUNDED_SPAN 0.2
#define PROFILE_FUZZ_LONGEST_STEP INFINITY

/* Mode-switch events (the FMI 3.0 driver's Co-Simulation checks): the run of
 * the start values over PROFILE_RUN_SPAN is an IWC (contact, one stick,
 * lift-off), which the event record's switches and sticks count (contact_record.h). */
#define PROFILE_MODE_SWITCHES 1
#define PROFILE_RUN_SPAN 0.1 /* the default experiment */

#endif
