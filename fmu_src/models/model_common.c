/* SPDX-License-Identifier: BSD-2-Clause */
/* What every model shares, made once from its config.h: the table of its
 * variables (MODEL_VARIABLES), a variable's field read and written, the fields
 * an FMU state holds, the accessors of the states and of what the model
 * derives from them (model.h: the Model's x, dx, z, stale, partials_stale and
 * its model_update), the partial derivatives every model has, and the default
 * of each optional part a model's config.h does not claim (model.h). */
#include "model.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A model with events has indicators and one without has none (C99 has no static
 * assertion: a negative array size stops the build). */
#ifdef MODEL_EVENTS
typedef char model_events_have_indicators[(MODEL_NZ) > 0 ? 1 : -1];
#else
typedef char model_without_events_has_no_indicators[(MODEL_NZ) == 0 ? 1 : -1];
#endif

#define MODEL_INFO(id, name, type, kind, field, min, max) [VR_##id] = { name, TYPE_##type, KIND_##kind, min, max },
static const VariableInfo VARIABLES[VR_COUNT] = { MODEL_VARIABLES(MODEL_INFO) };
#undef MODEL_INFO

void model_anchor(Model *m, const double x[MODEL_NX], bool anchored)
{
#ifdef MODEL_STEP_ANCHOR
    model_step_anchor(m, x, anchored);
#else
    (void)m, (void)x, (void)anchored;
#endif
}

const VariableInfo *model_variable(unsigned int vr)
{
    return vr < VR_COUNT ? &VARIABLES[vr] : NULL;
}

bool model_settable(const VariableInfo *info)
{
    return info->kind == KIND_PARAMETER || MODEL_KIND_IS_STATE(info->kind) || info->kind == KIND_INPUT;
}

/* Only settable kinds are written: the others' fields may be int or bool. */
#define ASSIGN_PARAMETER(lvalue, value) (lvalue) = (value)
#define ASSIGN_STATE ASSIGN_PARAMETER
#define ASSIGN_INPUT ASSIGN_PARAMETER
#define ASSIGN_CALCULATED(lvalue, value) (void)(value)
#define ASSIGN_DISCRETE ASSIGN_CALCULATED
#define ASSIGN_CALCULATED_PARAMETER ASSIGN_CALCULATED
#define ASSIGN_DERIVED_STATE ASSIGN_PARAMETER
#define MODEL_ASSIGN(id, name, type, kind, field, min, max) case VR_##id: ASSIGN_##kind(m->field, value); break;
#define MODEL_READ(id, name, type, kind, field, min, max) case VR_##id: return (double)m->field;

void model_assign(Model *m, unsigned int vr, double value)
{
    switch (vr) { MODEL_VARIABLES(MODEL_ASSIGN) default: break; }
}

double model_stored(const Model *m, unsigned int vr)
{
    switch (vr) { MODEL_VARIABLES(MODEL_READ) default: return NAN; }
}

const char *model_check(unsigned int vr, double value)
{
    const VariableInfo *info = model_variable(vr);
    if (!isfinite(value)) return "must be finite";
#ifdef MODEL_CHECK
    const char *broken = model_check_rules(vr, value);
    if (broken) return broken;
#endif
    if (value < info->min || value > info->max) return "is out of range";
    return NULL;
}

/* An FMU state holds what is set or changes at events; calculated values follow from it. */
#define FIELD_PARAMETER(id, name, type, field) { name, offsetof(Model, field), TYPE_##type },
#define FIELD_STATE FIELD_PARAMETER
#define FIELD_INPUT FIELD_PARAMETER
#define FIELD_DISCRETE FIELD_PARAMETER
#define FIELD_CALCULATED(id, name, type, field)
#define FIELD_CALCULATED_PARAMETER FIELD_CALCULATED
#define FIELD_DERIVED_STATE FIELD_PARAMETER
#define MODEL_FIELD(id, name, type, kind, field, min, max) FIELD_##kind(id, name, type, field)
#define INTERNAL_FIELD(name, field, type) { name, offsetof(Model, field), TYPE_##type },
const ModelField model_fields[] = { MODEL_VARIABLES(MODEL_FIELD) MODEL_INTERNALS(INTERNAL_FIELD) };
const size_t model_n_fields = sizeof model_fields / sizeof model_fields[0];

