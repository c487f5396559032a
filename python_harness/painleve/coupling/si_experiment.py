# SPDX-License-Identifier: BSD-2-Clause
"""Runs PainleveRodSI.fmu (the rod in SI units, docs/si_model.md) with its inputs, on fmpy.

`SIExperiment` is an `Experiment` (one extraction, one instance, reset between runs) of the
SI FMU. Its inputs (y_floor, w_floor, v_floor, F_x, F_y, tau) are a function of time,
`inputs(t) -> {name: value}`, by default a `si.Floor` at constant velocity and constant
`si.Loads`:

- Model Exchange: fmpy's CVode, each right-hand side and event indicator evaluated with the
  inputs at its own time (fmpy's simulate_fmu sets them at the communication points and in
  the root function only, so a ramp y_floor = y0 + W t would lag by a solver step: the gap
  is the contact's whole state, and k W h is not small). An input that jumps (a belt
  switched on, `jumps=(t, ...)`, the function right-continuous) stops CVode exactly there
  (no right-hand side sees it early) and is handed over in Event Mode.
- Co-Simulation: fmpy's simulate_fmu with `input=` a table sampled on the communication
  grid (two rows at each jump), and the inputs' derivatives if the FMU can interpolate them.

Both return fmpy's structured array (time and the outputs; Model Exchange also records each
event, the rows before and after it). `run_case` runs a paper's `Case` on the SI FMU and
reduces it to its `Outcome` in the paper's units (si.to_paper), so that everything the
harness checks on PainleveRod (acceptance.py) applies to the SI model.
"""
import math

import numpy as np
from fmpy import simulate_fmu
from fmpy.sundials import CVodeSolver

from ..experiments.case import horizon
from ..experiments.outcome import outcome_of_trajectory
from ..fmu.experiment import Experiment, default_fmu
from ..fmu.fmpy_internals import cvode_set_stop_time
from ..fmu.me_fast_loop import event_iteration
from . import si

# The SI FMU a pip install of the package carries beside PainleveRod.fmu.
INPUTS = ("y_floor", "w_floor", "v_floor", "F_x", "F_y", "tau")
STATES = ("x", "v", "y", "w", "theta", "phi")
OUTPUTS = STATES + ("F_N", "F_T", "energy", "x_cm", "y_cm", "vx_cm", "vy_cm", "gap", "slip", "mode", "contact")


def constant_inputs(floor=si.Floor(), loads=si.Loads()):
    """inputs(t) of a floor at constant velocity and constant loads."""
    def inputs(t):
        return {**floor.inputs(t), **loads.inputs(t)}
    return inputs


class _Applier:
    """Sets the inputs at time t, held at the left limit `until` the next jump."""

    def __init__(self, instance, vr, inputs):
        self.instance, self.inputs, self.until = instance, inputs, math.inf
        self.names = list(inputs(0.0))
        unknown = [n for n in self.names if n not in INPUTS]
        if unknown:
            raise ValueError(f"not inputs of PainleveRodSI: {unknown}; its inputs are {list(INPUTS)}")
        self.vrs = [vr[n] for n in self.names]

    def apply(self, t):
        t = min(t, np.nextafter(self.until, -math.inf))
        values = self.inputs(t)
        self.instance.setReal(self.vrs, [float(values[n]) for n in self.names])


class _InputCVode(CVodeSolver):
    """fmpy's CVodeSolver (BDF, atol = rtol * nominal) whose right-hand side applies the inputs at its time."""

    def f(self, t, y, ydot, user_data):
        self.input.apply(t)
        return super().f(t, y, ydot, user_data)


