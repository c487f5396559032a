/* SPDX-License-Identifier: BSD-2-Clause */
/* The contact core over a body (contact.h): forces, the right-hand side of each
 * mode, event indicators and the mode decision.
 *
 * Modes are discrete states that change only at events, so the right-hand
 * side is smooth between events (docs/model.md §2):
 *   contact  F_N = h/eps with h = h(y/eps, w) the compliance law
 *   slip     s = +1 / -1: u' = u'_free + (M^-1 W_N^T - s mu M^-1 W_T^T) F_N (eq Painleve)
 *   stick    s = 0: the exact Filippov field, F_T = (a + G_TN F_N)/G_TT holds v' = 0
 * Event indicators (slot: meaning per mode):
 *   0  y                       contact surface
 *   1  max(h, eps h')  (contact) F_N = 0 where the free motion leaves it too (h' of F_N = 0)
 *      min(-y/eps, h)  (flight)  both conditions of contact hold: h alone would also
 *                                cross 0 above the floor (y = -eps delta w > 0), where
 *                                nothing switches
 *   2  v            (slipping) reversal or stick
 *      +1           (flight)   nothing to watch: the slip label follows v at each event
 *      a + q_+ F_N  (sticking) forward fold of Lemma lemma:nonStick, < 0 inside
 *   3  a + q_- F_N  (sticking) backward fold, > 0 inside
 *      w            (flight)   bottom of a dip: makes a grazing contact that
 *                              falls inside one solver step change a sign once
 *      -1           (slipping in contact) nothing to watch */
#include "contact.h"

#include <float.h>
#include <math.h>

static int sign_of(double f) { return (f > 0) - (f < 0); }

/* Sign of f0, or of the first nonzero derivative after it: decides the side
 * of a switching surface for a state that sits exactly on it. */
static int lex_sign(double f0, double f1, double f2)
{
    if (f0 != 0) return sign_of(f0);
    if (f1 != 0) return sign_of(f1);
    return sign_of(f2);
}

static bool sticking(ContactMode m) { return m.contact && m.slip == 0; }

static double force_noise(const ContactLaw *law, const BodyState *s);
static double free_h_rate(const Compliance *h, const BodyState *s, double eps);

Compliance contact_compliance(const ContactLaw *law, double y, double w)
{
    /* Written so that kappa = beta = 0 evaluates -y/eps - delta w in the same
     * operations as the linear law (results bit for bit unchanged). */
    const double yh = y / law->epsilon, d = yh < 0 ? -yh : 0.0;
    const double damping = law->delta * (1 + law->beta * d);
    Compliance c;
    c.h = (-yh + law->kappa * d * d) - damping * w;
    c.h_yh = d > 0 ? -(1 + 2 * law->kappa * d - law->delta * law->beta * w) : -1.0;
    c.h_w = -damping;
    return c;
}

double contact_spring_energy(const ContactLaw *law, double y)
{
    const double d = -(y / law->epsilon), dp = d > 0 ? d : 0.0;
    return 0.5 * d * d + law->kappa * dp * dp * dp / 3;
}

BodyState contact_body(const Contact *c, const double x[])
{
    BodyState s = { 0 };
    c->body->evaluate(c->params, x, &s);
    return s;
}

bool contact_gap_rows(const Contact *c, const double x[], ContactGapRows *r)
{
    const Body *b = c->body;
    if (!b->gap_rows) return false;
    double dy_dq[BODY_MAX_DOF], dw_dq[BODY_MAX_DOF];
    *r = (ContactGapRows){ .y_scale = c->law.epsilon * c->law.epsilon, .w_scale = c->law.epsilon };
    b->gap_rows(c->params, x, &r->y_value, &r->w_value, dy_dq, dw_dq);
    for (int i = 0; i < b->dof; ++i) {
        r->y[b->position[i]] = b->has_gap_state ? 0.0 : dy_dq[i];   /* y moves with its own state alone */
        r->w[b->position[i]] = dw_dq[i];
        r->w[b->velocity[i]] = dy_dq[i];
    }
    if (b->has_gap_state) r->y[b->gap_state] = 1;
    return true;
}

/* num/G_TT, 0 where G_TT = 0: a contact point that cannot slip at all (W_T = 0, so G_TN = 0
 * too) has no sticking friction to find; a body with G_TT > 0 (the rod: G_TT >= 1) never comes here. */
static double per_G_TT(double num, const BodyState *s)
{
    return s->G_TT > 0 ? num / s->G_TT : 0.0;
}

