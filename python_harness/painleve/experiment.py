"""Impact without collision on the PainleveRod FMU, driven by fmpy, beside the paper's predictions.

One `Experiment` extracts the FMU and instantiates it once, then runs any
number of cases on that instance with fmi2Reset between them (fmpy's fast
loop). A case starts on the floor, y = 0, w = eps * w10 (MODEL.md §3), and
ends when the rod, having touched the floor, is back at y = 0 moving up.

What it knows of fmpy 0.3.32 and chooses for the user:
- `run` through Model Exchange is a master loop of its own (me_loop) around
  fmpy's CVode solver: CVode goes from event to event, the phases are read at
  each event and the run stops at the event that returns the rod to y = 0
  (exact, no output grid); `simulate` is fmpy's simulate_fmu, the trajectory
  on a grid (5 eps, or eps/2 through Co-Simulation), events recorded (two
  rows each, the exact event state). The two agree to the solver tolerance.
- CVode's absolute tolerance is the relative one times each state's nominal,
  and the FMU reports y ~ eps^2, w ~ eps: one tolerance fits every stiffness.
- The relative tolerance defaults to min(1e-6, eps/100), through Model
  Exchange and Co-Simulation alike (whose CVODE carries on across
  communication points), so the solver's error stays below the theorem's
  O(eps ln 1/eps) and the measured error is the model's, not the
  tolerance's. fmpy would otherwise use the DefaultExperiment's 1e-6.
- Euler (through simulate_fmu) steps once per output interval: both are set
  to the step.
- Through Co-Simulation (interface="CS") the FMU integrates itself with its
  embedded CVODE and the master sees communication points only: `run` (the
  Co-Simulation fast loop) reads the phases exactly from the FMU's logEvents
  messages, steps 4 eps at a time, and recovers the state at the return to
  y = 0 exactly by running the free flight (a closed form) back from the
  first point after it.
"""
import math
import re
from dataclasses import asdict, dataclass
from functools import cached_property

import numpy as np

from . import analytic as an
from .instance import LoadedFMU, SimulationError
from .me_loop import integrate

STATES = ["v", "y", "w", "theta", "phi"]     # those an Outcome reads
OUTPUTS = STATES + ["mode", "contact"]


@dataclass(frozen=True)
class Case:
    """An IWC experiment: the rod's parameters and its state on the floor at t = 0.
    The paper's predictions are computed once per case (a sweep asks for each several times)."""
    theta0: float = 1.0
    phi0: float = 0.5
    v0: float = 1.0
    delta: float = 1.0
    epsilon: float = 1e-3
    w10: float = 0.0      # w(0) = epsilon * w10: the inner scale of Theorem 2
    alpha: float = 3.0
    mu: float = 3.0

    @cached_property
    def theorem(self):
        """1 (inconsistent quadrant, b < 0) or 2 (indeterminate, b > 0)."""
        return 1 if an.b(self.theta0, self.phi0) < 0 else 2

    def check(self):
        """Raises HypothesisError, naming the hypothesis, if the paper's theorems do not cover this case."""
        err = self._hypothesis_error
        if err is not None:     # a fresh exception each time, not one traceback growing
            raise an.HypothesisError(str(err), getattr(err, "hypotheses", ()))

    @cached_property
    def _hypothesis_error(self):
        if not (self.epsilon > 0 and math.isfinite(self.epsilon)):
            return an.HypothesisError(f"epsilon must be > 0; got {self.epsilon}")
        check = an.check_theorem1 if self.theorem == 1 else an.check_theorem2
        try:
            check(self.theta0, self.phi0, self.v0, alpha=self.alpha, mu=self.mu, delta=self.delta)
        except an.HypothesisError as err:
            return err
        if self.theorem == 2 and not self.w10 < 0:
            return an.HypothesisError(f"Theorem 2 starts the rod moving down, w10 < 0; got w10 = {self.w10}")
        return None

    def start_values(self):
        return dict(alpha=self.alpha, mu=self.mu, delta=self.delta, epsilon=self.epsilon,
                    x=0.0, v=self.v0, y=0.0, w=self.epsilon * self.w10, theta=self.theta0, phi=self.phi0)

    def _params(self):
        return dict(alpha=self.alpha, mu=self.mu)

    @cached_property
    def e(self):
        return float(an.e(self.delta, self.theta0, **self._params()))

    @cached_property
    def predicted_phi(self):
        return float(an.phi_after_iwc(self.theta0, self.phi0, self.v0, self.delta, **self._params()))

    def w_error(self, w):
        """w/v0 - e for a return velocity w: o(1) as eps -> 0 (Theorem 1)."""
        return w / self.v0 - self.e

    def phi_error(self, phi):
        return phi - self.predicted_phi

    @cached_property
    def lambda_plus(self):
        """The unstable eigenvalue of slipping compression (eq lambdapm)."""
        return float(an.lambda_pm(self.theta0, self.delta, **self._params())[0])

    @cached_property
    def time_scale(self):
        """eps ln(1/eps) / lambda_+: the IWC's duration up to O(eps) (eq TT)."""
        return float(an.iwc_time_scale(self.epsilon, self.theta0, self.delta, **self._params()))

    @cached_property
    def w1_star(self):
        """Theorem 2's separatrix (NaN for a Theorem 1 case)."""
        if self.theorem == 1:
            return math.nan
        return float(an.w1_star(self.theta0, self.phi0, self.delta, **self._params()))

    @property
    def predicts_iwc(self):
        return self.theorem == 1 or self.w10 < self.w1_star


