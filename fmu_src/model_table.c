/* What a model's variable list (its config.h's MODEL_VARIABLES) gives the
 * model interface, made once for every model: the table of variables, a
 * variable's field read and written, and the fields an FMU state holds. */
#include "model.h"

#include <math.h>

#define MODEL_INFO(id, name, type, kind, field, min, max) [VR_##id] = { name, TYPE_##type, KIND_##kind, min, max },
static const VariableInfo VARIABLES[VR_COUNT] = { MODEL_VARIABLES(MODEL_INFO) };
#undef MODEL_INFO

const VariableInfo *model_variable(unsigned int vr)
{
    return vr < VR_COUNT ? &VARIABLES[vr] : NULL;
}

bool model_settable(const VariableInfo *info)
{
    return info->kind == KIND_PARAMETER || info->kind == KIND_STATE || info->kind == KIND_INPUT;
}

/* Only settable kinds are written: the others' fields may be int or bool. */
#define ASSIGN_PARAMETER(lvalue, value) (lvalue) = (value)
#define ASSIGN_STATE ASSIGN_PARAMETER
#define ASSIGN_INPUT ASSIGN_PARAMETER
#define ASSIGN_CALCULATED(lvalue, value) (void)(value)
#define ASSIGN_DISCRETE ASSIGN_CALCULATED
#define ASSIGN_CALCULATED_PARAMETER ASSIGN_CALCULATED
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

const char *model_check_range(unsigned int vr, double value)
{
    const VariableInfo *info = model_variable(vr);
    if (!isfinite(value)) return "must be finite";
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
#define MODEL_FIELD(id, name, type, kind, field, min, max) FIELD_##kind(id, name, type, field)
#define INTERNAL_FIELD(name, field, type) { name, offsetof(Model, field), TYPE_##type },
const ModelField model_fields[] = { MODEL_VARIABLES(MODEL_FIELD) MODEL_INTERNALS(INTERNAL_FIELD) };
const size_t model_n_fields = sizeof model_fields / sizeof model_fields[0];
