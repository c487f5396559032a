# SPDX-License-Identifier: BSD-2-Clause
"""PainleveRodSI and ShakerTable as FMI 3.0 FMUs (build/fmi3/NAME.fmu): the same model
cores and instance as their FMI 2.0 FMUs under FMI 3.0's layer (fmu_src/fmi/fmi3_*.c), their model
descriptions made from the FMI 2.0 ones (cmake/fmi3_model_description.py). The FMI 3.0 rod's checks
(test_fmi3.py, tests/interop/test_fmi3_importers.py) that are not its dimensionless physics, over
both: fmpy's validation, the variables, Model Exchange and Co-Simulation runs with inputs equal to
the FMI 2.0 FMU's (one core, one solver: to round-off), Event Mode, the FMU state with the step
means, directional and adjoint derivatives, the event indicators as variables, fmi-sim."""
import math
from ctypes import c_double

import fmpy
import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.fmi2 import FMU2Model
from fmpy.fmi3 import FMU3Model, FMU3Slave
from fmpy.validation import validate_fmu

from helpers.fmi_sim import fmi3_fmu_fmi_sim_can_read, run_fmi_sim
from helpers.fmi_versions import assert_same_variables_and_token

# name: (FMI 2.0 fixture, FMI 3.0 fixture, states, inputs, nominals in the model description, a step
# forward Euler is stable at over the default experiment [s])
MODELS = {
    "PainleveRodSI": ("si_fmu_path", "si_fmu3_path", ("x", "v", "y", "w", "theta", "phi"),
                      ("y_floor", "w_floor", "v_floor", "F_x", "F_y", "tau"), 0, 1e-5),
    "ShakerTable": ("table_path", "table3_path", ("position", "velocity"), ("F_N", "F_T"), 2, 1e-4),
}


def inputs_of(model, stop):
    """A load for each model over [0, stop]: the floor rising, then a belt (rod); the rod's force (table)."""
    t = np.linspace(0.0, stop, 11)
    if model == "PainleveRodSI":
        names = {"y_floor": 1e-3 * t / stop, "w_floor": np.full_like(t, 1e-3 / stop), "v_floor": 0.5 * (t > stop / 2)}
    else:
        names = {"F_N": 300.0 * (t > stop / 3), "F_T": -60.0 * (t > stop / 2)}
    signal = np.zeros(len(t), dtype=[("time", float)] + [(n, float) for n in names])
    signal["time"] = t
    for n, values in names.items():
        signal[n] = values
    return signal


@pytest.fixture(params=list(MODELS))
def pair(request):
    """(model, its FMI 2.0 FMU, its FMI 3.0 FMU)."""
    two, three = MODELS[request.param][:2]
    return request.param, request.getfixturevalue(two), request.getfixturevalue(three)


def test_fmpy_validation_finds_no_problem_and_the_interfaces_are_declared(pair):
    _, _, fmu3 = pair
    assert validate_fmu(fmu3) == []
    md = read_model_description(fmu3)
    assert md.fmiVersion == "3.0" and md.modelExchange is not None and md.coSimulation is not None
    assert md.coSimulation.hasEventMode and md.coSimulation.mightReturnEarlyFromDoStep
    time = next(v for v in md.modelVariables if v.causality == "independent")
    assert (time.name, time.unit) == ("time", "s")


def test_the_variables_units_and_the_token_are_the_fmi2_fmus(pair):
    model, fmu2, fmu3 = pair
    md2, md3 = assert_same_variables_and_token(fmu2, fmu3)
    assert {v.unit for v in md3.modelVariables if v.unit} <= {u.name for u in md3.unitDefinitions}
    assert len(md3.eventIndicators) == md2.numberOfEventIndicators == (4 if model == "PainleveRodSI" else 0)
    assert md3.defaultExperiment.stopTime == md2.defaultExperiment.stopTime


# fmpy's CVode runs the default experiment (it fails on either FMU, FMI 2.0 or 3.0, with the
# inputs' corners: mxstep, error test); forward Euler and the FMU's own CVODE run the inputs too.
@pytest.mark.parametrize("fmi_type, solver, loaded", [("ModelExchange", "CVode", False),
                                                      ("ModelExchange", "Euler", True), ("CoSimulation", None, True)])
