/* SPDX-License-Identifier: BSD-2-Clause */
/* What the C drivers and fuzz targets need to know of TwoLinkArm beyond
 * its modelDescription.xml (see PainleveRod.h). */
#ifndef DRIVER_PROFILE_H
#define DRIVER_PROFILE_H

#include <math.h>

/* The contact's compliance is epsilon = sqrt(M g/(k L)): the stiffness k for a
 * given epsilon at the start values M = 0.8 kg, g = 9.81 m/s2, L = 0.5 m.
 * k's max (1e15 N/m) allows epsilon down to 1.3e-7. */
#define PROFILE_KNOB VR_K
#define PROFILE_KNOB_VALUE(epsilon) arm_stiffness(epsilon)
static inline double arm_stiffness(double epsilon)
{
    const double per_k = epsilon * epsilon * 0.5; /* 0 (or NaN) for the fuzzer's epsilon: no k */
    return per_k > 0 ? 0.8 * 9.81 / per_k : INFINITY;
}
#define PROFILE_STIFFEST 1e-6

/* The bound config.h puts on every state (ARM_STATE_BOUND). */
#define PROFILE_STATE_BOUND 1e6

/* A point inside one mode: the tip 10 um into the floor, slipping forward at 0.2 m/s
 * (the arm provides no directional derivatives: the driver checks that each call is an
 * error, from here). */
#define PROFILE_DD_START                                                                                 \
    { { VR_THETA1, -1.0 }, { VR_THETA2, -1.3 }, { VR_OMEGA1, -0.6035 }, { VR_OMEGA2, 1.8283 },          \
      { VR_H, 0.44514 } }

/* The fuzz target's budget of integrated time per input, and the longest step
 * it takes beyond it, in seconds: a few swings of the arm (its period about 1 s). */
#define PROFILE_FUZZ_SPAN 0.2
#define PROFILE_FUZZ_LONGEST_STEP 0.2

/* Mode-switch events (the FMI 3.0 driver's Co-Simulation checks): the start values' run over
 * PROFILE_RUN_SPAN is an IWC (the tip in contact slipping, one stick, lift-off at 2 ms; it
 * lands again at 19 ms, after the span), which the event record's switches and sticks count. */
#define PROFILE_MODE_SWITCHES 1
#define PROFILE_RUN_SPAN 0.015 /* s: t + (0.015 - t) is 0.015 at its events' t (0.01 rounds past itself) */

#endif
