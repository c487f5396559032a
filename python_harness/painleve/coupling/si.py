# SPDX-License-Identifier: BSD-2-Clause
"""PainleveRodSI, the rod in SI units with inputs, in the paper's units and back.

The scaling of docs/si_model.md §5: lengths in the half-length l, time in T = sqrt(l/g),
velocities in sqrt(g l), forces in m g, torques and energies in m g l; alpha = m l^2/J,
epsilon = sqrt(m g/(k l)), delta = c/sqrt(m k). Positions and velocities of the end are
taken relative to the floor (the gap y - y_floor, the slip v - v_floor, w - w_floor): the
paper's theorems are statements about the motion in the floor's frame.

- `SIRod` (the FMU's parameters) and `SIState` (its states), `Floor` (a floor moving at
  constant velocity) and `Loads` (constant applied loads): the SI side;
- `case_of` / `si_of`: an SI start on the floor as the paper's `Case`, and back;
- `to_paper`: a trajectory of the SI FMU (fmpy's structured array) in the paper's units;
- `predict`: what the paper predicts for an SI start (e, the lift-off velocity, phi after IWC,
  w1*), in SI units, from analytic.py; with loads, from the loaded a and b (§5).

Only arithmetic and analytic.py here: nothing runs an FMU (si_experiment does).
"""
import math
from dataclasses import dataclass

import numpy as np

from ..experiments.case import Case
from ..theory import analytic as an
from ..theory.rod_coefficients import check_hypotheses

G = 9.81   # the FMU's default gravity [m/s2]


@dataclass(frozen=True)
class SIRod:
    """The FMU's parameters, with its defaults (a uniform rod of 1 kg and 1 m on a stiff floor)."""
    m: float = 1.0            # mass [kg]
    l: float = 0.5            # half-length [m]
    J: float = 0.5 ** 2 / 3   # moment of inertia about the centre of mass [kg m2]
    g: float = G              # gravity [m/s2]
    k: float = 2e7            # contact stiffness [N/m]
    c: float = 4500.0         # contact damping [N s/m]
    mu: float = 3.0           # friction coefficient

    @property
    def alpha(self):
        return self.m * self.l ** 2 / self.J

    @property
    def epsilon(self):
        return math.sqrt(self.m * self.g / (self.k * self.l))

    @property
    def delta(self):
        return self.c / math.sqrt(self.m * self.k)

    @property
    def time_scale(self):
        """T = sqrt(l/g) [s]: one unit of the paper's time."""
        return math.sqrt(self.l / self.g)

    @property
    def speed_scale(self):
        """sqrt(g l) [m/s]: one unit of the paper's velocities."""
        return math.sqrt(self.g * self.l)

    @property
    def force_scale(self):
        """m g [N]."""
        return self.m * self.g

    @property
    def energy_scale(self):
        """m g l [J], also the unit of torque [N m]."""
        return self.m * self.g * self.l

    def parameters(self):
        """The FMU's start values of its parameters."""
        return dict(m=self.m, l=self.l, J=self.J, g=self.g, k=self.k, c=self.c, mu=self.mu)

    @classmethod
    def from_paper(cls, *, alpha, mu, delta, epsilon, m=1.0, l=0.5, g=G):
        """The rod of mass m, half-length l under gravity g whose dimensionless numbers are these."""
        k = m * g / (l * epsilon ** 2)
        return cls(m=m, l=l, J=m * l ** 2 / alpha, g=g, k=k, c=delta * math.sqrt(m * k), mu=mu)


@dataclass(frozen=True)
class SIState:
    """The FMU's continuous states: the end A at (x, y) with velocity (v, w), the angle theta
    (clockwise, to the floor) and phi = theta' [rad/s]."""
    x: float = 0.0
    v: float = 2.0
    y: float = 0.0
    w: float = 0.0
    theta: float = 1.0
    phi: float = 2.0

    def start_values(self):
        return dict(x=self.x, v=self.v, y=self.y, w=self.w, theta=self.theta, phi=self.phi)


@dataclass(frozen=True)
class Floor:
    """A floor at height y0 at t = 0 moving vertically at the constant velocity w and
    horizontally (a belt) at v: the inputs y_floor = y0 + w t, w_floor = w, v_floor = v."""
    y0: float = 0.0
    w: float = 0.0
    v: float = 0.0

    def inputs(self, t):
        return dict(y_floor=self.y0 + self.w * t, w_floor=self.w, v_floor=self.v)


@dataclass(frozen=True)
class Loads:
    """Constant applied loads: a force (F_x, F_y) [N] on the centre of mass and a torque tau [N m]
    in theta's sense (clockwise)."""
    F_x: float = 0.0
    F_y: float = 0.0
    tau: float = 0.0

    def inputs(self, t=0.0):
        return dict(F_x=self.F_x, F_y=self.F_y, tau=self.tau)

    def scaled(self, rod):
        """(f_x, f_y, tau_hat) = (F_x/(m g), F_y/(m g), tau/(m g l))."""
        return self.F_x / rod.force_scale, self.F_y / rod.force_scale, self.tau / rod.energy_scale


