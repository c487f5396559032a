/* SPDX-License-Identifier: BSD-2-Clause */
/* PainleveRod on the model interface (model.h): its variables, states, modes
 * and events over the physics of rod.c. Knows the rod, not FMI. */
#include "model.h"

#include <math.h>
#include <string.h>

/* ------------------------------------------------------------ variables */

void model_reset(Model *m)
{
    /* A Theorem 1 case (inconsistent quadrant): the defaults show an IWC, with the
     * paper's linear compliance law (kappa = beta = 0). */
    *m = (Model){ .params = { .alpha = 3, .mu = 3, .delta = 1, .epsilon = 1e-3, .kappa = 0, .beta = 0 },
                  .x = { [ROD_X] = 0, [ROD_V] = 1, [ROD_Y] = 0, [ROD_W] = 0, [ROD_THETA] = 1, [ROD_PHI] = 0.5 },
                  .run = contact_record_new(),
                  .stale = true,
                  .partials_stale = true };
}

const char *model_check(unsigned int vr, double value)
{
    if (!isfinite(value)) return model_check_range(vr, value);
    /* kappa < 0 softens the spring until h grows with y at depth d > 1/(2|kappa|);
     * beta < 0 reverses the damper beyond d = 1/|beta|: both inside the contact. */
    if (vr == VR_KAPPA && value < 0)
        return "is out of range (a softening spring: the compliance law h would increase with y, d_y h > 0)";
    if (vr == VR_BETA && value < 0)
        return "is out of range (a damper that reverses: the compliance law h would increase with w, d_w h > 0)";
    return model_check_range(vr, value);
}

void model_update(Model *m)
{
    if (!m->stale) return;
    rod_derivatives(&m->params, m->run.mode, m->x, m->dx);
    rod_event_indicators(&m->params, m->run.mode, m->x, m->z);
    m->out[ROD_OUT_F_N] = rod_normal_force(&m->params, m->run.mode, m->x);
    m->out[ROD_OUT_F_T] = rod_friction_force(&m->params, m->run.mode, m->x);
    m->out[ROD_OUT_ENERGY] = rod_energy(&m->params, m->run.mode, m->x);
    rod_coefficient_outputs(&m->params, m->x, m->out);
    m->mean_out[MEAN_F_N] = m->means_held ? m->step_mean[MEAN_F_N] : m->out[ROD_OUT_F_N];
    m->mean_out[MEAN_F_T] = m->means_held ? m->step_mean[MEAN_F_T] : m->out[ROD_OUT_F_T];
    m->stale = false;
}

/* The centre of mass's velocity in the paper's units (l = 1): vy = w + phi cos(theta),
 * vx = v + phi sin(theta), at the places of the forces they give (MEAN_F_N, MEAN_F_T). */
static void centre_velocity(const Model *m, double v_cm[2])
{
    v_cm[MEAN_F_N] = m->x[ROD_W] + m->x[ROD_PHI] * cos(m->x[ROD_THETA]);
    v_cm[MEAN_F_T] = m->x[ROD_V] + m->x[ROD_PHI] * sin(m->x[ROD_THETA]);
}

void model_get_indicators(Model *m, double z[])
{
    model_update(m);
    memcpy(z, m->z, sizeof m->z);
}

void model_get_nominals(const Model *m, double nominal[MODEL_NX])
{
    rod_nominals(&m->params, nominal);
}

bool model_input_set(Model *m, unsigned int vr, double time)
{
    (void)m, (void)vr, (void)time;   /* the rod has no inputs */
    return false;
}

void model_step_begin(Model *m, double time)
{
    (void)time;
    centre_velocity(m, m->step_start);   /* the momentum the step's impulses change */
}

void model_set_time(Model *m, double time)
{
    (void)m, (void)time;   /* the rod is autonomous */
}

void model_derivatives_at(const Model *m, double time, const double x[MODEL_NX], double dx[MODEL_NX])
{
    (void)time;
    rod_derivatives(&m->params, m->run.mode, x, dx);
}

void model_indicators_at(const Model *m, double time, const double x[MODEL_NX], double z[])
{
    (void)time;
    rod_event_indicators(&m->params, m->run.mode, x, z);
}

void model_jacobian_at(const Model *m, double time, const double x[MODEL_NX], double J[MODEL_NX][MODEL_NX])
{
    (void)time;
    rod_jacobian(&m->params, m->run.mode, x, J);
}

