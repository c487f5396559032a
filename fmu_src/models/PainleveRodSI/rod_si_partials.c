/* SPDX-License-Identifier: BSD-2-Clause */
/* PainleveRodSI's partial derivatives (see rod_si_partials.h).
 *
 * The accelerations and contact forces are an SI factor A times a quantity of
 * the dimensionless rod, u = A u_s(xs, P, L), with xs_j = (x_j - offset_j)/scale_j,
 * the rod's parameters P (alpha, delta, epsilon, mu) and loads L (f_x, f_y, tau).
 * Every factor is a monomial in the parameters m, l, J, g, k: for one of them,
 * theta, with exponents e(.),
 *   du/dtheta = (1/theta) [ e(A) u + A ( sum_j du_s/dxs_j (-e(scale_j)) xs_j
 *                                      + sum_P du_s/dP e(P) P + sum_L du_s/dL e(L) L ) ].
 * c and mu enter through delta = c/sqrt(m k) and mu alone. */
#include "rod_si_partials.h"

#include <math.h>

#include "si_floor.h"

enum { E_M, E_L, E_J, E_G, E_K, NE };  /* the parameters with exponents: m, l, J, g, k */

/* Exponents of the scales (x_j = offset_j + scale_j xs_j): l, sqrt(g l), l, sqrt(g l), 1, sqrt(g/l). */
static const double SCALE_EXP[ROD_NX][NE] = {
    [ROD_X] = { 0, 1, 0, 0, 0 },   [ROD_V] = { 0, 0.5, 0, 0.5, 0 },     [ROD_Y] = { 0, 1, 0, 0, 0 },
    [ROD_W] = { 0, 0.5, 0, 0.5, 0 }, [ROD_THETA] = { 0, 0, 0, 0, 0 }, [ROD_PHI] = { 0, -0.5, 0, 0.5, 0 },
};
/* alpha = m l^2/J, delta = c m^-1/2 k^-1/2, epsilon = (m g/(k l))^1/2; mu, kappa, beta none. */
static const double PARAM_EXP[ROD_NP][NE] = {
    [ROD_P_ALPHA] = { 1, 2, -1, 0, 0 },
    [ROD_P_DELTA] = { -0.5, 0, 0, 0, -0.5 },
    [ROD_P_EPSILON] = { 0.5, -0.5, 0, 0.5, -0.5 },
};
/* f_x, f_y = F/(m g), tau/(m g l). */
static const double LOAD_EXP[ROD_NL][NE] = {
    [ROD_L_FX] = { -1, 0, 0, -1, 0 }, [ROD_L_FY] = { -1, 0, 0, -1, 0 }, [ROD_L_TAU] = { -1, -1, 0, -1, 0 } };

/* One unknown of the rod: its SI factor A (with exponents), value u and the rod's rows. */
typedef struct {
    double A, exp[NE], u;
    const double *d_x, *d_p, *d_l;
} RodRow;

static bool rod_row(const Model *m, unsigned int unknown, RodRow *r)
{
    const RodPartials *d = &m->partials;
    int i;
    switch (unknown) {
    case VR_DER_V: i = ROD_V; break;
    case VR_DER_W: i = ROD_W; break;
    case VR_DER_PHI: i = ROD_PHI; break;
    case VR_F_N: i = -1 - ROD_OUT_F_N; break;
    case VR_F_T: i = -1 - ROD_OUT_F_T; break;
    case VR_A: case VR_B: case VR_P_PLUS: case VR_P_MINUS: case VR_Q_PLUS: case VR_Q_MINUS: case VR_S_W: {
        /* the scaled coefficients: factor 1, no exponents */
        const int o = ROD_OUT_A + (int)(unknown - VR_A);
        *r = (RodRow){ .A = 1, .u = m->out[SI_A + o - ROD_OUT_A], .d_x = d->out_x[o], .d_p = d->out_p[o],
                       .d_l = d->out_l[o] };
        return true;
    }
    default: return false;
    }
    if (i >= 0) {   /* accelerations: g, g, g/l */
        *r = (RodRow){ .A = i == ROD_PHI ? m->g / m->l : m->g, .exp = { 0, i == ROD_PHI ? -1 : 0, 0, 1, 0 },
                       .u = m->dx[i], .d_x = d->dx_x[i], .d_p = d->dx_p[i], .d_l = d->dx_l[i] };
    } else {        /* forces: m g */
        const int o = -1 - i;
        *r = (RodRow){ .A = m->m * m->g, .exp = { 1, 0, 0, 1, 0 }, .u = m->out[unknown == VR_F_N ? SI_F_N : SI_F_T],
                       .d_x = d->out_x[o], .d_p = d->out_p[o], .d_l = d->out_l[o] };
    }
    return true;
}