ContactCoeffs contact_coeffs(const ContactLaw *law, const BodyState *s)
{
    const double mu = law->mu;
    return (ContactCoeffs){ .a = s->a, .b = s->b,
                            .q_plus = s->G_TN - mu * s->G_TT, .q_minus = s->G_TN + mu * s->G_TT,
                            .p_plus = s->G_NN - mu * s->G_TN, .p_minus = s->G_NN + mu * s->G_TN,
                            .S_w = s->G_NN - per_G_TT(s->G_TN * s->G_TN, s) };
}

double contact_time_scale(const Contact *c, const double x[])
{
    const BodyState s = contact_body(c, x);
    const ContactCoeffs k = contact_coeffs(&c->law, &s);
    const Compliance h = contact_compliance(&c->law, s.y, s.w);
    const double P = fmax(fmax(fabs(k.p_plus), fabs(k.p_minus)), fabs(k.S_w));
    const double rate = P * fabs(h.h_w) + sqrt(P * fabs(h.h_yh));
    return rate > 0 ? c->law.epsilon / rate : INFINITY;   /* nothing responds (or a NaN state) */
}

bool contact_fast_growth(const Contact *c, ContactMode m, const double x[])
{
    if (!m.contact || m.slip == 0) return false;
    const BodyState s = contact_body(c, x);
    const ContactCoeffs k = contact_coeffs(&c->law, &s);
    return (m.slip > 0 ? k.p_plus : k.p_minus) < 0;
}

static double normal_force(const Contact *c, ContactMode m, const BodyState *s)
{
    return m.contact ? contact_compliance(&c->law, s->y, s->w).h / c->law.epsilon : 0.0;
}

double contact_normal_force(const Contact *c, ContactMode m, const double x[])
{
    const BodyState s = contact_body(c, x);
    return normal_force(c, m, &s);
}

/* eq dynrodsc with v' = 0: the friction that holds the contact point. */
static double sticking_friction(const BodyState *s, double F)
{
    return per_G_TT(s->a + s->G_TN * F, s);
}

static double friction_force(const Contact *c, ContactMode m, const BodyState *s)
{
    if (!m.contact) return 0.0;
    const double F = normal_force(c, m, s);
    if (m.slip != 0) return m.slip * c->law.mu * F;
    return sticking_friction(s, F);
}

double contact_friction_force(const Contact *c, ContactMode m, const double x[])
{
    const BodyState s = contact_body(c, x);
    return friction_force(c, m, &s);
}

double contact_energy(const Contact *c, ContactMode m, const double x[])
{
    /* The spring holds energy only while it pushes: after a damped lift-off below
     * the floor (y < 0, F_N = 0) its d^2/2 + kappa d^3/3 has gone to the damper. */
    const BodyState s = contact_body(c, x);
    const double spring = m.contact ? contact_spring_energy(&c->law, s.y) : 0.0;
    return s.energy + spring;
}

int contact_nx(const Body *b)
{
    return 2 * b->dof + (b->has_gap_state ? 1 : 0);
}

/* u_i' in mode m: free part plus the contact forces' (the friction opposes slip s, or holds
 * v' = 0 while sticking: the Filippov combination of the two slip fields, with which
 * F_T v = 0 and only the damper works; docs/model.md §1). */
void contact_derivatives(const Contact *c, ContactMode m, const double x[], double dx[])
{
    const Body *b = c->body;
    const BodyState s = contact_body(c, x);
    if (b->has_gap_state) dx[b->gap_state] = s.w;
    const double F = normal_force(c, m, &s);
    const double F_T = sticking(m) ? sticking_friction(&s, F) : 0.0;
    const double smu = (m.slip >= 0 ? 1.0 : -1.0) * c->law.mu;   /* slip 0 out of contact: F = 0 */
    for (int i = 0; i < b->dof; ++i) {
        dx[b->position[i]] = x[b->velocity[i]];
        if (!sticking(m))
            dx[b->velocity[i]] = s.free[i] + (s.normal[i] - smu * s.friction[i]) * F;
        else if (i == b->slip_coordinate)
            dx[b->velocity[i]] = 0;   /* v' = 0 exactly on the sticking set */
        else
            dx[b->velocity[i]] = s.free[i] + s.normal[i] * F - s.friction[i] * F_T;
    }
}

void contact_jacobian_differences(const Contact *c, ContactMode m, const double x[], double J[])
{
    const int n = contact_nx(c->body);
    double nominal[CONTACT_MAX_NX], trial[CONTACT_MAX_NX], up[CONTACT_MAX_NX], down[CONTACT_MAX_NX];
    c->body->nominals(c->params, c->law.epsilon, nominal);
    for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) trial[k] = x[k];
        /* a step of 1e-6 of the state's scale: the contact's y ~ eps^2 is the finest */
        const double h = 1e-6 * fmax(nominal[j], fabs(x[j]));
        trial[j] = x[j] + h;
        contact_derivatives(c, m, trial, up);
        trial[j] = x[j] - h;
        contact_derivatives(c, m, trial, down);
        for (int i = 0; i < n; ++i) J[i * n + j] = (up[i] - down[i]) / (2 * h);
    }
}

