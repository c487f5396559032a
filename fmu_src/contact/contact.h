/* SPDX-License-Identifier: BSD-2-Clause */
/* The contact core: a compliant unilateral contact with Coulomb friction at one
 * point of a rigid body, written once over a body description (docs/general_body.md).
 *
 * The body has d generalized coordinates q (d <= BODY_MAX_DOF) and their rates u,
 * stored in the state vector where the body says (Body.position, Body.velocity).
 * At a state it fills a BodyState: the contact point's gap y = g_N(q) and
 * tangential position x = g_T(q), their rates w = W_N u and v = W_T u, and the
 * generalized accelerations as a free part (gravity, loads, velocity products)
 * plus the responses to a unit normal force (M^-1 W_N^T) and a unit friction
 * force opposing positive slip (-M^-1 W_T^T enters with F_T). From it the
 * core makes the paper's eq Painleve for any body:
 *   v' = a + q_s F_N,  w' = b + p_s F_N  (slip s = +1 / -1),
 *   q_s = G_TN - s mu G_TT,  p_s = G_NN - s mu G_NT,  G = W M^-1 W^T,
 * the exact Filippov stick (the friction that holds v' = 0), S_w = G_NN - G_NT^2/G_TT,
 * the compliance law, the event indicators and the mode logic of docs/model.md §2.
 * The core never knows which body it runs. Everything is in the scaled units
 * (lengths by a reference length, forces by a reference weight, time by
 * sqrt(length/g)), so that the gap's scale is eps^2 and the contact's eps. */
#ifndef CONTACT_H
#define CONTACT_H

#include <stdbool.h>

#include "namespace.h" /* every source includes this header: their names, prefixed */

#define BODY_MAX_DOF 3
#define CONTACT_MAX_NX (2 * BODY_MAX_DOF + 1)   /* the coordinates, their rates, a gap state */

/* Event indicators. Slots 2 and 3 change meaning with the mode (contact.c). */
enum { CONTACT_Z_Y, CONTACT_Z_FORCE, CONTACT_Z_SLIP, CONTACT_Z_AUX, CONTACT_NZ };

/* The contact law's parameters (the paper's scaled ones). */
typedef struct {
    double mu;      /* friction coefficient, >= 0 */
    double delta;   /* contact damping, >= 0 */
    double epsilon; /* compliance, > 0: stiffness epsilon^-2 */
    double kappa;   /* spring stiffening, >= 0: stiffness 1 + 2 kappa d at scaled penetration d */
    double beta;    /* damping growth, >= 0: damping delta (1 + beta d) (Hunt-Crossley-like) */
} ContactLaw;

typedef struct {
    bool contact; /* compliant force active */
    int slip;     /* +1 slip forward, 0 stick, -1 slip backward */
} ContactMode;

/* What a body says at one state, in scaled units. */
typedef struct {
    double x, y, v, w;              /* the contact point: g_T, g_N and their rates */
    double y_noise, w_noise, v_noise; /* their rounding errors as computed (0 for a state itself) */
    double free[BODY_MAX_DOF];      /* u' with no contact force */
    double normal[BODY_MAX_DOF];    /* u' per unit F_N: M^-1 W_N^T */
    double friction[BODY_MAX_DOF];  /* u' per unit F_T, taken with a minus sign: M^-1 W_T^T */
    double a, b;                    /* v', w' with no contact force: W u'_free + W' u */
    double a_scale;                 /* the largest terms summed in a (its rounding error is ulps of it) */
    double G_TT, G_TN, G_NN;        /* the Delassus matrix W M^-1 W^T (G_TT > 0) */
    double energy;                  /* kinetic + potential, without the contact spring */
} BodyState;

/* A body: where its coordinates sit in the state vector, and how it fills a BodyState.
 * slip_coordinate: the coordinate that is x itself (u = v exactly; the rod's), else -1:
 * sticking then holds its rate at exactly 0 and a stick begins by setting it to 0;
 * otherwise a stick begins by the friction impulse that stops the slip. */
typedef struct {
    int dof;
    int position[BODY_MAX_DOF], velocity[BODY_MAX_DOF];
    int slip_coordinate;
    void (*evaluate)(const void *params, const double x[], BodyState *s);
    void (*nominals)(const void *params, double epsilon, double nominal[]);
    /* y, w, dy/dq and dw/dq at x (dw/du is dy/dq): for a body whose gap is not one of its
     * coordinates, so that an integrator can hold y and w to their own scale (contact_gap_rows);
     * else NULL. */
    void (*gap_rows)(const void *params, const double x[], double *y, double *w, double dy_dq[], double dw_dq[]);
    /* A body whose gap is not one of its coordinates may hold it as one more state, x[gap_state],
     * integrated as y' = w and read by its evaluate: an integrator's error control then holds y
     * to its own scale, eps^2, however large the coordinates are (docs/general_body.md §1). */
    bool has_gap_state;
    int gap_state;
} Body;

/* The number of states of a body: its coordinates, their rates and its gap state if it has one. */
int contact_nx(const Body *b);

/* A body with its parameters and the contact law: what every function below runs on. */
typedef struct {
    const Body *body;
    const void *params;
    ContactLaw law;
} Contact;

/* The compliance law h(yh, w) of eq hNon in the scaled variables yh = y/eps and w,
 * with the scaled penetration d = max(-yh, 0):
 *   h = -yh + kappa d^2 - delta w (1 + beta d),   F_N = h/eps in contact.
 * Its linearization at the origin is exactly -yh - delta w (eq hLin): kappa = beta = 0
 * is the paper's linear law. With kappa, beta >= 0, h decreases in yh and (delta > 0)
 * in w wherever h > 0 and y <= 0 (the paper's d_y f < 0, d_w f < 0). */
