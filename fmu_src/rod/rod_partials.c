/* SPDX-License-Identifier: BSD-2-Clause */
/* Partial derivatives of the rod's smooth branches, derived by hand from the
 * equations that rod.c evaluates (the paper's eq coeffs and eq Sw, docs/model.md §1,
 * the exact Filippov sticking field of rod.c's mode_gains).
 *
 * Notation: sn = sin theta, cs = cos theta, al = alpha, k = 1 + al sn^2,
 * sg = the slip direction (+1 / -1). Within one mode the right-hand side is
 *   x' = v,  y' = w,  theta' = phi,
 *   slipping (sg = +1 / -1; in flight F = 0):
 *     v' = a + q_sg F,  w' = b + p_sg F,  phi' = c_sg F
 *   sticking (contact, sg = 0):
 *     v' = 0,  w' = b + A_w a + S_w F,  phi' = A_phi a + S_phi F
 * with (eq coeffs, eq Sw)
 *   a = -phi^2 cs + f_x - al sn tau,  b = -1 + phi^2 sn + f_y - al cs tau  (phi' also gains al tau),
 *   q_sg = al sn cs - sg mu k,  p_sg = 1 + al cs^2 - sg mu al sn cs,  c_sg = -al (cs - sg mu sn),
 *   S_w = (1 + al)/k,  S_phi = -al cs/k,  A_w = -al sn cs/k,  A_phi = al sn/k,
 * and, in contact, F = h(y/eps, w)/eps with the compliance law h of rod.h (the
 * linear law: -y/eps^2 - delta w/eps; 0 in flight).
 * Parameters enter through the gains (alpha, mu), through F (delta, eps, kappa, beta) and,
 * with a torque, through the load terms of a, b and phi' (alpha). */
#include "rod_partials.h"

#include <math.h>
#include <string.h>

/* F and its partials, F = h(yh, w)/eps with yh = y/eps, d = max(-yh, 0) (rod.h):
 *   F_y = h_yh/eps^2,  F_w = h_w/eps,  F_delta = -w (1 + beta d)/eps,
 *   F_eps = -h/eps^2 - h_yh y/eps^3,  F_kappa = d^2/eps,  F_beta = -delta w d/eps;
 * all 0 in flight. (Linear law: F_y = -1/eps^2, F_w = -delta/eps, F_delta = -w/eps,
 * F_eps = 2 y/eps^3 + delta w/eps^2.) */
typedef struct { double F, y, w, delta, eps, kappa, beta; } NormalForce;

static NormalForce normal_force(const RodParams *p, ContactMode m, const double x[ROD_NX])
{
    if (!m.contact) return (NormalForce){ 0, 0, 0, 0, 0, 0, 0 };
    const double eps = p->epsilon, y = x[ROD_Y], w = x[ROD_W];
    const Contact c = rod_contact(p);
    const Compliance h = contact_compliance(&c.law, y, w);
    const double d = y < 0 ? -y / eps : 0.0;
    return (NormalForce){ contact_normal_force(&c, m, x),
                          h.h_yh / (eps * eps),
                          h.h_w / eps,
                          -w * (1 + p->beta * d) / eps,
                          -h.h / (eps * eps) - h.h_yh * y / (eps * eps * eps),
                          d * d / eps,
                          -p->delta * w * d / eps };
}

/* How the mode's gains (rod.c's mode_gains: v' = a + v F, w' = b + w_a a + w F,
 * phi' = phi_a a + phi F) change with alpha and with mu. */
typedef struct { double v, w, phi, w_a, phi_a; } Gains;

static void gains_dp(const RodParams *p, ContactMode m, double theta, Gains *d_alpha, Gains *d_mu)
{
    const double sn = sin(theta), cs = cos(theta), al = p->alpha, mu = p->mu;
    const double k = 1 + al * sn * sn;
    if (m.contact && m.slip == 0) {
        /* dk/dalpha = sn^2: dS_w = cs^2/k^2, dS_phi = -cs/k^2, dA_w = -sn cs/k^2,
         * dA_phi = sn/k^2. The sticking field does not involve mu (the paper
         * notes it for S_w, S_phi; A_w, A_phi hold no mu either). */
        *d_alpha = (Gains){ 0, cs * cs / (k * k), -cs / (k * k), -sn * cs / (k * k), sn / (k * k) };
        *d_mu = (Gains){ 0, 0, 0, 0, 0 };
        return;
    }
    const double sg = m.slip >= 0 ? 1.0 : -1.0;  /* rod.c: slip 0 out of contact takes the + gains */
    /* dq/dalpha = sn cs - sg mu sn^2, dp/dalpha = cs^2 - sg mu sn cs, dc/dalpha = -(cs - sg mu sn);
     * dq/dmu = -sg k, dp/dmu = -sg al sn cs, dc/dmu = sg al sn. */
    *d_alpha = (Gains){ sn * cs - sg * mu * sn * sn, cs * cs - sg * mu * sn * cs, -(cs - sg * mu * sn), 0, 0 };
    *d_mu = (Gains){ -sg * k, -sg * al * sn * cs, sg * al * sn, 0, 0 };
}

