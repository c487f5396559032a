/* SPDX-License-Identifier: BSD-2-Clause */
/* PainleveRodSI's metadata: the paper's rod in SI units, with inputs for a
 * moving floor and applied loads, over the same physics (rod.c) and event
 * iteration (contact_record.c) as PainleveRod. The variable list drives value
 * references, range checks, getters, setters and the FMU state; its order is
 * that of its modelDescription.xml, in this folder. docs/si_model.md derives
 * the equations. */
#ifndef CONFIG_H
#define CONFIG_H

#include "contact_record.h"
#include "rod.h"
#include "rod_partials.h"

#define MODEL_IDENTIFIER PainleveRodSI
#define MODEL_NAME "PainleveRodSI"
#define MODEL_NX ROD_NX
#define MODEL_NZ CONTACT_NZ

/* The optional parts it provides (model.h): a floor that moves with time and jumps
 * when y_floor is set, the step means F_N_mean and F_T_mean, the contact's events. */
#define MODEL_SET_TIME
#define MODEL_INPUT_SET
#define MODEL_STEP_MEANS
#define MODEL_EVENTS

/* In flight the rod is a rigid body under gravity and the loads F_x, F_y, tau, which a
 * Co-Simulation step holds: Co-Simulation advances it in closed form (model.h, rod.h). */
#define MODEL_CLOSED_FLIGHT
typedef RodFlight ModelFlight;

/* Bounds that keep every scaled quantity finite: lengths, speeds, forces. */
#define SI_BOUND 1e9

/* VARIABLE(ID, name, type, kind, field, min, max), as in models/PainleveRod/config.h, with
 * the INPUT and CALCULATED_PARAMETER kinds. Reals first, then Integers, Booleans. */
#define MODEL_VARIABLES(VARIABLE)                                                                  \
    VARIABLE(M, "m", REAL, PARAMETER, m, 1e-9, 1e9)                                                \
    VARIABLE(L, "l", REAL, PARAMETER, l, 1e-6, 1e6)                                                \
    VARIABLE(J, "J", REAL, PARAMETER, J, 1e-18, 1e18)                                              \
    VARIABLE(G, "g", REAL, PARAMETER, g, 1e-3, 1e3)                                                \
    VARIABLE(K, "k", REAL, PARAMETER, k, 1e-6, 1e15)                                               \
    VARIABLE(C, "c", REAL, PARAMETER, c, 0, 1e12)                                                  \
    VARIABLE(MU, "mu", REAL, PARAMETER, mu, 0, 1e6)                                                \
    VARIABLE(ALPHA, "alpha", REAL, CALCULATED_PARAMETER, rod.alpha, 0, 0)                          \
    VARIABLE(EPSILON, "epsilon", REAL, CALCULATED_PARAMETER, rod.epsilon, 0, 0)                    \
    VARIABLE(DELTA, "delta", REAL, CALCULATED_PARAMETER, rod.delta, 0, 0)                          \
    VARIABLE(Y_FLOOR, "y_floor", REAL, INPUT, y_floor, -SI_BOUND, SI_BOUND)                        \
    VARIABLE(W_FLOOR, "w_floor", REAL, INPUT, w_floor, -SI_BOUND, SI_BOUND)                        \
    VARIABLE(V_FLOOR, "v_floor", REAL, INPUT, v_floor, -SI_BOUND, SI_BOUND)                        \
    VARIABLE(F_X, "F_x", REAL, INPUT, F_x, -SI_BOUND, SI_BOUND)                                    \
    VARIABLE(F_Y, "F_y", REAL, INPUT, F_y, -SI_BOUND, SI_BOUND)                                    \
    VARIABLE(TAU, "tau", REAL, INPUT, tau, -SI_BOUND, SI_BOUND)                                    \
    ROD_STATE_VARIABLES(VARIABLE, SI_BOUND)                                                        \
    VARIABLE(F_N, "F_N", REAL, CALCULATED, out[SI_F_N], 0, 0)                                      \
    VARIABLE(F_T, "F_T", REAL, CALCULATED, out[SI_F_T], 0, 0)                                      \
    VARIABLE(ENERGY, "energy", REAL, CALCULATED, out[SI_ENERGY], 0, 0)                             \
    VARIABLE(X_CM, "x_cm", REAL, CALCULATED, out[SI_X_CM], 0, 0)                                   \
    VARIABLE(Y_CM, "y_cm", REAL, CALCULATED, out[SI_Y_CM], 0, 0)                                   \
    VARIABLE(VX_CM, "vx_cm", REAL, CALCULATED, out[SI_VX_CM], 0, 0)                                \
    VARIABLE(VY_CM, "vy_cm", REAL, CALCULATED, out[SI_VY_CM], 0, 0)                                \
    VARIABLE(GAP, "gap", REAL, CALCULATED, out[SI_GAP], 0, 0)                                      \
    VARIABLE(SLIP, "slip", REAL, CALCULATED, out[SI_SLIP], 0, 0)                                   \
    CONTACT_RECORD_TIMES(VARIABLE)                                                                     \
    CONTACT_RECORD_MODES(VARIABLE)                                                                     \
    VARIABLE(F_N_MEAN, "F_N_mean", REAL, CALCULATED, out[SI_F_N_MEAN], 0, 0)                       \
    VARIABLE(F_T_MEAN, "F_T_mean", REAL, CALCULATED, out[SI_F_T_MEAN], 0, 0)                       \
    CONTACT_COEFFICIENT_VARIABLES(VARIABLE, out, SI_A)

