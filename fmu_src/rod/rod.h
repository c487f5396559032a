/* SPDX-License-Identifier: BSD-2-Clause */
/* The compliant Painleve rod of Hogan & Kristiansen: physics only, no FMI.
 *
 * The rod is the contact core's first body (contact.h, docs/general_body.md): its
 * generalized coordinates are the contact end's (x, y) and theta, so v and w are
 * states. This header keeps the rod's closed forms (eq coeffs, eq Sw), its analytic
 * Jacobian, and the rod-named entry points that PainleveRod, PainleveRodSI and
 * rod_partials.c call: each runs the core on the rod body. Every function is pure
 * apart from rod_event_update, which may move the state off a switching surface;
 * nothing here keeps global state. */
#ifndef ROD_H
#define ROD_H

#include <stdbool.h>

#include "contact.h"

/* Continuous states, in the order of modelDescription.xml. */
enum { ROD_X, ROD_V, ROD_Y, ROD_W, ROD_THETA, ROD_PHI, ROD_NX };

/* Event indicators: the core's (contact.c). */
enum { ROD_Z_Y = CONTACT_Z_Y, ROD_Z_FORCE = CONTACT_Z_FORCE, ROD_Z_SLIP = CONTACT_Z_SLIP, ROD_Z_AUX = CONTACT_Z_AUX,
       ROD_NZ = CONTACT_NZ };

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

typedef ContactMode RodMode;

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

/* The compliance law of contact.h (contact_compliance) with the rod's parameters. */
typedef Compliance RodCompliance;

RodCompliance rod_compliance(const RodParams *p, double y, double w);

/* h(y/eps, w): the bracket of eq FN (g = -y/eps - delta w for the linear law). */
double rod_force_bracket(const RodParams *p, const double x[ROD_NX]);

/* Energy held by the contact spring at height y: the integral of its force
 * -yh + kappa d^2 over the penetration, d^2/2 + kappa d^3/3 with d = -y/eps. */
double rod_spring_energy(const RodParams *p, double y);

/* F_N of the current mode: smooth (linear) while in contact, 0 otherwise. */
double rod_normal_force(const RodParams *p, RodMode m, const double x[ROD_NX]);

/* F_T: s mu F_N while slipping, the force that keeps v' = 0 while sticking. */
double rod_friction_force(const RodParams *p, RodMode m, const double x[ROD_NX]);

/* Mechanical energy plus the spring's while the contact force acts, in units
 * of m g l. */
double rod_energy(const RodParams *p, RodMode m, const double x[ROD_NX]);

void rod_derivatives(const RodParams *p, RodMode m, const double x[ROD_NX], double dx[ROD_NX]);

/* J[i][j] = d dx_i / d x_j of the current mode's smooth right-hand side. */
void rod_jacobian(const RodParams *p, RodMode m, const double x[ROD_NX], double J[ROD_NX][ROD_NX]);

void rod_event_indicators(const RodParams *p, RodMode m, const double x[ROD_NX], double z[ROD_NZ]);

/* Nominal magnitudes: the contact's own scales y ~ eps^2, w ~ eps. */
void rod_nominals(const RodParams *p, double nominal[ROD_NX]);

/* contact_move_off_surfaces on the rod: moves x off every switching surface on which an
 * indicator of mode m is 0 to within `margin` times its rounding error, towards the side mode m lives
 * on and past that, so that no importer restarts integration on a root.
 * margin >= 1: 1 at a first event; larger where the importer's solver came
 * straight back to the surface (its error exceeded the move). Sets *moved if
 * x changed; returns false if a surface could not be left by a step below the
 * state's nominal. */
bool rod_move_off_surfaces(const RodParams *p, RodMode m, double x[ROD_NX], double margin, bool *moved);

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