/* The gains themselves (the same selection as rod.c's mode_gains). */
static Gains gains(const RodCoeffs *c, ContactMode m)
{
    if (m.contact && m.slip == 0) return (Gains){ 0, c->S_w, c->S_phi, c->A_w, c->A_phi };
    if (m.slip >= 0) return (Gains){ c->q_plus, c->p_plus, c->c_plus, 0, 0 };
    return (Gains){ c->q_minus, c->p_minus, c->c_minus, 0, 0 };
}

/* d(state derivatives)/d(parameters):
 *   d rhs/dP = (d gain/dP)(a or F) + gain dF/dP,
 * plus, for alpha, the torque's terms: da/dalpha = -sn tau, db/dalpha = -cs tau, and phi' = ... + al tau. */
static void derivatives_dp(const RodParams *p, ContactMode m, const double x[ROD_NX], double dx_p[ROD_NX][ROD_NP])
{
    const RodCoeffs c = rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]);
    const Gains g = gains(&c, m);
    Gains ga, gm;
    gains_dp(p, m, x[ROD_THETA], &ga, &gm);
    const NormalForce F = normal_force(p, m, x);
    const bool stick = m.contact && m.slip == 0;
    if (!stick) {  /* v' = a + q F; 0 while sticking */
        dx_p[ROD_V][ROD_P_ALPHA] = ga.v * F.F;
        dx_p[ROD_V][ROD_P_MU] = gm.v * F.F;
        dx_p[ROD_V][ROD_P_DELTA] = g.v * F.delta;
        dx_p[ROD_V][ROD_P_EPSILON] = g.v * F.eps;
        dx_p[ROD_V][ROD_P_KAPPA] = g.v * F.kappa;
        dx_p[ROD_V][ROD_P_BETA] = g.v * F.beta;
    }
    dx_p[ROD_W][ROD_P_KAPPA] = g.w * F.kappa;
    dx_p[ROD_W][ROD_P_BETA] = g.w * F.beta;
    dx_p[ROD_PHI][ROD_P_KAPPA] = g.phi * F.kappa;
    dx_p[ROD_PHI][ROD_P_BETA] = g.phi * F.beta;
    dx_p[ROD_W][ROD_P_ALPHA] = ga.w_a * c.a + ga.w * F.F;
    dx_p[ROD_W][ROD_P_MU] = gm.w_a * c.a + gm.w * F.F;
    dx_p[ROD_W][ROD_P_DELTA] = g.w * F.delta;
    dx_p[ROD_W][ROD_P_EPSILON] = g.w * F.eps;
    dx_p[ROD_PHI][ROD_P_ALPHA] = ga.phi_a * c.a + ga.phi * F.F;
    dx_p[ROD_PHI][ROD_P_MU] = gm.phi_a * c.a + gm.phi * F.F;
    dx_p[ROD_PHI][ROD_P_DELTA] = g.phi * F.delta;
    dx_p[ROD_PHI][ROD_P_EPSILON] = g.phi * F.eps;
    const double sn = sin(x[ROD_THETA]), cs = cos(x[ROD_THETA]), a_alpha = -sn * p->tau, b_alpha = -cs * p->tau;
    if (!stick) dx_p[ROD_V][ROD_P_ALPHA] += a_alpha;
    dx_p[ROD_W][ROD_P_ALPHA] += b_alpha + g.w_a * a_alpha;
    dx_p[ROD_PHI][ROD_P_ALPHA] += g.phi_a * a_alpha + p->tau;
}

/* d(state derivatives)/d(loads): da/d(f_x, f_y, tau) = (1, 0, -al sn), db/d(.) = (0, 1, -al cs),
 * and phi' holds al tau itself. */
static void derivatives_dl(const RodParams *p, ContactMode m, const double x[ROD_NX], double dx_l[ROD_NX][ROD_NL])
{
    const RodCoeffs c = rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]);
    const Gains g = gains(&c, m);
    const double sn = sin(x[ROD_THETA]), cs = cos(x[ROD_THETA]), al = p->alpha;
    const double a_l[ROD_NL] = { 1, 0, -al * sn }, b_l[ROD_NL] = { 0, 1, -al * cs };
    const bool stick = m.contact && m.slip == 0;
    for (int j = 0; j < ROD_NL; ++j) {
        dx_l[ROD_V][j] = stick ? 0 : a_l[j];
        dx_l[ROD_W][j] = b_l[j] + g.w_a * a_l[j];
        dx_l[ROD_PHI][j] = g.phi_a * a_l[j] + (j == ROD_L_TAU ? al : 0);
    }
}

