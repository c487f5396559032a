# SPDX-License-Identifier: BSD-2-Clause
"""A plain reference implementation of the compliant Painleve rod with scipy's solve_ivp.

What it is: the model of docs/model.md §1-2 written the way a researcher would
write it without the FMU: the right-hand side and Jacobian of each mode in
numpy, integrated by ``scipy.integrate.solve_ivp`` (LSODA, DOP853, Radau or
BDF) piecewise by mode, with terminal events on the switching surfaces and a
restart of solve_ivp from each event state. Modes, switching
surfaces and their rules: reference_rod.

Why it exists: an independent check of the FMU (same equations, different
code, different solvers: tests/experiments/test_reference.py compares the two), and the
baseline of the benchmark (what the FMU saves over a Python model integrated
by scipy: the Outcome's solver_stats carry solve_ivp's cost counters).

``run_reference(case)`` runs one IWC case of experiment.py (start on the floor,
y = 0, w = eps w10; stop at the rod's return to y = 0 moving up after having
touched) and returns its ``Outcome`` (the harness's, phases and all); ``simulate(rod, x0, t_end)`` is
the general integrator from any state, with the trajectory if asked for.

Conventions shared with the FMU harness, so that the two are compared at equal
accuracy: the relative tolerance defaults to min(1e-6, eps/100), the absolute
tolerance of each state is rtol times its nominal (1 for x, v, theta, phi;
eps^2 for y; eps for w: the contact's own scales), and the run's horizon is
``case.horizon``'s, as for the FMU.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .case import horizon
from .outcome import outcome_from_switches
from .reference_rod import FILIPPOV, FLIGHT, SLIP_BACKWARD, SLIP_FORWARD, STICK, PHI, THETA, V, W, Y, Rod

__all__ = ["METHODS", "FILIPPOV", "FLIGHT", "SLIP_FORWARD", "STICK", "SLIP_BACKWARD", "Rod",
           "ReferenceRun", "ReferenceSimulationError", "run_reference", "simulate",
           "default_rtol", "nominals"]

METHODS = ("LSODA", "DOP853", "Radau", "BDF")
_IMPLICIT = ("LSODA", "Radau", "BDF")   # the methods that use a Jacobian
_TINY = 1e-300
_MAX_EVENTS = 1000          # a run of this many events is chatter, not an IWC
_MAX_STALLED = 10           # consecutive events without progress in time


class ReferenceSimulationError(RuntimeError):
    """The reference integration could not finish: solver failure, chatter, or no return."""


def _event(name, z, side, t0):
    """solve_ivp event for z leaving `side`. At the segment's start the state sits on the
    surface it just crossed, within rounding: z(t0) is then taken on the mode's side."""
    def event(t, x):
        value = z(x)
        if t == t0 and value * side <= 0:
            return side * _TINY
        return value
    event.terminal = True
    event.direction = -side
    event.__name__ = name
    return event


def default_rtol(epsilon):
    """min(1e-6, eps/100), as Experiment uses for CVode."""
    return min(1e-6, epsilon / 100)


def nominals(epsilon):
    """Scales of (x, v, y, w, theta, phi): 1, 1, eps^2, eps, 1, 1 (the FMU's nominals)."""
    return np.array([1.0, 1.0, epsilon ** 2, epsilon, 1.0, 1.0])


@dataclass
class ReferenceRun:
    """One integration: the segments (mode, t0, t1), the stop state, cost counters, and the
    trajectory (t, x) if recorded (step points, each event state included once per segment)."""
    t_stop: float = 0.0
    x_stop: np.ndarray = None
    returned: bool = False      # stopped at the return to y = 0 after touching
    touched: bool = False
    segments: list = field(default_factory=list)     # (mode, t_start, t_end, event name or None)
    nfev: int = 0
    njev: int = 0
    nlu: int = 0
    nsteps: int = 0
    nevents: int = 0            # events that restarted solve_ivp (the return that stops a run not counted)
    t: np.ndarray = None
    x: np.ndarray = None

    @property
    def modes(self):
        return tuple(s[0] for s in self.segments)


