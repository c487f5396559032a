# SPDX-License-Identifier: BSD-2-Clause
"""An independent numpy model of the compliant two-link arm (not the C): a pivot at
height H above the floor, link 1 (m1, l1, J1 about its middle) to the elbow, link 2 (m2, l2, J2)
to the tip, which touches the floor; absolute angles theta1, theta2 counterclockwise from +x.

Own mass matrix (Lagrange on the kinetic energy of the two links), own contact kinematics (the
tip's Jacobian rows W_T = d x/d theta, W_N = d y/d theta and their velocity products), and the
paper's coefficients of eq Painleve from them, scaled with L = l1 + l2, M = m1 + m2, g:
q_s = M (G_TN - s mu G_TT), p_s = M (G_NN - s mu G_TN), G = J M^-1 J^T (docs/general_body_theory.md).
"""
from dataclasses import dataclass, replace

import numpy as np


@dataclass(frozen=True)
class Arm:
    H: float = 0.8
    m1: float = 0.5
    l1: float = 0.5
    J1: float = 0.5 * 0.5 ** 2 / 12
    m2: float = 0.5
    l2: float = 0.5
    J2: float = 0.5 * 0.5 ** 2 / 12
    g: float = 1.0
    mu: float = 1.0

    @property
    def L(self):
        return self.l1 + self.l2

    @property
    def M(self):
        return self.m1 + self.m2

    def with_(self, **kw):
        return replace(self, **kw)


def mass_matrix(arm, th):
    """M(theta) from T = 1/2 sum (m |v_cm|^2 + J omega^2): centres at l1/2 on link 1, l2/2 beyond the elbow."""
    k = arm.m2 * arm.l1 * arm.l2 / 2 * np.cos(th[0] - th[1])
    return np.array([[arm.m1 * arm.l1 ** 2 / 4 + arm.J1 + arm.m2 * arm.l1 ** 2, k],
                     [k, arm.m2 * arm.l2 ** 2 / 4 + arm.J2]])


def applied(arm, th, om):
    """Generalized gravity minus the velocity terms of Lagrange's equations (absolute angles)."""
    k = arm.m2 * arm.l1 * arm.l2 / 2 * np.sin(th[0] - th[1])
    gravity = -arm.g * np.array([(arm.m1 / 2 + arm.m2) * arm.l1 * np.cos(th[0]), arm.m2 * arm.l2 / 2 * np.cos(th[1])])
    return gravity - np.array([k * om[1] ** 2, -k * om[0] ** 2])


def tip(arm, th):
    """(x, y) of the tip."""
    return (arm.l1 * np.cos(th[0]) + arm.l2 * np.cos(th[1]),
            arm.H + arm.l1 * np.sin(th[0]) + arm.l2 * np.sin(th[1]))


def jacobian(arm, th):
    """Rows W_T (tangential, x) and W_N (normal, y): (v, w) = J omega."""
    return np.array([[-arm.l1 * np.sin(th[0]), -arm.l2 * np.sin(th[1])],
                     [arm.l1 * np.cos(th[0]), arm.l2 * np.cos(th[1])]])


def velocity_products(arm, th, om):
    """(dJ/dt) omega: the tip's acceleration at zero angular acceleration."""
    return np.array([-arm.l1 * np.cos(th[0]) * om[0] ** 2 - arm.l2 * np.cos(th[1]) * om[1] ** 2,
                     -arm.l1 * np.sin(th[0]) * om[0] ** 2 - arm.l2 * np.sin(th[1]) * om[1] ** 2])


def free_acceleration(arm, th, om):
    """(v', w') without contact force, and M^-1."""
    minv = np.linalg.inv(mass_matrix(arm, th))
    return jacobian(arm, th) @ minv @ applied(arm, th, om) + velocity_products(arm, th, om), minv


def coefficients(arm, th, om):
    """Scaled eq Painleve coefficients a, b, p_+-, q_+-, S_w and the generalized-velocity responses
    c_+- = M^-1 (W_N - s mu W_T) (scaled: per unit M g of F_N, rates in sqrt(g/L))."""
    (ab, minv), J = free_acceleration(arm, th, om), jacobian(arm, th)
    G = arm.M * J @ minv @ J.T
    out = dict(a=ab[0] / arm.g, b=ab[1] / arm.g)
    for s, name in ((1, "plus"), (-1, "minus")):
        out[f"q_{name}"] = G[0, 1] - s * arm.mu * G[0, 0]
        out[f"p_{name}"] = G[1, 1] - s * arm.mu * G[1, 0]
        out[f"c_{name}"] = arm.M * minv @ (J[1] - s * arm.mu * J[0]) * arm.L
    with np.errstate(divide="ignore", invalid="ignore"):   # G_TT = 0 where the tip cannot slip (W_T = 0)
        out["S_w"] = np.linalg.det(G) / G[0, 0]
    return out


def floor_angle(arm, theta1, branch=-1):
    """theta2 that puts the tip on the floor (y = 0) for a given theta1; branch picks cos theta2's sign."""
    s2 = -(arm.H + arm.l1 * np.sin(theta1)) / arm.l2
    if abs(s2) > 1:
        raise ValueError(f"the tip cannot reach the floor at theta1 = {theta1}")
    return np.arcsin(s2) if branch > 0 else -np.pi - np.arcsin(s2)


def rates(arm, th, v, w):
    """omega giving the tip velocity (v, w)."""
    return np.linalg.solve(jacobian(arm, th), [v, w])