/* ------------------------------------------------------- modes, events */

void model_decide_initial_mode(Model *m)
{
    m->run.mode = rod_initial_mode(&m->params, m->x);
    model_touch(m);
}

void model_start(Model *m, double time, char *text, size_t size)
{
    rod_record_start(&m->run, &m->params, m->x, time);
    model_touch(m);
    contact_record_describe_start(&m->run, text, size);
}

void model_begin_integration(Model *m)
{
    model_update(m);
    memcpy(m->run.z_at_restart, m->z, sizeof m->z);
}

bool model_event_update(Model *m, double time, ModelEvent *e)
{
    model_update(m);
    const bool ok = rod_record_event(&m->run, &m->params, m->x, m->z, time, 1.0, false, e);
    model_touch(m);
    return ok;
}

void model_step_anchor(Model *m, const double x[MODEL_NX], bool anchored)
{
    rod_anchor(&m->params, x[ROD_THETA], anchored);
}

/* ------------------------------------- closed-form flight (model.h) */

/* In flight the rod's centre of mass falls at (f_x, f_y - 1) (weight 1 in units of m g, l = 1)
 * and it turns at alpha tau (eq dynrodsc without contact force: rod.h's loads, 0 here). */
bool model_flight_begin(const Model *m, double t0, const double x0[MODEL_NX], ModelFlight *f)
{
    if (m->run.mode.contact) return false;
    const RodParams *p = &m->params;
    *f = rod_flight(1, p->f_x, p->f_y - 1, p->alpha * p->tau, t0, x0);
    return true;
}

void model_flight_at(const ModelFlight *f, double t, double x[MODEL_NX])
{
    rod_flight_at(f, t, x);
}

double model_flight_sample_step(const ModelFlight *f, double t)
{
    return rod_flight_sample_step(f, t);
}

/* ------------------------------------------- step means (Co-Simulation) */

/* The floor's impulses over the step from the rod's momentum (mass 1, weight 1 in the paper's
 * units): dvy_cm = int F_N - h, dvx_cm = -int F_T; as PainleveRodSI's (docs/si_model.md). */
void model_step_end(Model *m, double elapsed)
{
    double now[2];
    centre_velocity(m, now);
    m->step_mean[MEAN_F_N] = elapsed > 0 ? (now[MEAN_F_N] - m->step_start[MEAN_F_N]) / elapsed + 1 : 0;
    m->step_mean[MEAN_F_T] = elapsed > 0 ? -(now[MEAN_F_T] - m->step_start[MEAN_F_T]) / elapsed : 0;
    m->means_held = true;
    model_touch(m);
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

const char *model_calculated_partial(Model *m, unsigned int unknown, unsigned int known, double *value)
{
    /* A step mean is the past's in Co-Simulation; in Model Exchange the force itself. */
    if (unknown == VR_F_N_MEAN || unknown == VR_F_T_MEAN) {
        if (m->means_held) {
            *value = 0;
            return NULL;
        }
        unknown = unknown == VR_F_N_MEAN ? VR_F_N : VR_F_T;
    }
    if (m->partials_stale) {
        rod_partials(&m->params, m->run.mode, m->x, &m->partials);
        m->partials_stale = false;
    }
    const RodPartials *d = &m->partials;
    const bool by_state = model_variable(known)->kind == KIND_STATE;
    const int col = by_state ? (int)(known - VR_X) : parameter_column(known);
    if (unknown >= VR_DER_X && unknown <= VR_DER_PHI) {
        const int row = (int)(unknown - VR_DER_X);
        *value = by_state ? d->dx_x[row][col] : d->dx_p[row][col];
    } else {
        const int row = unknown >= VR_A ? ROD_OUT_A + (int)(unknown - VR_A) : (int)(unknown - VR_F_N);
        *value = by_state ? d->out_x[row][col] : d->out_p[row][col];
    }
    return NULL;
}

/* ------------------------------------------------------ FMU state fields */

const char *model_internals_implausible(const Model *m)
{
    for (int i = 0; i < 2; ++i)
        if (!isfinite(m->step_mean[i]) || !isfinite(m->step_start[i])) return "step_mean_F_N";
    return contact_record_implausible(&m->run);
}
