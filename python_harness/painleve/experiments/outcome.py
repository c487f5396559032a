# SPDX-License-Identifier: BSD-2-Clause
"""What one IWC run did, for any body, and the one definition of its phases and of its return.

Every way of running a case (Model Exchange, Co-Simulation, a recorded
trajectory, the scipy reference; the rod or any other body FMU) reduces its run
to the same thing: the mode switches it went through, `[(t, contact, mode), ...]`
with the state after each change and the start (t = 0) first, and the state at
the return to the floor, the first instant at which `back_on_floor` holds.
`phases` reads the durations off the switches, with one definition:

- touch-down: the first instant the compliant contact is active (F_N > 0);
  a case starts on the floor, so this is usually t = 0;
- compression: from touch-down to the start of the first stick (the slip that
  compresses the contact);
- stick: from the start of that stick to the first switch out of it;
- lift-off: from the end of the stick (touch-down, if the body never stuck) to
  the last end of contact (F_N = 0) before the return;
- flight back: from that end of contact to the return to y = 0 moving up
  (the contact point is below the floor without force; zero when delta = 0,
  where F_N = 0 is y = 0).

Phases that did not happen are NaN; the four add up to t_return - t_touch.
"""
import math
from dataclasses import dataclass, field, fields

import numpy as np

from ..theory import analytic as an
from .case import Case

SLIP_FORWARD, STICK, SLIP_BACKWARD = 1, 0, -1     # the FMU's `mode`
STATE_AT_RETURN = ("v", "y", "w", "theta", "phi")    # what a run of the rod reads at the return to the floor


class SimulationError(RuntimeError):
    """The FMU or its solver gave up on a run; the message carries the FMU's own words."""


class NoReturn(SimulationError):
    """The run did not come back to the floor within its horizon."""


def back_on_floor(touched, contact, y):
    """The return to the floor after contact, the one rule every runner stops at: the contact point,
    having been in contact (`touched`), is out of it and at or above the floor (y >= 0)."""
    return bool(touched) and not contact and y >= 0


def w_error(w, v0, e):
    """w/v0 - e: the error of Theorem 1's law w = e v0 at the return, o(1) as eps -> 0."""
    return w / v0 - e