@dataclass(frozen=True)
class Outcome:
    """What the FMU did, at the rod's return to y = 0, beside the analytic predictions."""
    case: Case
    iwc: bool               # the rod stuck before lifting off
    w: float
    theta: float
    phi: float
    v: float
    t_return: float
    compression: float      # durations; NaN for phases that did not happen
    stick: float
    lift_off: float
    events: int

    @property
    def w_error(self):
        return self.case.w_error(self.w)

    @property
    def phi_error(self):
        return self.case.phi_error(self.phi)

    @property
    def theta_error(self):
        return self.theta - self.case.theta0

    def as_row(self):
        """A flat dict: the case, the outcome, the predictions and the errors."""
        row = {**asdict(self.case), **{k: v for k, v in asdict(self).items() if k != "case"}}
        row.update(e=self.case.e, predicted_w=self.case.e * self.case.v0, predicted_phi=self.case.predicted_phi,
                   w_error=self.w_error, phi_error=self.phi_error, theta_error=self.theta_error,
                   time_scale=self.case.time_scale)
        return row


class Experiment(LoadedFMU):
    """Runs IWC cases on one extracted FMU and one instance (fmpy's fast loop)."""

    def __init__(self, fmu_path, *, interface="ME", solver="CVode", relative_tolerance=None, steps_per_epsilon=100):
        if solver not in ("CVode", "Euler"):
            raise ValueError(f"solver must be 'CVode' or 'Euler', not {solver!r}")
        self._switches = []     # the FMU's logged mode switches in the current CS run
        super().__init__(fmu_path, interface=interface)
        self.solver = solver
        self.relative_tolerance = relative_tolerance
        self.steps_per_epsilon = steps_per_epsilon
        self._vr_yw, self._vr_contact, self._vr_mode = [self.vr["y"], self.vr["w"]], [self.vr["contact"]], [self.vr["mode"]]
        self.solver_stats = {}   # the last Model Exchange fast loop's dict(nfev, nsteps)
        self._vr_states = [self.vr[k] for k in STATES]

    def _back_on_floor(self):
        """fmpy's step_finished callback: stop one step after the rod, having touched,
        is back at y = 0, so that the state after that event is recorded too
        (with delta = 0 lift-off and the return are one event)."""
        seen = {"touched": False, "back": False}

        def step_finished(time, recorder):
            if seen["back"]:
                return False
            contact = bool(self.fmu.getBoolean(self._vr_contact)[0])
            seen["touched"] |= contact
            seen["back"] = seen["touched"] and not contact and self.fmu.getReal(self._vr_yw)[0] >= 0
            return True
        return step_finished

    def _solver_settings(self, case):
        # In fast time tau = t/eps the IWC takes ln(1/eps)/lambda_+ to compress and
        # O(1 + delta) to stick and lift off; the run stops itself at the return.
        fast = 10 * math.log(1 / case.epsilon) / case.lambda_plus + 50 * (1 + case.delta)
        horizon = case.epsilon * fast
        if self.interface == "CS" or self.solver == "CVode":
            rtol = self.relative_tolerance or min(1e-6, case.epsilon / 100)
            # Through ME the events are recorded exactly and the grid only decides when the
            # run sees the return: 5 eps costs a third less than eps/2 (fmpy's per-point
            # work), same w to 1e-8. Through CS the points are all the master sees: eps/2.
            interval = case.epsilon / 2 if self.interface == "CS" else 5 * case.epsilon
            return dict(relative_tolerance=rtol, output_interval=interval, stop_time=horizon)
        h = case.epsilon / self.steps_per_epsilon
        return dict(step_size=h, output_interval=h, stop_time=horizon)

    def simulate(self, case):
        """The raw trajectory of one case (fmpy's structured array), events included."""
        case.check()
        return super().simulate(case, solver=self.solver, start_values=case.start_values(), output=OUTPUTS,
                                step_finished=self._back_on_floor(), **self._solver_settings(case))

    def run(self, case):
        """One case, reduced to its Outcome."""
        if self.interface == "CS":
            return self._run_cs(case)
        if self.solver == "CVode":
            return self._run_me(case)
        return outcome_of(case, self.simulate(case))

    def _start(self, fmu, case, tolerance):
        """Set-up, the case's start values, initialization (fmi2ExitInitializationMode done)."""
        start = case.start_values()
        fmu.setupExperiment(tolerance=tolerance, startTime=0.0)
        fmu.setReal([self.vr[k] for k in start], list(start.values()))
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()

    def _contact_mode(self):
        return int(self.fmu.getBoolean(self._vr_contact)[0]), int(self.fmu.getInteger(self._vr_mode)[0])

    def _run_me(self, case):
        """Model Exchange's fast loop: fmpy's CVode from event to event (me_loop), the
        phases read at each event, the run stopped at the event that returns the rod to y = 0."""
        case.check()
        settings = self._solver_settings(case)
        switches, state = [], {}

        def at_event(t):
            contact, mode = self._contact_mode()
            if switches[-1][1:] != (contact, mode):
                switches.append((t, contact, mode))
            if any(c for _, c, _ in switches) and not contact:
                state.update(zip(STATES, self.fmu.getReal(self._vr_states)))
                return state["y"] >= 0
            return False

        with self.fresh_run(case) as fmu:
            self._start(fmu, case, settings["relative_tolerance"])
            switches.append((0.0, *self._contact_mode()))     # the start: a reference, not a switch
            t, self.solver_stats = integrate(fmu, self.model_description, tolerance=settings["relative_tolerance"],
                                             stop_time=settings["stop_time"], at_event=at_event)
        if state.get("y", -1) < 0:
            raise no_return(case, t)
        return outcome_from_switches(case, switches[1:], t, state)

    def _log(self, status, category, message):
        super()._log(status, category, message)
        if category == "logEvents" and (switch := SWITCH.match(message)):
            self._switches.append(switch)

    def _run_cs(self, case):
        """Co-Simulation's fast loop: the FMU's event log (logEvents, one message per mode
        switch, with its time) tells the phases exactly, so the master steps in chunks of
        CHUNK eps and reads the state only at the end of each, until the rod has left the
        floor; the return to y = 0 is then the closed-form free flight run back."""
        case.check()
        settings = self._solver_settings(case)
        h, stop = CHUNK * case.epsilon, settings["stop_time"]
        self._switches = []
        with self.fresh_run(case) as fmu:
            fmu.setDebugLogging(True, ["logEvents"])
            self._start(fmu, case, settings["relative_tolerance"])
            t = 0.0
            while t < stop:
                fmu.doStep(t, h)
                t += h
                left = any(m["contact_to"] == "0" for m in self._switches)
                if left and (state := dict(zip(STATES, fmu.getReal(self._vr_states))))["y"] >= 0:
                    break
            else:
                raise no_return(case, stop)
        s, back = flight_back_to_floor(state) if state["y"] > 0 else (0.0, state)
        return outcome_from_switches(case, [(float(m["t"]), int(m["contact_to"]), int(m["mode_to"]))
                                            for m in self._switches], t + s, back)


