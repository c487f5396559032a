# SPDX-License-Identifier: BSD-2-Clause
"""ShakerTable.fmu's FMI side (its physics: test_shaker_table.py): fmpy's validation, the
variable list of config.h against the model description, the documentation's units, the
source FMU built by a tool, an input set by a master between its steps, analytic directional
derivatives against central differences with exactly the dependencies the ModelStructure
declares, NaN and infinite inputs refused naming the input, the FMU state (inputs included)
restored and serialized."""
import re
import zipfile
from ctypes import POINTER, c_double

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from conftest import ROOT
from helpers.shaker_table import DEFAULTS, INTERFACES, START, closed_form, piecewise_closed_form

_P = POINTER(c_double)


@pytest.fixture(scope="module")
def table(table_path):
    """The FMU extracted once by the harness; raw fmpy instances from .instantiate."""
    from painleve.fmu.experiment import Experiment
    with Experiment(table_path) as experiment:
        yield experiment


# ------------------------------------------------------------------ the FMU as a file
def test_fmpy_validation_finds_no_problem(table_path):
    assert validate_fmu(table_path) == []


def test_config_h_lists_the_variables_of_the_model_description(table_path):
    """Value references, names, causalities and ranges: config.h's list is the model
    description's, in its order (the C side's value references are the list's indices)."""
    text = (ROOT / "fmu_src" / "models" / "ShakerTable" / "config.h").read_text()
    bounds = dict(FORCE_BOUND=1e9, STATE_BOUND=1e6)

    def number(s):
        s = s.strip()
        return -bounds[s[1:]] if s.startswith("-") and s[1:] in bounds else bounds.get(s, None) or float(s)
    rows = re.findall(r'VARIABLE\((\w+), "([^"]+)", REAL, (\w+), [^,]+, ([^,]+), ([^)]+)\)', text)
    md = read_model_description(table_path)
    assert [name for _, name, *_ in rows] == [v.name for v in md.modelVariables]
    causality = dict(PARAMETER="parameter", INPUT="input", STATE="output")
    for vr, ((_, name, kind, lo, hi), v) in enumerate(zip(rows, md.modelVariables)):
        assert v.valueReference == vr, name
        assert v.type == "Real" and v.description, name
        if kind in causality:
            assert v.causality == causality[kind], name
            assert (float(v.min), float(v.max)) == (number(lo), number(hi)), name
        else:
            assert v.causality in ("output", "local") and v.initial == "calculated", name
    units = {v.name: v.unit for v in md.modelVariables}
    assert units == dict(M="kg", K="N/m", C="N.s/m", F0="N", frequency="Hz", belt_speed="m/s", F_N="N",
                              F_T="N", position="m", velocity="m/s", **{"der(position)": "m/s"},
                              **{"der(velocity)": "m/s2"}, belt_velocity="m/s", drive_force="N", energy="J",
                              belt_power="W", mount_force="N", mount_force_mean="N", drive_force_mean="N")
    assert md.numberOfEventIndicators == 0 and len(md.derivatives) == 2


def test_the_documentation_lists_every_variable_with_its_unit_in_si(table_path):
    md = read_model_description(table_path)
    with zipfile.ZipFile(table_path) as z:
        page = z.read("documentation/index.html").decode()
    for v in md.modelVariables:
        assert f"<td>{v.name}</td>" in page and f"<td>{v.unit}</td>" in page, v.name
    assert "SI units" in page and "Dimensionless" not in page and "Hogan" not in page


@pytest.mark.parametrize("fmi_type", INTERFACES)
def test_a_tool_builds_the_source_fmu_from_its_source_files(table_path, tmp_path, fmi_type):
    """<SourceFiles> and sources/ are complete: fmpy compiles them (with the README's CVODE
    options) into a binary that simulates like the CMake build."""
    from helpers.source_build import source_build, with_cvode
    unzipped = source_build(table_path, tmp_path, with_cvode(), bundled=False)
    a, b = (simulate_fmu(f, fmi_type=fmi_type, start_values=dict(F_N=30.0), output=["position", "velocity"])
            for f in (table_path, unzipped))
    for name in ("position", "velocity"):
        np.testing.assert_allclose(b[name], a[name], rtol=1e-9, atol=1e-12 * np.abs(a[name]).max(), err_msg=name)
    z, _ = closed_form(b["time"], F_N=30.0, **DEFAULTS)
    assert np.abs(b["position"] - z).max() < 1e-4 * np.abs(z).max()


