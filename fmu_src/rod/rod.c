/* SPDX-License-Identifier: BSD-2-Clause */
/* The compliant Painleve rod (Hogan & Kristiansen) as the contact core's first body.
 *
 * The body (rod_evaluate): generalized coordinates (x, y, theta), the contact end and
 * the angle clockwise from the floor, rates (v, w, phi); in the paper's units (the
 * half-length l, m g, sqrt(l/g)) the contact point is (x, y) itself, W_T = (1, 0, 0),
 * W_N = (0, 1, 0), and eq dynrodsc gives the responses to F_N and F_T in closed form:
 * u' per unit F_N = (G_TN, G_NN, -alpha cos) and per unit F_T (minus) = (G_TT, G_NT,
 * -alpha sin) with G_TT = 1 + alpha sin^2, G_TN = alpha sin cos, G_NN = 1 + alpha cos^2.
 * The core (contact.c) makes the modes, forces, indicators and events from these; the
 * rod keeps its closed forms of eq coeffs and eq Sw (rod_coeffs) and its analytic
 * Jacobian (rod_jacobian, with rod_partials.c's partial derivatives). */
#include "rod.h"

#include <math.h>

/* eq coeffs' a and b, with the applied loads, at sin s and cos c of theta */
static double coeff_a(const RodParams *p, double s, double c, double phi)
{
    return -phi * phi * c + p->f_x - p->alpha * s * p->tau;
}

static double coeff_b(const RodParams *p, double s, double c, double phi)
{
    return -1 + phi * phi * s + p->f_y - p->alpha * c * p->tau;
}

RodCoeffs rod_coeffs(const RodParams *p, double theta, double phi)
{
    const double s = sin(theta), c = cos(theta), al = p->alpha, mu = p->mu;
    const double k = 1 + al * s * s;
    RodCoeffs r;
    r.a = coeff_a(p, s, c, phi);
    r.b = coeff_b(p, s, c, phi);
    r.q_plus = al * s * c - mu * k;
    r.q_minus = al * s * c + mu * k;
    r.p_plus = 1 + al * c * c - mu * al * s * c;
    r.p_minus = 1 + al * c * c + mu * al * s * c;
    r.c_plus = -al * (c - mu * s);
    r.c_minus = -al * (c + mu * s);
    r.S_w = (1 + al) / k;                       /* eq Sw */
    r.S_phi = -al * c / k;
    r.A_w = -al * s * c / k;                    /* the sticking field: see mode_gains */
    r.A_phi = al * s / k;
    return r;
}

/* The reach of the anchored sine and cosine: within it the polynomials below leave a relative
 * truncation error under 1.2e-22 (the first omitted terms, d^11/11! and d^12/12!), so the
 * results are libm's to rounding; the explicit pair's steps turn theta by far less. */
#define ANCHOR_REACH 0.05

void rod_anchor(RodParams *p, double theta, bool anchored)
{
    /* an anchor within half the reach serves a step from theta too: it is kept */
    if (anchored && p->anchored && fabs(theta - p->anchor_theta) < 0.5 * ANCHOR_REACH) return;
    p->anchored = anchored;
    if (!anchored) return;
    p->anchor_theta = theta;
    p->anchor_sin = sin(theta);
    p->anchor_cos = cos(theta);
}

/* sin and cos of th: near the anchor by the angle sum with Taylor polynomials of the small
 * difference (a step's six evaluations then cost one libm call between them), else libm's. */
static void rod_sincos(const RodParams *p, double th, double *sn, double *cs)
{
    const double d = th - p->anchor_theta;
    if (!p->anchored || !(fabs(d) < ANCHOR_REACH)) {
        *sn = sin(th);
        *cs = cos(th);
        return;
    }
    const double d2 = d * d;
    const double sd = d + d * d2 * (-1.0 / 6 + d2 * (1.0 / 120 + d2 * (-1.0 / 5040 + d2 * (1.0 / 362880))));
    const double cd_minus_1 =
        d2 * (-0.5 + d2 * (1.0 / 24 + d2 * (-1.0 / 720 + d2 * (1.0 / 40320 + d2 * (-1.0 / 3628800)))));
    *sn = p->anchor_sin + (p->anchor_sin * cd_minus_1 + p->anchor_cos * sd);
    *cs = p->anchor_cos + (p->anchor_cos * cd_minus_1 - p->anchor_sin * sd);
}

