# SPDX-License-Identifier: BSD-2-Clause
"""An event-driven Filippov reference for the TwoLinkArm FMU with any spring k and damper c (SI),
for the differential tests (tests/differential/): the arm of helpers.arm_lagrange, its equations
written again with scalar math (the right-hand side runs ~1e4 times a case), integrated by
scipy's DOP853 mode by mode between terminal events, restarting from each event state.

Modes and exits (the Filippov rules of docs/general_body.md, written here from the mechanics):
* flight (no contact force): watches y = 0 downwards (touch-down), the force bracket -k y - c w
  upwards while y < 0 (re-contact below the floor), and y = 0 upwards after a contact (the return);
* slip s = +-1 (friction -s mu F_N on the tip): watches F_N = 0 downwards (lift-off) and v = 0;
  at v = 0 the tip sticks if the friction that holds v' = 0 is inside the cone, |F_T| < mu F_N
  (then v is set to exactly 0), else the slip reverses;
* stick (v = 0 held; F_T solved from v' = 0): watches lift-off and the folds F_T = +-mu F_N,
  which start slip forward (+) or backward (-).

The state is (theta - theta0, omega), so that the angles' absolute tolerance can be of the order of
the contact's length scale M g/k over L without losing digits to theta0 itself."""
import math

import numpy as np
from scipy.integrate import solve_ivp

from .arm_lagrange import jacobian, tip

_TINY = 1e-300


class ArmReferenceError(RuntimeError):
    """The reference could not finish: no event before the horizon, chatter, or a solver failure."""


class Params:
    """The arm's parameters as plain floats (what the right-hand side reads)."""

    def __init__(self, m1, m2, l1, l2, J1, J2, g, mu, H, k, c):
        self.m1, self.m2, self.l1, self.l2, self.J1, self.J2 = m1, m2, l1, l2, J1, J2
        self.g, self.mu, self.H, self.k, self.c = g, mu, H, k, c
        self.M, self.L = m1 + m2, l1 + l2

    @classmethod
    def of(cls, d):
        return cls(**{n: float(d[n]) for n in ("m1", "m2", "l1", "l2", "J1", "J2", "g", "mu", "H", "k", "c")})


def _height(p, a0, b0, y0, d1, d2):
    """The tip's height at angles (a0 + d1, b0 + d2) from its height y0 at (a0, b0), by differences of
    sines (sin(a + d) - sin a = 2 cos(a + d/2) sin(d/2)): no rounding of H + l1 sin + l2 sin, whose
    1e-16 m times k ~ 1e11 N/m would be a force at the start."""
    return y0 + 2 * (p.l1 * math.cos(a0 + d1 / 2) * math.sin(d1 / 2) + p.l2 * math.cos(b0 + d2 / 2) * math.sin(d2 / 2))


def _terms(p, t1, t2, o1, o2, y=None):
    """Mass matrix (A, B; B, C), generalized applied forces (Q1, Q2), the tip's Jacobian rows
    W_T = (wt1, wt2), W_N = (wn1, wn2), its velocity products (pT, pN), and y (given, or from H and
    the angles), v, w."""
    s1, c1, s2, c2 = math.sin(t1), math.cos(t1), math.sin(t2), math.cos(t2)
    h = p.m2 * p.l1 * p.l2 / 2
    cd, sd = math.cos(t1 - t2), math.sin(t1 - t2)
    A = p.m1 * p.l1 ** 2 / 4 + p.J1 + p.m2 * p.l1 ** 2
    B = h * cd
    C = p.m2 * p.l2 ** 2 / 4 + p.J2
    Q1 = -p.g * (p.m1 / 2 + p.m2) * p.l1 * c1 - h * sd * o2 * o2
    Q2 = -p.g * p.m2 * p.l2 / 2 * c2 + h * sd * o1 * o1
    wt1, wt2, wn1, wn2 = -p.l1 * s1, -p.l2 * s2, p.l1 * c1, p.l2 * c2
    pT = -p.l1 * c1 * o1 * o1 - p.l2 * c2 * o2 * o2
    pN = -p.l1 * s1 * o1 * o1 - p.l2 * s2 * o2 * o2
    if y is None:
        y = p.H + p.l1 * s1 + p.l2 * s2
    return A, B, C, Q1, Q2, wt1, wt2, wn1, wn2, pT, pN, y, wt1 * o1 + wt2 * o2, wn1 * o1 + wn2 * o2