def test_fmi3_runs_with_inputs_as_the_fmi2_fmu_does(pair, fmi_type, solver, loaded):
    # The same core, events and solver: every output agrees to round-off, and the run did move.
    model, fmu2, fmu3 = pair
    stop = float(read_model_description(fmu2).defaultExperiment.stopTime)
    kw = dict(fmi_type=fmi_type, relative_tolerance=1e-8, output_interval=stop / 500)
    if loaded:
        kw["input"] = inputs_of(model, stop)
    if solver:
        # fmpy's Euler steps from output point to output point
        kw.update(solver=solver, step_size=MODELS[model][5], output_interval=MODELS[model][5])
    r2, r3 = fmpy.simulate_fmu(fmu2, **kw), fmpy.simulate_fmu(fmu3, **kw)
    assert len(r2) == len(r3) > 500
    for name in r2.dtype.names:
        np.testing.assert_allclose(r3[name].astype(float), r2[name].astype(float), rtol=1e-12, atol=1e-15,
                                   err_msg=name)
    states = MODELS[model][2]
    assert all(np.ptp(r3[s]) > 0 for s in states)


def slave(fmu3, unzipdir, *, event_mode):
    md = read_model_description(fmu3)
    s = FMU3Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="instance")
    s.vr = {v.name: v.valueReference for v in md.modelVariables}
    s.instantiate(eventModeUsed=event_mode, earlyReturnAllowed=event_mode)
    s.enterInitializationMode(tolerance=1e-8, startTime=0.0)
    s.exitInitializationMode()
    if event_mode:
        s.updateDiscreteStates()
        s.enterStepMode()
    return s


def test_event_mode_hands_the_si_rods_mode_switches_to_the_master_and_changes_nothing(si_fmu_path, si_fmu3_path,
                                                                                        tmp_path):
    # The default IWC: compression, stick, lift-off are events a master with Event Mode handles.
    s = slave(si_fmu3_path, fmpy.extract(si_fmu3_path, tmp_path), event_mode=True)
    t, stop, events = 0.0, 0.01, 0
    while t < stop:
        handling, _, early, t = s.doStep(t, stop - t)
        if handling:
            s.enterEventMode()
            s.updateDiscreteStates()
            s.enterStepMode()
            events += 1
    names = ["w", "phi", "F_N_mean", "switches"]
    mine = s.getFloat64([s.vr[n] for n in names[:2]]) + [float(s.getInt32([s.vr["switches"]])[0])]
    s.terminate()
    s.freeInstance()
    plain = fmpy.simulate_fmu(si_fmu_path, fmi_type="CoSimulation", relative_tolerance=1e-8, stop_time=stop,
                              output_interval=stop, output=["w", "phi", "switches"])
    assert events >= 2 and mine[2] == plain["switches"][-1] >= 2
    assert mine[:2] == pytest.approx([plain["w"][-1], plain["phi"][-1]], rel=1e-7)


def test_the_fmu_state_carries_the_step_means_bit_for_bit(pair, tmp_path):
    """Step, take the state (serialized and back), step on, restore, step again: the same states and
    step means; the mean after the restore is the first step's."""
    model, _, fmu3 = pair
    s = slave(fmu3, fmpy.extract(fmu3, tmp_path), event_mode=False)
    means = [s.vr[n] for n in (("F_N_mean", "F_T_mean") if model == "PainleveRodSI"
                               else ("mount_force_mean", "drive_force_mean"))]
    watched = [s.vr[n] for n in MODELS[model][2]] + means
    s.doStep(0.0, 1e-3)
    first = s.getFloat64(means)
    assert max(abs(x) for x in first) > 0.5        # the rod's IWC (F_N_mean 850 N), the table's drive (0.78 N)
    state = s.deserializeFMUState(s.serializeFMUState(s.getFMUState()))
    s.doStep(1e-3, 1e-3)
    later = s.getFloat64(watched)
    s.setFMUState(state)
    assert s.getFloat64(means) == first
    s.doStep(1e-3, 1e-3)
    assert s.getFloat64(watched) == later
    s.freeFMUState(state)
    s.terminate()
    s.freeInstance()


def model_exchange(fmu, unzipdir, cls, start):
    md = read_model_description(fmu)
    m = cls(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.modelExchange.modelIdentifier,
            instanceName="instance")
    vr = {v.name: v.valueReference for v in md.modelVariables}
    m.instantiate()
    if cls is FMU2Model:
        m.setupExperiment(startTime=0.0)
    m.enterInitializationMode(**({"startTime": 0.0} if cls is FMU3Model else {}))
    for name, value in start.items():
        (m.setFloat64 if cls is FMU3Model else m.setReal)([vr[name]], [value])
    m.exitInitializationMode()
    if cls is FMU3Model:
        m.updateDiscreteStates()
        m.enterContinuousTimeMode()
    else:
        m.newDiscreteStates()
        m.enterContinuousTimeMode()
    return m, vr