/* F_N = F (contact_normal_force). */
static void normal_force_partials(const RodParams *p, ContactMode m, const double x[ROD_NX], double d_x[ROD_NX],
                                  double d_p[ROD_NP])
{
    const NormalForce F = normal_force(p, m, x);
    d_x[ROD_Y] = F.y;
    d_x[ROD_W] = F.w;
    d_p[ROD_P_DELTA] = F.delta;
    d_p[ROD_P_EPSILON] = F.eps;
    d_p[ROD_P_KAPPA] = F.kappa;
    d_p[ROD_P_BETA] = F.beta;
}

/* F_T (contact_friction_force): 0 in flight; sg mu F while slipping; while
 * sticking the force that holds v' = 0, F_T = (a + al sn cs F)/k, whence
 *   dF_T/dtheta = (phi^2 sn - al cs tau + al (cs^2 - sn^2) F)/k - F_T (2 al sn cs)/k,
 *   dF_T/dphi = -2 phi cs/k,  dF_T/d(y, w, delta, eps) = al sn cs dF/d(.)/k,
 *   dF_T/dalpha = (sn cs F - sn tau - F_T sn^2)/k,  dF_T/dmu = 0,
 *   dF_T/d(f_x, f_y, tau) = (1, 0, -al sn)/k. */
static void friction_force_partials(const RodParams *p, ContactMode m, const double x[ROD_NX], double d_x[ROD_NX],
                                    double d_p[ROD_NP], double d_l[ROD_NL])
{
    if (!m.contact) return;
    const NormalForce F = normal_force(p, m, x);
    if (m.slip != 0) {
        const double smu = m.slip * p->mu;
        d_x[ROD_Y] = smu * F.y;
        d_x[ROD_W] = smu * F.w;
        d_p[ROD_P_MU] = m.slip * F.F;
        d_p[ROD_P_DELTA] = smu * F.delta;
        d_p[ROD_P_EPSILON] = smu * F.eps;
        d_p[ROD_P_KAPPA] = smu * F.kappa;
        d_p[ROD_P_BETA] = smu * F.beta;
        return;
    }
    const double th = x[ROD_THETA], phi = x[ROD_PHI], al = p->alpha;
    const double sn = sin(th), cs = cos(th), k = 1 + al * sn * sn, ssc = al * sn * cs / k;
    const Contact c = rod_contact(p);
    const double FT = contact_friction_force(&c, m, x);
    d_x[ROD_THETA] = (phi * phi * sn - al * cs * p->tau + al * (cs * cs - sn * sn) * F.F) / k - FT * 2 * al * sn * cs / k;
    d_x[ROD_PHI] = -2 * phi * cs / k;
    d_x[ROD_Y] = ssc * F.y;
    d_x[ROD_W] = ssc * F.w;
    d_p[ROD_P_ALPHA] = (sn * cs * F.F - sn * p->tau - FT * sn * sn) / k;
    d_l[ROD_L_FX] = 1 / k;
    d_l[ROD_L_TAU] = -al * sn / k;
    d_p[ROD_P_DELTA] = ssc * F.delta;
    d_p[ROD_P_EPSILON] = ssc * F.eps;
    d_p[ROD_P_KAPPA] = ssc * F.kappa;
    d_p[ROD_P_BETA] = ssc * F.beta;
}

/* energy (contact_energy) = (Xd^2 + Yd^2)/2 + phi^2/(2 al) + y + sn [+ S(d) in contact],
 * Xd = v + phi sn, Yd = w + phi cs (the centre of mass's velocity, eq coord), and the
 * spring's S(d) = d^2/2 + kappa dp^3/3, d = -y/eps, dp = max(d, 0), S'(d) = d + kappa dp^2:
 *   dE/dv = Xd, dE/dw = Yd, dE/dy = 1 [- S'(d)/eps],
 *   dE/dtheta = phi (Xd cs - Yd sn) + cs, dE/dphi = Xd sn + Yd cs + phi/al,
 *   dE/dalpha = -phi^2/(2 al^2), dE/deps = [S'(d) y/eps^2], dE/dkappa = [dp^3/3]. */
