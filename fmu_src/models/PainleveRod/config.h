/* SPDX-License-Identifier: BSD-2-Clause */
/* PainleveRod's metadata: what the generic FMI layer needs to know of this
 * model, in one place. The variable list below drives the value references,
 * range checks, getters, setters and the FMU state; its order is that of
 * modelDescription.xml (the C conformance tests, tests/fmu/test_c_robustness.py,
 * check every variable through its value reference in the XML),
 * which is not in this folder but at the repository's top level, where the
 * spec names it (CMakeLists.txt's painleve_add_model(PainleveRod ...) line). */
#ifndef CONFIG_H
#define CONFIG_H

#include "contact_record.h"
#include "rod.h"
#include "rod_partials.h"

#define MODEL_IDENTIFIER PainleveRod
#define MODEL_NAME "PainleveRod"
#define MODEL_NX ROD_NX
#define MODEL_NZ CONTACT_NZ

/* The optional parts it provides (model.h): rules beyond ranges for kappa and beta,
 * the step means F_N_mean and F_T_mean, the contact's events. */
#define MODEL_CHECK
#define MODEL_STEP_MEANS
#define MODEL_EVENTS

/* The rod's flight is a rigid body's under gravity: Co-Simulation advances it in closed
 * form (model.h, rod.h's RodFlight). */
#define MODEL_CLOSED_FLIGHT
typedef RodFlight ModelFlight;

/* Co-Simulation anchors the rod's sine and cosine once per step (model.h, rod_anchor). */
#define MODEL_STEP_ANCHOR

/* Parameter ranges keep every derived quantity finite in double precision:
 * F_N ~ y/eps^2 (kappa y^2/eps^3) and phi^2 must not overflow. kappa, beta >= 0
 * keep the compliance law h decreasing in y and w where the contact acts (rod.h). */
#define STATE_BOUND 1e6

/* VARIABLE(ID, name, type, kind, field, min, max): field is the member of Model that
 * holds the value; min and max bound what a setter accepts (settable kinds).
 * Kinds: PARAMETER (fixed, set before initialization ends), STATE (a
 * continuous state, initial exact), CALCULATED (continuous, derived),
 * DISCRETE (changes only at events). Reals first, then Integers, Booleans. */
#define MODEL_VARIABLES(VARIABLE)                                                                  \
    VARIABLE(ALPHA, "alpha", REAL, PARAMETER, params.alpha, 1e-6, 1e6)                             \
    VARIABLE(MU, "mu", REAL, PARAMETER, params.mu, 0, 1e6)                                         \
    VARIABLE(DELTA, "delta", REAL, PARAMETER, params.delta, 0, 1e6)                                \
    VARIABLE(EPSILON, "epsilon", REAL, PARAMETER, params.epsilon, 1e-8, 1)                         \
    ROD_STATE_VARIABLES(VARIABLE, STATE_BOUND)                                                     \
    VARIABLE(F_N, "F_N", REAL, CALCULATED, out[ROD_OUT_F_N], 0, 0)                                 \
    VARIABLE(F_T, "F_T", REAL, CALCULATED, out[ROD_OUT_F_T], 0, 0)                                 \
    VARIABLE(ENERGY, "energy", REAL, CALCULATED, out[ROD_OUT_ENERGY], 0, 0)                        \
    CONTACT_RECORD_TIMES(VARIABLE)                                                                     \
    VARIABLE(KAPPA, "kappa", REAL, PARAMETER, params.kappa, 0, 1e6)                                \
    VARIABLE(BETA, "beta", REAL, PARAMETER, params.beta, 0, 1e6)                                   \
    CONTACT_RECORD_MODES(VARIABLE)                                                                     \
    VARIABLE(F_N_MEAN, "F_N_mean", REAL, CALCULATED, mean_out[MEAN_F_N], 0, 0)                     \
    VARIABLE(F_T_MEAN, "F_T_mean", REAL, CALCULATED, mean_out[MEAN_F_T], 0, 0)                     \
    CONTACT_COEFFICIENT_VARIABLES(VARIABLE, out, ROD_OUT_A)

/* The model's data beyond its variables that an FMU state must carry
 * (the event log's reference and the event guard): INTERNAL(name, field, type). */
#define MODEL_INTERNALS(INTERNAL)                         \
    CONTACT_RECORD_INTERNALS(INTERNAL)                        \
    INTERNAL("step_mean_F_N", step_mean[MEAN_F_N], REAL)  \
    INTERNAL("step_mean_F_T", step_mean[MEAN_F_T], REAL)  \
    INTERNAL("step_vy_cm", step_start[CM_VY], REAL)       \
    INTERNAL("step_vx_cm", step_start[CM_VX], REAL)       \
    INTERNAL("means_held", means_held, BOOLEAN)

/* The step means (model.h), and the centre of mass's velocity components whose change
 * over the step gives them. */
enum { MEAN_F_N, MEAN_F_T };
enum { CM_VY, CM_VX };

/* The model's data: parameters, states, modes, what the events record, and
 * derived values and partial derivatives cached until a change marks them stale. Plain data with no
 * pointers, so an FMU state may hold a copy. */
typedef struct {
    RodParams params;
    double x[ROD_NX];
    ContactRecord run;                               /* the mode and what its events recorded */
    double step_mean[2];  /* F_N, F_T averaged over the last Co-Simulation step (the impulse / the step) */
    double step_start[2]; /* vy_cm, vx_cm when the step began (CM_VY, CM_VX) */
    bool means_held;      /* Co-Simulation: F_N_mean, F_T_mean are step_mean; else (Model Exchange) F_N, F_T */
    bool stale, partials_stale;
    double dx[ROD_NX], z[CONTACT_NZ], out[ROD_NOUT], mean_out[2];
    RodPartials partials;
} Model;

#endif