class SIExperiment(Experiment):
    """PainleveRodSI.fmu extracted and instantiated once; runs with inputs (see the module).
    Without a path, the FMU installed with the package."""

    def __init__(self, fmu_path=None, **kwargs):
        super().__init__(default_fmu("PainleveRodSI.fmu") if fmu_path is None else fmu_path, **kwargs)
        missing = [n for n in (*INPUTS, *si.SIRod().parameters()) if n not in self.vr]
        if missing:
            self.close()
            raise ValueError(f"{fmu_path} is not PainleveRodSI: it has no variables {', '.join(missing)}")

    def simulate(self, rod, state, *, floor=si.Floor(), loads=si.Loads(), inputs=None, jumps=(), stop_time,
                 output_interval, relative_tolerance=1e-8, output=OUTPUTS):
        """One run from the SI start `state` of `rod`: fmpy's structured array of `output`.
        `inputs(t)` replaces the floor and loads if given; `jumps` are the times it jumps at."""
        inputs = self._complete(inputs or constant_inputs(floor, loads))
        start = {**rod.parameters(), **state.start_values()}
        what = f"{rod} from {state}"
        with self.fresh_run(what) as instance:
            if self.fmi_type == "CoSimulation":
                return self._co_simulation(instance, start, inputs, sorted(jumps), stop_time, output_interval,
                                           relative_tolerance, list(output))
            return self._model_exchange(instance, start, inputs, sorted(jumps), stop_time, output_interval,
                                        relative_tolerance, list(output))

    def _complete(self, inputs):
        """inputs(t) with the inputs it does not give at their start values (the model's defaults)."""
        starts = {v.name: float(v.start) for v in self.model_description.modelVariables
                  if v.causality == "input" and v.start is not None}

        def completed(t):
            return {**starts, **inputs(t)}
        return completed

    def _co_simulation(self, instance, start, inputs, jumps, stop_time, interval, rtol, output):
        n = int(round(stop_time / interval))
        times = sorted(set(np.linspace(0.0, n * interval, n + 1)) | set(jumps))
        rows = []
        for t in times:
            if t in jumps:       # two rows: the value before the jump, then after (fmpy's discontinuity)
                rows.append((t, *inputs(np.nextafter(t, -math.inf)).values()))
            rows.append((t, *inputs(t).values()))
        names = list(inputs(0.0))
        table = np.array(rows, dtype=[("time", float)] + [(n_, float) for n_ in names])
        interpolate = bool(self.model_description.coSimulation.canInterpolateInputs)
        return simulate_fmu(self.unzipdir, model_description=self.model_description, fmu_instance=instance,
                            fmi_type="CoSimulation", start_values=start, input=table, output=output,
                            stop_time=stop_time, output_interval=interval, relative_tolerance=rtol,
                            set_input_derivatives=interpolate, validate=False)

    def _model_exchange(self, instance, start, inputs, jumps, stop_time, interval, rtol, output):
        md, vr = self.model_description, self.vr
        applier = _Applier(instance, vr, inputs)
        pending = [t for t in jumps if 0 < t < stop_time]
        applier.until = pending[0] if pending else math.inf
        instance.setupExperiment(tolerance=rtol, startTime=0.0)
        instance.setReal([vr[k] for k in start], list(start.values()))
        applier.apply(0.0)
        instance.enterInitializationMode()
        instance.exitInitializationMode()
        info = event_iteration(instance)
        instance.enterContinuousTimeMode()
        solver = _InputCVode(nx=md.numberOfContinuousStates, nz=md.numberOfEventIndicators,
                             get_x=instance.getContinuousStates, set_x=instance.setContinuousStates,
                             get_dx=instance.getDerivatives, get_z=instance.getEventIndicators,
                             get_nominals=instance.getNominalsOfContinuousStates, set_time=instance.setTime,
                             input=applier, startTime=0.0, maxStep=stop_time / 50, relativeTolerance=rtol,
                             maxNumSteps=100_000)
        recorder = _Recorder(instance, md, output)
        recorder.sample(0.0)
        t, n = 0.0, 0
        while t < stop_time and not math.isclose(t, stop_time, rel_tol=1e-12) and not info[1]:
            t_grid = min(stop_time, (n + 1) * interval)
            t_next = min(t_grid, applier.until, info[5] if info[4] else math.inf)
            cvode_set_stop_time(solver.cvode_mem, t_next)
            _, roots, t = solver.step(t, t_next)
            root = bool(np.any(roots))     # (fmpy's first value is also true at CV_TSTOP_RETURN)
            instance.setTime(t)
            applier.apply(t)
            step_event = False
            if not md.modelExchange.completedIntegratorStepNotNeeded:
                step_event, terminate = instance.completedIntegratorStep()
                if terminate:
                    break
            at_jump = math.isclose(t, applier.until, rel_tol=1e-15, abs_tol=0.0)
            at_time_event = info[4] and t >= info[5]
            if root or step_event or at_jump or at_time_event:
                recorder.sample(t)
                instance.enterEventMode()
                if at_jump:
                    pending.pop(0)
                    applier.until = pending[0] if pending else math.inf
                    applier.apply(t)       # the value after the jump
                info = event_iteration(instance)
                instance.enterContinuousTimeMode()
                solver.reset(t)
            if math.isclose(t, t_grid, rel_tol=1e-12):
                n += 1
                recorder.sample(t)
            elif root or step_event or at_jump or at_time_event:
                recorder.sample(t)
        return recorder.result()

    def run_case(self, case, *, m=1.0, l=0.5, g=si.G, floor=si.Floor(), relative_tolerance=None):
        """A paper's IWC `Case` on the SI FMU (a rod of mass m, half-length l under gravity g on
        this floor): its Outcome in the paper's units, as Experiment.run gives it for PainleveRod
        (same tolerance, same grids in the paper's time, the return read off the trajectory)."""
        case.check()
        rod, state = si.si_of(case, m=m, l=l, g=g, floor=floor)
        T, rtol = rod.time_scale, relative_tolerance or min(1e-6, case.epsilon / 100)
        cs = self.fmi_type == "CoSimulation"
        r = self.simulate(rod, state, floor=floor, stop_time=horizon(case) * T, relative_tolerance=rtol,
                          output_interval=(case.epsilon / 2 if cs else 5 * case.epsilon) * T,
                          output=list(STATES) + ["mode", "contact"])
        return outcome_of_trajectory(case, si.to_paper(rod, r, floor), exact_events=not cs)


class _Recorder:
    """The outputs read from the instance at each sample, as fmpy's structured array."""
    TYPES = {"Real": float, "Integer": np.int32, "Boolean": np.bool_}

    def __init__(self, instance, md, names):
        variables = {v.name: v for v in md.modelVariables}
        self.instance, self.names, self.rows = instance, names, []
        self.groups = {}     # type -> [(column, vr)]
        for i, name in enumerate(names):
            v = variables[name]
            self.groups.setdefault(v.type, []).append((i, v.valueReference))
        self.dtype = [("time", float)] + [(n, self.TYPES[variables[n].type]) for n in names]

    def sample(self, t):
        row = [0] * len(self.names)
        getters = {"Real": self.instance.getReal, "Integer": self.instance.getInteger,
                   "Boolean": self.instance.getBoolean}
        for kind, columns in self.groups.items():
            for (i, _), value in zip(columns, getters[kind]([vr for _, vr in columns])):
                row[i] = value
        self.rows.append((t, *row))

    def result(self):
        return np.array(self.rows, dtype=self.dtype)
