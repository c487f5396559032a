/* SPDX-License-Identifier: BSD-2-Clause */
/* The two-link arm as a body of the contact core (contact.h; docs/general_body.md):
 * a fixed pivot at height H above the floor, link 1 (mass m1, length l1, inertia J1
 * about its centre, at its middle) from the pivot to the elbow, link 2 (m2, l2, J2)
 * from the elbow to the tip, which touches the floor. Absolute angles theta1, theta2
 * counterclockwise from the direction of positive slip: the tip is at
 *   x = l1 cos theta1 + l2 cos theta2,   y = H + l1 sin theta1 + l2 sin theta2.
 * Everything here is scaled: lengths by L = l1 + l2, masses by M = m1 + m2,
 * inertias by M L^2, time by sqrt(L/g), forces by M g (so g is 1). */
#ifndef ARM_BODY_H
#define ARM_BODY_H

#include "contact.h"

/* The arm's state in the core's vector (the XML's order): angles, their rates, and the tip's
 * height y as a state of its own (the core's gap state, y' = w), so that an integrator holds the
 * gap to its own scale, eps^2, not to the angles' rtol |theta| (docs/general_body.md §1). */
enum { ARM_THETA1, ARM_THETA2, ARM_OMEGA1, ARM_OMEGA2, ARM_Y, ARM_NX };

typedef struct {
    double m1, l1, J1, m2, l2, J2, H; /* scaled: m1 + m2 = 1, l1 + l2 = 1 */
} ArmBody;

/* The tip's height H + l1 sin theta1 + l2 sin theta2 at the angles, the start of the state y:
 * 0 exactly when within its rounding error of 0 (a tip placed on the floor is on it, not an ulp
 * above or below, which a grazing start would turn into a square root's worth of its outcome). */
double arm_height(const ArmBody *b, double theta1, double theta2);

/* The core's description of the arm (Body; params: an ArmBody). */
extern const Body arm_body;

/* The mass matrix M(q) in absolute angles: M11 = J1 + m1 l1^2/4 + m2 l1^2,
 * M22 = J2 + m2 l2^2/4, M12 = m2 l1 l2/2 cos(theta1 - theta2). */
void arm_mass_matrix(const ArmBody *b, const double x[ARM_NX], double M[2][2]);

#endif
