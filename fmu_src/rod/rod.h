/* SPDX-License-Identifier: BSD-2-Clause */
/* The compliant Painleve rod of Hogan & Kristiansen: physics only, no FMI.
 *
 * The rod is the contact core's first body (contact.h, docs/general_body.md): its
 * generalized coordinates are the contact end's (x, y) and theta, so v and w are
 * states. rod_contact gives the core on the rod, which PainleveRod, PainleveRodSI and
 * rod_partials.c call for the forces, modes, indicators and events (contact_*). This
 * header keeps what only the rod has: its closed forms (eq coeffs, eq Sw), its analytic
 * Jacobian and its free flight in closed form. Every function is pure; nothing here
 * keeps global state. */
#ifndef ROD_H
#define ROD_H

#include <stdbool.h>

#include "contact.h"

/* Continuous states, in the order of modelDescription.xml (its event indicators are
 * the core's, CONTACT_Z_*). */
enum { ROD_X, ROD_V, ROD_Y, ROD_W, ROD_THETA, ROD_PHI, ROD_NX };

/* A rod model's continuous states (its Model's x, within +-BOUND) and their
 * derivatives (dx), for its config.h list, in the order above. */
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

/* Algebraic outputs: the forces, the energy, and the coefficients of eq Painleve and
 * eq Sw at the current state (RodCoeffs's a, b, p_+-, q_+-, S_w), which tell a user where
 * the paradox region p_plus < 0 lies. */
enum { ROD_OUT_F_N, ROD_OUT_F_T, ROD_OUT_ENERGY,
       ROD_OUT_A, ROD_OUT_B, ROD_OUT_P_PLUS, ROD_OUT_P_MINUS, ROD_OUT_Q_PLUS, ROD_OUT_Q_MINUS, ROD_OUT_S_W,
       ROD_NOUT };

typedef struct {
    double alpha;   /* m l^2 / I, > 0 */
    double mu;      /* friction coefficient, >= 0 */
    double delta;   /* contact damping, >= 0 */
    double epsilon; /* compliance, > 0: stiffness epsilon^-2 */
    double kappa;   /* spring stiffening, >= 0: stiffness 1 + 2 kappa d at scaled penetration d */
    double beta;    /* damping growth, >= 0: damping delta (1 + beta d) (Hunt-Crossley-like) */
    /* Applied loads, in units of m g and m g l (0 in the paper): a force (f_x, f_y) on the
     * centre of mass and a torque tau in theta's sense. They enter the paper's a and b
     * (a += f_x - alpha sin tau, b += f_y - alpha cos tau) and phi' (+= alpha tau). */
    double f_x, f_y, tau;
    /* Not a parameter: sin and cos of theta at the start of the explicit pair's step
     * (rod_anchor), which the body's evaluations near it complete by the angle sum; unset
     * (anchored false) everywhere else, where they are libm's. */
    bool anchored;
    double anchor_theta, anchor_sin, anchor_cos;
} RodParams;

/* Anchors sin and cos at theta (rod_evaluate's evaluations within 0.05 of it use them), or
 * releases the anchor (anchored false). */
void rod_anchor(RodParams *p, double theta, bool anchored);

/* The contact core on the rod with parameters p (p must outlive it). */
Contact rod_contact(const RodParams *p);

/* Coefficients of eq coeffs and eq Sw at one (theta, phi). Sticking follows
 * w' = b + A_w a + S_w F_N, phi' = A_phi a + S_phi F_N (the exact Filippov
 * field; Proposition lem:Filippov keeps only S_w, S_phi: see rod.c). */
typedef struct {
    double a, b;
    double q_plus, q_minus, p_plus, p_minus, c_plus, c_minus;
    double S_w, S_phi;
    double A_w, A_phi;
} RodCoeffs;

RodCoeffs rod_coeffs(const RodParams *p, double theta, double phi);

/* out[ROD_OUT_A .. ROD_OUT_S_W]: the core's coefficients (contact_coeffs) at the state x
 * (any mode: they are the body's, not the mode's); eq coeffs and eq Sw to round-off. */
void rod_coefficient_outputs(const RodParams *p, const double x[ROD_NX], double out[ROD_NOUT]);

/* J[i][j] = d dx_i / d x_j of mode m's smooth right-hand side (contact_derivatives on
 * rod_contact(p)). */
void rod_jacobian(const RodParams *p, ContactMode m, const double x[ROD_NX], double J[ROD_NX][ROD_NX]);

/* The rod in free flight (no contact force) under constant loads, in closed form: its
 * centre of mass moves at the constant acceleration (ax, ay), the rod turns at the constant
 * angular acceleration `angular`, from the state x0 at t0 (states in the order above, any
 * units: `length` is the half-length l, 1 in the paper's units). */
typedef struct {
    double length, ax, ay, angular;
    double t0, x0[ROD_NX];
    double sin0, cos0; /* of theta at t0 */
} RodFlight;

RodFlight rod_flight(double length, double ax, double ay, double angular, double t0, const double x0[ROD_NX]);

/* The state at time t; exactly x0 at t0 (increments from x0, free of cancellation). */
void rod_flight_at(const RodFlight *f, double t, double x[ROD_NX]);

/* A time from t on within which the rod turns by at most pi/8 and gravity moves its end by
 * at most l/32 from its tangent (rod.c says why the indicators' roots then show). */
double rod_flight_sample_step(const RodFlight *f, double t);

#endif
