# SPDX-License-Identifier: BSD-2-Clause
"""Any body FMU (the rod, the two-link arm, ...) through nothing but its own variables.

A body FMU has start values (its continuous outputs with initial="exact": the coordinates and rates
a user sets; its states may include more, such as the arm's `y`, which the FMU calculates at the
start), the contact point's height `y`, slip speed `v` and normal speed `w`, `contact`, `epsilon` and `delta` (parameters, or calculated from the
stiffness `k` and damping `c`: eps ~ k^-1/2, delta ~ c k^-1/2, as every body's scaling has it),
and the coefficients of eq Painleve at the current state as outputs (a, b, p_plus, p_minus,
q_plus, q_minus, S_w, scaled). `Body` gives, without any body-specific kinematics:

- `outputs(values)`: any outputs at a state (the instance initialized from those start values);
- `compliance(values, epsilon, delta)`: the start values that give the body that eps and delta;
- `floor_start(values, v0)`: a consistent start, the contact point on the floor (y = 0) with
  velocity (v0, w0), solving for the start values the user did not give (and any parameters named) by
  Gauss-Newton on the FMU's own y, v, w (finite-difference Jacobian; for the arm: theta2 and both
  rates from theta1, or both rates and the pivot's height H from theta1 and theta2);
- `run(case, predicted)`: the Outcome of a case of either kind (experiments.case: the rod's Case, a
  BodyCase), the prediction it was run from attached (its w error: experiments.outcome);
- `coefficients(values)`: theory.general.Coefficients at a state, with its epsilon and delta;
- `iwc(values)`: the run from that start until the contact point, having touched, is back at
  y = 0: its Outcome (experiments.outcome), through the interface the Body was opened with:
  Model Exchange (fmpy's CVode from event to event, me_fast_loop; an FMI 3.0 FMU through fmpy's
  simulate_fmu) or Co-Simulation (cs_fast_loop.run_to_return: the FMU's own integrator, the
  return bisected on its steps).
"""
import math
from dataclasses import replace

import numpy as np

from ..experiments.case import Case
from ..experiments.outcome import NoReturn, SimulationError, outcome_from_switches, outcome_of_trajectory
from ..theory import general
from . import cs_fast_loop, me_fast_loop
from .cs_calls import initialize
from .experiment import Experiment

CONTACT = ("y", "v", "w")
REQUIRED = CONTACT + ("contact", "mode", "epsilon", "delta") + general.NAMES
# What a Co-Simulation run reads besides: the FMU's record of its contact and stick, and its counts.
REQUIRED_CS = cs_fast_loop.RECORD + ("switches", "sticks")
STIFFNESS, DAMPING = "k", "c"      # the SI bodies' contact parameters when epsilon, delta are calculated


class BodyError(ValueError):
    """The FMU is not a body the harness can run, or no start state satisfies what was asked."""


