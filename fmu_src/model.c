/* PainleveRod on the model interface (model.h): its variables, states, modes
 * and events over the physics of rod.c. Knows the rod, not FMI. */
#include "model.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A run of this many events at one instant (no progress in time beyond
 * round-off) is a Zeno run, not a fast one: a physical IWC has at most four
 * switches at one instant, and a fast rod's events advance time. */
#define MAX_EVENTS_AT_ONE_INSTANT 100

/* ------------------------------------------------------------ variables */

#define MODEL_INFO(id, name, type, kind, field, min, max) [VR_##id] = { name, TYPE_##type, KIND_##kind, min, max },
static const VariableInfo VARIABLES[VR_COUNT] = { MODEL_VARIABLES(MODEL_INFO) };
#undef MODEL_INFO

const VariableInfo *model_variable(unsigned int vr)
{
    return vr < VR_COUNT ? &VARIABLES[vr] : NULL;
}

bool model_settable(const VariableInfo *info)
{
    return info->kind == KIND_PARAMETER || info->kind == KIND_STATE;
}

void model_reset(Model *m)
{
    /* A Theorem 1 case (inconsistent quadrant): the defaults show an IWC, with the
     * paper's linear compliance law (kappa = beta = 0). */
    *m = (Model){ .params = { .alpha = 3, .mu = 3, .delta = 1, .epsilon = 1e-3, .kappa = 0, .beta = 0 },
                  .x = { [ROD_X] = 0, [ROD_V] = 1, [ROD_Y] = 0, [ROD_W] = 0, [ROD_THETA] = 1, [ROD_PHI] = 0.5 },
                  .mode = { false, +1 },
                  .instant = -INFINITY,
                  .stale = true,
                  .partials_stale = true };
}

const char *model_check(unsigned int vr, double value)
{
    const VariableInfo *info = model_variable(vr);
    if (!isfinite(value)) return "must be finite";
    /* kappa < 0 softens the spring until h grows with y at depth d > 1/(2|kappa|);
     * beta < 0 reverses the damper beyond d = 1/|beta|: both inside the contact. */
    if (vr == VR_KAPPA && value < 0)
        return "is out of range (a softening spring: the compliance law h would increase with y, d_y h > 0)";
    if (vr == VR_BETA && value < 0)
        return "is out of range (a damper that reverses: the compliance law h would increase with w, d_w h > 0)";
    if (value < info->min || value > info->max) return "is out of range";
    return NULL;
}

/* Only settable kinds are written: the others' fields may be int or bool. */
#define ASSIGN_PARAMETER(lvalue, value) (lvalue) = (value)
#define ASSIGN_STATE(lvalue, value) (lvalue) = (value)
#define ASSIGN_CALCULATED(lvalue, value) (void)(value)
#define ASSIGN_DISCRETE(lvalue, value) (void)(value)
#define MODEL_SET(id, name, type, kind, field, min, max) case VR_##id: ASSIGN_##kind(m->field, value); break;
#define MODEL_READ(id, name, type, kind, field, min, max) case VR_##id: return (double)m->field;

/* Whatever changed, the cached values follow it when next asked for. */
static void touch(Model *m)
{
    m->stale = m->partials_stale = true;
}

void model_set(Model *m, unsigned int vr, double value)
{
    switch (vr) { MODEL_VARIABLES(MODEL_SET) default: break; }
    touch(m);
}

void model_restore(Model *m, const Model *saved)
{
    *m = *saved;
    touch(m);
}

static void update_derived(Model *m)
{
    if (!m->stale) return;
    rod_derivatives(&m->params, m->mode, m->x, m->dx);
    rod_event_indicators(&m->params, m->mode, m->x, m->z);
    m->out[ROD_OUT_F_N] = rod_normal_force(&m->params, m->mode, m->x);
    m->out[ROD_OUT_F_T] = rod_friction_force(&m->params, m->mode, m->x);
    m->out[ROD_OUT_ENERGY] = rod_energy(&m->params, m->mode, m->x);
    m->stale = false;
}

/* The value held, derived values as last computed. */
static double stored(const Model *m, unsigned int vr)
{
    switch (vr) { MODEL_VARIABLES(MODEL_READ) default: return NAN; }
}

double model_get(Model *m, unsigned int vr)
{
    update_derived(m);
    return stored(m, vr);
}

/* ---------------------------------------------------- continuous states */

unsigned int model_state_vr(size_t i)
{
    return VR_X + (unsigned int)i;
}

