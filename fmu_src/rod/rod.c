/* The compliant Painleve rod (Hogan & Kristiansen), physics and mode logic.
 *
 * Modes are discrete states that change only at events, so the right-hand
 * side is smooth between events (docs/model.md §2):
 *   contact  F_N = h/eps with h = h(y/eps, w) the compliance law (rod.h; the
 *            paper's linear g = -y/eps - delta w by default, eq FN)
 *   slip     s = +1 / -1: eq Painleve with q_s, p_s, c_s
 *   stick    s = 0: the exact Filippov field, v' = 0 (see mode_gains)
 * Event indicators (slot: meaning per mode):
 *   0  y                       contact surface
 *   1  h                       F_N = 0 while in contact, F_N > 0 ahead in flight
 *   2  v            (slipping) reversal or stick
 *      a + q_+ F_N  (sticking) forward fold of Lemma lemma:nonStick, < 0 inside
 *   3  a + q_- F_N  (sticking) backward fold, > 0 inside
 *      w            (flight)   bottom of a dip: makes a grazing contact that
 *                              falls inside one solver step change a sign once
 *      -1           (slipping in contact) nothing to watch */
#include "rod.h"

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

RodCoeffs rod_coeffs(const RodParams *p, double theta, double phi)
{
    const double s = sin(theta), c = cos(theta), al = p->alpha, mu = p->mu;
    const double k = 1 + al * s * s;
    RodCoeffs r;
    r.a = -phi * phi * c + p->f_x - al * s * p->tau;     /* eq coeffs, with the applied loads */
    r.b = -1 + phi * phi * s + p->f_y - al * c * p->tau;
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

void rod_coefficient_outputs(const RodParams *p, const double x[ROD_NX], double out[ROD_NOUT])
{
    const RodCoeffs k = rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]);
    out[ROD_OUT_A] = k.a;
    out[ROD_OUT_B] = k.b;
    out[ROD_OUT_P_PLUS] = k.p_plus;
    out[ROD_OUT_P_MINUS] = k.p_minus;
    out[ROD_OUT_Q_PLUS] = k.q_plus;
    out[ROD_OUT_Q_MINUS] = k.q_minus;
    out[ROD_OUT_S_W] = k.S_w;
}

RodCompliance rod_compliance(const RodParams *p, double y, double w)
{
    /* Written so that kappa = beta = 0 evaluates -y/eps - delta w in the same
     * operations as the linear law (results bit for bit unchanged). */
    const double yh = y / p->epsilon, d = yh < 0 ? -yh : 0.0;
    const double damping = p->delta * (1 + p->beta * d);
    RodCompliance c;
    c.h = (-yh + p->kappa * d * d) - damping * w;
    c.h_yh = d > 0 ? -(1 + 2 * p->kappa * d - p->delta * p->beta * w) : -1.0;
    c.h_w = -damping;
    return c;
}

double rod_force_bracket(const RodParams *p, const double x[ROD_NX])
{
    return rod_compliance(p, x[ROD_Y], x[ROD_W]).h;
}

double rod_spring_energy(const RodParams *p, double y)
{
    const double d = -(y / p->epsilon), dp = d > 0 ? d : 0.0;
    return 0.5 * d * d + p->kappa * dp * dp * dp / 3;
}

double rod_normal_force(const RodParams *p, RodMode m, const double x[ROD_NX])
{
    return m.contact ? rod_force_bracket(p, x) / p->epsilon : 0.0;
}

double rod_friction_force(const RodParams *p, RodMode m, const double x[ROD_NX])
{
    if (!m.contact) return 0.0;
    const double F = rod_normal_force(p, m, x);
    if (m.slip != 0) return m.slip * p->mu * F;
    const double s = sin(x[ROD_THETA]), c = cos(x[ROD_THETA]);
    const RodCoeffs k = rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]);
    /* eq dynrodsc with x'' = 0 */
    return (k.a + p->alpha * s * c * F) / (1 + p->alpha * s * s);
}