/* The index of parameter vr among the exponents' (E_*); -1 for any other variable. */
static int exponent_index(unsigned int vr)
{
    switch (vr) {
    case VR_M: return E_M;
    case VR_L: return E_L;
    case VR_J: return E_J;
    case VR_G: return E_G;
    case VR_K: return E_K;
    default: return -1;
    }
}

/* True if through_rod knows known: a state, an input, mu, c or a parameter with exponents. */
static bool rod_known(unsigned int known)
{
    switch (known) {
    case VR_X: case VR_V: case VR_Y: case VR_W: case VR_THETA: case VR_PHI:
    case VR_Y_FLOOR: case VR_W_FLOOR: case VR_V_FLOOR: case VR_F_X: case VR_F_Y: case VR_TAU:
    case VR_MU: case VR_C: return true;
    default: return exponent_index(known) >= 0;
    }
}

/* d u / d known for a parameter known (mu, c, or one with exponents). */
static double by_parameter(const Model *m, const RodRow *r, unsigned int known)
{
    if (known == VR_MU) return r->A * r->d_p[ROD_P_MU];
    if (known == VR_C) return r->A * r->d_p[ROD_P_DELTA] / sqrt(m->m * m->k);
    const int e = exponent_index(known);
    const double theta[NE] = { m->m, m->l, m->J, m->g, m->k };
    const double P[ROD_NP] = { [ROD_P_ALPHA] = m->rod.alpha, [ROD_P_DELTA] = m->rod.delta,
                               [ROD_P_EPSILON] = m->rod.epsilon };
    const double L[ROD_NL] = { m->rod.f_x, m->rod.f_y, m->rod.tau };
    double inner = 0;
    for (int j = 0; j < ROD_NX; ++j) inner -= r->d_x[j] * SCALE_EXP[j][e] * m->xs[j];
    for (int p = 0; p < ROD_NP; ++p) inner += r->d_p[p] * PARAM_EXP[p][e] * P[p];
    for (int l = 0; l < ROD_NL; ++l) inner += r->d_l[l] * LOAD_EXP[l][e] * L[l];
    return (r->exp[e] * r->u + r->A * inner) / theta[e];
}

static double through_rod(const Model *m, const RodRow *r, unsigned int known)
{
    const double mg = m->m * m->g, U = sqrt(m->g * m->l), per_T = sqrt(m->g / m->l);
    const double scale[ROD_NX] = { m->l, U, m->l, U, 1, per_T };
    if (known >= VR_X && known <= VR_PHI) return r->A * r->d_x[known - VR_X] / scale[known - VR_X];
    switch (known) {
    case VR_Y_FLOOR: return -r->A * r->d_x[ROD_Y] / m->l;
    case VR_W_FLOOR: return -r->A * (r->d_x[ROD_W] / U + r->d_x[ROD_Y] * si_floor_elapsed(m, m->time) / m->l);
    case VR_V_FLOOR: return -r->A * r->d_x[ROD_V] / U;
    case VR_F_X: return r->A * r->d_l[ROD_L_FX] / mg;
    case VR_F_Y: return r->A * r->d_l[ROD_L_FY] / mg;
    case VR_TAU: return r->A * r->d_l[ROD_L_TAU] / (mg * m->l);
    default: return by_parameter(m, r, known);
    }
}

/* energy = 1/2 m (vx^2 + vy^2) + 1/2 J phi^2 + m g y_cm [+ 1/2 k gap^2 in contact],
 * vx = v + l phi sn, vy = w + l phi cs, y_cm = y + l sn. */
