/* SPDX-License-Identifier: BSD-2-Clause */
/* The model interface: everything a model provides to the FMI layer above it, in
 * the way of the Reference-FMUs. An FMI file calls only these functions and knows
 * no state, mode or physics; a model knows no FMI. The model's own metadata and
 * data (its config.h) fill in the constants and the type Model.
 *
 * A model's files hold only what is special to it. model_common.c gives every model
 * what follows from its variable list, and the default of each optional part that
 * the model's config.h does not claim. A config.h that defines
 *   MODEL_CHECK          provides model_check_rules (rules beyond the variables'
 *                        ranges, asked of a finite value before its range); default:
 *                        the range check alone;
 *   MODEL_SET_TIME       provides model_set_time (a model driven by time);
 *                        default: an autonomous model, which ignores the time;
 *   MODEL_INPUT_SET      provides model_input_set (an input whose set changes the
 *                        trajectory beyond its value); default: none does;
 *   MODEL_STEP_MEANS     provides model_step_begin and model_step_end (outputs that
 *                        are means over a Co-Simulation step); default: none;
 *   MODEL_EVENTS         has event indicators (MODEL_NZ > 0, the Model's z[MODEL_NZ],
 *                        which model_update fills) and provides model_indicators_at,
 *                        model_decide_initial_mode, model_begin_integration and
 *                        model_event_update; default: no indicators and no modes;
 *   MODEL_CLOSED_FLIGHT  provides the model_flight_* functions (below); default: none;
 *   MODEL_GAP_ROWS       provides model_gap_rows_at (below: a contact's gap or normal
 *                        rate that is no state); default: the states' own error control;
 *   MODEL_STEP_ANCHOR    provides model_step_anchor (below: what evaluations near a
 *                        state share); default: none;
 *   MODEL_NO_PARTIALS    (a message) has no partial derivatives, and provides no
 *                        model_calculated_partial.
 * Every other function below a model provides, except those model_common.c defines. */
#ifndef MODEL_H
#define MODEL_H

#include <stdbool.h>
#include <stddef.h>

#include "model_event.h"
#include "namespace.h" /* every source includes this header: their names, prefixed */

/* The model's own metadata: its directory comes first on the include path
 * (painleve_model_sources, cmake/PainleveCommon.cmake), so each model built on
 * this interface, a folder of fmu_src/models, gets its own. */
#include <config.h>

typedef enum { TYPE_REAL, TYPE_INTEGER, TYPE_BOOLEAN } VariableType;
/* PARAMETER: fixed, set before initialization ends; STATE: a continuous state;
 * INPUT: continuous, set by the master at any time (causality input);
 * CALCULATED: continuous, derived; DISCRETE: changes only at events;
 * CALCULATED_PARAMETER: derived from parameters while initializing, fixed
 * after (causality calculatedParameter: an unknown of Initialization Mode only);
 * DERIVED_STATE: a continuous state the model calculates while initializing
 * (initial="calculated": set as a state is in Continuous-Time Mode, never before;
 * a model with one provides no partial derivatives, MODEL_NO_PARTIALS). */
typedef enum {
    KIND_PARAMETER, KIND_STATE, KIND_CALCULATED, KIND_DISCRETE, KIND_INPUT, KIND_CALCULATED_PARAMETER,
    KIND_DERIVED_STATE
} VariableKind;

/* A continuous state, set by the user or derived (a variable of kind STATE or DERIVED_STATE). */
#define MODEL_KIND_IS_STATE(kind) ((kind) == KIND_STATE || (kind) == KIND_DERIVED_STATE)

/* Value references, in the order of config.h's list and modelDescription.xml. */
#define MODEL_VR_ENUM(id, ...) VR_##id,
typedef enum { MODEL_VARIABLES(MODEL_VR_ENUM) VR_COUNT } ValueReference;
#undef MODEL_VR_ENUM

typedef struct {
    const char *name;
    VariableType type;
    VariableKind kind;
    double min, max; /* allowed range of a settable value, both inclusive */
} VariableInfo;

/* ------------------------------------------------------------ variables */

/* NULL if vr is not a variable of the model. */
const VariableInfo *model_variable(unsigned int vr);

/* Parameters, initial states and inputs may be set (instance_check_set says when). */
bool model_settable(const VariableInfo *info);

/* The start values of every variable: a new model. */
void model_reset(Model *m);

/* NULL when value is allowed for settable variable vr, else why not: finite, the
 * model's rules (MODEL_CHECK), then within [min, max]. */
const char *model_check(unsigned int vr, double value);