# The FMU's logEvents message for a switch (fmi2_me.c, handle_event).
SWITCH = re.compile(r"t = (?P<t>\S+): indicator .*; contact \d -> (?P<contact_to>\d), mode \S+ -> (?P<mode_to>\S+?)(;|$)")
CHUNK = 4     # communication step in eps: well inside the flight after the return (O(1) long)


def outcome_from_switches(case, switches, t_return, back):
    """The Outcome from the mode switches [(t, contact, mode) after each] of a run that
    starts on the floor at t = 0 and returns to it at t_return in state `back`."""
    stick_start = next((t for t, contact, mode in switches if contact and mode == 0), None)
    nan = math.nan
    if stick_start is None:
        compression, stick, lift_off = nan, nan, t_return
    else:
        stick_end = next((t for t, contact, mode in switches if t > stick_start and (mode != 0 or not contact)),
                         t_return)
        compression, stick, lift_off = stick_start, stick_end - stick_start, t_return - stick_end
    return Outcome(case=case, iwc=stick_start is not None, w=float(back["w"]), theta=float(back["theta"]),
                   phi=float(back["phi"]), v=float(back["v"]), t_return=float(t_return),
                   compression=float(compression), stick=float(stick), lift_off=float(lift_off),
                   events=len([t for t, *_ in switches if t <= t_return]))