double rod_energy(const RodParams *p, RodMode m, const double x[ROD_NX])
{
    /* Centre of mass (X, Y) = (x - cos theta, y + sin theta), eq coord. The
     * spring holds energy only while it pushes: after a damped lift-off below
     * the floor (y < 0, F_N = 0) its d^2/2 + kappa d^3/3 has gone to the damper. */
    const double s = sin(x[ROD_THETA]), c = cos(x[ROD_THETA]), phi = x[ROD_PHI];
    const double Xd = x[ROD_V] + phi * s, Yd = x[ROD_W] + phi * c;
    const double y = x[ROD_Y];
    const double spring = m.contact ? rod_spring_energy(p, y) : 0.0;
    return 0.5 * (Xd * Xd + Yd * Yd) + 0.5 * phi * phi / p->alpha + (y + s) + spring;
}

static bool sticking(RodMode m) { return m.contact && m.slip == 0; }

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

static ModeGains mode_gains(const RodCoeffs *k, RodMode m)
{
    if (sticking(m)) return (ModeGains){ 0, k->S_w, k->S_phi, k->A_w, k->A_phi };  /* exact Filippov */
    if (m.slip >= 0) return (ModeGains){ k->q_plus, k->p_plus, k->c_plus, 0, 0 };  /* eq PainleveEqs */
    return (ModeGains){ k->q_minus, k->p_minus, k->c_minus, 0, 0 };
}

void rod_derivatives(const RodParams *p, RodMode m, const double x[ROD_NX], double dx[ROD_NX])
{
    const RodCoeffs k = rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]);
    const ModeGains g = mode_gains(&k, m);
    const double F = rod_normal_force(p, m, x);
    dx[ROD_X] = x[ROD_V];
    dx[ROD_Y] = x[ROD_W];
    dx[ROD_THETA] = x[ROD_PHI];
    dx[ROD_V] = sticking(m) ? 0 : k.a + g.v * F;   /* v' = 0 exactly on the sticking set */
    dx[ROD_W] = k.b + g.w_a * k.a + g.w * F;
    dx[ROD_PHI] = g.phi_a * k.a + g.phi * F + p->alpha * p->tau;
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

void rod_jacobian(const RodParams *p, RodMode m, const double x[ROD_NX], double J[ROD_NX][ROD_NX])
{
    const double th = x[ROD_THETA], phi = x[ROD_PHI], eps = p->epsilon;
    const RodCoeffs k = rod_coeffs(p, th, phi), dk = coeffs_dtheta(p, th, phi);
    const double F = rod_normal_force(p, m, x);
    const double a_phi = -2 * phi * cos(th);     /* da/dphi; db/dphi = 2 phi sin */
    /* F = h(y/eps, w)/eps in contact: dF/dy = h_yh/eps^2, dF/dw = h_w/eps
     * (-1/eps^2 and -delta/eps for the linear law) */
    const RodCompliance h = rod_compliance(p, x[ROD_Y], x[ROD_W]);
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

void rod_event_indicators(const RodParams *p, RodMode m, const double x[ROD_NX], double z[ROD_NZ])
{
    z[ROD_Z_Y] = x[ROD_Y];
    z[ROD_Z_FORCE] = rod_force_bracket(p, x);
    if (sticking(m)) {
        const RodCoeffs k = rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]);
        const double F = rod_normal_force(p, m, x);
        z[ROD_Z_SLIP] = k.a + k.q_plus * F;
        z[ROD_Z_AUX] = k.a + k.q_minus * F;
    } else {
        z[ROD_Z_SLIP] = x[ROD_V];
        z[ROD_Z_AUX] = m.contact ? -1.0 : x[ROD_W];
    }
}

/* The rounding error of each indicator as computed at x: a few ulps of the
 * largest term it sums. An indicator within it of 0 is on its surface, since
 * its sign there is the rounding's (h = -y/eps + kappa d^2 - delta w (1 + beta d)
 * cancels terms of 1e4 and more deep in the floor: a sign that flips with the
 * last bit of y). The states themselves (y, v, w) are exact. */
#define NOISE_ULPS (8 * DBL_EPSILON)

static double force_noise(const RodParams *p, const double x[ROD_NX])
{
    const double yh = x[ROD_Y] / p->epsilon, d = yh < 0 ? -yh : 0.0;
    return NOISE_ULPS * (fabs(yh) + p->kappa * d * d + fabs(p->delta * (1 + p->beta * d) * x[ROD_W]));
}