def case_of(rod, state, floor=Floor()):
    """The paper's Case of an SI start on the floor (y = floor.y0): v0 = (v - v_floor)/sqrt(g l),
    phi0 = phi T, w10 = (w - w_floor)/(eps sqrt(g l))."""
    if not math.isclose(state.y, floor.y0, rel_tol=0.0, abs_tol=1e-12 * rod.l):
        raise ValueError(f"a Case starts on the floor: y = {state.y} m, y_floor = {floor.y0} m")
    V = rod.speed_scale
    return Case(theta0=state.theta, phi0=state.phi * rod.time_scale, v0=(state.v - floor.v) / V,
                delta=rod.delta, epsilon=rod.epsilon, w10=(state.w - floor.w) / (rod.epsilon * V),
                alpha=rod.alpha, mu=rod.mu)


def si_of(case, *, m=1.0, l=0.5, g=G, floor=Floor()):
    """(SIRod, SIState) of a Case for a rod of mass m and half-length l under gravity g on this floor."""
    if case.kappa or case.beta:
        raise ValueError("the SI model has the paper's linear compliance law only (kappa = beta = 0)")
    rod = SIRod.from_paper(alpha=case.alpha, mu=case.mu, delta=case.delta, epsilon=case.epsilon, m=m, l=l, g=g)
    V = rod.speed_scale
    return rod, SIState(x=0.0, v=floor.v + case.v0 * V, y=floor.y0, w=floor.w + case.epsilon * case.w10 * V,
                        theta=case.theta0, phi=case.phi0 / rod.time_scale)


def to_paper(rod, r, floor=Floor()):
    """A trajectory of the SI FMU (fmpy's structured array: time and outputs) in the paper's units,
    positions and velocities of the end relative to the floor; names as PainleveRod's."""
    t = r["time"]
    V, L = rod.speed_scale, rod.l
    y_f, x_f = floor.y0 + floor.w * t, floor.v * t
    scale = dict(time=lambda z: z / rod.time_scale, x=lambda z: (z - x_f) / L, y=lambda z: (z - y_f) / L,
                 v=lambda z: (z - floor.v) / V, w=lambda z: (z - floor.w) / V, theta=lambda z: z,
                 phi=lambda z: z * rod.time_scale, F_N=lambda z: z / rod.force_scale,
                 F_T=lambda z: z / rod.force_scale)
    names = [n for n in r.dtype.names if n in scale or n in ("mode", "contact")]
    out = np.zeros(len(r), dtype=[(n, r.dtype[n]) for n in names])
    for n in names:
        out[n] = scale[n](r[n]) if n in scale else r[n]
    return out


@dataclass(frozen=True)
class SIPrediction:
    """The paper's predictions for an SI start on the floor (eps -> 0), in SI units."""
    theorem: int          # 1 (loaded b < 0, inconsistent) or 2 (b > 0, indeterminate)
    e: float              # (w - w_floor)/(v - v_floor) at the return to the floor after IWC
    w: float              # w there [m/s] (floor's w + e times the slip at the start)
    phi: float            # phi there [rad/s] (Theorem 1)
    duration: float       # T eps ln(1/eps)/lambda_+ [s], the IWC's duration to O(eps)
    w1_star: float        # Theorem 2's separatrix: the touch-down w - w_floor [m/s] below which IWC
    b: float              # the loaded b (in units of g): its sign picks the theorem


def loaded_ab(theta, phi_hat, alpha, f_x=0.0, f_y=0.0, tau_hat=0.0):
    """The paper's a and b with applied loads (docs/si_model.md §5), in units of g."""
    s, c = math.sin(theta), math.cos(theta)
    return (-phi_hat ** 2 * c + f_x - alpha * s * tau_hat,
            -1 + phi_hat ** 2 * s + f_y - alpha * c * tau_hat)


def predict(rod, state, floor=Floor(), loads=Loads()):
    """SIPrediction for an SI start on the floor; raises analytic.HypothesisError if the
    rod is not in the Painleve wedge (p_+ < 0, q_+ < 0 < q_-) or slips backward."""
    case = case_of(rod, state, floor)
    a, b = loaded_ab(case.theta0, case.phi0, case.alpha, *loads.scaled(rod))
    who = "Theorem 1" if b < 0 else "Theorem 2"
    check_hypotheses(who, case.theta0, case.alpha, case.mu, v0=case.v0, delta=case.delta)   # the wedge
    if a == 0 or b == 0:
        raise an.HypothesisError(f"{who} needs a != 0 and b != 0 (with the loads): a = {a}, b = {b}")
    e = float(an.e(case.delta, case.theta0, alpha=case.alpha, mu=case.mu))
    lam_plus, lam_minus = an.lambda_pm(case.theta0, case.delta, alpha=case.alpha, mu=case.mu)
    p_plus = float(an.p_plus(case.theta0, alpha=case.alpha, mu=case.mu))
    w1 = -lam_minus * b / p_plus if b > 0 else math.nan      # eq w1star with the loaded b
    phi = an.phi_after_iwc(case.theta0, case.phi0, case.v0, case.delta, alpha=case.alpha, mu=case.mu, e=e)
    V = rod.speed_scale
    return SIPrediction(theorem=1 if b < 0 else 2, e=e, w=floor.w + e * case.v0 * V, phi=phi / rod.time_scale,
                        duration=rod.time_scale * case.epsilon * math.log(1 / case.epsilon) / lam_plus,
                        w1_star=w1 * case.epsilon * V, b=b)
