/* SPDX-License-Identifier: BSD-2-Clause */
/* The two-link arm's kinematics and dynamics for the contact core (arm_body.h).
 *
 * Lagrange's equations in absolute angles, with beta = m2 l1 l2 / 2, c12 = cos(theta1 - theta2),
 * s12 = sin(theta1 - theta2):
 *   M11 omega1' + beta c12 omega2' + beta s12 omega2^2 = Q1,
 *   beta c12 omega1' + M22 omega2' - beta s12 omega1^2 = Q2,
 * gravity Q = -(m1 l1/2 + m2 l1) cos theta1, -m2 l2/2 cos theta2 (g = 1), and the tip's
 * forces through the Jacobians of its position,
 *   W_T = dx/dq = (-l1 sin theta1, -l2 sin theta2),  W_N = dy/dq = (l1 cos theta1, l2 cos theta2):
 * Q += W_N^T F_N - W_T^T F_T (F_T opposes positive slip). The core needs M^-1 W_N^T,
 * M^-1 W_T^T, the free accelerations, and the tip's accelerations without contact force,
 *   a = W_T omega'_free - (l1 cos theta1 omega1^2 + l2 cos theta2 omega2^2),
 *   b = W_N omega'_free - (l1 sin theta1 omega1^2 + l2 sin theta2 omega2^2). */
#include "arm_body.h"

#include <float.h>
#include <math.h>

void arm_mass_matrix(const ArmBody *b, const double x[ARM_NX], double M[2][2])
{
    const double beta = 0.5 * b->m2 * b->l1 * b->l2;
    M[0][0] = b->J1 + 0.25 * b->m1 * b->l1 * b->l1 + b->m2 * b->l1 * b->l1;
    M[1][1] = b->J2 + 0.25 * b->m2 * b->l2 * b->l2;
    M[0][1] = M[1][0] = beta * cos(x[ARM_THETA1] - x[ARM_THETA2]);
}

/* u = M^-1 f for the 2 x 2 mass matrix; det written as a sum of terms >= 0
 * (M11 M22 - beta^2 c12^2 = (J1 + m1 l1^2/4) M22 + m2 l1^2 J2 + beta^2 s12^2), so it
 * has no cancellation, and at least DBL_MIN (m1 > 0 keeps it positive but for underflow). */
static void solve(double M11, double M12, double M22, double det, const double f[2], double u[2])
{
    u[0] = (M22 * f[0] - M12 * f[1]) / det;
    u[1] = (M11 * f[1] - M12 * f[0]) / det;
}

double arm_height(const ArmBody *b, double theta1, double theta2)
{
    const double a = b->l1 * sin(theta1), c = b->l2 * sin(theta2), y = b->H + a + c;
    return fabs(y) <= 8 * DBL_EPSILON * (fabs(b->H) + fabs(a) + fabs(c)) ? 0.0 : y;
}

