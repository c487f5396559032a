/* SPDX-License-Identifier: BSD-2-Clause */
/* TwoLinkArm on the model interface (model.h): the arm of arm_body.c in SI units over
 * the contact core (contact.c, contact_events.c, contact_record.c). Knows the arm,
 * not FMI.
 *
 * The model keeps SI states (theta1, theta2 in rad, omega1, omega2 in rad/s, the tip's
 * height y in m, calculated from the angles until the start and integrated after it);
 * the core runs on the scaled arm, exactly as PainleveRodSI's rod with m -> M and
 * l -> L: the reference length L = l1 + l2, mass M = m1 + m2, time T = sqrt(L/g),
 * force M g, so
 *   xs = (theta1, theta2, omega1 T, omega2 T, y / L),
 *   epsilon = sqrt(M g/(k L)), delta = c/sqrt(M k)   (docs/general_body.md). */
#include "model.h"

#include <math.h>
#include <string.h>

/* ------------------------------------------------------------ scaling */

static double time_unit(const Model *m) { return sqrt((m->l1 + m->l2) / m->g); }

/* The speed unit L/T = sqrt(g L): of the output w and of der(y), which are then the same bits. */
static double speed_unit(const Model *m) { return sqrt(m->g * (m->l1 + m->l2)); }

/* The scaled arm and contact law of the current parameters. */
static void scaled(const Model *m, ArmBody *b, ContactLaw *law)
{
    const double M = m->m1 + m->m2, L = m->l1 + m->l2, ML2 = M * L * L;
    *b = (ArmBody){ .m1 = m->m1 / M, .l1 = m->l1 / L, .J1 = m->J1 / ML2,
                    .m2 = m->m2 / M, .l2 = m->l2 / L, .J2 = m->J2 / ML2, .H = m->H / L };
    *law = (ContactLaw){ .mu = m->mu, .delta = m->c / sqrt(M * m->k), .epsilon = sqrt(M * m->g / (m->k * L)),
                         .kappa = m->kappa, .beta = m->beta };
}

/* A state's SI value per scaled unit: 1 for an angle, 1/T for a rate, L for the height. */
static void state_units(const Model *m, double unit[ARM_NX])
{
    const double T = time_unit(m);
    unit[ARM_THETA1] = unit[ARM_THETA2] = 1;
    unit[ARM_OMEGA1] = unit[ARM_OMEGA2] = 1 / T;
    unit[ARM_Y] = m->l1 + m->l2;
}

static void scale_state(const Model *m, const double x[ARM_NX], double xs[ARM_NX])
{
    double unit[ARM_NX];
    state_units(m, unit);
    for (int i = 0; i < ARM_NX; ++i) xs[i] = x[i] / unit[i];
}

/* The core on the scaled arm: valid while `b` lives. */
static Contact contact_of(const ArmBody *b, const ContactLaw *law)
{
    return (Contact){ .body = &arm_body, .params = b, .law = *law };
}

/* A trial state x of an embedded integrator, scaled, with the arm and law it is scaled by
 * (the model itself is not changed). */
typedef struct {
    ArmBody body;
    ContactLaw law;
    double xs[ARM_NX];
} Trial;

/* The core on trial state x: valid while `t` lives. */
static Contact contact_at(const Model *m, const double x[ARM_NX], Trial *t)
{
    scaled(m, &t->body, &t->law);
    scale_state(m, x, t->xs);
    return contact_of(&t->body, &t->law);
}

/* der(theta) = omega exactly; der(omega) = 1/T^2 times the scaled omega'; der(y) = w, the scaled
 * rate in speed_unit as the output w, so that der(y) is w to the bit. */