static void indicator_noise(const RodParams *p, RodMode m, const double x[ROD_NX], double noise[ROD_NZ])
{
    const double ulps = NOISE_ULPS;
    noise[ROD_Z_Y] = 0;
    noise[ROD_Z_FORCE] = force_noise(p, x);
    noise[ROD_Z_SLIP] = noise[ROD_Z_AUX] = 0;
    if (sticking(m)) {
        const double s = sin(x[ROD_THETA]), c = cos(x[ROD_THETA]), phi = x[ROD_PHI];
        const RodCoeffs k = rod_coeffs(p, x[ROD_THETA], phi);
        const double F = fabs(rod_normal_force(p, m, x));
        const double a_terms = phi * phi * fabs(c) + fabs(p->f_x) + p->alpha * fabs(s * p->tau);
        noise[ROD_Z_SLIP] = ulps * (a_terms + fabs(k.q_plus) * F);
        noise[ROD_Z_AUX] = ulps * (a_terms + fabs(k.q_minus) * F);
    }
}

void rod_nominals(const RodParams *p, double nominal[ROD_NX])
{
    const double eps = p->epsilon;
    nominal[ROD_X] = 1;
    nominal[ROD_V] = 1;
    nominal[ROD_Y] = eps * eps;
    nominal[ROD_W] = eps;
    nominal[ROD_THETA] = 1;
    nominal[ROD_PHI] = 1;
}

const char *rod_indicator_name(const RodMode m, int i)
{
    const bool stick = sticking(m);
    switch (i) {
    case ROD_Z_Y: return "y";
    case ROD_Z_FORCE: return "h(y/eps, w) (F_N = 0)";
    case ROD_Z_SLIP: return stick ? "a + q_+ F_N (forward fold)" : "v";
    case ROD_Z_AUX: return stick ? "a + q_- F_N (backward fold)" : m.contact ? "none" : "w (dip bottom)";
    default: return "?";
    }
}

/* Contact iff y <= 0 and h > 0 (eq FN), ties broken by the free motion
 * y'' = b, so a rod at rest on y = 0 and pushed down by b < 0 is in contact:
 * h' = h_yh w/eps + h_w b, h'' = h_yh b/eps to leading order. */
static bool in_contact(const RodParams *p, const double x[ROD_NX], double b)
{
    const double eps = p->epsilon, w = x[ROD_W];
    const RodCompliance h = rod_compliance(p, x[ROD_Y], w);
    const double h0 = fabs(h.h) > force_noise(p, x) ? h.h : 0.0;   /* on F_N = 0: decided by h' */
    return lex_sign(x[ROD_Y], w, b) < 0 && lex_sign(h0, h.h_yh * (w / eps) + h.h_w * b, h.h_yh * (b / eps)) > 0;
}

/* Slip direction at v = 0 in contact: stick inside the Filippov cone
 * a + q_+ F_N < 0 < a + q_- F_N (eq filineq), else the side v' points to. */
static int decide_at_rest(const RodCoeffs *k, double F)
{
    const double fwd = k->a + k->q_plus * F, bwd = k->a + k->q_minus * F;
    if (fwd < 0 && bwd > 0) return 0;
    return fwd >= 0 ? +1 : -1;
}

RodMode rod_decide_mode(const RodParams *p, RodMode m, double x[ROD_NX], bool *x_changed)
{
    const RodCoeffs k = rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]);
    const double v = x[ROD_V];
    RodMode n = { in_contact(p, x, k.b), m.slip };
    *x_changed = false;
    if (!n.contact) {                /* no friction in flight: s follows v */
        n.slip = v != 0 ? sign_of(v) : (k.a >= 0 ? +1 : -1);
        return n;
    }
    if (v != 0 && sign_of(v) == m.slip) return n;   /* still slipping */
    if (v != 0) {                    /* v crossed 0 (or drifted in stick) */
        x[ROD_V] = 0;
        *x_changed = true;
    }
    n.slip = decide_at_rest(&k, rod_normal_force(p, n, x));
    return n;
}

/* The side of indicator i on which mode m lives (0: nothing to keep). */
static int wanted_side(const RodParams *p, RodMode m, int i, const double x[ROD_NX])
{
    switch (i) {
    case ROD_Z_Y: return m.contact ? -1 : +1;
    case ROD_Z_FORCE: return m.contact ? +1 : x[ROD_Y] > 0 ? 0 : -1;   /* above the floor h does not decide */
    case ROD_Z_SLIP: return sticking(m) ? -1 : m.slip;
    case ROD_Z_AUX:
        if (m.contact) return m.slip == 0 ? +1 : 0;
        return rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]).b >= 0 ? +1 : -1;
    default: return 0;
    }
}