@dataclass(frozen=True)
class Outcome:
    """A run's return to the floor: its case, whether it stuck (`iwc`), the time and the state there
    (`state`: every state and output the run read, by name; `o.w`, `o.theta`, ... read it), its phase
    durations, its events, and what the run cost. `w_error` and `as_row` serve any case: the rod's
    Case from its closed forms (analytic.predict), any other from `prediction`, what the theory
    predicts from the FMU's coefficients at its start (fmu.body_case.predict, which run_body attaches);
    `phi_error` and `theta_error` are the rod's alone."""
    case: object            # what was run: a Case (the rod), or a body's case
    iwc: bool               # the contact point stuck before lifting off
    t_return: float
    state: dict = field(hash=False)   # {name: value} at the return: y, v, w and the body's states
    compression: float = math.nan     # durations (see the module's docstring); NaN for phases that did not happen
    stick: float = math.nan
    lift_off: float = math.nan
    flight_back: float = math.nan
    events: int = -1        # the FMU's events up to the return (-1: not seen)
    solver_stats: dict = field(default_factory=dict, compare=False)   # e.g. nfev, nsteps of the run
    # A body case's prediction (start_v0, e, coefficients, ...: fmu.body_case.BodyPrediction); None for the rod's
    # Case, whose closed forms are its own, and for a run nothing predicted.
    prediction: object = field(default=None, compare=False, repr=False)

    def __getattr__(self, name):
        """o.NAME: the state at the return's NAME (o.w, o.v, o.theta, o.theta1, ...)."""
        state = self.__dict__.get("state")
        if state is not None and name in state:
            return state[name]
        raise AttributeError(f"{type(self).__name__} has no field and its state no variable {name!r}")

    def _v0_and_e(self):
        """(v0, e) of the case: the rod's Case's own v0 and closed-form e (analytic.predict, whatever else
        is attached), any other case's from its `prediction` (the slip speed it started with, and the e of
        theory.general at its start)."""
        if isinstance(self.case, Case):
            return self.case.v0, an.predict(self.case).e
        if self.prediction is None:
            raise ValueError(f"{self.case}: a body case's e comes from the FMU's coefficients at its start; "
                             f"run it with fmu.body_case.run_body, which attaches that prediction")
        return self.prediction.start_v0, self.prediction.e

    @property
    def w_error(self):
        """w/v0 - e: o(1) as eps -> 0 (Theorem 1)."""
        return w_error(self.state["w"], *self._v0_and_e())

    @property
    def phi_error(self):
        return self.state["phi"] - an.predict(self.case).phi

    @property
    def theta_error(self):
        return self.state["theta"] - self.case.theta0

    def as_row(self):
        """A flat dict: the case, the outcome, the predictions and the errors (the rod's Case: its fields,
        its closed forms; any other case: its configuration, the theory at its start, see _body_row)."""
        if not isinstance(self.case, Case):
            return self._body_row()
        predicted = an.predict(self.case)
        s = self.state
        # shallow: asdict's deep copy of the case and the stats is a sweep's row's largest cost
        row = {**_fields(self.case), "iwc": self.iwc, "w": s["w"], "theta": s["theta"], "phi": s["phi"],
               "v": s["v"], "t_return": self.t_return, "compression": self.compression, "stick": self.stick,
               "lift_off": self.lift_off, "flight_back": self.flight_back, "events": self.events}
        row.update(e=predicted.e, predicted_w=predicted.e * self.case.v0, predicted_phi=predicted.phi,
                   w_error=self.w_error, phi_error=self.phi_error, theta_error=self.theta_error,
                   time_scale=predicted.time_scale)
        return row

    def _body_row(self):
        """A body case's row: its given start values by name, its v0 (the start's), eps, delta and w0;
        the outcome (iwc, w, v, t_return, the phases, events); the theory at its start (quadrant, p_plus,
        b, theorem, e, w1_star, predicted_w = e v0) and w_error."""
        v0, e = self._v0_and_e()
        p, case = self.prediction, self.case
        row = {**dict(case.given), "v0": v0, "epsilon": case.epsilon, "delta": case.delta, "w0": case.w0,
               "iwc": self.iwc, "w": self.state["w"], "v": self.state["v"], "t_return": self.t_return,
               "compression": self.compression, "stick": self.stick, "lift_off": self.lift_off,
               "flight_back": self.flight_back, "events": self.events}
        row.update(quadrant=p.quadrant, p_plus=float(p.coefficients.p_plus), b=float(p.coefficients.b),
                   theorem=p.theorem, e=e, w1_star=p.w1_star, predicted_w=e * v0, w_error=self.w_error)
        return row


def _fields(record):
    """{name: value} of a dataclass's fields, not copied (dataclasses.asdict copies them deeply)."""
    return {f.name: getattr(record, f.name) for f in fields(record)}


def phases(switches, t_return):
    """dict(iwc, compression, stick, lift_off, flight_back) from the switches [(t, contact, mode)]
    (the start first) of a run that returns to the floor at t_return; see the module's docstring."""
    seen = [(t, bool(contact), mode) for t, contact, mode in switches if t <= t_return]
    t_touch = next((t for t, contact, _ in seen if contact), t_return)
    stick_start = next((t for t, contact, mode in seen if contact and mode == STICK), None)
    stick_end = t_touch if stick_start is None else \
        next((t for t, contact, mode in seen if t > stick_start and (mode != STICK or not contact)), t_return)
    ends = [t for (_, was, _), (t, contact, _) in zip(seen, seen[1:]) if was and not contact and t >= stick_end]
    contact_end = ends[-1] if ends else t_return
    nan = math.nan
    return dict(iwc=stick_start is not None,
                compression=nan if stick_start is None else stick_start - t_touch,
                stick=nan if stick_start is None else stick_end - stick_start,
                lift_off=contact_end - stick_end, flight_back=t_return - contact_end)


