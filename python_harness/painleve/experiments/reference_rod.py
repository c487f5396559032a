# SPDX-License-Identifier: BSD-2-Clause
"""The compliant Painleve rod of docs/model.md §1-2 as a researcher would write it without
the FMU, for painleve.experiments.reference: per mode its right-hand side and analytic Jacobian in
numpy, its switching functions, and the rules that pick the mode after an event.

* ``flight``  y > 0 or no compressive force: F_N = 0, v' = a, w' = b, phi' = 0;
* ``slip+`` / ``slip-``  contact, v > 0 / v < 0: eq Painleve with q_s, p_s, c_s
  and F_N = (-y/eps - delta w)/eps (the linear branch of eq FN);
* ``stick``  contact, v = 0 held: the exact Filippov field (``filippov="exact"``,
  the default and the FMU's), the convex combination of the two slip fields
  that holds v' = 0: v' = 0, w' = b + S_w F_N - alpha sin cos a/k,
  phi' = S_phi F_N + alpha sin a/k (k = 1 + alpha sin^2), i.e. eq dynrodsc with
  the sticking friction force F_T = (a + alpha sin cos F_N)/k of docs/model.md §1.
  ``filippov="paper"`` is the paper's leading-order field of Proposition
  lem:Filippov (and docs/model.md §1), w' = b + S_w F_N, phi' = S_phi F_N: it drops
  the O(1) a-terms (O(eps) over a stick of duration O(eps): Theorem 1's limits
  are the same) and, unlike the exact field, does work while sticking: dE/dt
  gains phi^3 sin cos (tests/experiments/test_reference.py shows both).

Switching surfaces (each a terminal event, watched only in the modes where it
can end the mode): y = 0 (touch-down, and the return that ends a run),
F_N = 0 i.e. g = -y/eps - delta w = 0 (lift-off, re-contact while y < 0),
v = 0 (slip ends: stick if a + q_+ F_N < 0 < a + q_- F_N, eq filineq, else
the slip reverses), and the folds a + q_+ F_N = 0 / a + q_- F_N = 0 that end
sticking (forward / backward slip). In flight above the floor w = 0 is watched
as well, so a grazing dip below y = 0 inside one step is not missed.

The rod's coefficients are written out here with ``math`` (the right-hand side runs
~1e4 times per case, and analytic.py's public functions validate their arguments on
every call); tests/experiments/test_reference.py checks them against analytic.py.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

FILIPPOV = ("paper", "exact")
X, V, Y, W, THETA, PHI = range(6)       # state order
FLIGHT, SLIP_FORWARD, STICK, SLIP_BACKWARD = "flight", "slip+", "stick", "slip-"
_SLIP_SIGN = {SLIP_FORWARD: +1, SLIP_BACKWARD: -1}


def _sign(z):
    return int(z > 0) - int(z < 0)


def _lex_sign(*derivatives):
    """Sign of the first nonzero of (f, f', f'', ...): the side of a surface f = 0
    that a state sitting exactly on it is about to move to."""
    for d in derivatives:
        if d != 0:
            return _sign(d)
    return 0


@dataclass(frozen=True)
class Rod:
    """The rod's parameters and, per mode, its right-hand side, Jacobian and switching functions.

    filippov picks the sticking field: "exact" (the convex combination of the slip
    fields that holds v' = 0, a included; what the FMU integrates) or "paper" (the
    leading-order field of Proposition lem:Filippov as docs/model.md states it, which drops
    a); see the module docstring."""
    alpha: float = 3.0
    mu: float = 3.0
    delta: float = 1.0
    epsilon: float = 1e-3
    filippov: str = "exact"     # the sticking field: "exact" (the FMU's) or "paper" (leading order)

    def __post_init__(self):
        if self.filippov not in FILIPPOV:
            raise ValueError(f"filippov must be one of {', '.join(FILIPPOV)}; got {self.filippov!r}")
        for name, ok in (("alpha", self.alpha > 0), ("mu", self.mu >= 0), ("delta", self.delta >= 0),
                         ("epsilon", self.epsilon > 0)):
            value = getattr(self, name)
            if not (ok and math.isfinite(value)):
                raise ValueError(f"{name} = {value!r} is outside the model (alpha > 0, mu >= 0, delta >= 0, "
                                 f"epsilon > 0, all finite)")

    # ------------------------------------------------------------ coefficients
    def coefficients(self, theta, phi):
        """dict of a, b, q_pm, p_pm, c_pm, S_w, S_phi at (theta, phi) (eqs coeffs, Sw)."""
        al, mu = self.alpha, self.mu
        sn, cs = math.sin(theta), math.cos(theta)
        k = 1.0 + al * sn * sn
        return dict(a=-phi * phi * cs, b=-1.0 + phi * phi * sn,
                    q_plus=al * sn * cs - mu * k, q_minus=al * sn * cs + mu * k,
                    p_plus=1.0 + al * cs * cs - mu * al * sn * cs, p_minus=1.0 + al * cs * cs + mu * al * sn * cs,
                    c_plus=-al * (cs - mu * sn), c_minus=-al * (cs + mu * sn),
                    S_w=(1.0 + al) / k, S_phi=-al * cs / k)

    def _gains(self, mode, sn, cs):
        """(v, w, phi) coefficients of F_N in mode, and their theta-derivatives."""
        al, mu = self.alpha, self.mu
        if mode == STICK:
            k, dk = 1.0 + al * sn * sn, 2.0 * al * sn * cs
            sw, sphi = (1.0 + al) / k, -al * cs / k
            return (0.0, sw, sphi), (0.0, -(1.0 + al) * dk / (k * k), al * sn / k + al * cs * dk / (k * k))
        s = _SLIP_SIGN.get(mode, 0)
        c2 = cs * cs - sn * sn          # cos 2theta
        s2 = 2.0 * sn * cs              # sin 2theta
        q = al * sn * cs - s * mu * (1.0 + al * sn * sn)
        p = 1.0 + al * cs * cs - s * mu * al * sn * cs
        c = -al * (cs - s * mu * sn)
        dq = al * c2 - s * mu * al * s2
        dp = -al * s2 - s * mu * al * c2
        dc = al * (sn + s * mu * cs)
        return (q, p, c), (dq, dp, dc)

    def force_bracket(self, x):
        """g = -y/eps - delta w: F_N = g/eps in contact."""
        return -x[Y] / self.epsilon - self.delta * x[W]

    def normal_force(self, mode, x):
        return 0.0 if mode == FLIGHT else self.force_bracket(x) / self.epsilon

    def friction_force(self, mode, x):
        """F_T: s mu F_N slipping; the force that keeps v' = 0 sticking (docs/model.md §1)."""
        F = self.normal_force(mode, x)
        if mode == STICK:
            sn, cs, phi = math.sin(x[THETA]), math.cos(x[THETA]), x[PHI]
            return (-phi * phi * cs + self.alpha * sn * cs * F) / (1.0 + self.alpha * sn * sn)
        return _SLIP_SIGN.get(mode, 0) * self.mu * F

    def energy(self, x, mode):
        """Kinetic + gravitational + spring energy (the FMU's `energy`): centre of mass
        (x - cos theta, y + sin theta), rotational energy phi^2/(2 alpha), spring (y/eps)^2/2
        while its force acts (mode not FLIGHT; after a damped lift-off y < 0 holds none)."""
        x = np.asarray(x, dtype=float)
        sn, cs, phi = np.sin(x[THETA]), np.cos(x[THETA]), x[PHI]
        Xd, Yd = x[V] + phi * sn, x[W] + phi * cs
        spring = 0.0 if mode == FLIGHT else 0.5 * (x[Y] / self.epsilon) ** 2
        return 0.5 * (Xd * Xd + Yd * Yd) + 0.5 * phi * phi / self.alpha + x[Y] + sn + spring

    # ------------------------------------------------------ right-hand sides
    def rhs(self, mode):
        """f(t, x) of mode, smooth (no switch inside)."""
        eps, delta, gains = self.epsilon, self.delta, self._gains

        if mode == FLIGHT:
            def f(t, x):
                phi, th = x[PHI], x[THETA]
                return np.array([x[V], -phi * phi * math.cos(th), x[W], -1.0 + phi * phi * math.sin(th), phi, 0.0])
            return f

        stick = mode == STICK
        exact = stick and self.filippov == "exact"
        a_terms = self._stick_a_terms

        def f(t, x):
            th, phi = x[THETA], x[PHI]
            sn, cs = math.sin(th), math.cos(th)
            F = (-x[Y] / eps - delta * x[W]) / eps
            (gv, gw, gphi), _ = gains(mode, sn, cs)
            vdot = 0.0 if stick else -phi * phi * cs + gv * F
            wdot, phidot = -1.0 + phi * phi * sn + gw * F, gphi * F
            if exact:
                (aw, aphi), _ = a_terms(sn, cs, phi)
                wdot, phidot = wdot + aw, phidot + aphi
            return np.array([x[V], vdot, x[W], wdot, phi, phidot])
        return f

    def _stick_a_terms(self, sn, cs, phi):
        """What the exact Filippov field adds to (w', phi') in stick, and its (theta, phi)-derivatives.

        The convex combination of the slip fields with v' = 0 has weight
        (a + q_- F_N)/((q_- - q_+) F_N) on slip+; Proposition lem:Filippov takes
        q_-/(q_- - q_+), i.e. drops a. The difference: w' gains -alpha sin cos a/k and
        phi' gains alpha sin a/k (k = 1 + alpha sin^2, a = -phi^2 cos): the effect of a
        on the friction force that holds v = 0 (docs/model.md's F_T)."""
        al = self.alpha
        k, dk = 1.0 + al * sn * sn, 2.0 * al * sn * cs
        u, du = sn * cs * cs, cs ** 3 - 2.0 * sn * sn * cs        # A_w = alpha phi^2 u/k
        r, dr = sn * cs, cs * cs - sn * sn                         # A_phi = -alpha phi^2 r/k
        p2 = phi * phi
        values = (al * p2 * u / k, -al * p2 * r / k)
        derivatives = ((al * p2 * (du * k - u * dk) / (k * k), 2.0 * al * phi * u / k),
                       (-al * p2 * (dr * k - r * dk) / (k * k), -2.0 * al * phi * r / k))
        return values, derivatives

    def jacobian(self, mode):
        """J(t, x) = df/dx of mode (analytic)."""
        eps, delta, gains = self.epsilon, self.delta, self._gains
        contact = mode != FLIGHT
        exact = mode == STICK and self.filippov == "exact"
        F_y, F_w = (-1.0 / eps ** 2, -delta / eps) if contact else (0.0, 0.0)

        def J(t, x):
            th, phi = x[THETA], x[PHI]
            sn, cs = math.sin(th), math.cos(th)
            F = (-x[Y] / eps - delta * x[W]) / eps if contact else 0.0
            (gv, gw, gphi), (dv, dw, dphi) = gains(mode, sn, cs)
            m = np.zeros((6, 6))
            m[X, V] = m[Y, W] = m[THETA, PHI] = 1.0
            if mode != STICK:                                  # v' = a + q_s F_N (a alone in flight)
                m[V, THETA] = phi * phi * sn + (dv * F if contact else 0.0)
                m[V, PHI] = -2.0 * phi * cs
                m[V, Y], m[V, W] = gv * F_y, gv * F_w
            m[W, THETA] = phi * phi * cs + (dw * F if contact else 0.0)
            m[W, PHI] = 2.0 * phi * sn
            if contact:
                m[W, Y], m[W, W] = gw * F_y, gw * F_w
                m[PHI, THETA] = dphi * F
                m[PHI, Y], m[PHI, W] = gphi * F_y, gphi * F_w
            if exact:
                _, ((aw_th, aw_phi), (aphi_th, aphi_phi)) = self._stick_a_terms(sn, cs, phi)
                m[W, THETA] += aw_th
                m[W, PHI] += aw_phi
                m[PHI, THETA] += aphi_th
                m[PHI, PHI] += aphi_phi
            return m
        return J

    # ------------------------------------------------------------ mode rules
    def in_contact(self, x):
        """y <= 0 and g > 0 (eq FN); on a surface, the side the free motion goes to."""
        b = -1.0 + x[PHI] ** 2 * math.sin(x[THETA])
        eps, delta, w = self.epsilon, self.delta, x[W]
        below = _lex_sign(x[Y], w, b) < 0
        pressed = _lex_sign(self.force_bracket(x), -w / eps - delta * b, -b / eps) > 0
        return below and pressed

    def at_rest(self, x):
        """Friction mode of a contact with v = 0: stick inside the cone a + q_+ F_N < 0 < a + q_- F_N
        (eq filineq), else the slip the tangential acceleration starts."""
        k = self.coefficients(x[THETA], x[PHI])
        F = self.force_bracket(x) / self.epsilon
        forward, backward = k["a"] + k["q_plus"] * F, k["a"] + k["q_minus"] * F
        if forward < 0 < backward:
            return STICK
        return SLIP_FORWARD if forward >= 0 else SLIP_BACKWARD

    def contact_mode(self, x):
        """The contact mode entered with tangential velocity x[V]."""
        return SLIP_FORWARD if x[V] > 0 else SLIP_BACKWARD if x[V] < 0 else self.at_rest(x)

    def initial_mode(self, x):
        return self.contact_mode(x) if self.in_contact(x) else FLIGHT

    def switching_functions(self, mode, x0, crossed=None):
        """[(name, z(x), side)] watched in mode from state x0, just after event `crossed`;
        side is the sign z has inside the mode (for a surface just crossed: the far side)."""
        eps, delta = self.epsilon, self.delta

        def g(x):
            return -x[Y] / eps - delta * x[W]

        def fold(q_name):
            def z(x):
                k = self.coefficients(x[THETA], x[PHI])
                return k["a"] + k[q_name] * g(x) / eps
            return z

        if mode == STICK:
            return [("lift-off", g, +1), ("forward fold", fold("q_plus"), -1),
                    ("backward fold", fold("q_minus"), +1)]
        if mode in _SLIP_SIGN:
            return [("lift-off", g, +1), ("v = 0", lambda x: x[V], _SLIP_SIGN[mode])]
        b0 = -1.0 + x0[PHI] ** 2 * math.sin(x0[THETA])
        above = +1 if crossed == "return" else _lex_sign(x0[Y], x0[W], b0)
        if above >= 0:                                 # above the floor (or leaving it upwards)
            rising = (_sign(b0) if crossed == "w = 0" else _lex_sign(x0[W], b0)) or 1
            return [("touch-down", lambda x: x[Y], +1), ("w = 0", lambda x: x[W], rising)]
        return [("return", lambda x: x[Y], -1), ("re-contact", g, -1)]  # below y = 0 after lift-off
