# SPDX-License-Identifier: BSD-2-Clause
"""The one way the harness loads PainleveRod.fmu and runs it, on fmpy 0.3.32.

An `Experiment` extracts the FMU and instantiates it once, then runs any
number of cases on that instance with fmi2Reset between them (fmpy's fast
loop). It speaks fmpy's vocabulary: `fmi_type="ModelExchange"` or
`"CoSimulation"`, `solver`, `relative_tolerance`, structured arrays.

- `run(case)` reduces an IWC case (experiment `Case`: it starts on the floor,
  y = 0, w = eps * w10, docs/model.md §3, and ends when the rod, having touched
  the floor, is back at y = 0 moving up) to its `Outcome`, through the fast
  loop of its interface: me_fast_loop (fmpy's CVode from event to event, the
  return exact) or cs_fast_loop (fmi2DoStep, the phases from the FMU's log).
- `simulate(case)` is fmpy's simulate_fmu on the same instance: the
  trajectory, events recorded (two rows each, the exact event state).
- `simulate_from(start_values, ...)` is a free Model Exchange run from any
  state (the figures' rods outside the theorems' hypotheses).
- `instantiate(...)` gives a raw fmpy instance (FMU2Model / FMU2Slave) of the
  extracted FMU, with its own logger, to code that drives each FMI call itself;
  for an FMI 3.0 FMU (the version is read from its model description) the
  FMU3Model / FMU3Slave under the FMI 2.0 calls the harness makes (fmi3_adapter).

What it chooses for the user: CVode's absolute tolerance is the relative one
times each state's nominal (the FMU reports y ~ eps^2, w ~ eps: one tolerance
fits every stiffness), and the relative tolerance defaults to min(1e-6, eps/100)
through either interface, so the solver's error stays below the theorem's
O(eps ln 1/eps). Euler (through simulate_fmu) steps once per output interval.
"""
import contextlib
import functools
import importlib.resources
import shutil
import tempfile

