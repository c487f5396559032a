# SPDX-License-Identifier: BSD-2-Clause
"""The rigid limit eps -> 0 of impact without collision for a nonlinear compliance law.

The paper (Hogan & Kristiansen) proves Theorem 1 for any normal force
F_N = eps^-1 h(y/eps, w) with h = -yh - delta w + O((yh + w)^2) (eq hNon) but
computes e only for the linear truncation (eq hLin, `analytic.e`). Here e is
computed numerically for the compliance law of the FMU (fmu_src/rod/rod.h):

    h(yh, w) = -yh + kappa d^2 - delta w (1 + beta d),   d = max(-yh, 0),

kappa >= 0 a stiffening spring (scaled stiffness 1 + 2 kappa d), beta >= 0 a
damping that grows with the penetration (Hunt-Crossley-like). kappa = beta = 0
is the paper's linear law.

In the fast time tau = t/eps with yh = y/eps, Theorem 1's IWC is, at eps = 0:

1. Slipping compression (s = +1): yh' = w, w' = p_+ h(yh, w), v' = q_+ h(yh, w),
   theta frozen at theta0 (see `stick_start` for why v = 0 exactly where
   w = -p_+ v0/q_+). The rod starts O(eps) from the origin, a saddle
   (p_+ < 0), and leaves along the branch of its unstable manifold with
   yh < 0, w < 0, tangent to (1, lambda_+) (eq lambdapm).
2. Sticking from v = 0: yh' = w, w' = S_w h(yh, w) (Proposition prop:stick with
   h for the linear bracket) until h = 0 (lift-off); e = w there / v0.

With a nonlinear h the scaling symmetry of the linear law is gone: e depends on
v0 through kappa v0 and beta v0 (substitute yh = v0 Y, w = v0 W), not on
kappa, beta, v0 separately.

Pure numpy/scipy; vectorised over theta0 and the compliance parameters (all
broadcast together). Two methods: `e_rigid` (manifold parametrised by ln w,
then the stick system in time with one dense-output integration and root
location) and `e_shooting` (the full fast system yh, w, v from the floor in
time, each case on its own with solve_ivp's event location on v = 0 and h = 0),
independent enough to check each other.
"""
from dataclasses import dataclass

import numpy as np
import scipy.integrate
import scipy.optimize

from .hypotheses import HypothesisError
from .rod_coefficients import ALPHA, MU, S_w, lambda_pm, p_plus, q_plus

RTOL, ATOL = 1e-13, 1e-15
START = 1e-7   # the manifold is entered at |w| = START |w_stick|: its curvature error ~ START^2


def h(yh, w, delta, kappa=0.0, beta=0.0):
    """The compliance law h(yh, w) (as fmu_src/contact/contact.c's contact_compliance computes it)."""
    d = np.maximum(-yh, 0.0)
    return -yh + kappa * d * d - delta * w * (1 + beta * d)


@dataclass(frozen=True)
class RigidLimit:
    """The eps -> 0 IWC of Theorem 1 for a compliance law, per case (arrays, broadcast shape)."""
    e: np.ndarray           # w at lift-off / v0
    yhat_stick: np.ndarray  # yh where slipping compression ends (v = 0): eq initStick's -p_+ v0/(q_+ lambda_+) if linear
    w_stick: np.ndarray     # w there: -p_+ v0/q_+ for every law
    yhat_lift: np.ndarray   # yh at lift-off (h = 0)
    tau_stick: np.ndarray   # fast duration of the stick


def _coefficients(delta, theta0, alpha, mu):
    """p_+, q_+, S_w, lambda_+ at theta0 (Theorem 1's hypotheses checked by lambda_pm)."""
    pp = np.asarray(p_plus(theta0, alpha=alpha, mu=mu), dtype=float)
    qp = np.asarray(q_plus(theta0, alpha=alpha, mu=mu), dtype=float)
    sw = np.asarray(S_w(theta0, alpha=alpha), dtype=float)
    lp = np.asarray(lambda_pm(theta0, delta, alpha=alpha, mu=mu)[0], dtype=float)
    if np.any(pp >= 0) or np.any(qp >= 0):
        raise HypothesisError("Theorem 1 needs p_+ < 0 and q_+ < 0 (inside the Painleve wedge)")
    return pp, qp, sw, lp


def _broadcast(delta, theta0, kappa, beta, v0):
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (delta, theta0, kappa, beta, v0)))
    if np.any(arrays[0] < 0) or np.any(arrays[2] < 0) or np.any(arrays[3] < 0):
        raise ValueError("delta, kappa and beta must be >= 0 (h decreasing in yh and w, as the FMU requires)")
    if np.any(arrays[4] <= 0):
        raise HypothesisError("Theorem 1 needs v0 > 0")
    return [a.ravel() for a in arrays], arrays[0].shape


