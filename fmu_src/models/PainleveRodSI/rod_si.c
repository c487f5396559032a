/* SPDX-License-Identifier: BSD-2-Clause */
/* PainleveRodSI on the model interface (model.h): the rod of rod.c in SI
 * units, driven by a moving floor and applied loads (docs/si_model.md).
 *
 * The model keeps SI states: the contact end (x, y), its velocity (v, w), theta
 * and phi. Everything physical is evaluated by rod.c on the paper's
 * dimensionless rod in the floor's frame: with the length l, the time
 * T = sqrt(l/g), the speed U = sqrt(g l) and the force m g,
 *   xs = (x/l, (v - v_floor)/U, (y - y_floor)/l, (w - w_floor)/U, theta, phi T),
 *   alpha = m l^2/J, epsilon = sqrt(m g/(k l)), delta = c/sqrt(m k),
 *   loads f_x = F_x/(m g), f_y = F_y/(m g), tau/(m g l).
 * The floor moves vertically with the inputs y_floor, w_floor (in
 * Co-Simulation, between the instants the master sets y_floor, on at w_floor
 * from where it put it: a first-order hold, so a step sees a floor that moves,
 * not a staircase) and horizontally at the belt speed v_floor, piecewise
 * constant (a jump is an event), so the
 * floor's frame is inertial horizontally: v' = g v_s' and, sticking, v = v_floor
 * exactly. Vertically the floor enters only through the gap and the relative
 * velocity of the contact law, so w' = g w_s' whatever the floor's acceleration. */
#include "model.h"

#include <math.h>
#include <string.h>

#include "model_dependencies.h"
#include "rod_si_partials.h"
#include "si_floor.h"

/* ------------------------------------------------------------ scaling */

typedef struct {
    double scale[ROD_NX];  /* x_j = offset_j + scale_j xs_j */
    double offset[ROD_NX];
    double rate[ROD_NX];   /* der(x_j) = rate_j der(xs_j) for v, w, phi: g, g, g/l */
} Scaling;

/* The floor's height at `time`: y_floor, moved on at w_floor since it was set. */
static double floor_height(const Model *m, double time)
{
    return m->y_floor + m->w_floor * si_floor_elapsed(m, time);
}

static Scaling scaling(const Model *m, double time)
{
    const double U = sqrt(m->g * m->l), per_T = sqrt(m->g / m->l);
    return (Scaling){ .scale = { m->l, U, m->l, U, 1, per_T },
                      .offset = { 0, m->v_floor, floor_height(m, time), m->w_floor, 0, 0 },
                      .rate = { 0, m->g, 0, m->g, 0, m->g / m->l } };
}

static RodParams rod_params(const Model *m)
{
    const double mg = m->m * m->g;
    return (RodParams){ .alpha = m->m * m->l * m->l / m->J, .mu = m->mu, .delta = m->c / sqrt(m->m * m->k),
                        .epsilon = sqrt(mg / (m->k * m->l)), .kappa = 0, .beta = 0,
                        .f_x = m->F_x / mg, .f_y = m->F_y / mg, .tau = m->tau / (mg * m->l) };
}

/* The rod's view of an SI state x: the scaling, the rod's parameters and the scaled state. */
typedef struct {
    Scaling s;
    RodParams p;
    double xs[ROD_NX];
} RodView;

static RodView rod_view(const Model *m, double time, const double x[ROD_NX])
{
    RodView v = { .s = scaling(m, time), .p = rod_params(m) };
    for (int j = 0; j < ROD_NX; ++j) v.xs[j] = (x[j] - v.s.offset[j]) / v.s.scale[j];
    return v;
}

/* The SI right-hand side from the rod's: der(x) = v, der(y) = w, der(theta) = phi
 * in the ground's frame, accelerations scaled. */
static void derivatives(const Model *m, const RodView *r, const double x[ROD_NX], double dx[ROD_NX])
{
    double dxs[ROD_NX];
    const Contact c = rod_contact(&r->p);
    contact_derivatives(&c, m->run.mode, r->xs, dxs);
    dx[ROD_X] = x[ROD_V];
    dx[ROD_Y] = x[ROD_W];
    dx[ROD_THETA] = x[ROD_PHI];
    for (int j = ROD_V; j <= ROD_PHI; j += 2) dx[j] = r->s.rate[j] * dxs[j];
}

/* ------------------------------------------------------------ variables */

void model_reset(Model *m)
{
    /* A uniform rod of 1 kg and 1 m (alpha = 3) on a stiff, damped floor with mu = 3:
     * epsilon ~ 1e-3, delta ~ 1, the paper's Theorem 1 regime. */
    *m = (Model){ .m = 1, .l = 0.5, .J = 1.0 / 12, .g = 9.81, .k = 2e7, .c = 4500, .mu = 3,
                  .x = { [ROD_X] = 0, [ROD_V] = 2, [ROD_Y] = 0, [ROD_W] = 0, [ROD_THETA] = 1, [ROD_PHI] = 2 },
                  .run = contact_record_new(),
                  .stale = true,
                  .partials_stale = true };
}