void model_get_states(const Model *m, double x[MODEL_NX])
{
    memcpy(x, m->x, sizeof m->x);
}

void model_set_states(Model *m, const double x[MODEL_NX])
{
    memcpy(m->x, x, sizeof m->x);
    touch(m);
}

void model_get_derivatives(Model *m, double dx[MODEL_NX])
{
    update_derived(m);
    memcpy(dx, m->dx, sizeof m->dx);
}

void model_get_indicators(Model *m, double z[])
{
    update_derived(m);
    memcpy(z, m->z, sizeof m->z);
}

void model_get_nominals(const Model *m, double nominal[MODEL_NX])
{
    rod_nominals(&m->params, nominal);
}

void model_set_time(Model *m, double time)
{
    (void)m, (void)time;   /* the rod is autonomous */
}

void model_derivatives_at(const Model *m, double time, const double x[MODEL_NX], double dx[MODEL_NX])
{
    (void)time;
    rod_derivatives(&m->params, m->mode, x, dx);
}

void model_indicators_at(const Model *m, double time, const double x[MODEL_NX], double z[])
{
    (void)time;
    rod_event_indicators(&m->params, m->mode, x, z);
}

void model_jacobian_at(const Model *m, double time, const double x[MODEL_NX], double J[MODEL_NX][MODEL_NX])
{
    (void)time;
    rod_jacobian(&m->params, m->mode, x, J);
}

/* ------------------------------------------------------- modes, events */

void model_decide_initial_mode(Model *m)
{
    /* Nothing is remembered before the start: slip follows the sign of v. */
    const double v = m->x[ROD_V];
    m->mode = (RodMode){ false, (v > 0) - (v < 0) };
    bool changed;
    m->mode = rod_decide_mode(&m->params, m->mode, m->x, &changed);
    touch(m);
}

void model_start(Model *m, double time, char *text, size_t n)
{
    model_decide_initial_mode(m);
    m->t_switch = m->t_stick_begin = m->t_stick_end = m->t_contact_begin = m->t_contact_end = time;
    m->switches = m->sticks = 0;
    m->initial_event = true;
    m->instant = -INFINITY;
    m->events_at_instant = 0;
    snprintf(text, n, "initial mode contact = %d, mode = %+d", m->mode.contact, m->mode.slip);
}

void model_begin_integration(Model *m)
{
    update_derived(m);
    memcpy(m->z_at_restart, m->z, sizeof m->z);
}

/* Which indicators changed sign since integration last restarted. */
static void describe_fired(const Model *m, char *text, size_t size)
{
    size_t n = 0;
    if (m->initial_event) {
        snprintf(text, size, "none (initial event iteration)");
        return;
    }
    for (int i = 0; i < ROD_NZ && n < size; ++i)
        if ((m->z[i] > 0) != (m->z_at_restart[i] > 0) || m->z[i] == 0)
            n += (size_t)snprintf(text + n, size - n, "%s'%s' = %.3g", n ? ", " : "",
                                  rod_indicator_name(m->mode, i), m->z[i]);
    if (n == 0) snprintf(text, size, "none (time or step event)");
}

static bool sticking(RodMode mode) { return mode.contact && mode.slip == 0; }

/* The switch from `before` to the current mode, at `time`, in the record. */
static void record_switch(Model *m, RodMode before, double time)
{
    m->t_switch = time;
    ++m->switches;
    if (sticking(m->mode) && !sticking(before)) {
        m->t_stick_begin = time;
        ++m->sticks;
    }
    if (sticking(before) && !sticking(m->mode)) m->t_stick_end = time;
    if (m->mode.contact && !before.contact) m->t_contact_begin = time;
    if (before.contact && !m->mode.contact) m->t_contact_end = time;
}