/* The rod body: the contact end and its accelerations without contact force (eq coeffs'
 * a, b; phi' = alpha tau), the responses above, the energy in units of m g l (centre of
 * mass (x - cos theta, y + sin theta), eq coord). v and w are states: exact. */
static void rod_evaluate(const void *params, const double x[], BodyState *s)
{
    const RodParams *p = params;
    const double th = x[ROD_THETA], phi = x[ROD_PHI], al = p->alpha;
    double sn, cs;
    rod_sincos(p, th, &sn, &cs);
    /* a and b from this sin and cos: the right-hand side's hot path needs none of rod_coeffs'
     * other coefficients, nor sin and cos twice */
    const double a = coeff_a(p, sn, cs, phi), b = coeff_b(p, sn, cs, phi);
    const double G_TT = 1 + al * sn * sn, G_TN = al * sn * cs, G_NN = 1 + al * cs * cs;
    /* every field written one by one (a compound literal would clear the whole struct first, a
     * measurable part of the right-hand side's cost) */
    s->x = x[ROD_X], s->y = x[ROD_Y], s->v = x[ROD_V], s->w = x[ROD_W];
    s->y_noise = s->w_noise = s->v_noise = 0;
    s->free[0] = a, s->free[1] = b, s->free[2] = al * p->tau;
    s->normal[0] = G_TN, s->normal[1] = G_NN, s->normal[2] = -al * cs;
    s->friction[0] = G_TT, s->friction[1] = G_TN, s->friction[2] = -al * sn;
    s->a = a, s->b = b;
    s->a_scale = phi * phi * fabs(cs) + fabs(p->f_x) + al * fabs(sn * p->tau);
    s->G_TT = G_TT, s->G_TN = G_TN, s->G_NN = G_NN;
    const double Xd = x[ROD_V] + phi * sn, Yd = x[ROD_W] + phi * cs;
    s->energy = 0.5 * (Xd * Xd + Yd * Yd) + 0.5 * phi * phi / al + (x[ROD_Y] + sn);
}

static void rod_body_nominals(const void *params, double epsilon, double nominal[])
{
    (void)params;
    nominal[ROD_X] = 1;
    nominal[ROD_V] = 1;
    nominal[ROD_Y] = epsilon * epsilon;
    nominal[ROD_W] = epsilon;
    nominal[ROD_THETA] = 1;
    nominal[ROD_PHI] = 1;
}

/* x is the contact point's own coordinate: a stick holds its rate v at exactly 0. */
static const Body ROD_BODY = { .dof = 3, .position = { ROD_X, ROD_Y, ROD_THETA },
                               .velocity = { ROD_V, ROD_W, ROD_PHI }, .slip_coordinate = 0,
                               .evaluate = rod_evaluate, .nominals = rod_body_nominals };

Contact rod_contact(const RodParams *p)
{
    return (Contact){ .body = &ROD_BODY, .params = p,
                      .law = { .mu = p->mu, .delta = p->delta, .epsilon = p->epsilon, .kappa = p->kappa,
                               .beta = p->beta } };
}

void rod_coefficient_outputs(const RodParams *p, const double x[ROD_NX], double out[ROD_NOUT])
{
    const Contact c = rod_contact(p);
    const BodyState s = contact_body(&c, x);
    const ContactCoeffs k = contact_coeffs(&c.law, &s);
    out[ROD_OUT_A] = k.a;
    out[ROD_OUT_B] = k.b;
    out[ROD_OUT_P_PLUS] = k.p_plus;
    out[ROD_OUT_P_MINUS] = k.p_minus;
    out[ROD_OUT_Q_PLUS] = k.q_plus;
    out[ROD_OUT_Q_MINUS] = k.q_minus;
    out[ROD_OUT_S_W] = k.S_w;
}

/* ------------------------------------------- the free flight in closed form */

RodFlight rod_flight(double length, double ax, double ay, double angular, double t0, const double x0[ROD_NX])
{
    RodFlight f = { .length = length, .ax = ax, .ay = ay, .angular = angular, .t0 = t0,
                    .sin0 = sin(x0[ROD_THETA]), .cos0 = cos(x0[ROD_THETA]) };
    for (int i = 0; i < ROD_NX; ++i) f.x0[i] = x0[i];
    return f;
}

