/* PainleveRod's variables: start values, ranges, get/set, derived values. */
#include "model.h"

#include <math.h>
#include <stdio.h>

/* Parameter ranges keep every derived quantity finite in double precision:
 * F_N ~ y/eps^2 and phi^2 must not overflow. */
#define STATE_BOUND 1e6

static const VariableInfo REALS[N_REALS] = {
    [VR_ALPHA] = { "alpha", KIND_PARAMETER, 1e-6, 1e6 },
    [VR_MU] = { "mu", KIND_PARAMETER, 0, 1e6 },
    [VR_DELTA] = { "delta", KIND_PARAMETER, 0, 1e6 },
    [VR_EPSILON] = { "epsilon", KIND_PARAMETER, 1e-8, 1 },
    [VR_X] = { "x", KIND_STATE, -STATE_BOUND, STATE_BOUND },
    [VR_V] = { "v", KIND_STATE, -STATE_BOUND, STATE_BOUND },
    [VR_Y] = { "y", KIND_STATE, -STATE_BOUND, STATE_BOUND },
    [VR_W] = { "w", KIND_STATE, -STATE_BOUND, STATE_BOUND },
    [VR_THETA] = { "theta", KIND_STATE, -STATE_BOUND, STATE_BOUND },
    [VR_PHI] = { "phi", KIND_STATE, -STATE_BOUND, STATE_BOUND },
    [VR_DER_X] = { "der(x)", KIND_CALCULATED, 0, 0 },
    [VR_DER_V] = { "der(v)", KIND_CALCULATED, 0, 0 },
    [VR_DER_Y] = { "der(y)", KIND_CALCULATED, 0, 0 },
    [VR_DER_W] = { "der(w)", KIND_CALCULATED, 0, 0 },
    [VR_DER_THETA] = { "der(theta)", KIND_CALCULATED, 0, 0 },
    [VR_DER_PHI] = { "der(phi)", KIND_CALCULATED, 0, 0 },
    [VR_F_N] = { "F_N", KIND_CALCULATED, 0, 0 },
    [VR_F_T] = { "F_T", KIND_CALCULATED, 0, 0 },
    [VR_ENERGY] = { "energy", KIND_CALCULATED, 0, 0 },
};

const VariableInfo *model_real_info(unsigned int vr)
{
    return vr < N_REALS ? &REALS[vr] : NULL;
}

void model_set_start_values(Model *m)
{
    /* A Theorem 1 case (inconsistent quadrant): the defaults show an IWC. */
    m->params = (RodParams){ .alpha = 3, .mu = 3, .delta = 1, .epsilon = 1e-3 };
    const double x0[ROD_NX] = { [ROD_X] = 0, [ROD_V] = 1, [ROD_Y] = 0,
                                [ROD_W] = 0, [ROD_THETA] = 1, [ROD_PHI] = 0.5 };
    for (int i = 0; i < ROD_NX; ++i) m->x[i] = x0[i];
    m->mode = (RodMode){ false, +1 };
    m->stale = true;
}

const char *model_check_real(unsigned int vr, double value)
{
    static const char *const reason[] = { "must be finite", "is out of range" };
    const VariableInfo *info = model_real_info(vr);
    if (!isfinite(value)) return reason[0];
    if (value < info->min || value > info->max) return reason[1];
    return NULL;
}

static double *state_of(Model *m, unsigned int vr)
{
    return &m->x[vr - VR_X];
}

void model_set_real(Model *m, unsigned int vr, double value)
{
    switch (vr) {
    case VR_ALPHA: m->params.alpha = value; break;
    case VR_MU: m->params.mu = value; break;
    case VR_DELTA: m->params.delta = value; break;
    case VR_EPSILON: m->params.epsilon = value; break;
    default: *state_of(m, vr) = value; break;
    }
    m->stale = true;
}

void model_update_derived(Model *m)
{
    if (!m->stale) return;
    rod_derivatives(&m->params, m->mode, m->x, m->dx);
    rod_event_indicators(&m->params, m->mode, m->x, m->z);
    m->F_N = rod_normal_force(&m->params, m->mode, m->x);
    m->F_T = rod_friction_force(&m->params, m->mode, m->x);
    m->energy = rod_energy(&m->params, m->mode, m->x);
    m->stale = false;
}

double model_get_real(Model *m, unsigned int vr)
{
    model_update_derived(m);
    switch (vr) {
    case VR_ALPHA: return m->params.alpha;
    case VR_MU: return m->params.mu;
    case VR_DELTA: return m->params.delta;
    case VR_EPSILON: return m->params.epsilon;
    case VR_F_N: return m->F_N;
    case VR_F_T: return m->F_T;
    case VR_ENERGY: return m->energy;
    default:
        if (vr >= VR_DER_X) return m->dx[vr - VR_DER_X];
        return *state_of(m, vr);
    }
}

void model_initial_mode(Model *m)
{
    /* Nothing is remembered before the start: slip follows the sign of v. */
    const double v = m->x[ROD_V];
    m->mode = (RodMode){ false, (v > 0) - (v < 0) };
    bool changed;
    m->mode = rod_decide_mode(&m->params, m->mode, m->x, &changed);
    m->stale = true;
}