bool model_event_update(Model *m, double time, ModelEvent *e)
{
    update_derived(m);
    char fired[512];
    describe_fired(m, fired, sizeof fired);
    m->initial_event = false;
    const RodMode before = m->mode;
    bool moved;
    const RodEventResult r = rod_event_update(&m->params, &m->mode, m->x, &moved);
    touch(m);
    e->switched = before.contact != m->mode.contact || before.slip != m->mode.slip;
    e->states_changed = moved;
    if (r != ROD_SETTLED) {
        snprintf(e->text, sizeof e->text, r == ROD_PING_PONG
                 ? "mode decision does not settle at t = %.17g (contact = %d, mode = %+d): rules ping-pong"
                 : "the state cannot be moved off a switching surface at t = %.17g (contact = %d, mode = %+d)",
                 time, m->mode.contact, m->mode.slip);
        return false;
    }
    if (e->switched) record_switch(m, before, time);
    snprintf(e->text, sizeof e->text, "t = %.17g: indicator %s; contact %d -> %d, mode %+d -> %+d%s", time, fired,
             before.contact, m->mode.contact, before.slip, m->mode.slip, moved ? "; continuous states changed" : "");
    /* Zeno guard: events that do not advance time beyond round-off. */
    if (time - m->instant > 1e-12 * (1 + fabs(time))) {
        m->instant = time;
        m->events_at_instant = 0;
    }
    if (++m->events_at_instant < MAX_EVENTS_AT_ONE_INSTANT) return true;
    snprintf(e->text, sizeof e->text,
             "%d events at t = %.17g without progress in time (a Zeno run: the modes chatter; last indicator %s; "
             "contact = %d, mode = %+d, theta = %g)",
             MAX_EVENTS_AT_ONE_INSTANT, time, fired, m->mode.contact, m->mode.slip, m->x[ROD_THETA]);
    return false;
}

/* ------------------------------------------------ partial derivatives */

/* The column of parameter vr in RodPartials (ROD_P_*). */
static int parameter_column(unsigned int vr)
{
    switch (vr) {
    case VR_ALPHA: return ROD_P_ALPHA;
    case VR_MU: return ROD_P_MU;
    case VR_DELTA: return ROD_P_DELTA;
    case VR_EPSILON: return ROD_P_EPSILON;
    case VR_KAPPA: return ROD_P_KAPPA;
    default: return ROD_P_BETA;
    }
}

const char *model_partial_derivative(Model *m, unsigned int unknown, unsigned int known, double *value)
{
    const VariableInfo *u = model_variable(unknown), *k = model_variable(known);
    if (!u || u->type != TYPE_REAL) return "the unknown is not a Real variable";
    if (!k || !model_settable(k)) return "the known is neither a state nor a parameter";
    if (model_settable(u) || u->kind == KIND_DISCRETE) {     /* a known itself, or frozen between events */
        *value = unknown == known;
        return NULL;
    }
    if (m->partials_stale) {
        rod_partials(&m->params, m->mode, m->x, &m->partials);
        m->partials_stale = false;
    }
    const RodPartials *d = &m->partials;
    const bool by_state = k->kind == KIND_STATE;
    const int col = by_state ? (int)(known - VR_X) : parameter_column(known);
    if (unknown >= VR_DER_X && unknown <= VR_DER_PHI) {
        const int row = (int)(unknown - VR_DER_X);
        *value = by_state ? d->dx_x[row][col] : d->dx_p[row][col];
    } else {
        const int row = (int)(unknown - VR_F_N);
        *value = by_state ? d->out_x[row][col] : d->out_p[row][col];
    }
    return NULL;
}

/* ------------------------------------------------------ FMU state fields */

#define FIELD_PARAMETER(id, name, type, field) { name, offsetof(Model, field), TYPE_##type },
#define FIELD_STATE FIELD_PARAMETER
#define FIELD_DISCRETE FIELD_PARAMETER
#define FIELD_CALCULATED(id, name, type, field)
#define MODEL_FIELD(id, name, type, kind, field, min, max) FIELD_##kind(id, name, type, field)
#define INTERNAL_FIELD(name, field, type) { name, offsetof(Model, field), TYPE_##type },
const ModelField model_fields[] = { MODEL_VARIABLES(MODEL_FIELD) MODEL_INTERNALS(INTERNAL_FIELD) };
const size_t model_n_fields = sizeof model_fields / sizeof model_fields[0];

const char *model_implausible(const Model *m)
{
    for (unsigned int vr = 0; vr < VR_COUNT; ++vr) {
        const VariableInfo *info = model_variable(vr);
        if (model_settable(info) && model_check(vr, stored(m, vr))) return info->name;
    }
    if (m->mode.slip < -1 || m->mode.slip > 1) return "mode";
    if (m->switches < 0 || m->sticks < 0 || m->sticks > m->switches) return "switches";
    const double times[] = { m->t_switch, m->t_stick_begin, m->t_stick_end, m->t_contact_begin, m->t_contact_end };
    for (size_t i = 0; i < sizeof times / sizeof times[0]; ++i)
        if (!isfinite(times[i])) return "t_switch";
    if (m->events_at_instant < 0 || m->events_at_instant >= MAX_EVENTS_AT_ONE_INSTANT) return "events_at_instant";
    return NULL;
}