static void derivatives(const Model *m, const Contact *c, const double x[ARM_NX], const double xs[ARM_NX],
                        double dx[ARM_NX])
{
    double dxs[ARM_NX];
    contact_derivatives(c, m->run.mode, xs, dxs);
    const double T = time_unit(m), rate = 1 / T / T;
    dx[ARM_THETA1] = x[ARM_OMEGA1];
    dx[ARM_THETA2] = x[ARM_OMEGA2];
    dx[ARM_OMEGA1] = rate * dxs[ARM_OMEGA1];
    dx[ARM_OMEGA2] = rate * dxs[ARM_OMEGA2];
    dx[ARM_Y] = speed_unit(m) * dxs[ARM_Y];
}

/* ------------------------------------------------------------ variables */

void model_reset(Model *m)
{
    /* Plausible bench-top links (docs/general_body.md): aluminium bars of 0.5 and 0.3 kg, 0.3 and
     * 0.2 m, uniform (J = m l^2/12), a rubber tip (mu = 0.8) on a stiff damped floor (eps = 1e-3,
     * delta = 1 at M = 0.8 kg, L = 0.5 m). The tip starts on the floor (H = the tip's depth below
     * the pivot at theta1 = -1, theta2 = -1.3) slipping forward at 0.2 m/s, w = -8 um/s, where
     * p_plus = -0.79 < 0, q_plus < 0 < q_minus, a > 0 > b: the paradox region, Theorem 1's quadrant. */
    *m = (Model){ .m1 = 0.5, .l1 = 0.3, .J1 = 0.5 * 0.09 / 12, .m2 = 0.3, .l2 = 0.2, .J2 = 0.3 * 0.04 / 12,
                  .H = 0.44515293252580757, .g = 9.81, .k = 1.5696e7, .c = 3543.6, .mu = 0.8, .kappa = 0, .beta = 0,
                  .x = { [ARM_THETA1] = -1.0, [ARM_THETA2] = -1.3, [ARM_OMEGA1] = -0.6035, [ARM_OMEGA2] = 1.8283 },
                  .run = contact_record_new(),
                  .stale = true,
                  .partials_stale = true };
}

/* The tip in SI, the forces (M g), the energy (M g L) and the scaled coefficients. */
static void outputs(Model *m, const Contact *c)
{
    const double M = m->m1 + m->m2, L = m->l1 + m->l2, U = speed_unit(m), Mg = M * m->g;
    const BodyState s = contact_body(c, m->xs);
    const ContactCoeffs k = contact_coeffs(&c->law, &s);
    double *out = m->out;
    out[ARM_OUT_X] = L * s.x;
    out[ARM_OUT_V] = U * s.v;
    out[ARM_OUT_W] = U * s.w;
    out[ARM_OUT_F_N] = Mg * contact_normal_force(c, m->run.mode, m->xs);
    out[ARM_OUT_F_T] = Mg * contact_friction_force(c, m->run.mode, m->xs);
    out[ARM_OUT_ENERGY] = Mg * L * contact_energy(c, m->run.mode, m->xs);
    const double coefficients[] = { k.a, k.b, k.p_plus, k.p_minus, k.q_plus, k.q_minus, k.S_w };
    memcpy(out + ARM_OUT_A, coefficients, sizeof coefficients);
}

void model_update(Model *m)
{
    if (!m->stale) return;
    scaled(m, &m->body, &m->law);
    if (!m->started) m->x[ARM_Y] = (m->l1 + m->l2) * arm_height(&m->body, m->x[ARM_THETA1], m->x[ARM_THETA2]);
    scale_state(m, m->x, m->xs);
    const Contact c = contact_of(&m->body, &m->law);
    derivatives(m, &c, m->x, m->xs, m->dx);
    contact_event_indicators(&c, m->run.mode, m->xs, m->z);
    outputs(m, &c);
    m->stale = false;
}

/* The core's nominals (angles and y eps^2, scaled rates eps), in SI. */
void model_get_nominals(const Model *m, double nominal[MODEL_NX])
{
    ArmBody b;
    ContactLaw law;
    double unit[ARM_NX];
    scaled(m, &b, &law);
    arm_body.nominals(&b, law.epsilon, nominal);
    state_units(m, unit);
    for (int i = 0; i < ARM_NX; ++i) nominal[i] *= unit[i];
}