def stick_start(delta, theta0, *, kappa=0.0, beta=0.0, v0=1.0, alpha=ALPHA, mu=MU):
    """(yh, w) where slipping compression ends, v = 0, at eps = 0.

    Why w = -p_+ v0/q_+ still holds for any h: while slipping forward the one
    contact force F_N drives both velocities, w' = b + p_+ F_N and
    v' = a + q_+ F_N, with theta frozen at theta0 on the fast scale. In fast
    time dw/dtau = eps b + p_+ h and dv/dtau = eps a + q_+ h, so
    d(v - (q_+/p_+) w)/dtau = eps (a - q_+ b/p_+): over the compression's fast
    duration O(ln 1/eps) it moves by O(eps ln 1/eps) -> 0, whatever h is. Hence
    v - v0 = (q_+/p_+)(w - w(0)) with w(0) = O(eps), and v = 0 at w = -p_+ v0/q_+.
    Only the depth yh reached there depends on h: it is where the unstable
    manifold of the saddle at the origin (yh' = w, w' = p_+ h) reaches that w.

    Along that branch yh and w decrease (yh' = w < 0, w' = p_+ h < 0) so h grows
    (it decreases in both arguments) and w is monotone: the manifold is
    integrated as yh(u) with u = ln(w/w_stick) from ln START to 0,
    dyh/du = w dyh/dw = w^2/(p_+ h), entered on its tangent yh = w/lambda_+.
    The end, w = w_stick, is u = 0 for every case at once (no event needed).
    """
    (delta, theta0, kappa, beta, v0), shape = _broadcast(delta, theta0, kappa, beta, v0)
    pp, qp, sw, lp = _coefficients(delta, theta0, alpha, mu)
    w_stick = -pp * v0 / qp            # < 0: moving down
    u0 = np.log(START)

    def rhs(u, yh):
        w = w_stick * np.exp(u)
        return w * w / (pp * h(yh, w, delta, kappa, beta))

    sol = scipy.integrate.solve_ivp(rhs, (u0, 0.0), w_stick * START / lp, method="DOP853", rtol=RTOL,
                                    atol=ATOL * np.abs(w_stick / lp))
    if not sol.success:
        raise RuntimeError(f"slipping compression: {sol.message}")
    return sol.y[:, -1].reshape(shape), w_stick.reshape(shape)


