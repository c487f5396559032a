/* PainleveRod's metadata: what the generic FMI layer needs to know of this
 * model, in one place. The variable list below drives the value references,
 * range checks, getters, setters and the FMU state; its order is that of
 * modelDescription.xml (tests/test_fmu_standard.py checks the two agree),
 * which is not in this folder but at the repository's top level, where the
 * spec names it (CMakeLists.txt's painleve_add_model(PainleveRod ...) line). */
#ifndef CONFIG_H
#define CONFIG_H

#include "rod.h"
#include "rod_partials.h"
#include "rod_record.h"

#define MODEL_IDENTIFIER PainleveRod
#define MODEL_NAME "PainleveRod"
#define MODEL_NX ROD_NX
#define MODEL_NZ ROD_NZ

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
    ROD_RECORD_TIMES(VARIABLE)                                                                     \
    VARIABLE(KAPPA, "kappa", REAL, PARAMETER, params.kappa, 0, 1e6)                                \
    VARIABLE(BETA, "beta", REAL, PARAMETER, params.beta, 0, 1e6)                                   \
    ROD_RECORD_MODES(VARIABLE)

/* The model's data beyond its variables that an FMU state must carry
 * (the event log's reference and the event guard): INTERNAL(name, field, type). */
#define MODEL_INTERNALS(INTERNAL)                         \
    ROD_RECORD_INTERNALS(INTERNAL)

/* The model's data: parameters, states, modes, what the events record, and
 * derived values and partial derivatives cached until a change marks them stale. Plain data with no
 * pointers, so an FMU state may hold a copy. */
typedef struct {
    RodParams params;
    double x[ROD_NX];
    RodRecord run;                               /* the mode and what its events recorded */
    bool stale, partials_stale;
    double dx[ROD_NX], z[ROD_NZ], out[ROD_NOUT];
    RodPartials partials;
} Model;

#endif