def _check_method(method):
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}; got {method!r}")


def simulate(rod, x0, t_end, *, method="Radau", rtol=None, jac=True, stop_at_return=True, record=False):
    """Integrate the rod from state x0 (x, v, y, w, theta, phi) at t = 0 up to t_end,
    or, if stop_at_return, up to its return to y = 0 moving up after having touched.

    rtol defaults to min(1e-6, eps/100); atol = rtol * (1, 1, eps^2, eps, 1, 1).
    jac=True gives the implicit methods the analytic Jacobian; jac=False lets them
    use finite differences. Raises ReferenceSimulationError if the solver fails or the
    modes chatter without progress in time.
    """
    _check_method(method)
    x = np.array(x0, dtype=float)
    if x.shape != (6,) or not np.all(np.isfinite(x)):
        raise ValueError(f"x0 must be 6 finite numbers (x, v, y, w, theta, phi); got {x0!r}")
    if not (t_end > 0 and math.isfinite(t_end)):
        raise ValueError(f"t_end must be > 0 and finite; got {t_end!r}")
    rtol = default_rtol(rod.epsilon) if rtol is None else float(rtol)
    if not 0 < rtol < 1:
        raise ValueError(f"rtol must be in (0, 1); got {rtol!r}")
    atol = rtol * nominals(rod.epsilon)
    options = dict(method=method, rtol=rtol, atol=atol)
    use_jac = jac and method in _IMPLICIT

    run = ReferenceRun()
    t, mode, name = 0.0, rod.initial_mode(x), None
    run.touched = mode != FLIGHT
    ts, xs = [np.array([t])], [x[:, None]]
    stalled = 0
    while True:
        names, events = [], []
        for watched, z, side in rod.switching_functions(mode, x, crossed=name):
            names.append(watched)
            events.append(_event(watched, z, side, t))
        extra = dict(jac=rod.jacobian(mode)) if use_jac else {}
        sol = solve_ivp(_counted(rod.rhs(mode), run), (t, t_end), x, events=events, dense_output=mode == FLIGHT,
                        **options, **extra)
        run.njev += sol.njev
        run.nlu += sol.nlu
        run.nsteps += len(sol.t) - 1
        if record:
            ts.append(sol.t[1:])
            xs.append(sol.y[:, 1:])
        if sol.status == -1:
            raise ReferenceSimulationError(f"{method} failed at t = {sol.t[-1]:.6g} in mode {mode}: {sol.message}")
        if sol.status == 0:                 # horizon reached without an event
            run.segments.append((mode, t, sol.t[-1], None))
            t, x = sol.t[-1], sol.y[:, -1].copy()
            break
        fired = [(te[-1], i) for i, te in enumerate(sol.t_events) if len(te)]
        t_event, i = min(fired)
        name, x_new = names[i], sol.y_events[i][-1].copy()
        run.segments.append((mode, t, t_event, name))
        stalled = stalled + 1 if t_event <= t + 4 * np.spacing(max(abs(t), 1e-300)) else 0
        if stalled > _MAX_STALLED or run.nevents >= _MAX_EVENTS:
            why = "without progress in time" if stalled > _MAX_STALLED else f"({_MAX_EVENTS} events)"
            raise ReferenceSimulationError(f"the modes chatter {why} at t = {t_event:.9g}; last event: {name} "
                                           f"in mode {mode}, state {x_new.tolist()}")
        t, x = t_event, x_new

        if name == "w = 0" and x[Y] < 0:
            # a grazing dip below the floor inside one step: go back to where y crossed 0
            t = _root_of_y(sol.sol, sol.t[-2], t_event)
            x = sol.sol(t).copy()
            x[Y] = 0.0
            name = "touch-down"
            run.segments[-1] = (mode, run.segments[-1][1], t, name)
            if record:
                keep = ts[-1] < t
                ts[-1], xs[-1] = np.append(ts[-1][keep], t), np.column_stack([xs[-1][:, keep], x])
        mode, stop = _next_mode(rod, mode, name, x, run)
        if stop and stop_at_return:
            run.returned = True
            break
        run.nevents += 1
    run.t_stop, run.x_stop = t, x
    if record:
        run.t, run.x = np.concatenate(ts), np.concatenate(xs, axis=1)
    return run