static void arm_evaluate(const void *params, const double x[], BodyState *s)
{
    const ArmBody *b = params;
    const double t1 = x[ARM_THETA1], t2 = x[ARM_THETA2], w1 = x[ARM_OMEGA1], w2 = x[ARM_OMEGA2];
    const double s1 = sin(t1), c1 = cos(t1), s2 = sin(t2), c2 = cos(t2), s12 = sin(t1 - t2);
    const double l1 = b->l1, l2 = b->l2, beta = 0.5 * b->m2 * l1 * l2;
    double M[2][2];
    arm_mass_matrix(b, x, M);
    double det = (b->J1 + 0.25 * b->m1 * l1 * l1) * M[1][1] + b->m2 * l1 * l1 * b->J2 + beta * beta * s12 * s12;
    if (!(det >= DBL_MIN)) det = DBL_MIN;
    const double WT[2] = { -l1 * s1, -l2 * s2 }, WN[2] = { l1 * c1, l2 * c2 };
    const double f[2] = { -beta * s12 * w2 * w2 - (0.5 * b->m1 + b->m2) * l1 * c1,
                          beta * s12 * w1 * w1 - 0.5 * b->m2 * l2 * c2 };
    double free[2], normal[2], friction[2];
    solve(M[0][0], M[0][1], M[1][1], det, f, free);
    solve(M[0][0], M[0][1], M[1][1], det, WN, normal);
    solve(M[0][0], M[0][1], M[1][1], det, WT, friction);
    const double cent_x = l1 * c1 * w1 * w1 + l2 * c2 * w2 * w2, cent_y = l1 * s1 * w1 * w1 + l2 * s2 * w2 * w2;
    s->x = l1 * c1 + l2 * c2;
    s->y = x[ARM_Y];   /* a state: no rounding error */
    s->y_noise = 0;
    s->v = WT[0] * w1 + WT[1] * w2;
    s->w = WN[0] * w1 + WN[1] * w2;
    /* The rounding of the sums above: ulps of their largest terms. */
    const double ulps = 8 * DBL_EPSILON;
    s->v_noise = ulps * (fabs(WT[0] * w1) + fabs(WT[1] * w2));
    s->w_noise = ulps * (fabs(WN[0] * w1) + fabs(WN[1] * w2));
    for (int i = 0; i < 2; ++i) {
        s->free[i] = free[i];
        s->normal[i] = normal[i];
        s->friction[i] = friction[i];
    }
    s->a = (WT[0] * free[0] + WT[1] * free[1]) - cent_x;
    s->b = (WN[0] * free[0] + WN[1] * free[1]) - cent_y;
    s->a_scale = fabs(WT[0] * free[0]) + fabs(WT[1] * free[1]) + fabs(l1 * c1 * w1 * w1) + fabs(l2 * c2 * w2 * w2);
    s->G_TT = WT[0] * friction[0] + WT[1] * friction[1];
    s->G_TN = WT[0] * normal[0] + WT[1] * normal[1];
    s->G_NN = WN[0] * normal[0] + WN[1] * normal[1];
    /* kinetic 1/2 u^T M u, potential of the centres of mass above the floor (g = 1) */
    const double kinetic = 0.5 * (M[0][0] * w1 * w1 + 2 * M[0][1] * w1 * w2 + M[1][1] * w2 * w2);
    const double potential = b->m1 * (b->H + 0.5 * l1 * s1) + b->m2 * (b->H + l1 * s1 + 0.5 * l2 * s2);
    s->energy = kinetic + potential;
}

/* The contact's scales: the gap ~ eps^2 and its rate ~ eps move with the angles and rates by
 * as much (lengths are O(1) in these units), so those are the angles', the rates' and y's nominals. */
static void arm_nominals(const void *params, double epsilon, double nominal[])
{
    (void)params;
    nominal[ARM_THETA1] = nominal[ARM_THETA2] = nominal[ARM_Y] = epsilon * epsilon;
    nominal[ARM_OMEGA1] = nominal[ARM_OMEGA2] = epsilon;
}

/* The tip's height is its state, and its normal rate the sum over the links w = W_N omega, so
 * dy/dtheta = W_N (what y' = w would move it by; the core holds y to its state alone) and
 * dw/dtheta_i = -l_i sin theta_i omega_i. */
static void arm_gap_rows(const void *params, const double x[], double *y, double *w, double dy_dq[],
                         double dw_dq[])
{
    const ArmBody *b = params;
    const double s1 = sin(x[ARM_THETA1]), c1 = cos(x[ARM_THETA1]), s2 = sin(x[ARM_THETA2]), c2 = cos(x[ARM_THETA2]);
    dy_dq[0] = b->l1 * c1;
    dy_dq[1] = b->l2 * c2;
    dw_dq[0] = -b->l1 * s1 * x[ARM_OMEGA1];
    dw_dq[1] = -b->l2 * s2 * x[ARM_OMEGA2];
    *y = x[ARM_Y];
    *w = dy_dq[0] * x[ARM_OMEGA1] + dy_dq[1] * x[ARM_OMEGA2];
}

/* No coordinate is the tip's x: a stick begins by the friction impulse that stops the slip. */
const Body arm_body = { .dof = 2, .position = { ARM_THETA1, ARM_THETA2 }, .velocity = { ARM_OMEGA1, ARM_OMEGA2 },
                        .slip_coordinate = -1, .evaluate = arm_evaluate, .nominals = arm_nominals,
                        .gap_rows = arm_gap_rows, .has_gap_state = true, .gap_state = ARM_Y };
