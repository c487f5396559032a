# SPDX-License-Identifier: BSD-2-Clause
"""Three co-simulation masters that run an SSP archive (painleve.coupling.ssp), each returning the same
table: one row per communication point t_k = k h, k = 1 .. N (stop = N h), field "time" and
one field per recorded variable "component.variable" (an output's value at t_k; an input's
value as the FMU read it back after the step: what it held over [t_(k-1), t_k]).

- fmpy 0.3.32 (fmpy.ssp.simulation.simulate_ssp; always installed): Jacobi, zero-order hold.
  Every FMU steps from t_k with the inputs of the previous exchange, then every connection
  is copied. Before the first step its connectors hold 0.0, not the FMUs' initial outputs.
  It labels a row with the time the step started (the values are those at its end), records
  connectors only (inputs: the value just copied, for the next step), reads no
  ParameterBindings (they are passed as its parameter_set) and sums h into its time, so a
  round-off may add one step past the stop time. `run_fmpy` relabels, shifts the inputs back
  by one step and drops the extra row.
- libcosim (libcosimpy 0.0.6, PyPI; tests/importers/requirements.txt): fixed-step algorithm,
  Jacobi: all FMUs step (in parallel), then connected values are transferred. Its clock counts
  integer nanoseconds; it reads an .ssp archive (typed connectors required: "A valid connector
  type was not found!") and applies inline parameter bindings to parameters and inputs only
  (`run_libcosim` sets the states' start values). The initialization transfers initial outputs
  to inputs. Its observer reads an input as the value held in the step.
- ecos (ecospy 0.7.2, PyPI; Debian's libtbb12), the one of the three that runs FMI 3.0 FMUs
  (FMI3_MASTERS): fixed-step algorithm, Jacobi (each instance:
  set inputs, step, get outputs, in parallel; then connections). It applies a parameter set
  of the SSP by name at init (ssp.START_VALUES), states included, and transfers the initial
  outputs. It reads an input back as the value already copied for the next step; `run_ecos`
  shifts it back by one step.
"""
from __future__ import annotations

import contextlib
import io
import os
import shutil
import tempfile

import numpy as np

from .ssp import START_VALUES, parameter_set, start_values

MASTERS = ("fmpy", "libcosim", "ecos")
# The masters that run FMI 3.0 FMUs, and why each other one does not (docs/coupling.md; each a test).
FMI3_MASTERS = ("ecos",)
NO_FMI3 = {
    "fmpy": "fmpy 0.3.32's simulate_ssp instantiates every FMU that is not FMI 1.0 as an FMI 2.0 FMU2Slave "
            "(fmpy/ssp/simulation.py, instantiate_fmu), which looks for binaries/linux64",
    "libcosim": "libcosim (libcosimpy 0.0.6) imports FMI 1.0 and 2.0 only: \"Unsupported FMI version\"",
}


class MasterUnavailable(RuntimeError):
    """The master's Python package is not installed."""


def steps_of(stop_time, step):
    n = round(stop_time / step)
    if n < 1 or abs(n * step - stop_time) > 1e-9 * stop_time:
        raise ValueError(f"the stop time {stop_time!r} is not a whole number of steps {step!r}")
    return n


def _table(times, columns, names):
    out = np.zeros(len(times), dtype=[("time", float)] + [(n, float) for n in names])
    out["time"] = times
    for n in names:
        out[n] = columns[n]
    return out


def _split(name):
    comp, _, var = name.partition(".")
    return comp, var


def _inputs(ssp_path):
    """The archive's input connectors, as "component.variable"."""
    from fmpy.ssp.ssd import read_ssd
    return {f"{el.name}.{c.name}" for el in read_ssd(str(ssp_path)).system.elements
            for c in el.connectors if c.kind == "input"}


def run_fmpy(ssp_path, stop_time, step, record):
    from fmpy.ssp.simulation import simulate_ssp
    n = steps_of(stop_time, step)
    pset = parameter_set(ssp_path)
    # simulate_ssp unzips the archive and each FMU with tempfile.mkdtemp and removes them only when
    # it ends normally; the FMUs' log goes to print. Both are kept here: the unzipped files in a
    # directory of ours, removed whatever happens, the log to name an FMU's error.
    log, scratch, saved = io.StringIO(), tempfile.mkdtemp(prefix="painleve-fmpy-ssp-"), tempfile.tempdir
    try:
        tempfile.tempdir = scratch
        with contextlib.redirect_stdout(log):
            r = simulate_ssp(str(ssp_path), stop_time=stop_time, step_size=step, parameter_set=pset)
    except Exception as err:
        errors = [line for line in log.getvalue().splitlines() if line.startswith(("[ERROR]", "[FATAL]"))]
        raise RuntimeError(f"fmpy: {errors[-1].split('] ', 1)[1] if errors else err}") from None
    finally:
        tempfile.tempdir = saved
        shutil.rmtree(scratch, ignore_errors=True)
    r = r[:n]                                        # a round-off in fmpy's sum of h may add a step
    missing = [name for name in record if name not in r.dtype.names]
    if missing:
        raise KeyError(f"fmpy: {missing} are not connectors of the SSP (it records connectors only)")
    inputs = _inputs(ssp_path)
    columns = {}
    for name in record:
        values = np.asarray(r[name], dtype=float)
        # an input connector holds what was copied after the step, for the next one:
        # the value held during step k is the previous row's (0.0 in the first step)
        columns[name] = np.concatenate(([0.0], values[:-1])) if name in inputs else values
    return _table(step * np.arange(1, n + 1), columns, record)