/* h' of the free motion (F_N = 0), the same from either side of F_N = 0. */
static double free_h_rate(const Compliance *h, const BodyState *s, double eps)
{
    return h->h_yh * (s->w / eps) + h->h_w * s->b;
}

/* The contact's F_N = 0 indicator: contact goes on while h > 0, or while the free motion
 * would at once re-enter it (h' > 0, in_contact's rule), so it ends where both fail;
 * eps h' has h's units (eps is the contact's time scale). */
static double contact_goes_on(const Compliance *h, const BodyState *s, double eps)
{
    return fmax(h->h, eps * free_h_rate(h, s, eps));
}

void contact_event_indicators(const Contact *c, ContactMode m, const double x[], double z[CONTACT_NZ])
{
    const BodyState s = contact_body(c, x);
    const Compliance h = contact_compliance(&c->law, s.y, s.w);
    z[CONTACT_Z_Y] = s.y;
    z[CONTACT_Z_FORCE] = m.contact ? contact_goes_on(&h, &s, c->law.epsilon) : fmin(-s.y / c->law.epsilon, h.h);
    if (sticking(m)) {
        const ContactCoeffs k = contact_coeffs(&c->law, &s);
        const double F = normal_force(c, m, &s);
        z[CONTACT_Z_SLIP] = k.a + k.q_plus * F;
        z[CONTACT_Z_AUX] = k.a + k.q_minus * F;
    } else {
        z[CONTACT_Z_SLIP] = m.contact ? s.v : 1.0;   /* in flight v switches nothing: no friction acts */
        z[CONTACT_Z_AUX] = m.contact ? -1.0 : s.w;
    }
}

/* The rounding error of each indicator as computed at x: a few ulps of the
 * largest term it sums, plus what the body says of its own y, w, v. An indicator
 * within it of 0 is on its surface, since its sign there is the rounding's
 * (h = -y/eps + kappa d^2 - delta w (1 + beta d) cancels terms of 1e4 and more deep in
 * the floor: a sign that flips with the last bit of y). */
#define NOISE_ULPS (8 * DBL_EPSILON)

static double force_noise(const ContactLaw *law, const BodyState *s)
{
    const double yh = s->y / law->epsilon, d = yh < 0 ? -yh : 0.0, damping = law->delta * (1 + law->beta * d);
    return NOISE_ULPS * (fabs(yh) + law->kappa * d * d + fabs(damping * s->w)) +
           (s->y_noise / law->epsilon + damping * s->w_noise);
}

void contact_indicator_noise(const Contact *c, ContactMode m, const double x[], double noise[CONTACT_NZ])
{
    const BodyState s = contact_body(c, x);
    noise[CONTACT_Z_Y] = s.y_noise;
    const double eps = c->law.epsilon;
    const Compliance h = contact_compliance(&c->law, s.y, s.w);
    noise[CONTACT_Z_FORCE] = force_noise(&c->law, &s);
    if (!m.contact && -s.y / eps <= h.h)
        noise[CONTACT_Z_FORCE] = s.y_noise / eps;   /* flight's min(-y/eps, h) is -y/eps */
    if (m.contact && eps * free_h_rate(&h, &s, eps) > h.h)   /* contact's max(h, eps h') is eps h' */
        noise[CONTACT_Z_FORCE] = NOISE_ULPS * (fabs(h.h_yh * s.w) + eps * fabs(h.h_w * s.b)) +
                                 fabs(h.h_yh) * s.w_noise;
    noise[CONTACT_Z_SLIP] = m.contact ? s.v_noise : 0;
    noise[CONTACT_Z_AUX] = m.contact ? 0 : s.w_noise;
    if (sticking(m)) {
        const ContactCoeffs k = contact_coeffs(&c->law, &s);
        const double F = fabs(normal_force(c, m, &s));
        noise[CONTACT_Z_SLIP] = NOISE_ULPS * (s.a_scale + fabs(k.q_plus) * F);
        noise[CONTACT_Z_AUX] = NOISE_ULPS * (s.a_scale + fabs(k.q_minus) * F);
    }
}

const char *contact_indicator_name(ContactMode m, int i)
{
    const bool stick = sticking(m);
    switch (i) {
    case CONTACT_Z_Y: return "y";
    case CONTACT_Z_FORCE: return m.contact ? "h(y/eps, w) (F_N = 0)" : "min(-y/eps, h) (contact ahead)";
    case CONTACT_Z_SLIP: return stick ? "a + q_+ F_N (forward fold)" : m.contact ? "v" : "none";
    case CONTACT_Z_AUX: return stick ? "a + q_- F_N (backward fold)" : m.contact ? "none" : "w (dip bottom)";
    default: return "?";
    }
}