/* The core's rows over the scaled state, in SI: y = L ys, w = (L/T) ws with rates omega = omegas/T. */
void model_gap_rows_at(const Model *m, double time, const double x[MODEL_NX], ModelGapRows *r)
{
    (void)time;
    Trial t;
    const Contact c = contact_at(m, x, &t);
    ContactGapRows g;
    contact_gap_rows(&c, t.xs, &g);
    const double L = m->l1 + m->l2, T = time_unit(m);
    double unit[ARM_NX];
    state_units(m, unit);
    for (int i = 0; i < ARM_NX; ++i) {
        r->row[0][i] = L * g.y[i] / unit[i];
        r->row[1][i] = L / T * g.w[i] / unit[i];
    }
    r->value[0] = L * g.y_value;
    r->value[1] = L / T * g.w_value;
    r->nominal[0] = L * g.y_scale;
    r->nominal[1] = L / T * g.w_scale;
}

void model_derivatives_at(const Model *m, double time, const double x[MODEL_NX], double dx[MODEL_NX])
{
    (void)time;
    Trial t;
    const Contact c = contact_at(m, x, &t);
    derivatives(m, &c, x, t.xs, dx);
}

void model_indicators_at(const Model *m, double time, const double x[MODEL_NX], double z[])
{
    (void)time;
    Trial t;
    const Contact c = contact_at(m, x, &t);
    contact_event_indicators(&c, m->run.mode, t.xs, z);
}

/* The core's central differences on the scaled arm (the arm has no analytic partials), in
 * SI: d der(x_i)/d x_j = (unit_i / T) J_s[i][j] / unit_j (state_units). */
void model_jacobian_at(const Model *m, double time, const double x[MODEL_NX], double J[MODEL_NX][MODEL_NX])
{
    (void)time;
    Trial t;
    double Js[ARM_NX * ARM_NX], unit[ARM_NX];
    const Contact c = contact_at(m, x, &t);
    contact_jacobian_differences(&c, m->run.mode, t.xs, Js);
    state_units(m, unit);
    const double T = time_unit(m);
    for (int i = 0; i < ARM_NX; ++i)
        for (int j = 0; j < ARM_NX; ++j) J[i][j] = unit[i] / T * Js[i * ARM_NX + j] / unit[j];
}

/* ------------------------------------------------------- modes, events */

void model_decide_initial_mode(Model *m)
{
    model_update(m);
    const Contact c = contact_of(&m->body, &m->law);
    m->run.mode = contact_initial_mode(&c, m->xs);
    model_touch(m);
}

/* What the core changed in the scaled state goes back to the SI one. */
static void unscale_changes(Model *m, const double xs[ARM_NX])
{
    double unit[ARM_NX];
    state_units(m, unit);
    for (int j = 0; j < ARM_NX; ++j)
        if (xs[j] != m->xs[j]) m->x[j] = xs[j] * unit[j];
}

void model_start(Model *m, double time, char *text, size_t size)
{
    model_update(m);
    m->started = true;   /* y, calculated from the angles so far, is integrated from here */
    const Contact c = contact_of(&m->body, &m->law);
    double xs[ARM_NX];
    memcpy(xs, m->xs, sizeof xs);
    contact_record_start(&m->run, &c, xs, time);
    unscale_changes(m, xs);
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
    const Contact c = contact_of(&m->body, &m->law);
    double xs[ARM_NX];
    memcpy(xs, m->xs, sizeof xs);
    const bool ok = contact_record_event(&m->run, &c, xs, m->z, time, time_unit(m), false, e);
    unscale_changes(m, xs);
    model_touch(m);
    return ok;
}

/* ------------------------------------------------------ FMU state fields */

const char *model_internals_implausible(const Model *m)
{
    if (!(fabs(m->x[ARM_Y]) <= ARM_STATE_BOUND)) return "y";
    return contact_record_implausible(&m->run);
}
