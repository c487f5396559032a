# SPDX-License-Identifier: BSD-2-Clause
"""Four FMI 2.0 importers independent of fmpy, each running PainleveRod.fmu's default
experiment (no start value changed) on a fixed communication grid.

Co-Simulation masters (MASTERS):
- libcosim (Open Simulation Platform, C++; PyPI libcosimpy): integer nanosecond time,
  one `step()` per communication step, outputs read by a last-value observer.
- ecos (C++; PyPI ecospy): `step()` adds the step size to its time.
- FMI4j (Kotlin over JNI; Maven Central info.laht.fmi4j) and JavaFMI (Java over JNA;
  Maven Central org.siani.javafmi): tests/importers/jvm, run by `java`.
Model Exchange: FMI4j's instance under a forward Euler master written like fmpy's
(run_fmi4j_euler; FMI4j ships no integrator).

`bash run.sh test` installs them (tests/importers/requirements.txt, Debian's libtbb12
for ecos, tests/importers/jvm/pom.xml). Each runner returns a structured array with
fmpy's field names: time, the states, F_N, F_T, energy, mode, contact, one row per
communication point (Euler: per step) from t = 0 (libcosim: from the first step's end,
it initializes the FMU inside that step).
"""
import subprocess
import tempfile

import fmpy
import numpy as np

from conftest import ROOT

JVM = ROOT / "tests" / "importers" / "jvm" / "target"
REALS = ("x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "energy")
FIELDS = ("time",) + REALS + ("mode", "contact")


def _table(rows):
    result = np.zeros(len(rows), dtype=[(name, float) for name in FIELDS])
    for k, name in enumerate(FIELDS):
        result[name] = [row[k] for row in rows]
    return result


def _value_references(fmu_path):
    md = fmpy.read_model_description(fmu_path)
    return {v.name: v.valueReference for v in md.modelVariables}


def run_libcosim(fmu_path, stop_time, steps):
    from libcosimpy.CosimEnums import CosimExecutionState
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.WARNING)
    vr = _value_references(fmu_path)
    step_ns = round(stop_time * 1e9 / steps)               # libcosim's clock counts nanoseconds
    assert step_ns * steps == round(stop_time * 1e9), "the grid must be whole nanoseconds"
    execution = CosimExecution.from_step_size(step_ns)
    rod = execution.add_local_slave(CosimLocalSlave(fmu_path=str(fmu_path), instance_name="rod"))
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    rows = []
    for i in range(1, steps + 1):   # libcosim initializes the FMU inside its first step: rows from t = h
        if not execution.step():
            raise RuntimeError(f"libcosim: step {i} failed, execution {execution.status()}")
        status = execution.status()
        assert CosimExecutionState(status.state) != CosimExecutionState.ERROR, status
        reals = observer.last_real_values(rod, [vr[name] for name in REALS])
        mode, = observer.last_integer_values(rod, [vr["mode"]])
        contact, = observer.last_boolean_values(rod, [vr["contact"]])
        rows.append((status.current_time * 1e-9, *reals, mode, contact))
    return _table(rows)


def run_ecos(fmu_path, stop_time, steps):
    from ecospy import EcosLib, EcosSimulation, EcosSimulationStructure

    EcosLib.set_log_level("warn")
    structure = EcosSimulationStructure()
    structure.add_model("rod", str(fmu_path))
    rows = []
    with EcosSimulation(structure=structure, step_size=stop_time / steps) as sim:
        if not sim.init():
            raise RuntimeError(f"ecos: init failed: {EcosLib.get_last_error()}")
        for i in range(steps + 1):
            t = sim.step() if i > 0 else sim.get_time()
            rows.append((t, *(sim.get_real(f"rod::{name}") for name in REALS),
                         sim.get_integer("rod::mode"), sim.get_bool("rod::contact")))
        sim.terminate()
    return _table(rows)


def _java(main_class, *args):
    """Runs a class of tests/importers/jvm; its CSV output as a table."""
    classes, jars = JVM / "classes", JVM / "dependency"
    if not (classes / "painleve" / "importers" / f"{main_class}.class").exists():
        raise FileNotFoundError(f"{classes} is missing: `bash run.sh test` builds tests/importers/jvm")
    # JavaFMI 2.24.3 calls java.util.prefs' private chmod through reflection (to make the
    # unpacked binary executable); JDK 17 allows that only when the package is opened.
    # Both importers unpack (the FMU, FMI4j its JNI library) into java.io.tmpdir and leave it there.
    with tempfile.TemporaryDirectory(prefix="jvm-importer-") as scratch:
        cmd = ["java", "--add-opens", "java.prefs/java.util.prefs=ALL-UNNAMED", f"-Djava.io.tmpdir={scratch}",
               "-cp", f"{classes}:{jars}/*", f"painleve.importers.{main_class}", *map(str, args)]
        done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({done.returncode}): {done.stderr[-2000:]}")
    table = np.genfromtxt(done.stdout.splitlines(), delimiter=",", names=True)
    assert table.dtype.names == FIELDS, table.dtype.names
    return _table([tuple(row) for row in table])


def run_jvm(importer, fmu_path, stop_time, steps):
    """importer: 'fmi4j' or 'javafmi' (tests/importers/jvm/src/.../CoSimulate.java)."""
    return _java("CoSimulate", importer, fmu_path, repr(stop_time), steps)


def run_fmi4j_euler(fmu_path, stop_time, steps):
    """Model Exchange: FMI4j's instance, forward Euler with h = stop_time/steps (ModelExchangeEuler.java)."""
    return _java("ModelExchangeEuler", fmu_path, repr(stop_time), steps)


MASTERS = {
    "libcosim": run_libcosim,
    "ecos": run_ecos,
    "fmi4j": lambda *a: run_jvm("fmi4j", *a),
    "javafmi": lambda *a: run_jvm("javafmi", *a),
}