/* NULL when a finite value keeps the model's rules beyond the ranges, else why not
 * (optional: MODEL_CHECK). */
const char *model_check_rules(unsigned int vr, double value);

/* Sets a settable variable (checked before); values travel as double
 * whatever the variable's type. */
void model_set(Model *m, unsigned int vr, double value);
double model_get(Model *m, unsigned int vr);

/* A variable's field written (settable kinds only) and read (model_common.c, from
 * config.h's list). A model's Model has the fields x[MODEL_NX], dx[MODEL_NX], stale
 * and partials_stale; model_update computes what it derives (dx, z, outputs) when
 * stale; model_touch marks it stale: whatever changed, the derived values follow it
 * when next asked for. model_touch is inline so that a model's files call nothing of
 * model_common.c, which calls them. */
void model_update(Model *m);
void model_assign(Model *m, unsigned int vr, double value);
double model_stored(const Model *m, unsigned int vr);

static inline void model_touch(Model *m)
{
    m->stale = m->partials_stale = true;
}

/* The model becomes `saved` (an FMU state restored). */
void model_restore(Model *m, const Model *saved);

/* ---------------------------------------------------- continuous states */

/* The value reference of continuous state i (for messages and checks). */
unsigned int model_state_vr(size_t i);

void model_get_states(const Model *m, double x[MODEL_NX]);
void model_set_states(Model *m, const double x[MODEL_NX]);
void model_get_derivatives(Model *m, double dx[MODEL_NX]);
void model_get_indicators(Model *m, double z[]);   /* model_common.c: the Model's z (MODEL_EVENTS) */
void model_get_nominals(const Model *m, double nominal[MODEL_NX]);

/* Input vr was set at `time` (after model_set). True if the set changed the
 * model's trajectory beyond the value itself (a Co-Simulation step must then
 * restart its integrator), as when an input starts a new interpolation
 * (optional: MODEL_INPUT_SET). */
bool model_input_set(Model *m, unsigned int vr, double time);

/* A Co-Simulation step begins at `time`: a model whose inputs it interpolates
 * between communication points starts doing so, one with step means takes what
 * they start from. (Model Exchange never calls it: there the master gives the
 * inputs at every time.) Optional: MODEL_STEP_MEANS. */
void model_step_begin(Model *m, double time);

/* The time the getters above evaluate at (the instance's; a model driven by
 * time, such as a harmonic force, needs it; an autonomous one ignores it).
 * Optional: MODEL_SET_TIME. */
void model_set_time(Model *m, double time);

/* The current mode's right-hand side, indicators and d der(x)/d x at a trial
 * time and state x, for an embedded integrator; the model is not changed.
 * (Indicator arrays are [] : a model may have none; model_indicators_at is
 * optional: MODEL_EVENTS.) */
void model_derivatives_at(const Model *m, double time, const double x[MODEL_NX], double dx[MODEL_NX]);
void model_indicators_at(const Model *m, double time, const double x[MODEL_NX], double z[]);
void model_jacobian_at(const Model *m, double time, const double x[MODEL_NX], double J[MODEL_NX][MODEL_NX]);

/* ------------------------------------- closed-form flight (optional) */

/* A model whose config.h defines MODEL_CLOSED_FLIGHT, and the type ModelFlight, knows its
 * free flight in closed form (a rigid body under gravity and constant loads: translation
 * at constant acceleration, rotation at constant angular acceleration). Co-Simulation then
 * advances such a flight exactly (closed_flight.c), not with the explicit pair; a model
 * without it (no MODEL_CLOSED_FLIGHT) is integrated by the pair throughout. */
#ifdef MODEL_CLOSED_FLIGHT
/* True if the current mode at the model's inputs (held over a Co-Simulation step) is such
 * a flight, with *f made ready to give its state from x0 at time t0; false otherwise. */
bool model_flight_begin(const Model *m, double t0, const double x0[MODEL_NX], ModelFlight *f);

/* The flight's exact state at time t (the model's indicators are model_indicators_at). */
void model_flight_at(const ModelFlight *f, double t, double x[MODEL_NX]);

/* The longest time, from t on, over which each event indicator's sign at the two ends
 * shows whether it has a root (the physics bounds it: the rotation, the gap's curvature). */
double model_flight_sample_step(const ModelFlight *f, double t);
#endif

/* ------------------------------------- the contact in the error control (optional) */

/* A model whose config.h defines MODEL_GAP_ROWS has states that are not its contact's gap or
 * normal rate (a linkage's angles and rates, whose size says nothing of the rate's eps): it gives
 * the two as linear functions of a change of state at x (rows), with their values and nominals there,
 * so that an embedded integrator's error control holds them to their own scale, as it holds a
 * state to its nominal (docs/general_body.md §1). */