static double energy(const Model *m, unsigned int known)
{
    const double l = m->l, sn = sin(m->x[ROD_THETA]), cs = cos(m->x[ROD_THETA]), phi = m->x[ROD_PHI];
    const double vx = m->out[SI_VX_CM], vy = m->out[SI_VY_CM], gap = m->out[SI_GAP];
    const double spring = m->run.mode.contact ? m->k * gap : 0;   /* d(1/2 k gap^2)/d gap */
    switch (known) {
    case VR_V: return m->m * vx;
    case VR_W: return m->m * vy;
    case VR_Y: return m->m * m->g + spring;
    case VR_Y_FLOOR: return -spring;
    case VR_W_FLOOR: return -spring * si_floor_elapsed(m, m->time);
    case VR_THETA: return m->m * l * phi * (vx * cs - vy * sn) + m->m * m->g * l * cs;
    case VR_PHI: return m->m * l * (vx * sn + vy * cs) + m->J * phi;
    case VR_M: return 0.5 * (vx * vx + vy * vy) + m->g * m->out[SI_Y_CM];
    case VR_L: return m->m * phi * (vx * sn + vy * cs) + m->m * m->g * sn;
    case VR_J: return 0.5 * phi * phi;
    case VR_G: return m->m * m->out[SI_Y_CM];
    case VR_K: return m->run.mode.contact ? 0.5 * gap * gap : 0;
    default: return 0;
    }
}

/* x_cm = x - l cs, y_cm = y + l sn, vx_cm = v + l phi sn, vy_cm = w + l phi cs. */
static double centre_of_mass(const Model *m, unsigned int unknown, unsigned int known)
{
    const double l = m->l, sn = sin(m->x[ROD_THETA]), cs = cos(m->x[ROD_THETA]), phi = m->x[ROD_PHI];
    const unsigned int own[] = { VR_X, VR_Y, VR_V, VR_W };  /* x_cm, y_cm, vx_cm, vy_cm move with these */
    const unsigned int which = unknown - VR_X_CM;
    if (known == own[which]) return 1;
    const double d_theta[] = { l * sn, l * cs, l * phi * cs, -l * phi * sn };
    const double d_phi[] = { 0, 0, l * sn, l * cs };
    const double d_l[] = { -cs, sn, phi * sn, phi * cs };
    if (known == VR_THETA) return d_theta[which];
    if (known == VR_PHI) return d_phi[which];
    if (known == VR_L) return d_l[which];
    return 0;
}

/* alpha = m l^2/J, epsilon = sqrt(m g/(k l)), delta = c/sqrt(m k). */
static double calculated_parameter(const Model *m, unsigned int unknown, unsigned int known)
{
    const RodParams *p = &m->rod;
    const double theta[NE] = { m->m, m->l, m->J, m->g, m->k };
    if (unknown == VR_DELTA && known == VR_C) return 1 / sqrt(m->m * m->k);
    const int row = unknown == VR_ALPHA ? ROD_P_ALPHA : unknown == VR_DELTA ? ROD_P_DELTA : ROD_P_EPSILON;
    const double value = unknown == VR_ALPHA ? p->alpha : unknown == VR_DELTA ? p->delta : p->epsilon;
    const int e = exponent_index(known);
    return e < 0 ? 0 : PARAM_EXP[row][e] * value / theta[e];   /* alpha, epsilon, delta depend on no other */
}

const char *si_partial(const Model *m, unsigned int unknown, unsigned int known, double *value)
{
    RodRow r;
    if (rod_row(m, unknown, &r)) {
        if (!rod_known(known)) return "the known is not a variable the SI rod's partial derivatives know";
        *value = through_rod(m, &r, known);
        return NULL;
    }
    const double elapsed = si_floor_elapsed(m, m->time);
    switch (unknown) {
    case VR_DER_X: *value = known == VR_V; break;
    case VR_DER_Y: *value = known == VR_W; break;
    case VR_DER_THETA: *value = known == VR_PHI; break;
    case VR_ENERGY: *value = energy(m, known); break;
    case VR_X_CM: case VR_Y_CM: case VR_VX_CM: case VR_VY_CM: *value = centre_of_mass(m, unknown, known); break;
    case VR_GAP: *value = known == VR_Y ? 1 : known == VR_Y_FLOOR ? -1 : known == VR_W_FLOOR ? -elapsed : 0; break;
    case VR_SLIP: *value = known == VR_V ? 1 : known == VR_V_FLOOR ? -1 : 0; break;
    case VR_ALPHA: case VR_EPSILON: case VR_DELTA: *value = calculated_parameter(m, unknown, known); break;
    default: return "the unknown is not a variable the SI rod's partial derivatives know";
    }
    return NULL;
}