def _solve(A, B, C, r1, r2):
    det = A * C - B * B
    return (C * r1 - B * r2) / det, (A * r2 - B * r1) / det


def _contact(p, T, s):
    """(domega1, domega2, F_N, F_T) in contact with slip sign s (0: stick) from _terms' T."""
    A, B, C, Q1, Q2, wt1, wt2, wn1, wn2, pT, pN, y, v, w = T
    fn = -p.k * y - p.c * w
    r1, r2 = Q1 + wn1 * fn, Q2 + wn2 * fn
    if s:
        ft = s * p.mu * fn
    else:   # the friction that keeps v' = W_T M^-1 (r - W_T ft) + pT at 0
        a1, a2 = _solve(A, B, C, r1, r2)
        b1, b2 = _solve(A, B, C, wt1, wt2)
        ft = (wt1 * a1 + wt2 * a2 + pT) / (wt1 * b1 + wt2 * b2)
    d1, d2 = _solve(A, B, C, r1 - wt1 * ft, r2 - wt2 * ft)
    return d1, d2, fn, ft


class Run:
    """Where a reference run ended: t, theta, omega, the tip's (y, v, w), the phases [(event, t)],
    the contact's begin and end times (None if it never touched), and the Run at the last
    lift-off (lift, None if none)."""

    def __init__(self, t, th, om, y, v, w, phases, t_contact_begin, t_contact_end, lift=None):
        self.t, self.th, self.om, self.y, self.v, self.w = t, th, om, y, v, w
        self.phases, self.t_contact_begin, self.t_contact_end = phases, t_contact_begin, t_contact_end
        self.lift = lift

    @property
    def events(self):
        return [name for name, _ in self.phases]


def initial_mode(p, th, om):
    """(contact, s) at the start, by the FMU's rules: in contact where y <= 0 and the force bracket is
    positive, or on the floor (y = 0, w = 0) where the free tip would sink (w' < 0); slip by the sign of v."""
    T = _terms(p, th[0], th[1], om[0], om[1])
    y, v, w = T[11], T[12], T[13]
    fn = -p.k * y - p.c * w
    contact = y <= 0 and fn > 0
    if y <= 0 and fn == 0:
        A, B, C, Q1, Q2, wt1, wt2, wn1, wn2, pT, pN = T[:11]
        a1, a2 = _solve(A, B, C, Q1, Q2)
        contact = wn1 * a1 + wn2 * a2 + pN < 0
    return contact, (1 if v > 0 else -1 if v < 0 else 0)


MAX_EVALUATIONS = 200_000     # right-hand sides per run: an IWC takes a few thousand; lasting contact, millions