/* ----------------------------------------------------- states, derived values */

void model_set(Model *m, unsigned int vr, double value)
{
    model_assign(m, vr, value);
    model_touch(m);
}

void model_restore(Model *m, const Model *saved)
{
    *m = *saved;
    model_touch(m);
}

double model_get(Model *m, unsigned int vr)
{
    model_update(m);
    return model_stored(m, vr);
}

unsigned int model_state_vr(size_t i)
{
    for (unsigned int vr = 0; vr < VR_COUNT; ++vr)
        if (MODEL_KIND_IS_STATE(VARIABLES[vr].kind) && i-- == 0) return vr;
    return VR_COUNT;
}

void model_get_states(const Model *m, double x[MODEL_NX])
{
    memcpy(x, m->x, sizeof m->x);
}

void model_set_states(Model *m, const double x[MODEL_NX])
{
    memcpy(m->x, x, sizeof m->x);
    model_touch(m);
}

void model_get_derivatives(Model *m, double dx[MODEL_NX])
{
    model_update(m);
    memcpy(dx, m->dx, sizeof m->dx);
}

void model_get_indicators(Model *m, double z[])
{
#ifdef MODEL_EVENTS
    model_update(m);
    memcpy(z, m->z, sizeof m->z);
#else
    (void)m, (void)z;
#endif
}

/* ------------------------------------------- defaults of the optional parts */

#ifndef MODEL_SET_TIME
void model_set_time(Model *m, double time)
{
    (void)m, (void)time;   /* an autonomous model */
}
#endif

#ifndef MODEL_INPUT_SET
bool model_input_set(Model *m, unsigned int vr, double time)
{
    (void)m, (void)vr, (void)time;   /* an input is its value alone */
    return false;
}
#endif

#ifndef MODEL_STEP_MEANS
void model_step_begin(Model *m, double time)
{
    (void)m, (void)time;
}

void model_step_end(Model *m, double elapsed)
{
    (void)m, (void)elapsed;
}
#endif

#ifndef MODEL_EVENTS
void model_indicators_at(const Model *m, double time, const double x[MODEL_NX], double z[])
{
    (void)m, (void)time, (void)x, (void)z;
}

void model_decide_initial_mode(Model *m)
{
    (void)m;
}

void model_begin_integration(Model *m)
{
    (void)m;
}

/* No modes: an event (an input that jumped) changes nothing of the model's own,
 * and integration restarts from the same state. */
bool model_event_update(Model *m, double time, ModelEvent *e)
{
    (void)m;
    e->states_changed = e->switched = false;
    snprintf(e->text, sizeof e->text, "t = %.17g: no modes to update", time);
    return true;
}
#endif

/* ------------------------------------------------------ FMU state fields */

const char *model_implausible(const Model *m)
{
    for (unsigned int vr = 0; vr < VR_COUNT; ++vr) {
        const VariableInfo *info = model_variable(vr);
        if (model_settable(info) && model_check(vr, model_stored(m, vr))) return info->name;
    }
    return model_internals_implausible(m);
}

/* ------------------------------------------------------ partial derivatives */

#ifdef MODEL_NO_PARTIALS
/* A model without partial derivatives (its description: providesDirectionalDerivative="false")
 * answers none, not even a known's own. */
const char *model_partial_derivative(Model *m, unsigned int unknown, unsigned int known, double *value)
{
    (void)m, (void)unknown, (void)known, (void)value;
    return MODEL_NO_PARTIALS;
}
#else
const char *model_partial_derivative(Model *m, unsigned int unknown, unsigned int known, double *value)
{
    const VariableInfo *u = model_variable(unknown), *k = model_variable(known);
    if (!u || u->type != TYPE_REAL) return "the unknown is not a Real variable";
    if (!k || !model_settable(k)) return "the known is neither a state, an input nor a parameter";
    if (model_settable(u) || u->kind == KIND_DISCRETE) {     /* a known itself, or frozen between events */
        *value = unknown == known;
        return NULL;
    }
    return model_calculated_partial(m, unknown, known, value);
}
#endif