def _first_roots(sol, f, t_end, n_cases):
    """First time in (0, t_end] at which each case's f(state) <= 0, from the dense output: the
    sign scanned at 16 points per step, the crossing refined with brentq (NaN: none yet)."""
    steps = sol.t
    grid = np.concatenate([np.linspace(a, b, 16, endpoint=False) for a, b in zip(steps[:-1], steps[1:])] + [[t_end]])
    values = f(sol.sol(grid))                     # (n_cases, len(grid))
    roots = np.full(n_cases, np.nan)
    for i in range(n_cases):
        below = np.nonzero(values[i] <= 0)[0]
        if below.size == 0:
            continue
        k = below[0]
        if k == 0:
            roots[i] = grid[0]
            continue
        roots[i] = scipy.optimize.brentq(lambda t: f(sol.sol(t)[:, None])[i, 0], grid[k - 1], grid[k],
                                         xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
    return roots


def e_rigid(delta, theta0, *, kappa=0.0, beta=0.0, v0=1.0, alpha=ALPHA, mu=MU):
    """The rigid-limit IWC (RigidLimit, with e) for the compliance law (delta, kappa, beta), by
    `stick_start` and then the stick system yh' = w, w' = S_w h integrated for all cases at once
    until each one's h = 0 (dense output, root refined per case)."""
    (delta, theta0, kappa, beta, v0), shape = _broadcast(delta, theta0, kappa, beta, v0)
    _, _, sw, _ = _coefficients(delta, theta0, alpha, mu)
    y0, w0 = (a.ravel() for a in stick_start(delta, theta0, kappa=kappa, beta=beta, v0=v0, alpha=alpha, mu=mu))
    n = y0.size

    def rhs(t, z):
        yh, w = z[:n], z[n:]
        return np.concatenate([w, sw * h(yh, w, delta, kappa, beta)])

    def force(z):
        return h(z[:n], z[n:], delta[:, None], kappa[:, None], beta[:, None])

    # Time scales of the stick: 1/sqrt(S_w) (oscillation), delta S_w and 1/delta (damping);
    # the stick ends within a few of the longest (the linear law: tau_s < pi/omega or ~ delta).
    span = 4.0 * float(np.max(np.maximum(1 / np.sqrt(sw), 1 + delta)))
    z, t0, tau = np.concatenate([y0, w0]), 0.0, np.full(n, np.nan)
    end = np.zeros((2, n))
    for _ in range(30):
        sol = scipy.integrate.solve_ivp(rhs, (t0, t0 + span), z, method="DOP853", rtol=RTOL,
                                        atol=ATOL * np.concatenate([np.abs(y0), np.abs(w0)]), dense_output=True)
        if not sol.success:
            raise RuntimeError(f"sticking: {sol.message}")
        todo = np.isnan(tau)
        roots = _first_roots(sol, force, t0 + span, n)
        found = todo & ~np.isnan(roots)
        for i in np.nonzero(found)[0]:
            state = sol.sol(roots[i])
            end[:, i] = state[i], state[n + i]
            tau[i] = roots[i]
        if not np.any(np.isnan(tau)):
            break
        z, t0 = sol.y[:, -1], t0 + span
    else:
        raise RuntimeError("the stick did not end: h stayed > 0")
    return RigidLimit(e=(end[1] / v0).reshape(shape), yhat_stick=y0.reshape(shape), w_stick=w0.reshape(shape),
                      yhat_lift=end[0].reshape(shape), tau_stick=tau.reshape(shape))


def e(delta, theta0, *, kappa=0.0, beta=0.0, v0=1.0, alpha=ALPHA, mu=MU):
    """e(delta, theta0; kappa, beta, v0): the rigid limit's lift-off velocity over v0."""
    return e_rigid(delta, theta0, kappa=kappa, beta=beta, v0=v0, alpha=alpha, mu=mu).e


def _shoot_one(delta, pp, qp, sw, kappa, beta, v0, w_start):
    """One case by the full fast system at eps = 0, in time: (yh, w, v) slipping from the floor
    yh = 0, w = w_start < 0 (off the manifold, as the FMU starts) until v = 0, then
    (yh, w) sticking until h = 0, both ends by solve_ivp's own event location."""
    def slip(t, z):
        f = h(z[0], z[1], delta, kappa, beta)
        return [z[1], pp * f, qp * f]

    def stopped(t, z):
        return z[2]
    stopped.terminal, stopped.direction = True, -1
    tiny = 1e-6 * abs(w_start)
    first = scipy.integrate.solve_ivp(slip, (0.0, 1e4), [0.0, w_start, v0], method="LSODA", events=stopped,
                                      rtol=1e-12, atol=[tiny, tiny, 1e-14 * v0])
    if first.status != 1:
        raise RuntimeError(f"slipping compression did not stop: {first.message}")
    yh, w, _ = first.y_events[0][0]

    def stick(t, z):
        return [z[1], sw * h(z[0], z[1], delta, kappa, beta)]

    def lift_off(t, z):
        return h(z[0], z[1], delta, kappa, beta)
    lift_off.terminal, lift_off.direction = True, -1
    second = scipy.integrate.solve_ivp(stick, (0.0, 1e4), [yh, w], method="LSODA", events=lift_off,
                                       rtol=1e-12, atol=1e-14 * v0)
    if second.status != 1:
        raise RuntimeError(f"the stick did not end: {second.message}")
    return second.y_events[0][0][1] / v0, yh, w


def shooting(delta, theta0, *, kappa=0.0, beta=0.0, v0=1.0, alpha=ALPHA, mu=MU, w_start=1e-10):
    """The second method (`_shoot_one`, case by case): (e, yh, w at v = 0). No manifold, no ln w
    parametrisation, v integrated rather than w = -p_+ v0/q_+ assumed, LSODA instead of DOP853.
    The rod starts at w = -w_start |w_stick| (w_start relative to the end of compression): its
    error is that start off the manifold, w_start^(1 + |lambda_-|/lambda_+) relative, below the
    tolerances' ~1e-10."""
    (delta, theta0, kappa, beta, v0), shape = _broadcast(delta, theta0, kappa, beta, v0)
    pp, qp, sw, _ = _coefficients(delta, theta0, alpha, mu)
    starts = -w_start * np.abs(pp * v0 / qp)
    out = np.array([_shoot_one(*args) for args in zip(delta, pp, qp, sw, kappa, beta, v0, starts)])
    return tuple(out[:, k].reshape(shape) for k in range(3))


def e_shooting(delta, theta0, **kw):
    """e by `shooting`."""
    return shooting(delta, theta0, **kw)[0]