def simulate(params, th0, om0, t_end=None, stop_at_return=True, rtol=1e-11, scale=None, max_events=200,
             max_evaluations=MAX_EVALUATIONS):
    """Integrate the arm from (th0, om0) at t = 0 to t_end, or to the return to y = 0 after a
    contact if stop_at_return and that comes first. rtol: DOP853's; the absolute tolerances are
    rtol times the contact's scales (angles: M g/(k L) and the tip's speed over L; rates: the speed
    over L). scale: the tip's speed scale (|v0| + |w0| by default). Raises ArmReferenceError after
    max_evaluations right-hand sides (a tip that stays on the floor, stiff, takes steps of the
    contact's period for as long as it stays)."""
    p = params if isinstance(params, Params) else Params.of(params)
    th0, om0 = np.asarray(th0, float), np.asarray(om0, float)
    J = jacobian(_ArmView(p), th0)
    speed = scale or max(float(np.sum(np.abs(J @ om0))), 1e-3 * math.sqrt(p.g * p.L))
    y_scale = min(p.M * p.g / p.k, speed * math.sqrt(p.M / p.k))      # the penetration's scale
    atol = np.array([rtol * y_scale / p.L] * 2 + [rtol * speed / p.L] * 2)
    if t_end is None:
        t_end = 1e3 * math.sqrt(p.M / p.k) + 10 * speed / p.g
    contact, s = initial_mode(p, th0, om0)
    y0 = p.H + p.l1 * math.sin(th0[0]) + p.l2 * math.sin(th0[1])
    w0 = p.l1 * math.cos(th0[0]) * om0[0] + p.l2 * math.cos(th0[1]) * om0[1]
    on_surface = contact and -p.k * y0 - p.c * w0 <= 0     # in contact with no force yet: on F_N = 0
    touched = contact
    z, t, phases = np.concatenate([[0.0, 0.0], om0]), 0.0, []
    t_begin = 0.0 if contact else None
    t_lift = lift = None
    if contact and s == 0:
        s = _at_rest(p, th0, z)
    name, budget = None, [0]
    for _ in range(max_events):
        crossed = _CROSSED.get(name) if name else ("lift" if on_surface else None)
        fns, names = _events(p, th0, y0, contact, s, touched, t, crossed)
        rhs = _counted(_rhs(p, th0, y0, contact, s), budget, max_evaluations)
        with np.errstate(over="ignore", invalid="ignore"):  # DOP853's rejected trial steps may overflow
            sol = solve_ivp(rhs, (t, t_end), z, method="DOP853", rtol=rtol, atol=atol, events=fns)
        if sol.status == -1:
            raise ArmReferenceError(f"DOP853 failed at t = {sol.t[-1]:.6g}: {sol.message}")
        hits = [(te[0], i) for i, te in enumerate(sol.t_events) if len(te)]
        if not hits:
            return _run(p, th0, sol.t[-1], sol.y[:, -1], phases, t_begin, t_lift, lift)
        t, i = min(hits)
        z = sol.y_events[i][0].copy()
        name = names[i]
        phases.append((name, t))
        if name == "return":
            run = _run(p, th0, t, z, phases, t_begin, t_lift, lift)
            if stop_at_return:
                return run
            touched = False
        elif name == "lift":
            contact, t_lift = False, t
            lift = _run(p, th0, t, z, list(phases), t_begin, t)
        elif name in ("touch", "re-contact"):
            contact, touched, t_begin = True, True, t
            th, om = th0 + z[:2], z[2:]
            v = _terms(p, th[0], th[1], om[0], om[1])[12]
            s = 1 if v > 0 else -1 if v < 0 else _at_rest(p, th0, z)
        elif name == "v=0":
            s = _at_rest(p, th0, z, s)
            if s == 0:
                z = _project(p, th0, z)
        else:
            s = 1 if name == "slip+" else -1
    raise ArmReferenceError(f"more than {max_events} events: {phases[-10:]}")


class _ArmView:
    """arm_lagrange's Arm interface (l1, l2, H) over Params, for its tip and Jacobian."""

    def __init__(self, p):
        self.l1, self.l2, self.H = p.l1, p.l2, p.H


def _run(p, th0, t, z, phases, t_begin, t_lift, lift=None):
    th, om = th0 + z[:2], z[2:]
    y0 = p.H + p.l1 * math.sin(th0[0]) + p.l2 * math.sin(th0[1])
    T = _terms(p, th[0], th[1], om[0], om[1], _height(p, th0[0], th0[1], y0, z[0], z[1]))
    return Run(t, th, om.copy(), T[11], T[12], T[13], list(phases), t_begin, t_lift, lift)


def _at_rest(p, th0, z, s=0):
    """The mode at v = 0 in contact: stick (0) if the holding friction is inside the cone, else
    slip the way it pushes (reversing s if s was the slip that ended)."""
    th, om = th0 + z[:2], z[2:]
    T = _terms(p, th[0], th[1], om[0], om[1])
    _, _, fn, ft = _contact(p, T, 0)
    if abs(ft) < p.mu * fn:
        return 0
    if s:
        return -s
    return 1 if ft > 0 else -1


