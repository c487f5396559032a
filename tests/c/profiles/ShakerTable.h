/* SPDX-License-Identifier: BSD-2-Clause */
/* What the C drivers and fuzz targets need to know of ShakerTable beyond
 * its modelDescription.xml (see PainleveRod.h). */
#ifndef DRIVER_PROFILE_H
#define DRIVER_PROFILE_H

#include <math.h>

/* The table has no contact: the runs' knob is its spring K, softer for a
 * larger "epsilon" (40 N/m over it: 800 N/m at 0.05, a period of 0.7 s). */
#define PROFILE_KNOB VR_K
#define PROFILE_KNOB_VALUE(epsilon) table_stiffness(epsilon)
static inline double table_stiffness(double epsilon)
{
    return epsilon > 0 ? 40.0 / epsilon : INFINITY; /* 0 or NaN for the fuzzer's epsilon: no K */
}
#define PROFILE_STIFFEST 1e-6

/* The bound config.h puts on the states (STATE_BOUND). */
#define PROFILE_STATE_BOUND 1e6

/* Any point will do (the table has no modes): loaded, moving, on a belt. */
#define PROFILE_DD_START                                                                         \
    { { VR_BELT_SPEED, 0.3 }, { VR_POSITION, 1e-3 }, { VR_VELOCITY, 2e-2 }, { VR_F_N, 30.0 },    \
      { VR_F_T, -5.0 } }

/* The fuzz target's budget of integrated time per input, and the longest
 * step it takes beyond it, in seconds: the drive's frequency goes up to 1 MHz. */
#define PROFILE_FUZZ_SPAN 0.2
#define PROFILE_FUZZ_LONGEST_STEP 0.2

/* No mode switches: the FMI 3.0 driver's Co-Simulation checks run PROFILE_RUN_SPAN
 * without the checks of an IWC's events. */
#define PROFILE_MODE_SWITCHES 0
#define PROFILE_RUN_SPAN 0.1

#endif