import numpy as np
from fmpy import calloc, extract, free, read_model_description, simulate_fmu
from fmpy.fmi2 import (FMU2Model, FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

from ..experiments.case import Case, horizon
from ..experiments import interrupt
from ..experiments.outcome import SimulationError, back_on_floor, outcome_of_trajectory
from . import fmi3_adapter
from .cs_calls import DirectCalls, WrapperCalls, contact_and_mode
from .cs_fast_loop import READ, run_co_simulation
from .me_fast_loop import run_model_exchange


def bundled(name):
    """The FMU `name` that a pip install of the package carries (CMake builds it into the wheel). Through
    the package's resources, so that an editable install (its FMU in site-packages, its code here) finds it."""
    return importlib.resources.files("painleve").joinpath(name)


BUNDLED_FMU = bundled("PainleveRod.fmu")
# fmpy's fmi_type by the short name `painleve --interface` and the validation report use.
FMI_TYPES = {"ME": "ModelExchange", "CS": "CoSimulation"}
STATES = ("x", "v", "y", "w", "theta", "phi")     # the FMU's continuous states, in its order
OUTPUTS = STATES + ("mode", "contact")
FMI2_ERROR = 3


class FmuLoadError(RuntimeError):
    """The FMU cannot be loaded or instantiated here (its binary does not load, it refuses to
    instantiate: a GUID that does not match its binary, ...); the message says which."""


def default_fmu(name="PainleveRod.fmu"):
    """The FMU `name` installed with the package, if this installation has one."""
    installed = bundled(name)
    if not installed.exists():
        raise FileNotFoundError(f"no FMU given and none installed at {installed}: `pip install` the "
                                f"repository (it builds {name}), or give the path of one")
    return str(installed)


class Experiment:
    """One extracted FMU and one instance, reset between runs (fmpy's fast loop), so a
    study of thousands of runs pays the unzip and the load once."""

    def __init__(self, fmu_path=None, *, fmi_type="ModelExchange", solver="CVode", relative_tolerance=None,
                 steps_per_epsilon=100, tmp_dir=None, direct_calls=True):
        if fmi_type not in FMI_TYPES.values():
            raise ValueError(f"fmi_type must be 'ModelExchange' or 'CoSimulation', not {fmi_type!r}")
        if solver not in ("CVode", "Euler"):
            raise ValueError(f"solver must be 'CVode' or 'Euler', not {solver!r}")
        self.fmu_path = str(fmu_path) if fmu_path is not None else default_fmu()
        self.fmi_type, self.solver = fmi_type, solver
        self.relative_tolerance, self.steps_per_epsilon = relative_tolerance, steps_per_epsilon
        self.direct_calls = direct_calls    # Co-Simulation's calls straight into an FMI 2.0 FMU (cs_calls)
        self.model_description = read_model_description(self.fmu_path)
        self.vr = {v.name: v.valueReference for v in self.model_description.modelVariables}
        self.messages = []      # the current run's log messages (status, category, message)
        self.solver_stats = {}  # the last Model Exchange fast loop's dict(nfev, nsteps)
        self._used = False
        self.instance = None
        # The extracted FMU lives in a painleve-* directory that close() removes; until __init__
        # has returned nobody can call close(), so a failure here removes it itself.
        self._tmp = tempfile.mkdtemp(prefix="painleve-", dir=tmp_dir)
        try:
            self.unzipdir = extract(self.fmu_path, self._tmp)
            try:
                self.instance = self.instantiate(on_message=lambda *m: self.messages.append(m))
            except Exception as err:    # fmpy: "Failed to load shared library ...", "Failed to instantiate model"
                text = " ".join(str(err).replace(str(self.unzipdir), "<FMU>").split())
                if isinstance(err, OSError) or "shared library" in text:
                    raise FmuLoadError(f"its binary does not load here ({text})") from err
                said = [m for status, _, m in self.messages if status >= FMI2_ERROR]
                raise FmuLoadError(f"the FMU refused to instantiate ({said[0] if said else text})") from err
        except BaseException:
            shutil.rmtree(self._tmp, ignore_errors=True)
            raise

    def instantiate(self, *, fmi_type=None, instance_name="PainleveRod", guid=None, logging_on=False,
                    on_message=None):
        """A new instance (fmpy's FMU2Model or FMU2Slave, instantiated) of the extracted FMU that calls
        on_message(status, category, message) for each log message. Each instance gets its own Python
        logger: fmpy's native logger proxy keeps one for the whole process, so the last instance created
        would receive every instance's messages. (The FMU formats its messages itself: '%%' is a '%'.)"""
        fmi_type = fmi_type or self.fmi_type
        md = self.model_description
        kind = md.modelExchange if fmi_type == "ModelExchange" else md.coSimulation
        if kind is None:
            raise ValueError(f"this FMU does not declare {fmi_type}")
        if md.fmiVersion.startswith("3."):
            return fmi3_adapter.instantiate(self.unzipdir, md, fmi_type, guid=guid, instance_name=instance_name,
                                            logging_on=logging_on, on_message=on_message)

        def logger(env, name, status, category, message):
            if on_message:
                on_message(status, category.decode(), message.decode(errors="replace").replace("%%", "%"))

        callbacks = fmi2CallbackFunctions()
        callbacks.logger = fmi2CallbackLoggerTYPE(logger)
        callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        cls = FMU2Model if fmi_type == "ModelExchange" else FMU2Slave
        instance = cls(guid=guid or md.guid, unzipDirectory=self.unzipdir, modelIdentifier=kind.modelIdentifier,
                       instanceName=instance_name)
        instance.instantiate(callbacks=callbacks, loggingOn=logging_on)
        return instance

    @functools.cached_property
    def cs_calls(self):
        """The Co-Simulation fast loop's FMI calls on the instance (cs_calls): straight into an FMI 2.0
        FMU's C functions if `direct_calls`, else (and for FMI 3.0) through fmpy's wrappers."""
        direct = self.direct_calls and isinstance(self.instance, FMU2Slave)
        return (DirectCalls if direct else WrapperCalls)(self.instance, self.vr, READ)

    def close(self):
        self.__dict__.pop("cs_calls", None)     # its C functions' component goes with the instance
        try:
            if self.instance is not None:
                self.instance.freeInstance()
                self.instance = None
        finally:
            shutil.rmtree(self._tmp, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @contextlib.contextmanager
    def fresh_run(self, what, calls=None):
        """The instance reset (through `calls`, if given) for a new run (after the first); a failure
        inside raises SimulationError naming `what` and quoting the FMU's first error message (the
        cause: after it the instance is in its Error state and refuses what follows)."""
        interrupt.check()
        if self._used:
            (calls or self.instance).reset()
        self._used = True
        self.messages.clear()
        try:
            yield self.instance
            interrupt.check()       # a Ctrl-C held back in a CVode callback stops here
        except Exception as err:
            interrupt.check()       # a failure that a dropped Ctrl-C caused is the Ctrl-C
            errors = [message for status, _, message in self.messages if status >= FMI2_ERROR]
            raise SimulationError(f"{what}: the FMU stopped: {errors[0] if errors else err}") from err

    def read(self, names):
        """{name: value} of Real variables of the instance."""
        return dict(zip(names, self.instance.getReal([self.vr[k] for k in names])))

    def contact_and_mode(self):
        return contact_and_mode(self.instance, self.vr)

    def settings(self, case, prediction=None):
        """fmpy's solver settings for one case: relative_tolerance (or Euler's step_size),
        output_interval and stop_time (`prediction`: predict(case), if known)."""
        stop_time = horizon(case, prediction)     # the run stops itself at the return
        if self.fmi_type == "CoSimulation" or self.solver == "CVode":
            rtol = self.relative_tolerance or min(1e-6, case.epsilon / 100)
            # Through ME the events are recorded exactly and the grid only decides when the
            # run sees the return: 5 eps costs a third less than eps/2 (fmpy's per-point
            # work), same w to 1e-8. Through CS the points are all the master sees: eps/2.
            interval = case.epsilon / 2 if self.fmi_type == "CoSimulation" else 5 * case.epsilon
            return dict(relative_tolerance=rtol, output_interval=interval, stop_time=stop_time)
        h = case.epsilon / self.steps_per_epsilon
        return dict(step_size=h, output_interval=h, stop_time=stop_time)

    def _simulate(self, what, **kwargs):
        with self.fresh_run(what):
            fmu = getattr(self.instance, "fmu", self.instance)       # fmpy takes an FMI 3.0 instance as it is
            return simulate_fmu(self.unzipdir, model_description=self.model_description, fmu_instance=fmu,
                                fmi_type=self.fmi_type, record_events=True, validate=False, **kwargs)

    def simulate(self, case):
        """The trajectory of one case (fmpy's structured array), events included, up to one
        step after the return to the floor."""
        case.check()
        return self.simulate_to_return(case, case.start_values(), output=OUTPUTS, solver=self.solver,
                                       **self.settings(case))

    def simulate_to_return(self, what, start_values, *, output, **settings):
        """fmpy's simulate_fmu from `start_values` (fmpy's settings: stop_time, relative_tolerance, ...),
        events recorded, stopped one step after the run is back_on_floor, so that the state after that
        event is recorded too (with delta = 0 lift-off and the return are one event). `output` must
        hold y, contact and mode; a failure raises SimulationError naming `what`."""
        seen = {"touched": False, "back": False}

        def step_finished(time, recorder):
            if seen["back"]:
                return False
            contact = self.contact_and_mode()[0]
            seen["touched"] |= contact
            seen["back"] = back_on_floor(seen["touched"], contact, self.read(["y"])["y"])
            return True
        return self._simulate(what, start_values=dict(start_values), output=list(output), step_finished=step_finished,
                              **settings)

    def simulate_from(self, start_values, *, stop_time, output_interval=None, relative_tolerance=1e-8,
                      output=OUTPUTS, solver="CVode", step_size=None):
        """A free Model Exchange run from any start values (fmpy's simulate_fmu arguments): fmpy's
        structured array, events recorded; the FMU's own words in a SimulationError if it stops
        or returns a non-finite value."""
        what = f"run from {dict(start_values)}"
        r = self._simulate(what, start_values=dict(start_values), output=list(output), stop_time=stop_time,
                           output_interval=output_interval, relative_tolerance=relative_tolerance, solver=solver,
                           step_size=step_size)
        for name in output:
            if r[name].dtype.kind == "f" and not np.all(np.isfinite(r[name])):
                raise SimulationError(f"{what}: the FMU returned a non-finite {name}")
        return r

    def run(self, case, prediction=None):
        """One IWC case, reduced to its Outcome (`prediction`: predict(case), if known: a sweep's, made
        over its batch's arrays). (The Model Exchange fast loop drives fmpy's CVode with FMI 2.0
        calls; an FMI 3.0 FMU's Model Exchange runs are its simulate_fmu trajectories.)"""
        if self.fmi_type == "CoSimulation":
            return run_co_simulation(self, case, prediction)
        if self.solver == "CVode" and self.model_description.fmiVersion == "2.0":
            return run_model_exchange(self, case)
        return outcome_of_trajectory(case, self.simulate(case))


def run_iwc(fmu_path=None, *, fmi_type="ModelExchange", solver="CVode", relative_tolerance=None, **case):
    """One case, fmpy style: run_iwc("PainleveRod.fmu", theta0=1.0, epsilon=1e-4)."""
    with Experiment(fmu_path, fmi_type=fmi_type, solver=solver, relative_tolerance=relative_tolerance) as experiment:
        return experiment.run(Case(**case))