def outcome_from_switches(case, switches, t_return, back, *, events, solver_stats=None):
    """The Outcome of a run with these switches (see phases), back on the floor at t_return in state `back`
    ({name: value})."""
    return Outcome(case=case, t_return=float(t_return), state={k: float(x) for k, x in back.items()}, events=events,
                   solver_stats=solver_stats or {},
                   **{k: (v if k == "iwc" else float(v)) for k, v in phases(switches, t_return).items()})


def no_return(case, t):
    eps, delta = getattr(case, "epsilon", None), getattr(case, "delta", None)
    hint = "" if eps is None or delta is None else \
        f" (is eps small enough for the asymptotic regime? eps * delta = {eps * delta:g})"
    return NoReturn(f"{case} did not return to y = 0 within t = {t:.3g}{hint}")


def flight_back_to_floor(state):
    """The free flight run back from `state` (in flight above the floor) to its last
    y = 0: (time offset s <= 0, state there). Closed form: the centre of mass
    (x - cos theta, y + sin theta) falls freely, the rod spins uniformly."""
    th, ph = float(state["theta"]), float(state["phi"])
    y, w, v = float(state["y"]), float(state["w"]), float(state["v"])
    # Written as increments from `state` (sin(th + ph s) - sin th = 2 cos(th + ph s/2) sin(ph s/2)):
    # at a return with w = O(eps) the height's O(1) terms would cancel to a rounding error of
    # 1e-16 / w in the time, O(1e-10) at eps = 1e-6.
    # height(s) = y + w s - s^2/2 + ph s cos th - 2 cos(th + ph s/2) sin(ph s/2), and its derivative
    # speed(s) = w(s) = w - s + 2 ph sin(th + ph s/2) sin(ph s/2), written out in the loop (a sweep
    # runs it for every case).
    cos_th = math.cos(th)
    s = -y / w
    for _ in range(20):   # Newton from the straight-line guess; the root is simple (w > 0)
        half = ph * s / 2
        sin_half = math.sin(half)
        step = (y + w * s - s * s / 2 + ph * s * cos_th - 2 * math.cos(th + half) * sin_half) / \
            (w - s + 2 * ph * math.sin(th + half) * sin_half)
        s -= step
        if abs(step) <= 1e-14:    # height's round-off (~1e-16) over w: s is then exact
            break
    half = ph * s / 2
    sin_half = math.sin(half)
    return s, dict(v=v - 2 * ph * math.cos(th + half) * sin_half, y=0.0,
                   w=w - s + 2 * ph * math.sin(th + half) * sin_half, theta=th + ph * s, phi=ph)


def _first(mask, start=0):
    hits = np.flatnonzero(mask[start:])
    return start + hits[0] if hits.size else None


def outcome_of_trajectory(case, r, *, read=STATE_AT_RETURN, exact_events=True):
    """The Outcome of a recorded trajectory (fmpy's structured array with time, contact, mode and the
    names `read`, y among them) that starts on the floor: the return is the first row at which
    back_on_floor holds. With exact event rows (Model Exchange) that row is the return; on a
    Co-Simulation grid the rod's return is found by flight_back_to_floor."""
    for name in ("time",) + tuple(read):
        if not np.all(np.isfinite(r[name])):
            raise SimulationError(f"{case}: the FMU returned a non-finite {name}")
    t, contact, mode = r["time"], r["contact"].astype(bool), r["mode"]
    touched = np.maximum.accumulate(contact)
    end = _first(np.array([back_on_floor(*row) for row in zip(touched, contact, r["y"])], dtype=bool))
    if end is None:
        raise no_return(case, t[-1])
    changed = np.flatnonzero((contact[1:end + 1] != contact[:end]) | (mode[1:end + 1] != mode[:end])) + 1
    switches = [(t[i], contact[i], mode[i]) for i in np.concatenate(([0], changed))]
    back, t_return = {k: r[k][end] for k in read}, t[end]
    if not exact_events and r["y"][end] > 0:
        s, back = flight_back_to_floor(back)
        t_return += s
        switches = [(min(ts, t_return), c, m) for ts, c, m in switches]   # a switch is known to a grid step only
    return outcome_from_switches(case, switches, t_return, back,
                                 events=int(np.sum(np.diff(t[:end + 1]) == 0)) if exact_events else -1)