#define MODEL_INTERNALS(INTERNAL)                             \
    CONTACT_RECORD_INTERNALS(INTERNAL) \
    INTERNAL("v_floor_decided", v_floor_decided, REAL)    \
    INTERNAL("time", time, REAL)                          \
    INTERNAL("t_floor", t_floor, REAL)                    \
    INTERNAL("floor_moves", floor_moves, BOOLEAN)         \
    INTERNAL("step_mean_F_N", step_mean[SI_MEAN_F_N], REAL) \
    INTERNAL("step_mean_F_T", step_mean[SI_MEAN_F_T], REAL) \
    INTERNAL("step_vx_cm", step_start[SI_CM_VX], REAL)     \
    INTERNAL("step_vy_cm", step_start[SI_CM_VY], REAL)     \
    INTERNAL("means_held", means_held, BOOLEAN)

/* Outputs beyond the states and derivatives. */
enum { SI_F_N, SI_F_T, SI_ENERGY, SI_X_CM, SI_Y_CM, SI_VX_CM, SI_VY_CM, SI_GAP, SI_SLIP, SI_F_N_MEAN, SI_F_T_MEAN,
       SI_A, SI_NOUT = SI_A + ROD_OUT_S_W - ROD_OUT_A + 1 };  /* SI_A ..: the rod's coefficients, scaled */
/* The step means (model.h), and the centre of mass's velocity components whose change
 * over the step gives them. */
enum { SI_MEAN_F_N, SI_MEAN_F_T };
enum { SI_CM_VY, SI_CM_VX };

/* The model's data: SI parameters, inputs, SI states (the rod's contact end
 * (x, y) and its velocity (v, w), theta, phi), the event record; and, derived
 * and cached until a change marks them stale, the paper's dimensionless rod
 * in the floor's frame (rod, xs), derivatives, indicators, outputs. */
typedef struct {
    double m, l, J, g, k, c, mu;
    double y_floor, w_floor, v_floor, F_x, F_y, tau;
    double x[ROD_NX];
    ContactRecord run;
    double v_floor_decided; /* the belt speed the mode was last decided for */
    double time;            /* the instance's (model_set_time) */
    double t_floor;         /* when y_floor was last set: in Co-Simulation the floor moves on at w_floor */
    bool floor_moves;       /* a Co-Simulation step has begun: the floor moves between communication points */
    double step_mean[2];    /* F_N, F_T averaged over the last Co-Simulation step (the impulse / the step) */
    double step_start[2];   /* vy_cm, vx_cm when the step began (SI_CM_VY, SI_CM_VX) */
    bool means_held;        /* Co-Simulation: F_N_mean, F_T_mean are step_mean; else (Model Exchange) F_N, F_T */
    bool stale, partials_stale;
    RodParams rod;        /* alpha, mu, delta, epsilon and the loads in units of m g, m g l */
    double xs[ROD_NX];    /* the state in the paper's units, in the floor's frame */
    double dx[ROD_NX], z[CONTACT_NZ], out[SI_NOUT];
    RodPartials partials; /* of the dimensionless rod at xs */
} Model;

#endif