def no_return(case, t):
    return SimulationError(f"{case} did not return to y = 0 within t = {t:.3g} (is eps small enough "
                           f"for the asymptotic regime? eps * delta = {case.epsilon * case.delta:g})")


def _first(mask, start=0):
    hits = np.flatnonzero(mask[start:])
    return start + hits[0] if hits.size else None


def flight_back_to_floor(state):
    """The free flight run back from `state` (a row in flight above the floor) to
    its last y = 0: (time offset s <= 0, state there). Closed form: the centre of
    mass (x - cos theta, y + sin theta) falls freely, the rod spins uniformly."""
    th, ph, y, w, v = (float(state[k]) for k in ("theta", "phi", "y", "w", "v"))
    Ydot, Xdot = w + ph * math.cos(th), v + ph * math.sin(th)

    def height(s):
        return y + math.sin(th) + Ydot * s - s * s / 2 - math.sin(th + ph * s)

    def speed(s):    # d height / ds = w(s)
        return Ydot - s - ph * math.cos(th + ph * s)
    s = -y / w
    for _ in range(20):   # Newton from the straight-line guess; the root is simple (w > 0)
        step = height(s) / speed(s)
        s -= step
        if abs(step) <= 1e-14:    # height's round-off (~1e-16) over w: s is then exact
            break
    return s, dict(w=speed(s), v=Xdot - ph * math.sin(th + ph * s), theta=th + ph * s, phi=ph)


def outcome_of(case, r, exact_events=True):
    """Reads the phases off a trajectory: compression (slip), stick, lift-off, return.
    Without exact event rows (Co-Simulation) the return is found by flight_back_to_floor."""
    t, contact, mode = r["time"], r["contact"].astype(bool), r["mode"]
    for name in ("time", "v", "y", "w", "theta", "phi"):
        if not np.all(np.isfinite(r[name])):
            raise SimulationError(f"{case}: the FMU returned a non-finite {name}")
    touch = _first(contact)
    end = None if touch is None else _first(~contact & (r["y"] >= 0), touch)
    if end is None:
        raise no_return(case, t[-1])
    stick_start = _first(contact[:end] & (mode[:end] == 0), touch)    # a stick after the return is not this IWC's
    nan = math.nan
    if stick_start is None:
        compression, stick, lift_off = nan, nan, t[end] - t[touch]
    else:
        stick_end = _first((mode != 0) | ~contact, stick_start)
        compression = t[stick_start] - t[touch]
        stick = t[stick_end] - t[stick_start]
        lift_off = t[end] - t[stick_end]
    back = dict(w=r["w"][end], v=r["v"][end], theta=r["theta"][end], phi=r["phi"][end])
    t_return = t[end]
    if not exact_events and r["y"][end] > 0:
        s, back = flight_back_to_floor(r[end])
        t_return += s
        lift_off = max(0.0, lift_off + s)   # stick's end is known to a communication step only
    return Outcome(case=case, iwc=stick_start is not None, w=float(back["w"]), theta=float(back["theta"]),
                   phi=float(back["phi"]), v=float(back["v"]), t_return=float(t_return),
                   compression=float(compression), stick=float(stick), lift_off=float(lift_off),
                   events=int(np.sum(np.diff(t[:end + 1]) == 0)) if exact_events else -1)


def run_iwc(fmu_path, *, interface="ME", solver="CVode", relative_tolerance=None, **case):
    """One case, fmpy style: run_iwc("PainleveRod.fmu", theta0=1.0, epsilon=1e-4)."""
    with Experiment(fmu_path, interface=interface, solver=solver, relative_tolerance=relative_tolerance) as experiment:
        return experiment.run(Case(**case))