static void energy_partials(const RodParams *p, ContactMode m, const double x[ROD_NX], double d_x[ROD_NX],
                            double d_p[ROD_NP])
{
    const double th = x[ROD_THETA], phi = x[ROD_PHI], y = x[ROD_Y], eps = p->epsilon, al = p->alpha;
    const double sn = sin(th), cs = cos(th);
    const double Xd = x[ROD_V] + phi * sn, Yd = x[ROD_W] + phi * cs;
    const double d = -y / eps, dp = d > 0 ? d : 0.0, S_d = d + p->kappa * dp * dp;
    d_x[ROD_V] = Xd;
    d_x[ROD_W] = Yd;
    d_x[ROD_Y] = 1 - (m.contact ? S_d / eps : 0);
    d_x[ROD_THETA] = phi * (Xd * cs - Yd * sn) + cs;
    d_x[ROD_PHI] = Xd * sn + Yd * cs + phi / al;
    d_p[ROD_P_ALPHA] = -0.5 * phi * phi / (al * al);
    d_p[ROD_P_EPSILON] = m.contact ? S_d * y / (eps * eps) : 0;
    d_p[ROD_P_KAPPA] = m.contact ? dp * dp * dp / 3 : 0;
}

/* The coefficients (rod_coefficient_outputs), mode-independent: with sg = +1 (plus), -1 (minus),
 *   a = -phi^2 cs + f_x - al sn tau,  b = -1 + phi^2 sn + f_y - al cs tau,
 *   q_sg = al sn cs - sg mu k,  p_sg = 1 + al cs^2 - sg mu al sn cs,  S_w = (1 + al)/k. */
static void coefficient_partials(const RodParams *p, const double x[ROD_NX], RodPartials *d)
{
    const double th = x[ROD_THETA], phi = x[ROD_PHI], al = p->alpha, mu = p->mu, tau = p->tau;
    const double sn = sin(th), cs = cos(th), k = 1 + al * sn * sn, c2s2 = cs * cs - sn * sn;
    double(*dx)[ROD_NX] = d->out_x, (*dp)[ROD_NP] = d->out_p, (*dl)[ROD_NL] = d->out_l;
    dx[ROD_OUT_A][ROD_THETA] = phi * phi * sn - al * cs * tau;
    dx[ROD_OUT_A][ROD_PHI] = -2 * phi * cs;
    dp[ROD_OUT_A][ROD_P_ALPHA] = -sn * tau;
    dl[ROD_OUT_A][ROD_L_FX] = 1;
    dl[ROD_OUT_A][ROD_L_TAU] = -al * sn;
    dx[ROD_OUT_B][ROD_THETA] = phi * phi * cs + al * sn * tau;
    dx[ROD_OUT_B][ROD_PHI] = 2 * phi * sn;
    dp[ROD_OUT_B][ROD_P_ALPHA] = -cs * tau;
    dl[ROD_OUT_B][ROD_L_FY] = 1;
    dl[ROD_OUT_B][ROD_L_TAU] = -al * cs;
    for (int sg = -1; sg <= 1; sg += 2) {
        const int q = sg > 0 ? ROD_OUT_Q_PLUS : ROD_OUT_Q_MINUS, pp = sg > 0 ? ROD_OUT_P_PLUS : ROD_OUT_P_MINUS;
        dx[q][ROD_THETA] = al * c2s2 - sg * mu * 2 * al * sn * cs;
        dp[q][ROD_P_ALPHA] = sn * cs - sg * mu * sn * sn;
        dp[q][ROD_P_MU] = -sg * k;
        dx[pp][ROD_THETA] = -2 * al * sn * cs - sg * mu * al * c2s2;
        dp[pp][ROD_P_ALPHA] = cs * cs - sg * mu * sn * cs;
        dp[pp][ROD_P_MU] = -sg * al * sn * cs;
    }
    dx[ROD_OUT_S_W][ROD_THETA] = -(1 + al) * 2 * al * sn * cs / (k * k);
    dp[ROD_OUT_S_W][ROD_P_ALPHA] = cs * cs / (k * k);
}

void rod_partials(const RodParams *p, ContactMode m, const double x[ROD_NX], RodPartials *d)
{
    memset(d, 0, sizeof *d);   /* every pair not written below is structurally 0 */
    rod_jacobian(p, m, x, d->dx_x);
    derivatives_dp(p, m, x, d->dx_p);
    derivatives_dl(p, m, x, d->dx_l);
    normal_force_partials(p, m, x, d->out_x[ROD_OUT_F_N], d->out_p[ROD_OUT_F_N]);
    friction_force_partials(p, m, x, d->out_x[ROD_OUT_F_T], d->out_p[ROD_OUT_F_T], d->out_l[ROD_OUT_F_T]);
    energy_partials(p, m, x, d->out_x[ROD_OUT_ENERGY], d->out_p[ROD_OUT_ENERGY]);
    coefficient_partials(p, x, d);
}