def _counted(f, run):
    """f, adding each call to run.nfev: solve_ivp's own nfev leaves out the calls of
    Radau's and BDF's finite-difference Jacobians, so the methods would not compare."""
    def counted(t, x):
        run.nfev += 1
        return f(t, x)
    return counted


def _root_of_y(dense, t0, t1):
    return brentq(lambda s: dense(s)[Y], t0, t1, xtol=4 * np.finfo(float).eps, rtol=4 * np.finfo(float).eps)


def _next_mode(rod, mode, name, x, run):
    """The mode after event `name` in `mode` at state x (v may be set to exactly 0).
    Returns (new mode, whether this is the return to y = 0 after touching)."""
    if name == "lift-off":
        # with delta = 0, g = -y/eps: lift-off is itself the return to y = 0
        return FLIGHT, run.touched and x[Y] >= 0
    if name == "v = 0":
        x[V] = 0.0
        return rod.at_rest(x), False
    if name == "forward fold":
        return SLIP_FORWARD, False
    if name == "backward fold":
        return SLIP_BACKWARD, False
    if name in ("touch-down", "re-contact"):
        run.touched = True
        return rod.contact_mode(x), False
    if name == "return":
        return FLIGHT, run.touched
    if name == "w = 0":
        return FLIGHT, False
    raise AssertionError(name)  # pragma: no cover


# The FMU's (contact, mode) of each reference mode, for the one phase extraction (outcome.phases).
_CONTACT_MODE = {FLIGHT: (False, 0), SLIP_FORWARD: (True, 1), STICK: (True, 0), SLIP_BACKWARD: (True, -1)}


def run_reference(case, method="Radau", relative_tolerance=None, *, jac=True, filippov="exact"):
    """One IWC case (a Case) integrated by solve_ivp, reduced to its Outcome like Experiment.run;
    solver_stats: nfev (right-hand sides, finite-difference Jacobians included), njev, nlu,
    nsteps (accepted), nevents (mode switches; the return not counted), method,
    relative_tolerance, modes (in order, e.g. ("slip+", "stick", "slip-", "flight")), filippov.

    Starts on the floor (y = 0, w = eps w10, v = v0, theta0, phi0) and stops at the
    return to y = 0 moving up after having touched. Raises ValueError for an unknown
    method, HypothesisError (via case.check()) for a case outside the theorems, and
    ReferenceSimulationError if the rod does not return within the horizon.
    jac: see simulate; filippov: the sticking field, see Rod.
    """
    _check_method(method)
    case.check()
    rod = Rod(alpha=case.alpha, mu=case.mu, delta=case.delta, epsilon=case.epsilon, filippov=filippov)
    x0 = [0.0, case.v0, 0.0, case.epsilon * case.w10, case.theta0, case.phi0]
    run = simulate(rod, x0, horizon(case), method=method, rtol=relative_tolerance, jac=jac)
    if not run.returned:
        raise ReferenceSimulationError(f"{case} did not return to y = 0 within t = {run.t_stop:.3g} "
                                       f"(modes {run.modes})")
    x = run.x_stop
    switches = [(t0, *_CONTACT_MODE[mode]) for mode, t0, _, _ in run.segments]
    stats = dict(nfev=run.nfev, njev=run.njev, nlu=run.nlu, nsteps=run.nsteps, nevents=run.nevents, method=method,
                 relative_tolerance=default_rtol(case.epsilon) if relative_tolerance is None
                 else float(relative_tolerance), modes=run.modes, filippov=filippov)
    back = dict(v=x[V], y=x[Y], w=x[W], theta=x[THETA], phi=x[PHI])
    return outcome_from_switches(case, switches, run.t_stop, back,
                                 events=run.nevents, solver_stats=stats)
