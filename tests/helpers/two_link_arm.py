# SPDX-License-Identifier: BSD-2-Clause
"""The two-link arm of fmu_src/models/TwoLinkArm written out again for its tests, from the
links' centres of mass alone (numpy; not the FMU's closed forms): the mass matrix as
sum m_i J_i^T J_i + J_i e^T e over the links (J_i the centres' Jacobians), gravity and the
velocity-product terms by differences of the Lagrangian's parts, the tip's Jacobians and
acceleration by differences of its position."""
import numpy as np

DEFAULTS = dict(m1=0.5, l1=0.3, J1=0.5 * 0.09 / 12, m2=0.3, l2=0.2, J2=0.3 * 0.04 / 12, H=0.44515293252580757,
                g=9.81)


def centres(q, p):
    """The links' centres of mass: link 1 at half of l1 from the pivot, link 2 half of l2 past the elbow."""
    t1, t2 = q
    pivot = np.array([0.0, p["H"]])
    elbow = pivot + p["l1"] * np.array([np.cos(t1), np.sin(t1)])
    return (pivot + 0.5 * p["l1"] * np.array([np.cos(t1), np.sin(t1)]),
            elbow + 0.5 * p["l2"] * np.array([np.cos(t2), np.sin(t2)]))


def tip(q, p):
    t1, t2 = q
    return np.array([p["l1"] * np.cos(t1) + p["l2"] * np.cos(t2), p["H"] + p["l1"] * np.sin(t1) + p["l2"] * np.sin(t2)])


def jacobian(f, q, h=1e-6):
    q = np.asarray(q, float)
    cols = [(f(q + h * e) - f(q - h * e)) / (2 * h) for e in np.eye(len(q))]
    return np.array(cols).T


def centre_jacobians(q, p):
    """d(centre)/dq of each link: link 1's turns with theta1 at half of l1; link 2's with theta1 at
    the elbow (l1) and with theta2 at half of l2."""
    s1, c1, s2, c2 = np.sin(q[0]), np.cos(q[0]), np.sin(q[1]), np.cos(q[1])
    l1, l2 = p["l1"], p["l2"]
    return (np.array([[-0.5 * l1 * s1, 0.0], [0.5 * l1 * c1, 0.0]]),
            np.array([[-l1 * s1, -0.5 * l2 * s2], [l1 * c1, 0.5 * l2 * c2]]))


def mass_matrix(q, p):
    """sum over links of m J_c^T J_c (the centre's translation) + J e_i e_i^T (link i turns with theta_i)."""
    M = np.zeros((2, 2))
    for i, (Jc, m, J) in enumerate(zip(centre_jacobians(q, p), (p["m1"], p["m2"]), (p["J1"], p["J2"]))):
        e = np.eye(2)[i]
        M += m * Jc.T @ Jc + J * np.outer(e, e)
    return M


def potential(q, p):
    c1, c2 = centres(q, p)
    return p["g"] * (p["m1"] * c1[1] + p["m2"] * c2[1])


def energy(q, u, p):
    return 0.5 * u @ mass_matrix(q, p) @ u + potential(q, p)


def free_acceleration(q, u, p, h=1e-5):
    """u' with no contact force: M u' = -dV/dq - (dM/dt u - 1/2 d(u^T M u)/dq)."""
    q, u = np.asarray(q, float), np.asarray(u, float)
    M = mass_matrix(q, p)
    dV = jacobian(lambda qq: np.atleast_1d(potential(qq, p)), q)[0]
    Mdot = (mass_matrix(q + h * u, p) - mass_matrix(q - h * u, p)) / (2 * h)
    dT = jacobian(lambda qq: np.atleast_1d(0.5 * u @ mass_matrix(qq, p) @ u), q)[0]
    return np.linalg.solve(M, -dV - Mdot @ u + dT)


def tip_acceleration(q, u, udot, p, h=1e-4):
    """d^2/dt^2 of the tip along q(t) = q + u t + udot t^2/2, by central differences in t."""
    q, u, udot = (np.asarray(a, float) for a in (q, u, udot))
    at = lambda t: tip(q + u * t + 0.5 * udot * t * t, p)  # noqa: E731
    return (at(h) - 2 * at(0.0) + at(-h)) / (h * h)