# In contact and slipping on a floor that moves up and sideways (rod); loaded (table).
ME_START = {"PainleveRodSI": dict(y=-1e-6, w=-0.01, v=0.3, y_floor=2e-7, w_floor=0.02, v_floor=-0.1, F_x=1.0, tau=0.2),
            "ShakerTable": dict(position=1e-3, velocity=0.02, F_N=200.0)}


def test_directional_derivatives_are_the_fmi2_fmus_and_adjoints_their_transpose(pair, tmp_path):
    model, fmu2, fmu3 = pair
    states, inputs = MODELS[model][2], MODELS[model][3]
    m3, vr = model_exchange(fmu3, fmpy.extract(fmu3, tmp_path / "3"), FMU3Model, ME_START[model])
    m2, _ = model_exchange(fmu2, fmpy.extract(fmu2, tmp_path / "2"), FMU2Model, ME_START[model])
    md = read_model_description(fmu3)
    unknowns = [u.variable.valueReference for u in md.derivatives + md.outputs
                if u.variable.variability == "continuous"]
    knowns = [vr[n] for n in states + inputs]
    seeds = np.eye(len(knowns))
    J3 = np.array([m3.getDirectionalDerivative(unknowns, knowns, list(seeds[j])) for j in range(len(knowns))]).T
    J2 = np.array([m2.getDirectionalDerivative(unknowns, knowns, list(seeds[j])) for j in range(len(knowns))]).T
    # (fmpy 0.3.32 sizes the sensitivity by the unknowns unless told: nSensitivity)
    JT = np.array([m3.getAdjointDerivative(unknowns, knowns, list(np.eye(len(unknowns))[i]), len(knowns))
                   for i in range(len(unknowns))])
    np.testing.assert_array_equal(J3, J2)
    np.testing.assert_array_equal(JT, J3)
    # the physics' largest entry: the contact's stiffness k = 2e7 N/m over m = 1 kg; K/M = 4e3 1/s^2
    assert np.abs(J3).max() >= (2e7 if model == "PainleveRodSI" else 4e3)
    m3.freeInstance()
    m2.freeInstance()


def test_the_si_rods_event_indicators_are_variables_in_the_floors_frame(si_fmu3_path, tmp_path):
    """In contact and slipping: indicator_y = (y - y_floor)/l, indicator_slip = (v - v_floor)/sqrt(g l)
    (cmake/fmi3_model_description.py's descriptions; l = 0.5 m, g = 9.81 m/s^2); the variables are
    fmi3GetEventIndicators' values."""
    s = ME_START["PainleveRodSI"]
    m, vr = model_exchange(si_fmu3_path, fmpy.extract(si_fmu3_path, tmp_path), FMU3Model, s)
    names = ["indicator_y", "indicator_g", "indicator_slip", "indicator_aux"]
    values = m.getFloat64([vr[n] for n in names])
    z = (c_double * 4)()
    m.getEventIndicators(z, 4)
    assert values == list(z)
    assert values[0] == pytest.approx((s["y"] - s["y_floor"]) / 0.5, rel=1e-12)
    assert values[2] == pytest.approx((s["v"] - s["v_floor"]) / math.sqrt(9.81 * 0.5), rel=1e-12)
    assert values[1] > 0                          # the compliant force pushes: the end is below the floor
    m.freeInstance()


@pytest.mark.parametrize("interface", ["CS", "ME"])
def test_fmi_sim_runs_them_as_fmpy_does(pair, interface, tmp_path):
    # fmi-sim: one fmi3DoStep per output interval (the FMU's CVODE), or forward Euler at that step
    # (fmpy's Euler, the same method): the same numbers to the masters' ulps of t.
    model, _, fmu3 = pair
    readable = fmi3_fmu_fmi_sim_can_read(fmu3, tmp_path, nominals=MODELS[model][4])
    stop = float(read_model_description(fmu3).defaultExperiment.stopTime)
    h = stop / 500 if interface == "CS" else MODELS[model][5]
    theirs = run_fmi_sim(readable, tmp_path, interface, output_interval=h)
    kw = dict(fmi_type="CoSimulation") if interface == "CS" else \
        dict(fmi_type="ModelExchange", solver="Euler", step_size=h)
    ours = fmpy.simulate_fmu(fmu3, output_interval=h, **kw)
    assert theirs["time"][-1] == pytest.approx(stop)
    for name in MODELS[model][2]:
        scale = 1 + float(np.max(np.abs(ours[name])))
        assert theirs[name][-1] == pytest.approx(ours[name][-1], rel=1e-9, abs=1e-9 * scale), name