def _project(p, th0, z):
    """omega moved along M^-1 W_T to the nearest point with v = 0 exactly (the FMU's reset)."""
    th, om = th0 + z[:2], z[2:]
    A, B, C, _, _, wt1, wt2 = _terms(p, th[0], th[1], om[0], om[1])[:7]
    b1, b2 = _solve(A, B, C, wt1, wt2)
    lam = (wt1 * om[0] + wt2 * om[1]) / (wt1 * b1 + wt2 * b2)
    return np.array([z[0], z[1], om[0] - lam * b1, om[1] - lam * b2])


def _counted(f, budget, limit):
    def counted(t, z):
        budget[0] += 1
        if budget[0] > limit:
            raise ArmReferenceError(f"more than {limit} right-hand sides by t = {t:.6g}")
        return f(t, z)
    return counted


def _rhs(p, th0, y0, contact, s):
    a0, b0 = float(th0[0]), float(th0[1])

    def f(t, z):
        t1, t2, o1, o2 = a0 + z[0], b0 + z[1], z[2], z[3]
        if not math.isfinite(t1 + t2 + o1 + o2):    # an overflowed trial step: NaN makes DOP853 reject it
            return np.full(4, np.nan)
        T = _terms(p, t1, t2, o1, o2, _height(p, a0, b0, y0, z[0], z[1]))
        if contact:
            d1, d2 = _contact(p, T, s)[:2]
        else:
            d1, d2 = _solve(T[0], T[1], T[2], T[3], T[4])
        return np.array([o1, o2, d1, d2])
    return f


# The surface an event leaves the state on, by the name it is watched under in the next mode.
_CROSSED = {"lift": "re-contact", "re-contact": "lift", "v=0": "v=0", "slip+": "v=0", "slip-": "v=0",
            "return": "touch"}


def _events(p, th0, y0, contact, s, touched, t0, crossed):
    a0, b0 = float(th0[0]), float(th0[1])

    def terms(z):
        return _terms(p, a0 + z[0], b0 + z[1], z[2], z[3], _height(p, a0, b0, y0, z[0], z[1]))

    def y(z):
        return terms(z)[11]

    def bracket(z):
        T = terms(z)
        return -p.k * T[11] - p.c * T[13]

    if contact:
        out = [("lift", bracket, +1)]
        if s:
            out.append(("v=0", lambda z: terms(z)[12], s))
        else:
            def forward(z):
                _, _, fn, ft = _contact(p, terms(z), 0)
                return p.mu * fn - ft

            def backward(z):
                _, _, fn, ft = _contact(p, terms(z), 0)
                return ft + p.mu * fn
            out += [("slip+", forward, +1), ("slip-", backward, +1)]
    else:
        out = [("touch", y, +1), ("re-contact", lambda z: -bracket(z) if y(z) < 0 else 1.0, +1)]
        if touched:
            out.append(("return", lambda z: -y(z), +1))
    return [_event(f, side, t0 if n == crossed else None) for n, f, side in out], [n for n, _, _ in out]


def _event(f, side, t0):
    """A terminal event for f(z) leaving its positive side (side = +1) or negative side (-1). For
    the surface the last event crossed (t0 given), the state at the segment's start t0 sits on it
    within rounding and is taken on the mode's side there."""
    def event(t, z):
        value = f(z)
        if t == t0 and value * side <= 0:
            return side * _TINY
        return value
    event.terminal = True
    event.direction = -side
    return event


def tip_velocity_rates(params, th, v, w):
    """omega giving the tip the velocity (v, w) at angles th."""
    p = params if isinstance(params, Params) else Params.of(params)
    return np.linalg.solve(jacobian(_ArmView(p), np.asarray(th, float)), [v, w])


def tip_height(params, th):
    p = params if isinstance(params, Params) else Params.of(params)
    return tip(_ArmView(p), np.asarray(th, float))[1]