class Body:
    """One body FMU, extracted and instantiated once (Experiment, with its `options`: tmp_dir, ...) for one
    interface (fmpy's fmi_type, "ModelExchange" or "CoSimulation"), for any number of evaluations and runs."""

    def __init__(self, fmu_path, *, fmi_type="ModelExchange", **options):
        self.experiment = Experiment(fmu_path, fmi_type=fmi_type, **options)
        md = self.experiment.model_description
        self.variables = {v.name: v for v in md.modelVariables}
        needed = REQUIRED + (REQUIRED_CS if fmi_type == "CoSimulation" else ())
        missing = [n for n in needed if n not in self.variables]
        if missing:
            self.close()
            raise BodyError(f"{fmu_path} is not a body FMU: it has no variable {', '.join(missing)}")
        if fmi_type == "CoSimulation" and not md.coSimulation.canGetAndSetFMUstate:
            self.close()
            raise BodyError(f"{fmu_path}: its Co-Simulation cannot get and set its state, which a run's return "
                            f"is located with")
        self.start_variables = [v.name for v in md.modelVariables
                                if v.causality == "output" and v.variability == "continuous" and v.initial == "exact"]
        self.name = md.modelName
        self.fmi_type = fmi_type
        # What a run reads at the return: the contact point's height and speeds, and every start value.
        self.read = CONTACT + tuple(s for s in self.start_variables if s not in CONTACT)

    def close(self):
        self.experiment.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def defaults(self, names):
        return {n: float(self.variables[n].start) for n in names if self.variables[n].start is not None}

    def _known(self, values):
        unknown = [k for k in values if k not in self.experiment.vr]
        if unknown:
            raise BodyError(f"{self.name} has no variable {unknown[0]!r}")

    def _initialize(self, instance, values, tolerance=None):
        initialize(instance, self.experiment.vr, {k: float(x) for k, x in values.items()}, tolerance)

    def outputs(self, values, names):
        """{name: value} after initialization from the start values `values`."""
        self._known(values)
        self._known(dict.fromkeys(names))
        with self.experiment.fresh_run(f"{self.name} at {values}") as instance:
            self._initialize(instance, values)
            return self.experiment.read(list(names))

    def coefficients(self, values):
        """(theory.general.Coefficients, epsilon, delta) at the state `values`."""
        out = self.outputs(values, general.NAMES + ("epsilon", "delta"))
        return general.Coefficients.of(out), out["epsilon"], out["delta"]

    def compliance(self, values, epsilon, delta):
        """`values` with what gives this epsilon and delta: the parameters themselves, or k and c scaled
        by eps ~ k^-1/2, delta ~ c k^-1/2 from their current values (checked by reading them back)."""
        if self.variables["epsilon"].causality == "parameter":
            return dict(values, epsilon=epsilon, delta=delta)
        if STIFFNESS not in self.variables or DAMPING not in self.variables:
            raise BodyError(f"{self.name}: epsilon is not a parameter and there is no {STIFFNESS}, {DAMPING} to set it")
        now = self.outputs(values, ("epsilon", STIFFNESS))
        k = now[STIFFNESS] * (now["epsilon"] / epsilon) ** 2
        c = delta / self.outputs(dict(values, **{STIFFNESS: k, DAMPING: 1.0}), ("delta",))["delta"]  # delta ~ c
        out = dict(values, **{STIFFNESS: k, DAMPING: c})
        got = self.outputs(out, ("epsilon", "delta"))
        if not (math.isclose(got["epsilon"], epsilon, rel_tol=1e-9) and math.isclose(got["delta"], delta,
                                                                                     rel_tol=1e-9, abs_tol=1e-12)):
            raise BodyError(f"{self.name}: scaling {STIFFNESS}, {DAMPING} gave epsilon {got['epsilon']:.6g}, "
                            f"delta {got['delta']:.6g}, not {epsilon:g}, {delta:g}")
        return out

    def start_names(self, given, solve=()):
        """The names, in order, of the start values a case that gives `given` (names) and solves for `solve`
        starts from (body_case.predict's start): those given, the compliance's (compliance: epsilon and
        delta, or k and c), then what floor_start solves for (the start variables not given, the parameters in
        `solve`)."""
        names = dict.fromkeys(given)
        names.update(dict.fromkeys(("epsilon", "delta") if self.variables["epsilon"].causality == "parameter"
                                   else (STIFFNESS, DAMPING)))
        names.update(dict.fromkeys([s for s in self.start_variables if s not in names] +
                                   [p for p in solve if p not in self.start_variables]))
        return list(names)

    def floor_start(self, values, v0, w0=0.0, guess=None, max_iterations=40, solve=()):
        """`values` completed with the start values it does not give (and the parameters named in `solve`), so
        that y = 0, v = v0, w = w0 (Gauss-Newton, least squares: unknowns that do not move y, v, w keep
        their guess, the FMU's start otherwise). With nothing to solve for, `values` themselves, checked."""
        self._known(dict.fromkeys(solve))
        unknown = [s for s in self.start_variables if s not in values] + [p for p in solve if p not in self.start_variables]
        target = np.array([0.0, v0, w0])
        tolerance = 1e-12 * (1 + abs(v0) + abs(w0))
        if not unknown:
            out = self.outputs(values, CONTACT)
            r = np.array([out[n] for n in CONTACT]) - target
            if np.any(np.abs(r) > tolerance):
                raise BodyError(f"{self.name}: the start {values} is not on the floor with v = {v0:g}, w = {w0:g} "
                                f"(y, v - v0, w - w0 = {r}); leave the start values to solve for out")
            return dict(values)
        u = np.array([float((guess or {}).get(s, self.defaults([s]).get(s, 0.0))) for s in unknown])

        def residual(u):
            out = self.outputs(dict(values, **dict(zip(unknown, (float(x) for x in u)))), CONTACT)
            return np.array([out[n] for n in CONTACT]) - target
        try:
            u, r = self._gauss_newton(residual, u, v0, max_iterations)
        except SimulationError as err:    # a trial state outside the FMU's ranges: no start near the guess
            raise BodyError(f"{self.name}: no state with y = 0, v = {v0:g}, w = {w0:g} found from {values}: "
                            f"the search left the FMU's ranges ({str(err).split('the FMU stopped: ')[-1]}); "
                            f"give other start values or --guess") from None
        if np.any(np.abs(r) > tolerance):
            raise BodyError(f"{self.name}: no state with y = 0, v = {v0:g}, w = {w0:g} found from {values} "
                            f"(residual y, v - v0, w - w0 = {r}); give other start values or --guess")
        return dict(values, **dict(zip(unknown, (float(x) for x in u))))

    @staticmethod
    def _gauss_newton(residual, u, v0, max_iterations):
        r = residual(u)
        for _ in range(max_iterations):
            h = 1e-7 * (1 + np.abs(u))
            jac = np.column_stack([(residual(u + h[i] * np.eye(len(u))[i]) - r) / h[i] for i in range(len(u))])
            step = np.linalg.lstsq(jac, -r, rcond=None)[0]
            u = u + step
            r = residual(u)
            if np.all(np.abs(step) <= 1e-15 * (1 + np.abs(u))) or np.all(np.abs(r) <= 1e-15 * (1 + abs(v0))):
                break
        return u, r

    def run(self, case, predicted=None, *, closed_form=None, doublings=30):
        """The Outcome of a case of either kind (experiments.case) from its start on the floor, carrying
        `predicted` (body_case.predict(self, case), if known) as its prediction. The rod's Case runs as
        Experiment.run runs it (its horizon and, through Co-Simulation, its return from the closed forms,
        `closed_form`: analytic.predict(case) if known, a sweep's made over its batch's arrays; every
        state of it is given, so its start is its start_values); any other case from the start
        `predicted` solved (iwc, its horizon doubled at most `doublings` times)."""
        if isinstance(case, Case):
            outcome = self.experiment.run(case, closed_form)
        elif predicted is None:
            raise BodyError("a body's case runs from its solved start: body_case.run_body(body, case) solves it")
        else:
            outcome = self.iwc(predicted.start, case=case, doublings=doublings)
        return outcome if predicted is None else replace(outcome, prediction=predicted)

    def iwc(self, values, *, case=None, relative_tolerance=None, horizon=None, doublings=30):
        """The Outcome of the run from `values` (its case: `case`, else the values) until the contact point,
        having been in contact, is back at y = 0 with contact off. The horizon, unknown in a body's own
        time unit, starts at `horizon` (default epsilon) and doubles until the run returns."""
        eps = self.outputs(values, ("epsilon",))["epsilon"]
        rtol = relative_tolerance or min(1e-6, eps / 100)
        stop = horizon or eps
        for _ in range(doublings):
            out = self._run(dict(values) if case is None else case, values, rtol, stop, eps)
            if out is not None:
                return out
            stop *= 2
        raise NoReturn(f"{self.name}: no return to y = 0 before t = {stop / 2:g}")

    def _run(self, case, values, rtol, stop_time, eps):
        """The Outcome of one run to stop_time, or None if it is not back on the floor by then."""
        start = {k: float(x) for k, x in values.items()}
        if self.fmi_type == "CoSimulation":
            # a communication step of eps: well inside the flight after the return (O(1) long)
            return cs_fast_loop.run_to_return(self.experiment, case, start, relative_tolerance=rtol,
                                              stop_time=stop_time, step=eps, read=self.read)
        if self.experiment.model_description.fmiVersion.startswith("2."):
            switches, t, back, returned, stats = me_fast_loop.run_to_return(
                self.experiment, f"{self.name} from {values}", start, relative_tolerance=rtol, stop_time=stop_time,
                read=self.read)
            return outcome_from_switches(case, switches, t, back, events=len(switches) - 1,
                                         solver_stats=stats) if returned else None
        # FMI 3.0 Model Exchange: fmpy's simulate_fmu (CVode, events recorded as two rows each)
        r = self.experiment.simulate_to_return(f"{self.name} from {values}", start,
                                               output=self.read + ("contact", "mode"), stop_time=stop_time,
                                               output_interval=stop_time / 500, relative_tolerance=rtol,
                                               solver="CVode")
        try:
            return outcome_of_trajectory(case, r, read=self.read)
        except NoReturn:
            return None