/* The end is the centre plus l (cos theta, -sin theta) (eq coord): with the centre's motion
 * at constant acceleration and theta = theta0 + phi0 s + angular s^2/2, each state is x0's
 * plus an increment in which sin theta - sin theta0 = cos0 sin D - 2 sin0 sin^2(D/2) and
 * cos theta - cos theta0 = -sin0 sin D - 2 cos0 sin^2(D/2) (D = theta - theta0) lose no
 * digits to cancellation: near the floor y is of order eps^2, its increments too. */
void rod_flight_at(const RodFlight *f, double t, double x[ROD_NX])
{
    const double s = t - f->t0, l = f->length, phi0 = f->x0[ROD_PHI];
    const double turn = s * (phi0 + 0.5 * f->angular * s), phi = phi0 + f->angular * s;
    const double half = sin(0.5 * turn), versine = 2 * half * half, sine = sin(turn);
    const double dsin = f->cos0 * sine - f->sin0 * versine, dcos = -f->sin0 * sine - f->cos0 * versine;
    /* the end's velocity is the centre's, (v + l phi sin, w + l phi cos) at t0, minus l phi (sin, cos) */
    x[ROD_X] = f->x0[ROD_X] + s * (f->x0[ROD_V] + l * phi0 * f->sin0 + 0.5 * f->ax * s) + l * dcos;
    x[ROD_V] = f->x0[ROD_V] + f->ax * s - l * (phi * dsin + (phi - phi0) * f->sin0);
    x[ROD_Y] = f->x0[ROD_Y] + s * (f->x0[ROD_W] + l * phi0 * f->cos0 + 0.5 * f->ay * s) - l * dsin;
    x[ROD_W] = f->x0[ROD_W] + f->ay * s - l * (phi * dcos + (phi - phi0) * f->cos0);
    x[ROD_THETA] = f->x0[ROD_THETA] + turn;
    x[ROD_PHI] = phi;
}

/* Within such a time each event indicator of a flight (the gap y, the force bracket, linear in
 * y and w above the floor, v and w: contact.c) is a quadratic in time plus an arc of sin and cos
 * of at most pi/8, so it has at most one root unless it turns there; and where the gap turns,
 * so does the end's height, at the root of w, itself an indicator (the dip bottom): a touch
 * and go of the end between two samples shows as w's root. */
#define TURN_PER_SAMPLE (3.14159265358979323846 / 8)
#define DROP_PER_SAMPLE (1.0 / 32)

double rod_flight_sample_step(const RodFlight *f, double t)
{
    const double phi = fabs(f->x0[ROD_PHI] + f->angular * (t - f->t0)), ang = fabs(f->angular);
    /* phi s + ang s^2/2 = TURN, solved without cancellation */
    const double by_turn = 2 * TURN_PER_SAMPLE / (phi + sqrt(phi * phi + 2 * ang * TURN_PER_SAMPLE));
    /* the end's acceleration is at most the centre's plus l (phi^2 + ang): K s^2/2 = l DROP
     * (|ax| + |ay| bounds the centre's without hypot, whose glibc 2.35 symbol no FMU may need:
     * docs/platforms.md) */
    const double K = fabs(f->ax) + fabs(f->ay) + f->length * (phi * phi + ang);
    const double by_drop = K > 0 ? sqrt(2 * DROP_PER_SAMPLE * f->length / K) : INFINITY;
    return fmin(by_turn, by_drop);
}

/* ------------------------------------------- the rod's analytic Jacobian */

static bool sticking(ContactMode m) { return m.contact && m.slip == 0; }

/* How a and F_N enter the mode's right-hand side:
 *   v' = a + g.v F_N (0 while sticking),  w' = b + g.w_a a + g.w F_N,
 *   phi' = g.phi_a a + g.phi F_N,
 * with g taken from k (coefficients) or its theta-derivative.
 *
 * While sticking the friction force is whatever holds v' = 0,
 * F_T = (a + alpha sin cos F_N)/k (k = 1 + alpha sin^2), and eq dynrodsc with
 * that F_T gives w' = b + S_w F_N - alpha sin cos a/k, phi' = S_phi F_N +
 * alpha sin a/k: the Filippov combination of the two slip fields with weight
 * (a + q_- F_N)/((q_- - q_+) F_N) on slip+. Proposition lem:Filippov (as
 * docs/model.md §1 notes) takes the weight q_-/(q_- - q_+), i.e. drops the a-terms: O(1)
 * over a stick of duration O(eps), so Theorem 1's limits are the same, but
 * without them (w', phi') are not those of any friction force, and the stuck
 * rod gains energy at the rate phi^3 sin cos. With them F_T v = 0 and only the
 * damper works. */
