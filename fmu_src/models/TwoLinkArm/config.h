/* SPDX-License-Identifier: BSD-2-Clause */
/* TwoLinkArm's metadata: a planar two-link arm whose tip drags on a rough floor,
 * the contact core's second body (arm_body.h), in SI units. The variable list
 * drives value references, range checks, getters, setters and the FMU state; its
 * order is that of its modelDescription.xml, in this folder. docs/general_body.md
 * derives the equations and the scaling. */
#ifndef CONFIG_H
#define CONFIG_H

#include "arm_body.h"
#include "contact_record.h"

#define MODEL_IDENTIFIER TwoLinkArm
#define MODEL_NAME "TwoLinkArm"
#define MODEL_NX ARM_NX
#define MODEL_NZ CONTACT_NZ

/* The optional parts it provides (model.h): the contact's events, and its gap and normal rate
 * as rows for the error control (the gap is a state, the normal rate is not). */
#define MODEL_EVENTS
#define MODEL_GAP_ROWS

/* No analytic partial derivatives (providesDirectionalDerivative="false" in the XML):
 * fmi2GetDirectionalDerivative and its FMI 3.0 twins answer this error. */
#define MODEL_NO_PARTIALS "TwoLinkArm provides no directional derivatives (providesDirectionalDerivative = false)"

/* Bounds on the states (angles in rad, rates in rad/s, the tip's height in m). */
#define ARM_STATE_BOUND 1e6

/* VARIABLE(ID, name, type, kind, field, min, max), as in models/PainleveRod/config.h.
 * The parameter ranges keep the scaled arm finite: masses and lengths within 1e6 of
 * each other's scale, eps = sqrt(M g/(k L)) and delta = c/sqrt(M k) finite. */
#define MODEL_VARIABLES(VARIABLE)                                                                  \
    VARIABLE(M1, "m1", REAL, PARAMETER, m1, 1e-3, 1e3)                                             \
    VARIABLE(L1, "l1", REAL, PARAMETER, l1, 1e-3, 1e3)                                             \
    VARIABLE(J1, "J1", REAL, PARAMETER, J1, 0, 1e6)                                                \
    VARIABLE(M2, "m2", REAL, PARAMETER, m2, 1e-3, 1e3)                                             \
    VARIABLE(L2, "l2", REAL, PARAMETER, l2, 1e-3, 1e3)                                             \
    VARIABLE(J2, "J2", REAL, PARAMETER, J2, 0, 1e6)                                                \
    VARIABLE(H, "H", REAL, PARAMETER, H, 0, 1e4)                                                   \
    VARIABLE(G, "g", REAL, PARAMETER, g, 1e-3, 1e3)                                                \
    VARIABLE(K, "k", REAL, PARAMETER, k, 1e-6, 1e15)                                               \
    VARIABLE(C, "c", REAL, PARAMETER, c, 0, 1e12)                                                  \
    VARIABLE(MU, "mu", REAL, PARAMETER, mu, 0, 1e6)                                                \
    VARIABLE(KAPPA, "kappa", REAL, PARAMETER, kappa, 0, 1e6)                                       \
    VARIABLE(BETA, "beta", REAL, PARAMETER, beta, 0, 1e6)                                          \
    VARIABLE(EPSILON, "epsilon", REAL, CALCULATED_PARAMETER, law.epsilon, 0, 0)                    \
    VARIABLE(DELTA, "delta", REAL, CALCULATED_PARAMETER, law.delta, 0, 0)                          \
    VARIABLE(THETA1, "theta1", REAL, STATE, x[ARM_THETA1], -ARM_STATE_BOUND, ARM_STATE_BOUND)      \
    VARIABLE(THETA2, "theta2", REAL, STATE, x[ARM_THETA2], -ARM_STATE_BOUND, ARM_STATE_BOUND)      \
    VARIABLE(OMEGA1, "omega1", REAL, STATE, x[ARM_OMEGA1], -ARM_STATE_BOUND, ARM_STATE_BOUND)      \
    VARIABLE(OMEGA2, "omega2", REAL, STATE, x[ARM_OMEGA2], -ARM_STATE_BOUND, ARM_STATE_BOUND)      \
    VARIABLE(DER_THETA1, "der(theta1)", REAL, CALCULATED, dx[ARM_THETA1], 0, 0)                    \
    VARIABLE(DER_THETA2, "der(theta2)", REAL, CALCULATED, dx[ARM_THETA2], 0, 0)                    \
    VARIABLE(DER_OMEGA1, "der(omega1)", REAL, CALCULATED, dx[ARM_OMEGA1], 0, 0)                    \
    VARIABLE(DER_OMEGA2, "der(omega2)", REAL, CALCULATED, dx[ARM_OMEGA2], 0, 0)                    \
    VARIABLE(X, "x", REAL, CALCULATED, out[ARM_OUT_X], 0, 0)                                       \
    VARIABLE(Y, "y", REAL, DERIVED_STATE, x[ARM_Y], -ARM_STATE_BOUND, ARM_STATE_BOUND)             \
    VARIABLE(V, "v", REAL, CALCULATED, out[ARM_OUT_V], 0, 0)                                       \
    VARIABLE(W, "w", REAL, CALCULATED, out[ARM_OUT_W], 0, 0)                                       \
    VARIABLE(F_N, "F_N", REAL, CALCULATED, out[ARM_OUT_F_N], 0, 0)                                 \
    VARIABLE(F_T, "F_T", REAL, CALCULATED, out[ARM_OUT_F_T], 0, 0)                                 \
    VARIABLE(ENERGY, "energy", REAL, CALCULATED, out[ARM_OUT_ENERGY], 0, 0)                        \
    CONTACT_COEFFICIENT_VARIABLES(VARIABLE, out, ARM_OUT_A)                                        \
    CONTACT_RECORD_TIMES(VARIABLE)                                                                 \
    CONTACT_RECORD_MODES(VARIABLE)                                                                 \
    VARIABLE(DER_Y, "der(y)", REAL, CALCULATED, dx[ARM_Y], 0, 0)

/* Whether the start has been: y is calculated from the angles before it and integrated after. */
#define MODEL_INTERNALS(INTERNAL) CONTACT_RECORD_INTERNALS(INTERNAL) INTERNAL("started", started, BOOLEAN)

/* Outputs: the tip (SI; its height is a state), the contact forces and the energy (SI), the coefficients (scaled). */
enum { ARM_OUT_X, ARM_OUT_V, ARM_OUT_W, ARM_OUT_F_N, ARM_OUT_F_T, ARM_OUT_ENERGY, ARM_OUT_A,
       ARM_NOUT = ARM_OUT_A + 7 };

/* The model's data: SI parameters and states, the event record; derived and cached until a
 * change marks them stale: the scaled arm (body, law, xs) and what the getters return. */
typedef struct {
    double m1, l1, J1, m2, l2, J2, H, g, k, c, mu, kappa, beta;
    double x[ARM_NX];
    ContactRecord run;
    bool started;
    bool stale, partials_stale;
    ArmBody body;       /* the arm in the scaled units */
    ContactLaw law;     /* mu, delta, epsilon, kappa, beta */
    double xs[ARM_NX];  /* the scaled state: angles, rates times sqrt(L/g) */
    double dx[ARM_NX], z[CONTACT_NZ], out[ARM_NOUT];
} Model;

#endif
