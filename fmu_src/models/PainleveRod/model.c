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

const char *model_check_rules(unsigned int vr, double value)
{
    /* kappa < 0 softens the spring until h grows with y at depth d > 1/(2|kappa|);
     * beta < 0 reverses the damper beyond d = 1/|beta|: both inside the contact. */
    if (vr == VR_KAPPA && value < 0)
        return "is out of range (a softening spring: the compliance law h would increase with y, d_y h > 0)";
    if (vr == VR_BETA && value < 0)
        return "is out of range (a damper that reverses: the compliance law h would increase with w, d_w h > 0)";
    return NULL;
}

void model_update(Model *m)
{
    if (!m->stale) return;
    const Contact c = rod_contact(&m->params);
    contact_derivatives(&c, m->run.mode, m->x, m->dx);
    contact_event_indicators(&c, m->run.mode, m->x, m->z);
    m->out[ROD_OUT_F_N] = contact_normal_force(&c, m->run.mode, m->x);
    m->out[ROD_OUT_F_T] = contact_friction_force(&c, m->run.mode, m->x);
    m->out[ROD_OUT_ENERGY] = contact_energy(&c, m->run.mode, m->x);
    rod_coefficient_outputs(&m->params, m->x, m->out);
    m->mean_out[MEAN_F_N] = m->means_held ? m->step_mean[MEAN_F_N] : m->out[ROD_OUT_F_N];
    m->mean_out[MEAN_F_T] = m->means_held ? m->step_mean[MEAN_F_T] : m->out[ROD_OUT_F_T];
    m->stale = false;
}

/* The centre of mass's velocity in the paper's units (l = 1): vy = w + phi cos(theta),
 * vx = v + phi sin(theta). */
static void centre_velocity(const Model *m, double v_cm[2])
{
    v_cm[CM_VY] = m->x[ROD_W] + m->x[ROD_PHI] * cos(m->x[ROD_THETA]);
    v_cm[CM_VX] = m->x[ROD_V] + m->x[ROD_PHI] * sin(m->x[ROD_THETA]);
}

/* The contact's own scales: y ~ eps^2, w ~ eps. */
void model_get_nominals(const Model *m, double nominal[MODEL_NX])
{
    const Contact c = rod_contact(&m->params);
    c.body->nominals(c.params, c.law.epsilon, nominal);
}

void model_step_begin(Model *m, double time)
{
    (void)time;
    centre_velocity(m, m->step_start);   /* the momentum the step's impulses change */
}

void model_derivatives_at(const Model *m, double time, const double x[MODEL_NX], double dx[MODEL_NX])
{
    (void)time;
    const Contact c = rod_contact(&m->params);
    contact_derivatives(&c, m->run.mode, x, dx);
}

void model_indicators_at(const Model *m, double time, const double x[MODEL_NX], double z[])
{
    (void)time;
    const Contact c = rod_contact(&m->params);
    contact_event_indicators(&c, m->run.mode, x, z);
}

void model_jacobian_at(const Model *m, double time, const double x[MODEL_NX], double J[MODEL_NX][MODEL_NX])
{
    (void)time;
    rod_jacobian(&m->params, m->run.mode, x, J);
}

/* ------------------------------------------------------- modes, events */

void model_decide_initial_mode(Model *m)
{
    const Contact c = rod_contact(&m->params);
    m->run.mode = contact_initial_mode(&c, m->x);
    model_touch(m);
}

void model_start(Model *m, double time, char *text, size_t size)
{
    const Contact c = rod_contact(&m->params);
    contact_record_start(&m->run, &c, m->x, time);
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
    const Contact c = rod_contact(&m->params);
    const bool ok = contact_record_event(&m->run, &c, m->x, m->z, time, 1.0, false, e);
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
    m->step_mean[MEAN_F_N] = elapsed > 0 ? (now[CM_VY] - m->step_start[CM_VY]) / elapsed + 1 : 0;
    m->step_mean[MEAN_F_T] = elapsed > 0 ? -(now[CM_VX] - m->step_start[CM_VX]) / elapsed : 0;
    m->means_held = true;
    model_touch(m);
}

/* ------------------------------------------------ partial derivatives */

/* The column of known vr in RodPartials: a state's (ROD_X ...), a parameter's (ROD_P_*);
 * -1 for any other variable. */
static int known_column(unsigned int vr, bool *by_state)
{
    *by_state = vr >= VR_X && vr <= VR_PHI;
    if (*by_state) return (int)(vr - VR_X);
    switch (vr) {
    case VR_ALPHA: return ROD_P_ALPHA;
    case VR_MU: return ROD_P_MU;
    case VR_DELTA: return ROD_P_DELTA;
    case VR_EPSILON: return ROD_P_EPSILON;
    case VR_KAPPA: return ROD_P_KAPPA;
    case VR_BETA: return ROD_P_BETA;
    default: return -1;
    }
}

/* The row of calculated unknown vr in RodPartials: a derivative's in dx_* (*in_dx), an
 * output's (ROD_OUT_*) in out_*; -1 for any other variable. */
static int unknown_row(unsigned int vr, bool *in_dx)
{
    *in_dx = vr >= VR_DER_X && vr <= VR_DER_PHI;
    if (*in_dx) return (int)(vr - VR_DER_X);
    if (vr >= VR_F_N && vr <= VR_ENERGY) return ROD_OUT_F_N + (int)(vr - VR_F_N);
    if (vr >= VR_A && vr <= VR_S_W) return ROD_OUT_A + (int)(vr - VR_A);
    return -1;
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
    bool by_state, in_dx;
    const int col = known_column(known, &by_state), row = unknown_row(unknown, &in_dx);
    if (col < 0) return "the known is not a variable the rod's partial derivatives know";
    if (row < 0) return "the unknown is not a variable the rod's partial derivatives know";
    const RodPartials *d = &m->partials;
    if (in_dx) *value = by_state ? d->dx_x[row][col] : d->dx_p[row][col];
    else *value = by_state ? d->out_x[row][col] : d->out_p[row][col];
    return NULL;
}

/* ------------------------------------------------------ FMU state fields */

const char *model_internals_implausible(const Model *m)
{
    if (!isfinite(m->step_mean[MEAN_F_N])) return "step_mean_F_N";
    if (!isfinite(m->step_mean[MEAN_F_T])) return "step_mean_F_T";
    if (!isfinite(m->step_start[CM_VY])) return "step_vy_cm";
    if (!isfinite(m->step_start[CM_VX])) return "step_vx_cm";
    return contact_record_implausible(&m->run);
}