/* Mechanical energy in the ground's frame plus the contact spring's while it
 * pushes: 1/2 m |V_cm|^2 + 1/2 J phi^2 + m g y_cm + 1/2 k gap^2. */
static void outputs(Model *m)
{
    const double *x = m->x, l = m->l, sn = sin(x[ROD_THETA]), cs = cos(x[ROD_THETA]), phi = x[ROD_PHI];
    const double mg = m->m * m->g, gap = x[ROD_Y] - floor_height(m, m->time);
    double *out = m->out;
    const Contact c = rod_contact(&m->rod);
    out[SI_F_N] = mg * contact_normal_force(&c, m->run.mode, m->xs);
    out[SI_F_T] = mg * contact_friction_force(&c, m->run.mode, m->xs);
    out[SI_X_CM] = x[ROD_X] - l * cs;
    out[SI_Y_CM] = x[ROD_Y] + l * sn;
    out[SI_VX_CM] = x[ROD_V] + l * phi * sn;
    out[SI_VY_CM] = x[ROD_W] + l * phi * cs;
    out[SI_GAP] = gap;
    out[SI_SLIP] = x[ROD_V] - m->v_floor;
    const double spring = m->run.mode.contact ? 0.5 * m->k * gap * gap : 0.0;
    out[SI_ENERGY] = 0.5 * m->m * (out[SI_VX_CM] * out[SI_VX_CM] + out[SI_VY_CM] * out[SI_VY_CM]) +
                     0.5 * m->J * phi * phi + mg * out[SI_Y_CM] + spring;
    double coefficients[ROD_NOUT];   /* the paper's scaled form, in the floor's frame */
    rod_coefficient_outputs(&m->rod, m->xs, coefficients);
    for (int i = ROD_OUT_A; i <= ROD_OUT_S_W; ++i) out[SI_A + i - ROD_OUT_A] = coefficients[i];
    out[SI_F_N_MEAN] = m->means_held ? m->step_mean[SI_MEAN_F_N] : out[SI_F_N];
    out[SI_F_T_MEAN] = m->means_held ? m->step_mean[SI_MEAN_F_T] : out[SI_F_T];
}

/* The velocity of the centre of mass, vy_cm = w + l phi cos(theta) and vx_cm = v + l phi sin(theta). */
static void centre_velocity(const Model *m, double v_cm[2])
{
    const double *x = m->x, lphi = m->l * x[ROD_PHI];
    v_cm[SI_CM_VY] = x[ROD_W] + lphi * cos(x[ROD_THETA]);
    v_cm[SI_CM_VX] = x[ROD_V] + lphi * sin(x[ROD_THETA]);
}

void model_update(Model *m)
{
    if (!m->stale) return;
    const RodView r = rod_view(m, m->time, m->x);
    m->rod = r.p;
    memcpy(m->xs, r.xs, sizeof m->xs);
    derivatives(m, &r, m->x, m->dx);
    const Contact c = rod_contact(&m->rod);
    contact_event_indicators(&c, m->run.mode, m->xs, m->z);
    outputs(m);
    m->stale = false;
}

void model_get_nominals(const Model *m, double nominal[MODEL_NX])
{
    const RodView r = rod_view(m, m->time, m->x);
    const Contact c = rod_contact(&r.p);
    c.body->nominals(c.params, c.law.epsilon, nominal);
    for (int j = 0; j < ROD_NX; ++j) nominal[j] *= r.s.scale[j];
}

void model_set_time(Model *m, double time)
{
    if (time == m->time) return;
    m->time = time;
    if (m->floor_moves && m->w_floor != 0) model_touch(m);   /* the floor has moved */
}

/* Setting y_floor puts the floor there now; a moving floor then jumps back to it. */
bool model_input_set(Model *m, unsigned int vr, double time)
{
    if (vr != VR_Y_FLOOR) return false;
    const bool moved = si_floor_elapsed(m, time) != 0 && m->w_floor != 0;
    m->t_floor = time;
    model_touch(m);
    return moved;
}

void model_step_begin(Model *m, double time)
{
    (void)time;
    m->floor_moves = true;
    centre_velocity(m, m->step_start);   /* the momentum the step's impulses change */
    model_touch(m);
}

void model_derivatives_at(const Model *m, double time, const double x[MODEL_NX], double dx[MODEL_NX])
{
    const RodView r = rod_view(m, time, x);
    derivatives(m, &r, x, dx);
}

void model_indicators_at(const Model *m, double time, const double x[MODEL_NX], double z[])
{
    const RodView r = rod_view(m, time, x);
    const Contact c = rod_contact(&r.p);
    contact_event_indicators(&c, m->run.mode, r.xs, z);
}

/* d der(x_i)/d x_j = rate_i J_s[i][j]/scale_j for the accelerations (v, w, phi:
 * the odd rows); the kinematic rows der(x) = v, der(y) = w, der(theta) = phi. */
