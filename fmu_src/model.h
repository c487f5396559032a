/* PainleveRod's metadata and the small model interface that the FMI layer
 * calls: value references in the order of modelDescription.xml, variable
 * ranges, start values, derived values. Knows the variables, not the standard. */
#ifndef MODEL_H
#define MODEL_H

#include <stdbool.h>
#include <stddef.h>

#include "rod.h"

#define MODEL_IDENTIFIER PainleveRod

/* Value references, unique across types, as in modelDescription.xml. */
typedef enum {
    VR_ALPHA, VR_MU, VR_DELTA, VR_EPSILON,
    VR_X, VR_V, VR_Y, VR_W, VR_THETA, VR_PHI,
    VR_DER_X, VR_DER_V, VR_DER_Y, VR_DER_W, VR_DER_THETA, VR_DER_PHI,
    VR_F_N, VR_F_T, VR_ENERGY,
    VR_MODE,    /* Integer */
    VR_CONTACT, /* Boolean */
    VR_COUNT
} ValueReference;

#define N_REALS (VR_ENERGY + 1)

typedef enum { KIND_PARAMETER, KIND_STATE, KIND_CALCULATED } VariableKind;

typedef struct {
    const char *name;
    VariableKind kind;
    double min, max; /* allowed range of a settable value, both inclusive */
} VariableInfo;

/* NULL if vr is not a Real variable. */
const VariableInfo *model_real_info(unsigned int vr);

/* The model's data: parameters, states, modes, and derived values cached
 * until a setter marks them stale. */
typedef struct {
    RodParams params;
    double x[ROD_NX];
    RodMode mode;
    bool stale;
    double dx[ROD_NX], z[ROD_NZ];
    double F_N, F_T, energy;
} Model;

void model_set_start_values(Model *m);

/* NULL when the value is allowed, else a reason naming the range. */
const char *model_check_real(unsigned int vr, double value);

void model_set_real(Model *m, unsigned int vr, double value);
double model_get_real(Model *m, unsigned int vr);

/* Recomputes the cached derived values if a setter made them stale. */
void model_update_derived(Model *m);

/* The initial mode, decided from the initial state alone (MODEL.md §2). */
void model_initial_mode(Model *m);

#endif