typedef struct {
    double h;    /* h(yh, w) */
    double h_yh; /* dh/dyh (the contact side at d = 0) */
    double h_w;  /* dh/dw */
} Compliance;

Compliance contact_compliance(const ContactLaw *law, double y, double w);

/* The contact's fastest time scale at state x, in the scaled time: 1/|lambda| for the
 * faster root of the normal motion linearized there, y'' = P F_N = P h(y/eps, w)/eps,
 *   lambda^2 - (P h_w/eps) lambda - P h_yh/eps^2 = 0,  |lambda| <= (P |h_w| + sqrt(P |h_yh|))/eps,
 * with P = max(|p_+|, |p_-|, S_w) (the fastest mode's normal response) and the law's slopes
 * at the state (its depth stiffens and damps it; in flight the slopes at touch-down).
 * eps for the paper's rod at rest in contact without damping; +inf if nothing responds
 * (or the state is NaN). */
double contact_time_scale(const Contact *c, const double x[]);

/* Energy held by the contact spring at height y: d^2/2 + kappa d^3/3 with d = -y/eps. */
double contact_spring_energy(const ContactLaw *law, double y);

/* The paper's coefficients of the body at one state (eq coeffs, eq Sw, in any body). */
typedef struct {
    double a, b, q_plus, q_minus, p_plus, p_minus, S_w;
} ContactCoeffs;

ContactCoeffs contact_coeffs(const ContactLaw *law, const BodyState *s);

BodyState contact_body(const Contact *c, const double x[]);

/* The gap y and the normal rate w at x as linear functions of a change of state: rows over
 * the state vector, y and w there, and their scales (eps^2 and eps); false, and nothing
 * written, for a body whose coordinates hold y and w themselves (Body.gap_rows NULL). */
typedef struct {
    double y[CONTACT_MAX_NX], w[CONTACT_MAX_NX]; /* dy/dx, dw/dx */
    double y_value, w_value, y_scale, w_scale;
} ContactGapRows;

bool contact_gap_rows(const Contact *c, const double x[], ContactGapRows *r);

/* Whether mode m's fast normal motion at x grows: a slip in contact with p_s < 0 (the paradox),
 * where F_N grows from any start and the body either sticks or lifts off (Theorem 1). */
bool contact_fast_growth(const Contact *c, ContactMode m, const double x[]);

/* F_N of the current mode: h/eps while in contact, 0 otherwise. */
double contact_normal_force(const Contact *c, ContactMode m, const double x[]);

/* F_T: s mu F_N while slipping, the force that keeps v' = 0 while sticking. */
double contact_friction_force(const Contact *c, ContactMode m, const double x[]);

/* The body's energy plus the spring's while the contact force acts. */
double contact_energy(const Contact *c, ContactMode m, const double x[]);

void contact_derivatives(const Contact *c, ContactMode m, const double x[], double dx[]);

/* J[i][j] = d dx_i/d x_j by central differences of contact_derivatives, for a body
 * without analytic partials (J is n x n, n = contact_nx, row-major in J[i * n + j]). */
void contact_jacobian_differences(const Contact *c, ContactMode m, const double x[], double J[]);

void contact_event_indicators(const Contact *c, ContactMode m, const double x[], double z[CONTACT_NZ]);

/* The rounding error of each indicator as computed at x (contact.c). */
void contact_indicator_noise(const Contact *c, ContactMode m, const double x[], double noise[CONTACT_NZ]);

/* The contact's surfaces that a state sits on because an integrator located an event there:
 * the indicator's sign at such a state is the root finder's overshoot, not the physics', so the
 * rules decide by the derivatives, as for a state exactly on the surface. */
typedef struct {
    bool gap;   /* y = 0 */
    bool force; /* h = 0 (F_N = 0) */
    bool still; /* w = 0 (a start given at rest on the floor) */
} ContactSurfaces;

/* The mode the rules of docs/model.md §2 give at state x, coming from mode m, with x on the
 * surfaces `on`. May stop the slip (v = 0, entering or re-deciding stick); says so in *x_changed. */
ContactMode contact_decide_mode(const Contact *c, ContactMode m, double x[], ContactSurfaces on, bool *x_changed);

/* The surfaces on which indicators of mode m that changed sign (bit i: indicator i) put x, an
 * event placed to within dt (scaled time): those whose indicator is within its change over dt. */
ContactSurfaces contact_surfaces_of(const Contact *c, ContactMode m, const double x[], unsigned crossed, double dt);

/* Moves x off every switching surface on which an indicator of mode m is 0 to within
 * `margin` times its rounding error, or (the surfaces `on`) is on the wrong side, towards the
 * side mode m lives on (contact_events.c). */
bool contact_move_off_surfaces(const Contact *c, ContactMode m, double x[], ContactSurfaces on, double margin,
                               bool *moved);

typedef enum { CONTACT_SETTLED, CONTACT_PING_PONG, CONTACT_STUCK_ON_SURFACE } ContactEventResult;

/* Mode decision iterated to a fixpoint, then contact_move_off_surfaces with `margin`. */
ContactEventResult contact_event_update(const Contact *c, ContactMode *m, double x[], ContactSurfaces on,
                                        double margin, bool *x_changed);

const char *contact_indicator_name(ContactMode m, int i);

#endif