def run_libcosim(ssp_path, stop_time, step, record):
    try:
        from libcosimpy.CosimExecution import CosimExecution
        from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
        from libcosimpy.CosimObserver import CosimObserver
        from libcosimpy._internal import get_last_error_message
    except ImportError as err:
        raise MasterUnavailable(f"libcosim: libcosimpy is not installed ({err}); "
                                f"pip install -r tests/importers/requirements.txt") from None
    log_output_level(CosimLogLevel.FATAL)        # its errors come back through get_last_error_message
    n = steps_of(stop_time, step)
    step_ns = round(step * 1e9)
    if abs(step_ns * 1e-9 - step) > 1e-12 * step:
        raise ValueError(f"libcosim counts whole nanoseconds: the step {step!r} is not one")
    try:
        execution = CosimExecution.from_ssp_file(str(ssp_path), step_ns)
    except AssertionError:
        raise RuntimeError(f"libcosim: cannot load {ssp_path}: {get_last_error_message()}") from None
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    index = {s.name.decode(): s.index for s in execution.slave_infos()}
    refs = {}
    for comp, i in index.items():
        refs[comp] = {v.name.decode(): v.reference for v in execution.slave_variables(i)}
    # libcosim 0.0.6 applies a binding to parameters and inputs only ("SSP parameter set start
    # values: Non-input causality for variable rod:theta", a warning): the start values of the
    # states (outputs with initial="exact") are set through its initial-value API.
    for comp, values in start_values(ssp_path).items():
        for var, value in values.items():
            if not execution.real_initial_value(index[comp], refs[comp][var], value):
                raise RuntimeError(f"libcosim: cannot set the start value {comp}.{var} = {value!r}")
    wanted = [(_split(name), name) for name in record]
    rows = np.zeros((n, len(record)))
    times = np.zeros(n)
    for k in range(n):
        if not execution.step():
            raise RuntimeError(f"libcosim: step {k + 1} failed: {get_last_error_message()}")
        times[k] = execution.status().current_time * 1e-9
        for j, ((comp, var), _) in enumerate(wanted):
            rows[k, j] = observer.last_real_values(index[comp], [refs[comp][var]])[0]
    del execution
    return _table(times, {name: rows[:, j] for j, (_, name) in enumerate(wanted)}, record)


@contextlib.contextmanager
def _quiet_stdout():
    """Holds back what C code prints on stdout (file descriptor 1): ecos 0.7.2 (its fmi4c) prints
    'Function "fmi3GetVersion" is not provided by this FMU.' and 'Loading FMI version 3...' for each
    FMI 3.0 FMU it loads (the FMUs export fmi3GetVersion); its errors come through get_last_error."""
    import sys
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(saved, 1)
            os.close(saved)


def run_ecos(ssp_path, stop_time, step, record):
    try:
        from ecospy import EcosLib, EcosSimulation
    except (ImportError, OSError) as err:    # OSError: libecosc.so without Debian's libtbb12
        raise MasterUnavailable(f"ecos: ecospy does not load ({err}); pip install -r "
                                f"tests/importers/requirements.txt (and apt-get install libtbb12)") from None
    EcosLib.set_log_level("off")                 # its errors come back through get_last_error
    n = steps_of(stop_time, step)
    ids = [name.replace(".", "::", 1) for name in record]
    rows = np.zeros((n, len(record)))
    times = np.zeros(n)
    # ecos unzips the archive into $TMPDIR/ecos_ssp_<uuid> and leaves it there: it gets a directory
    # of ours, removed after the run.
    scratch, saved = tempfile.mkdtemp(prefix="painleve-ecos-"), os.environ.get("TMPDIR")
    os.environ["TMPDIR"] = scratch
    try:
        try:
            with _quiet_stdout():
                sim = EcosSimulation(ssp_path=str(ssp_path), step_size=step)
        except Exception as err:
            raise RuntimeError(f"ecos: cannot load {ssp_path}: {err}") from None
        with sim:
            if not sim.init(parameter_set=START_VALUES):
                raise RuntimeError(f"ecos: init failed: {EcosLib.get_last_error()}")
            previous = [sim.get_real(i) for i in ids]      # t = 0, after the initial exchange
            for k in range(n):
                times[k] = sim.step()
                rows[k] = [sim.get_real(i) for i in ids]
            sim.terminate()
    finally:
        if saved is None:
            os.environ.pop("TMPDIR", None)
        else:
            os.environ["TMPDIR"] = saved
        shutil.rmtree(scratch, ignore_errors=True)
    columns = {name: rows[:, j] for j, name in enumerate(record)}
    # ecos reads an input back after the exchange that follows the step: the value for the next
    # step. The value held during step k is the one read after step k - 1 (after init for k = 1).
    for j, name in enumerate(record):
        if name in _inputs(ssp_path):
            columns[name] = np.concatenate(([previous[j]], rows[:-1, j]))
    return _table(times, columns, record)


RUNNERS = {"fmpy": run_fmpy, "libcosim": run_libcosim, "ecos": run_ecos}


def run(master, ssp_path, stop_time, step, record):
    """The master's run of the archive on the grid t_k = k step up to stop_time (see the module)."""
    return RUNNERS[master](ssp_path, stop_time, step, list(record))
