# SPDX-License-Identifier: BSD-2-Clause
"""The coefficients of eq Painleve for any rigid body, computed here from its mass matrix and
the contact point's Jacobians (numpy; independent of the FMUs' C): with the generalized
coordinates q, mass matrix M, the contact point's tangential and normal rows W_T, W_N
(x' = W_T q', y' = W_N q') and the Delassus matrix G = W M^-1 W^T, a friction force
-s mu F_N along x while slipping in direction s gives
    v' = a + (G_TN - s mu G_TT) F_N,   w' = b + (G_NN - s mu G_NT) F_N,
so q_s = G_TN - s mu G_TT, p_s = G_NN - s mu G_NT, and the friction that holds v' = 0 gives
the sticking gain S_w = G_NN - G_NT^2 / G_TT (the Schur complement)."""
import numpy as np


def coefficients(M, W_T, W_N, mu):
    Minv = np.linalg.inv(np.asarray(M, float))
    W = np.vstack([W_T, W_N])
    G = W @ Minv @ W.T
    tt, tn, nn = G[0, 0], G[0, 1], G[1, 1]
    return dict(q_plus=tn - mu * tt, q_minus=tn + mu * tt, p_plus=nn - mu * tn, p_minus=nn + mu * tn,
                S_w=nn - tn * tn / tt)


def rod(theta, alpha, mu):
    """The uniform rod in the paper's units: q = (X, Y, theta) of the centre of mass and the angle
    (clockwise), unit mass, inertia 1/alpha; the contact end at (X + cos theta, Y - sin theta)."""
    s, c = np.sin(theta), np.cos(theta)
    return coefficients(np.diag([1.0, 1.0, 1.0 / alpha]), [1.0, 0.0, -s], [0.0, 1.0, -c], mu)