#ifdef MODEL_GAP_ROWS
typedef struct {
    double row[2][MODEL_NX]; /* d gap/dx, d normal rate/dx */
    double value[2], nominal[2];
} ModelGapRows;

void model_gap_rows_at(const Model *m, double time, const double x[MODEL_NX], ModelGapRows *r);
#endif

/* ------------------------------------------ a step's anchor (optional) */

/* A model whose config.h defines MODEL_STEP_ANCHOR may prepare, for evaluations at states
 * near x, what they share (the sine and cosine of an angle that moves little within a step),
 * so that they cost less; their values are the same to rounding. Co-Simulation anchors the
 * explicit pair's steps, the pair's restarts and its own event updates, and releases the
 * anchor (anchored false) before it goes on, so that nothing else (Model Exchange, CVODE,
 * the getters) ever sees one. */
#ifdef MODEL_STEP_ANCHOR
void model_step_anchor(Model *m, const double x[MODEL_NX], bool anchored);
#endif

/* model_step_anchor where the model has one, else nothing (model_common.c): what the FMI
 * layer calls. */
void model_anchor(Model *m, const double x[MODEL_NX], bool anchored);

/* ------------------------------------------- step means (Co-Simulation) */

/* The step that began at model_step_begin is done, after `elapsed` (> 0; 0 when
 * it made no progress, and when Co-Simulation's initialization ends: nothing
 * delivered yet). A model that outputs means over the last step (a contact
 * force whose impulse a coupled model must receive whatever the contact's
 * duration) takes them from its own balances over the step. Model Exchange
 * never calls it: there, where the importer's integrator owns the steps, a
 * step mean is the quantity now (the mean over a step shrunk to an instant).
 * Optional: MODEL_STEP_MEANS. */
void model_step_end(Model *m, double elapsed);

/* ------------------------------------------------------- modes, events */

/* The initial mode, decided from the state alone (initialization mode).
 * Optional, with model_begin_integration and model_event_update: MODEL_EVENTS. */
void model_decide_initial_mode(Model *m);

/* Initialization ends at `time`: the initial mode, the event record reset;
 * `text` says what the model starts in (for the event log). */
void model_start(Model *m, double time, char *text, size_t size);

/* Integration (re)starts from the current state (the event log's reference). */
void model_begin_integration(Model *m);

/* The event update at `time`: new modes iterated to a fixpoint, the state
 * moved off every switching surface, the switch recorded, and e->text saying
 * so when the caller asks (e->describe: it logs events). False, with the
 * reason in e->text, if the modes do not settle or too many events fall on
 * one instant (a Zeno run). */
bool model_event_update(Model *m, double time, ModelEvent *e);

/* ------------------------------------------------ partial derivatives */

/* d unknown / d known of the current mode's smooth branch, analytic. A model whose config.h
 * defines MODEL_NO_PARTIALS (a message) has none: every call returns it. Unknowns
 * are Reals (a state, input or parameter is its own identity, a discrete output
 * is frozen between events), knowns states, inputs and parameters. NULL on
 * success, else why the pair has none. (model_common.c; it asks the model for
 * the rest, model_calculated_partial.) */
const char *model_partial_derivative(Model *m, unsigned int unknown, unsigned int known, double *value);

/* The model's own part of model_partial_derivative: d unknown / d known for a
 * calculated unknown (not a settable or discrete variable) and a settable known;
 * NULL on success, else why the pair has none (a variable the model does not know
 * is such an error, never another variable's value). Not with MODEL_NO_PARTIALS. */
const char *model_calculated_partial(Model *m, unsigned int unknown, unsigned int known, double *value);

/* ------------------------------------------------------ FMU state fields */

/* What an FMU state holds of the model, by name: every parameter, state and
 * discrete variable, then the internals of config.h. */
typedef struct {
    const char *name;
    size_t offset; /* in Model */
    VariableType type;
} ModelField;

extern const ModelField model_fields[];
extern const size_t model_n_fields;

/* NULL if m (restored from bytes) holds values this model can have, else
 * the name of the first field that does not: every settable variable passes
 * model_check (model_common.c), then the model's own part, model_internals_implausible. */
const char *model_implausible(const Model *m);

/* The model's own part of model_implausible: NULL if the data beyond its settable
 * variables (config.h's internals, its mode) hold values it can have, else a name. */
const char *model_internals_implausible(const Model *m);

#endif