/* The state whose smallest relative move changes indicator i most, and the
 * direction of that move that raises it; -1 if no state moves it. */
static int steepest_state(const RodParams *p, RodMode m, int i, const double x[ROD_NX],
                          const double nominal[ROD_NX], int *direction)
{
    double z0[ROD_NZ], z[ROD_NZ], trial[ROD_NX];
    rod_event_indicators(p, m, x, z0);
    int best = -1;
    double largest = 0;
    for (int j = 0; j < ROD_NX; ++j) {
        for (int k = 0; k < ROD_NX; ++k) trial[k] = x[k];
        trial[j] += fmax(1e-6 * nominal[j], 1e-9 * fabs(x[j]));  /* seen above the rounding of a deep state */
        rod_event_indicators(p, m, trial, z);
        const double change = z[i] - z0[i];
        if (fabs(change) > largest) {
            largest = fabs(change);
            best = j;
            *direction = sign_of(change);
        }
    }
    return best;
}

/* Whether indicator i, at z with rounding error `noise`, is clear of its surface on `side`. */
static bool clear_of(double z, double noise, int side)
{
    return sign_of(z) == side && fabs(z) > noise;
}

/* Moves x[state] by the smallest step, doubling from 1e-15 margin nominal up to the
 * nominal (or 1e-6 of the state, deep in the floor where the nominal is below its
 * rounding), that leaves indicator i clear of margin times its rounding error on `side`. */
static bool leave_surface(const RodParams *p, RodMode m, double x[ROD_NX], int i, int side, int state,
                          int direction, double nominal, double margin)
{
    double z[ROD_NZ], noise[ROD_NZ];
    const double start = x[state], largest = fmax(nominal, 1e-6 * fabs(start));
    for (double step = 1e-15 * margin * nominal; step < largest; step *= 2) {
        x[state] = start + side * direction * step;
        rod_event_indicators(p, m, x, z);
        indicator_noise(p, m, x, noise);
        if (clear_of(z[i], margin * noise[i], side)) return true;
    }
    x[state] = start;
    return false;
}

bool rod_move_off_surfaces(const RodParams *p, RodMode m, double x[ROD_NX], double margin, bool *moved)
{
    double z[ROD_NZ], nominal[ROD_NX], noise[ROD_NZ];
    *moved = false;
    rod_nominals(p, nominal);
    for (int i = 0; i < ROD_NZ; ++i) {
        rod_event_indicators(p, m, x, z);
        indicator_noise(p, m, x, noise);
        const int side = wanted_side(p, m, i, x);
        if (side == 0 || fabs(z[i]) > margin * noise[i]) continue;
        int direction = 0;
        const int state = steepest_state(p, m, i, x, nominal, &direction);
        if (state < 0) return false;
        /* A margin the nominal cannot reach falls back to the plain one (clear of the rounding). */
        const bool left = leave_surface(p, m, x, i, side, state, direction, nominal[state], margin) ||
                          (margin > 1 && leave_surface(p, m, x, i, side, state, direction, nominal[state], 1));
        *moved = true;
        if (!left) return false;
    }
    return true;
}

RodEventResult rod_event_update(const RodParams *p, RodMode *m, double x[ROD_NX], double margin, bool *x_changed)
{
    *x_changed = false;
    /* decide and move-off must reach a fixpoint; a few rounds always do
     * unless the rules ping-pong, which is reported, never looped on. */
    for (int round = 0; round < 8; ++round) {
        bool changed, moved;
        const RodMode n = rod_decide_mode(p, *m, x, &changed);
        *x_changed |= changed;
        const bool same = n.contact == m->contact && n.slip == m->slip;
        *m = n;
        if (!same || changed) continue;
        const bool off = rod_move_off_surfaces(p, *m, x, margin, &moved);
        margin = 1;   /* a later round moves only what the decision moved back onto a surface */
        *x_changed |= moved;
        if (!off) return ROD_STUCK_ON_SURFACE;
        if (!moved) return ROD_SETTLED;
    }
    return ROD_PING_PONG;
}
