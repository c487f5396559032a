/* SPDX-License-Identifier: BSD-2-Clause */
/* The variables and <ModelStructure> of modelDescription.xml, as C tables
 * generated at configure time by model_structure.py (model_structure_data.c),
 * (either FMI version), and the questions FMI 2.0.4 asks of them (FMI 3.0
 * asks the same, §2.2.11 of 3.0 "Getting Partial Derivatives"): which variables may be read or
 * set in which state, which (unknown, known) pairs a directional derivative
 * is defined for. The conformance tests take their expectations from here. */
#ifndef MODEL_STRUCTURE_H
#define MODEL_STRUCTURE_H

#include <stdbool.h>

typedef enum { MD_REAL, MD_INTEGER, MD_BOOLEAN, MD_STRING, MD_ENUMERATION } MdType;
typedef enum { MD_PARAMETER, MD_CALCULATEDPARAMETER, MD_INPUT, MD_OUTPUT, MD_LOCAL, MD_INDEPENDENT } MdCausality;
typedef enum { MD_CONSTANT, MD_FIXED, MD_TUNABLE, MD_DISCRETE, MD_CONTINUOUS } MdVariability;
typedef enum { MD_INITIAL_EXACT, MD_INITIAL_APPROX, MD_INITIAL_CALCULATED, MD_INITIAL_NONE } MdInitial;

typedef struct {
    const char *name;
    unsigned int vr;
    MdType type;
    MdCausality causality;
    MdVariability variability;
    MdInitial initial; /* the XML's, or FMI 2.0.4 §2.2.7's default */
    bool has_start;
    double start;      /* Boolean: 0 or 1; String: unused */
    int derivative;    /* index of the variable this one is the derivative of, 0 if none */
    bool state;        /* a continuous-time state: named by a <Derivatives> unknown */
    bool has_min;      /* the type element's min and max, where given */
    double min;
    bool has_max;
    double max;
} MdVariable;

/* An <Unknown>: ScalarVariable index (1-based), its dependencies (indices);
 * n_deps = -1 when the attribute is absent (depends on every known). */
typedef struct {
    int index, n_deps;
    const int *deps;
} MdUnknown;

extern const MdVariable MD_VARIABLES[]; /* MD_VARIABLES[index - 1] */
extern const int MD_N_VARIABLES;
extern const MdUnknown MD_OUTPUTS[], MD_DERIVATIVES[], MD_INITIALUNKNOWNS[];
extern const int MD_N_OUTPUTS, MD_N_DERIVATIVES, MD_N_INITIALUNKNOWNS;
/* FMI 3.0's <EventIndicator> elements (none in an FMI 2.0 description). */
/* The model description's providesDirectionalDerivative(s) flag. */
extern const bool MD_PROVIDES_DIRECTIONAL_DERIVATIVE;
extern const MdUnknown MD_EVENTINDICATORS[];
extern const int MD_N_EVENTINDICATORS;

const MdVariable *md_var(int index);

/* Continuous state i of the state vector (FMI 2.0: the order of <Derivatives>):
 * its variable's index; and the position of variable `index` in that vector
 * (-1 if it is no state). */
int md_state_index(int i);
int md_state_position(int index);
/* The first Real variable with this causality and variability (0: none). */
int md_first(MdCausality causality, MdVariability variability);

/* The modes in which the standard defines the unknowns and knowns of
 * fmi2GetDirectionalDerivative (FMI 2.0.4 §2.1.9 and §2.2.8). */
typedef enum { MD_MODE_INIT, MD_MODE_EVENT, MD_MODE_CONTINUOUS, MD_MODE_STEP } MdMode;

/* Listed under <InitialUnknowns>. */
bool md_initial_unknown(int index);
/* The <Unknown> of `index` in the list that defines the unknowns of `mode`,
 * or NULL if `index` is no Real unknown of that mode (§2.1.9):
 * InitializationMode: <InitialUnknowns> of type Real; Continuous-Time Mode:
 * <Outputs> of type Real and variability continuous, and <Derivatives>; Event
 * Mode: those and the discrete Real outputs; Co-Simulation's communication
 * points: Real <Outputs> (continuous or discrete) and <Derivatives>. */
const MdUnknown *md_unknown_of_mode(MdMode mode, int index);
/* A known of `mode` (§2.2.8): inputs and continuous-time states in Event and
 * Continuous-Time Mode and at communication points; inputs and variables
 * with initial = "exact" in Initialization Mode. */
bool md_known_of_mode(MdMode mode, int index);

/* The unknowns and knowns of `mode` (ScalarVariable indices, at most `max` of each). */
void md_mode_sets(MdMode mode, int max, int *unknowns, int *nu, int *knowns, int *nk);
/* Whether `u` declares a dependency on known `index`. */
bool md_depends(const MdUnknown *u, int index);

#endif