void model_jacobian_at(const Model *m, double time, const double x[MODEL_NX], double J[MODEL_NX][MODEL_NX])
{
    const RodView r = rod_view(m, time, x);
    rod_jacobian(&r.p, m->run.mode, r.xs, J);
    for (int i = 0; i < ROD_NX; ++i)
        for (int j = 0; j < ROD_NX; ++j) J[i][j] = (i % 2 ? r.s.rate[i] * J[i][j] / r.s.scale[j] : 0);
    J[ROD_X][ROD_V] = J[ROD_Y][ROD_W] = J[ROD_THETA][ROD_PHI] = 1;
}

/* ------------------------------------------- step means (Co-Simulation) */

/* The floor's impulses over the step are what the rod's momentum says it received
 * (si_model.md, Momentum): m dvy_cm = (F_y - m g) h + int F_N, m dvx_cm = F_x h - int F_T,
 * the loads held over the step. The solver integrated the forces into the momentum, so
 * a coupled floor that takes these impulses conserves the momentum of the two bodies to
 * rounding (a separate quadrature of F_N would differ from it by the solver's error). */
void model_step_end(Model *m, double elapsed)
{
    double now[2];
    centre_velocity(m, now);
    const double dvy = now[SI_CM_VY] - m->step_start[SI_CM_VY], dvx = now[SI_CM_VX] - m->step_start[SI_CM_VX];
    m->step_mean[SI_MEAN_F_N] = elapsed > 0 ? m->m * dvy / elapsed + m->m * m->g - m->F_y : 0;
    m->step_mean[SI_MEAN_F_T] = elapsed > 0 ? m->F_x - m->m * dvx / elapsed : 0;
    m->means_held = true;
    model_touch(m);
}

/* ------------------------------------- closed-form flight (model.h) */

/* Free of the floor (which enters only the gap and the contact law), the rod's centre falls
 * at (F_x/m, F_y/m - g) and it turns at tau/J, the loads held over the step (they change
 * only at communication points, where the integrator restarts). */
bool model_flight_begin(const Model *m, double t0, const double x0[MODEL_NX], ModelFlight *f)
{
    if (m->run.mode.contact) return false;
    *f = rod_flight(m->l, m->F_x / m->m, m->F_y / m->m - m->g, m->tau / m->J, t0, x0);
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

/* ------------------------------------------------------- modes, events */

void model_decide_initial_mode(Model *m)
{
    model_update(m);
    const Contact c = rod_contact(&m->rod);
    m->run.mode = contact_initial_mode(&c, m->xs);
    model_touch(m);
}

void model_start(Model *m, double time, char *text, size_t size)
{
    model_update(m);
    const Contact c = rod_contact(&m->rod);
    contact_record_start(&m->run, &c, m->xs, time);
    m->v_floor_decided = m->v_floor;
    m->time = m->t_floor = time;   /* the floor is where y_floor says at the start */
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
    const Scaling s = scaling(m, m->time);
    double xs[ROD_NX];
    memcpy(xs, m->xs, sizeof xs);
    /* A belt that changed speed leaves the rod's own velocity as it was. */
    const bool belt_jumped = m->v_floor != m->v_floor_decided;
    m->v_floor_decided = m->v_floor;
    const Contact c = rod_contact(&m->rod);
    const bool ok = contact_record_event(&m->run, &c, xs, m->z, time, sqrt(m->l / m->g), belt_jumped, e);
    /* Only what the event moved changes (v = v_floor exactly when a stick begins). */
    for (int j = 0; j < ROD_NX; ++j)
        if (xs[j] != m->xs[j]) m->x[j] = s.offset[j] + s.scale[j] * xs[j];
    model_touch(m);
    return ok;
}

/* ------------------------------------------------ partial derivatives */

const char *model_calculated_partial(Model *m, unsigned int unknown, unsigned int known, double *value)
{
    /* A step mean is the past's in Co-Simulation (nothing now moves it); in Model
     * Exchange it is the force itself, with the force's partials. */
    if (unknown == VR_F_N_MEAN || unknown == VR_F_T_MEAN) {
        if (m->means_held) {
            *value = 0;
            return NULL;
        }
        unknown = unknown == VR_F_N_MEAN ? VR_F_N : VR_F_T;
    }
    /* A pair the model description does not declare is 0 by the structure of the
     * equations; the chain rule below would give round-off there. */
    if (!model_depends(unknown, known)) {
        *value = 0;
        return NULL;
    }
    model_update(m);
    if (m->partials_stale) {
        rod_partials(&m->rod, m->run.mode, m->xs, &m->partials);
        m->partials_stale = false;
    }
    return si_partial(m, unknown, known, value);
}

/* ------------------------------------------------------ FMU state fields */

const char *model_internals_implausible(const Model *m)
{
    if (!isfinite(m->v_floor_decided)) return "v_floor_decided";
    if (!isfinite(m->t_floor) || !isfinite(m->time)) return "t_floor";
    if (!isfinite(m->step_mean[SI_MEAN_F_N])) return "step_mean_F_N";
    if (!isfinite(m->step_mean[SI_MEAN_F_T])) return "step_mean_F_T";
    if (!isfinite(m->step_start[SI_CM_VY])) return "step_vy_cm";
    if (!isfinite(m->step_start[SI_CM_VX])) return "step_vx_cm";
    return contact_record_implausible(&m->run);
}