# ------------------------------------------------------------------ FMI: inputs, derivatives, state
def test_cs_input_set_mid_step_sequence_restarts_from_the_current_state(table):
    """A master that sets F_N between its own steps of 0.1 s (no input event of fmpy's)."""
    slave = table.instantiate(fmi_type="CoSimulation", instance_name="table")
    vr = table.vr
    slave.setupExperiment(tolerance=1e-8, startTime=0.0)
    slave.enterInitializationMode()
    slave.setReal([vr["position"], vr["velocity"]], [START["position"], START["velocity"]])
    slave.exitInitializationMode()
    loads = {0.0: 0.0, 0.3: 300.0, 0.6: 0.0, 1.2: -100.0}
    t, rows = 0.0, []
    for k in range(20):
        t = round(0.1 * k, 10)
        if t in loads:
            slave.setReal([vr["F_N"]], [loads[t]])
        slave.doStep(t, 0.1)
        rows.append((round(t + 0.1, 10), *slave.getReal([vr["position"], vr["velocity"]])))
    slave.terminate()
    slave.freeInstance()
    times, zs, vs = np.array(rows).T
    z, v = piecewise_closed_form(times, sorted(loads.items()), z0=START["position"], v0=START["velocity"], **DEFAULTS)
    assert np.abs(zs - z).max() < 2e-6 * np.abs(z).max()
    assert np.abs(vs - v).max() < 2e-6 * np.abs(v).max()


@pytest.mark.parametrize("fmi_type", INTERFACES)
@pytest.mark.parametrize("name, value, when", [("F_N", float("nan"), "initialization"), ("F_T", float("inf"), "step"),
                                               ("F_N", float("-inf"), "step"), ("F_T", float("nan"), "step")])
def test_a_bad_input_is_an_error_naming_it(table, fmi_type, name, value, when):
    messages = []
    fmu = table.instantiate(fmi_type=fmi_type, instance_name="table", on_message=lambda *m: messages.append(m))
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    if when == "step":
        fmu.setReal([table.vr[name]], [12.5])    # a good value is taken, in every mode the standard allows
        fmu.exitInitializationMode()
        if fmi_type == "ModelExchange":
            fmu.newDiscreteStates()
            fmu.enterContinuousTimeMode()
        else:
            fmu.doStep(0.0, 0.01)
        fmu.setReal([table.vr[name]], [-3.0])
    with pytest.raises(FMICallException):
        fmu.setReal([table.vr[name]], [value])
    assert messages[-1][0] == 3 and f"{name} = {value:g} must be finite" in messages[-1][2], messages[-1]
    fmu.freeInstance()


def test_no_event_indicators_is_an_empty_array_and_any_other_size_is_an_error(table):
    messages = []
    fmu = table.instantiate(instance_name="table", on_message=lambda *m: messages.append(m))
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.newDiscreteStates()
    fmu.enterContinuousTimeMode()
    fmu.getEventIndicators(None, 0)              # an importer's empty array may be NULL
    z = np.zeros(1)
    with pytest.raises(FMICallException):
        fmu.getEventIndicators(z.ctypes.data_as(_P), 1)
    assert "size 1 given, ShakerTable has 0" in messages[-1][2]
    fmu.freeInstance()


def test_parameters_out_of_range_are_errors_naming_them(table):
    for name, value in [("M", 0.0), ("K", -1.0), ("C", -0.5), ("frequency", -2.0)]:
        messages = []
        fmu = table.instantiate(instance_name="table", on_message=lambda *m: messages.append(m))
        with pytest.raises(FMICallException):
            fmu.setReal([table.vr[name]], [value])
        assert messages[-1][2].startswith(f"fmi2SetReal: {name} = {value:g} is out of range"), messages[-1]
        fmu.freeInstance()


KNOWN_SCALES = dict(M=10.0, K=4e4, C=40.0, F0=50.0, frequency=5.0, belt_speed=1.0, F_N=100.0, F_T=100.0,
                    position=1e-3, velocity=0.05)
# A generic point: every partial that is not identically 0 is not 0 here (t0: sin, cos of W t0 not 0).
POINT = dict(M=7.0, K=3e4, C=55.0, F0=42.0, frequency=4.3, belt_speed=0.8, F_N=35.0, F_T=-12.0,
             position=1.3e-3, velocity=-0.031)
T0 = 0.37


def structure_of(md):
    return {name: {u.variable.name: {v.name for v in u.dependencies} for u in unknowns}
            for name, unknowns in dict(Outputs=md.outputs, Derivatives=md.derivatives,
                                       InitialUnknowns=md.initialUnknowns).items()}


def jacobian_check(fmu, vr, unknowns, knowns, set_known):
    """(directional derivatives, central differences), columns scaled by the knowns' scales."""
    def values():
        return np.array(fmu.getReal([vr[u] for u in unknowns]))
    D = np.column_stack([fmu.getDirectionalDerivative([vr[u] for u in unknowns], [vr[k]], [1.0]) for k in knowns])
    FD = np.zeros_like(D)
    for j, k in enumerate(knowns):
        h = 1e-6 * KNOWN_SCALES[k]
        set_known(k, POINT[k] + h)
        up = values()
        set_known(k, POINT[k] - h)
        down = values()
        set_known(k, POINT[k])
        FD[:, j] = (up - down) / (2 * h)
    return D, FD