typedef struct { double v, w, phi, w_a, phi_a; } ModeGains;

static ModeGains mode_gains(const RodCoeffs *k, ContactMode m)
{
    if (sticking(m)) return (ModeGains){ 0, k->S_w, k->S_phi, k->A_w, k->A_phi };  /* exact Filippov */
    if (m.slip >= 0) return (ModeGains){ k->q_plus, k->p_plus, k->c_plus, 0, 0 };  /* eq PainleveEqs */
    return (ModeGains){ k->q_minus, k->p_minus, k->c_minus, 0, 0 };
}

/* d/dtheta of the coefficients in RodCoeffs (phi enters a and b only). */
static RodCoeffs coeffs_dtheta(const RodParams *p, double theta, double phi)
{
    const double s = sin(theta), c = cos(theta), al = p->alpha, mu = p->mu;
    const double k = 1 + al * s * s, dk = 2 * al * s * c, c2s2 = c * c - s * s;
    RodCoeffs d;
    d.a = phi * phi * s - al * c * p->tau;
    d.b = phi * phi * c + al * s * p->tau;
    d.q_plus = al * c2s2 - mu * dk;
    d.q_minus = al * c2s2 + mu * dk;
    d.p_plus = -2 * al * s * c - mu * al * c2s2;
    d.p_minus = -2 * al * s * c + mu * al * c2s2;
    d.c_plus = al * (s + mu * c);
    d.c_minus = al * (s - mu * c);
    d.S_w = -(1 + al) * dk / (k * k);
    d.S_phi = al * s / k + al * c * dk / (k * k);
    d.A_w = -al * c2s2 / k + al * s * c * dk / (k * k);
    d.A_phi = al * c / k - al * s * dk / (k * k);
    return d;
}

void rod_jacobian(const RodParams *p, ContactMode m, const double x[ROD_NX], double J[ROD_NX][ROD_NX])
{
    const double th = x[ROD_THETA], phi = x[ROD_PHI], eps = p->epsilon;
    const RodCoeffs k = rod_coeffs(p, th, phi), dk = coeffs_dtheta(p, th, phi);
    const Contact c = rod_contact(p);
    const double F = contact_normal_force(&c, m, x);
    const double a_phi = -2 * phi * cos(th);     /* da/dphi; db/dphi = 2 phi sin */
    /* F = h(y/eps, w)/eps in contact: dF/dy = h_yh/eps^2, dF/dw = h_w/eps
     * (-1/eps^2 and -delta/eps for the linear law) */
    const Compliance h = contact_compliance(&c.law, x[ROD_Y], x[ROD_W]);
    const double F_y = m.contact ? h.h_yh / (eps * eps) : 0, F_w = m.contact ? h.h_w / eps : 0;
    for (int i = 0; i < ROD_NX; ++i)
        for (int j = 0; j < ROD_NX; ++j) J[i][j] = 0;
    J[ROD_X][ROD_V] = 1;
    J[ROD_Y][ROD_W] = 1;
    J[ROD_THETA][ROD_PHI] = 1;
    const ModeGains g = mode_gains(&k, m), dg = mode_gains(&dk, m);
    if (!sticking(m)) {
        J[ROD_V][ROD_THETA] = dk.a + dg.v * F;
        J[ROD_V][ROD_PHI] = a_phi;
        J[ROD_V][ROD_Y] = g.v * F_y;
        J[ROD_V][ROD_W] = g.v * F_w;
    }
    J[ROD_W][ROD_THETA] = dk.b + dg.w_a * k.a + g.w_a * dk.a + dg.w * F;
    J[ROD_W][ROD_PHI] = 2 * phi * sin(th) + g.w_a * a_phi;
    J[ROD_W][ROD_Y] = g.w * F_y;
    J[ROD_W][ROD_W] = g.w * F_w;
    J[ROD_PHI][ROD_THETA] = dg.phi_a * k.a + g.phi_a * dk.a + dg.phi * F;
    J[ROD_PHI][ROD_PHI] = g.phi_a * a_phi;
    J[ROD_PHI][ROD_Y] = g.phi * F_y;
    J[ROD_PHI][ROD_W] = g.phi * F_w;
}