/* Contact iff y <= 0 and h > 0 (eq FN), ties broken by the free motion
 * y'' = b, so a body at rest on y = 0 and pushed down by b < 0 is in contact:
 * h' = h_yh w/eps + h_w b, h'' = h_yh b/eps to leading order. On F_N = 0 this keeps a
 * contact whose free motion would at once re-enter it (h' > 0): the motion goes on along
 * the surface in contact instead of chattering across it. */
static bool in_contact(const ContactLaw *law, const BodyState *s, ContactSurfaces on)
{
    BodyState at = *s;   /* on a surface, at it */
    if (on.gap || fabs(s->y) <= s->y_noise) at.y = 0;
    if (on.still) at.w = 0;
    const double eps = law->epsilon;
    const Compliance h = contact_compliance(law, at.y, at.w);
    const double h0 = on.force || fabs(h.h) <= force_noise(law, s) ? 0.0 : h.h;   /* on F_N = 0: decided by h' */
    return lex_sign(at.y, at.w, at.b) < 0 && lex_sign(h0, free_h_rate(&h, &at, eps), h.h_yh * (at.b / eps)) > 0;
}

/* Slip direction at v = 0 in contact: stick inside the Filippov cone
 * a + q_+ F_N < 0 < a + q_- F_N (eq filineq), else the side v' points to. */
static int decide_at_rest(const ContactCoeffs *k, double F)
{
    const double fwd = k->a + k->q_plus * F, bwd = k->a + k->q_minus * F;
    if (fwd < 0 && bwd > 0) return 0;
    return fwd >= 0 ? +1 : -1;
}

/* v, or 0 within its rounding error (a body whose v is not a state cannot hold it at 0 exactly). */
static double slip_speed(const BodyState *s)
{
    return fabs(s->v) > s->v_noise ? s->v : 0.0;
}

/* Stops the slip: v = 0 by the body's own coordinate, else by the friction impulse
 * -v/G_TT along M^-1 W_T^T (the smallest change of the kinetic energy that does it). */
static void stop_slip(const Contact *c, const BodyState *s, double x[])
{
    const Body *b = c->body;
    if (b->slip_coordinate >= 0) {
        x[b->velocity[b->slip_coordinate]] = 0;
        return;
    }
    const double impulse = per_G_TT(s->v, s);
    for (int i = 0; i < b->dof; ++i) x[b->velocity[i]] -= s->friction[i] * impulse;
}

ContactSurfaces contact_surfaces_of(const Contact *c, ContactMode m, const double x[], unsigned crossed, double dt)
{
    const BodyState s = contact_body(c, x);
    const double eps = c->law.epsilon;
    const Compliance h = contact_compliance(&c->law, s.y, s.w);
    /* in flight the force indicator is min(-y/eps, h): the smaller one crossed */
    const bool force = crossed & 1u << CONTACT_Z_FORCE && (m.contact || h.h < -s.y / eps);
    const bool gap = crossed & 1u << CONTACT_Z_Y || (crossed & 1u << CONTACT_Z_FORCE && !force);
    /* on a surface where the root finder could have put it: within the indicator's change over dt */
    return (ContactSurfaces){
        .gap = gap && fabs(s.y) <= fabs(s.w) * dt + s.y_noise,
        .force = force && fabs(h.h) <= fabs(free_h_rate(&h, &s, eps)) * dt + force_noise(&c->law, &s),
    };
}

ContactMode contact_decide_mode(const Contact *c, ContactMode m, double x[], ContactSurfaces on, bool *x_changed)
{
    BodyState s = contact_body(c, x);
    const double v = slip_speed(&s);
    ContactMode n = { in_contact(&c->law, &s, on), m.slip };
    *x_changed = false;
    if (!m.contact || !n.contact) {  /* no friction in flight: s follows v */
        n.slip = v != 0 ? sign_of(v) : (s.a >= 0 ? +1 : -1);
        m.slip = n.slip;
        if (!n.contact) return n;
    }
    if (v != 0 && sign_of(v) == m.slip) return n;   /* still slipping */
    if (v != 0) {                    /* v crossed 0 (or drifted in stick) */
        stop_slip(c, &s, x);
        s = contact_body(c, x);
        *x_changed = true;
    }
    const ContactCoeffs k = contact_coeffs(&c->law, &s);
    n.slip = decide_at_rest(&k, normal_force(c, n, &s));
    return n;
}