def assert_exact(D, FD, unknowns, knowns, declared, where):
    scale = np.array([KNOWN_SCALES[k] for k in knowns])
    Ds, FDs = D * scale, FD * scale
    row = np.maximum(np.abs(FDs).max(axis=1, keepdims=True), 1e-300)
    wrong = [f"d {unknowns[i]}/d {knowns[j]}: {D[i, j]:.10g} vs {FD[i, j]:.10g}"
             for i, j in zip(*np.nonzero(np.abs(Ds - FDs) > 1e-6 * row))]
    assert not wrong, f"{where}: " + "; ".join(wrong)
    # Exactly the declared dependencies change the unknown (at a generic point).
    changes = np.abs(FDs) > 1e-9 * row
    wrong = [f"{u} on {k}: declared {k in declared.get(u, set())}, changes {changes[i, j]}"
             for i, u in enumerate(unknowns) for j, k in enumerate(knowns)
             if (k in declared.get(u, set())) != changes[i, j]]
    assert not wrong, f"{where}: " + "; ".join(wrong)


def test_directional_derivatives_in_continuous_time_mode_are_the_declared_dependencies(table):
    md = table.model_description
    structure = structure_of(md)
    vr = table.vr
    fmu = table.instantiate(instance_name="table")
    fmu.setupExperiment(startTime=T0)
    fmu.enterInitializationMode()
    fmu.setReal([vr[k] for k in POINT], list(POINT.values()))
    fmu.exitInitializationMode()
    fmu.newDiscreteStates()
    fmu.enterContinuousTimeMode()
    fmu.setTime(T0 + 0.21)     # time moves the drive, and nothing the knowns see
    unknowns = list(dict.fromkeys([*structure["Outputs"], *structure["Derivatives"]]))
    knowns = ["F_N", "F_T", "position", "velocity"]
    declared = {u: structure["Outputs"].get(u, set()) | structure["Derivatives"].get(u, set()) for u in unknowns}

    def set_known(k, value):
        if k in ("position", "velocity"):
            x = np.array(fmu.getReal([vr["position"], vr["velocity"]]))
            x[["position", "velocity"].index(k)] = value
            fmu.setContinuousStates(x.ctypes.data_as(_P), 2)
        else:
            fmu.setReal([vr[k]], [value])
    D, FD = jacobian_check(fmu, vr, unknowns, knowns, set_known)
    assert_exact(D, FD, unknowns, knowns, declared, "Continuous-Time Mode")
    # The acceleration's row by hand: -K/M, -C/M for the states, -1/M for the load, 0 for F_T.
    row = D[unknowns.index("der(velocity)")]
    assert row == pytest.approx([-1 / POINT["M"], 0, -POINT["K"] / POINT["M"], -POINT["C"] / POINT["M"]], rel=1e-14)
    fmu.freeInstance()


def test_directional_derivatives_in_initialization_mode_are_the_declared_initial_dependencies(table):
    md = table.model_description
    structure = structure_of(md)["InitialUnknowns"]
    vr = table.vr
    fmu = table.instantiate(instance_name="table")
    fmu.setupExperiment(startTime=T0)
    fmu.enterInitializationMode()
    fmu.setReal([vr[k] for k in POINT], list(POINT.values()))
    unknowns = list(structure)
    knowns = list(POINT)
    D, FD = jacobian_check(fmu, vr, unknowns, knowns, lambda k, value: fmu.setReal([vr[k]], [value]))
    assert_exact(D, FD, unknowns, knowns, structure, "Initialization Mode")
    fmu.freeInstance()


def test_fmu_state_with_its_inputs_is_restored_and_serialized(table):
    vr = table.vr
    out = [vr["position"], vr["velocity"], vr["energy"]]

    def slave():
        s = table.instantiate(fmi_type="CoSimulation", instance_name="table")
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.setReal([vr["F_N"], vr["C"]], [50.0, 70.0])
        s.exitInitializationMode()
        return s

    def run(s, t, until):
        while t < until - 1e-12:
            s.doStep(t, 0.05)
            t = round(t + 0.05, 10)
        return s.getReal(out)
    s = slave()
    run(s, 0.0, 0.3)
    state = s.getFMUstate()
    data = s.serializeFMUstate(state)
    first = run(s, 0.3, 0.6)
    s.setReal([vr["F_N"]], [900.0])        # an input changed after the state was taken ...
    s.setFMUstate(state)                   # ... is restored with it
    assert s.getReal([vr["F_N"]]) == [50.0]
    assert run(s, 0.3, 0.6) == first
    other = slave()
    restored = other.deSerializeFMUstate(data)
    other.setFMUstate(restored)
    assert other.getReal([vr["F_N"], vr["C"]]) == [50.0, 70.0]
    assert run(other, 0.3, 0.6) == first
    # And the restored run is the physics, not a copy of a wrong one.
    z, v = closed_form([0.6], F_N=50.0, **dict(DEFAULTS, C=70.0))
    assert first[:2] == pytest.approx([z[0], v[0]], rel=1e-4)
    for fmu, st in ((s, state), (other, restored)):
        fmu.freeFMUstate(st)
        fmu.freeInstance()
