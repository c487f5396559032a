# SPDX-License-Identifier: BSD-2-Clause
"""The SI rod's inputs through fmpy's low-level API (FMU2Model, FMU2Slave): a NaN or an
infinite input is refused with fmi2Error and a message naming the input, in
every state in which inputs may be set; a finite one is taken."""
import math

import pytest
from fmpy.fmi1 import FMICallException

from painleve.coupling.si_experiment import INPUTS, SIExperiment

FMI2_ERROR = 3


@pytest.fixture(scope="module")
def loaded(si_fmu_path):
    with SIExperiment(si_fmu_path) as ex:
        yield ex


def instance_in(loaded, fmi_type, state):
    """A raw instance brought to `state` ('instantiated', 'initialization', 'continuous-time',
    'event' for Model Exchange; 'step' for Co-Simulation), and its log."""
    messages = []
    fmu = loaded.instantiate(fmi_type=fmi_type, logging_on=True, on_message=lambda *m: messages.append(m))
    if state != "instantiated":
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
    if state in ("continuous-time", "event", "step"):
        fmu.exitInitializationMode()
        if fmi_type == "ModelExchange":
            while fmu.newDiscreteStates()[0]:
                pass
            fmu.enterContinuousTimeMode()
            if state == "event":
                fmu.enterEventMode()
        else:
            fmu.doStep(0.0, 1e-4)
    return fmu, messages


STATES = [("ModelExchange", s) for s in ("instantiated", "initialization", "continuous-time", "event")] + \
         [("CoSimulation", s) for s in ("instantiated", "initialization", "step")]


@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
@pytest.mark.parametrize("name", INPUTS)
@pytest.mark.parametrize("fmi_type, state", STATES)
def test_a_non_finite_input_is_an_error_that_names_it(loaded, fmi_type, state, name, value):
    fmu, messages = instance_in(loaded, fmi_type, state)
    try:
        with pytest.raises(FMICallException) as refused:
            fmu.setReal([loaded.vr[name]], [value])
        assert refused.value.status == FMI2_ERROR
        errors = [m for status, _, m in messages if status == FMI2_ERROR]
        assert errors and any(name in m for m in errors), messages
    finally:
        fmu.freeInstance()


@pytest.mark.parametrize("fmi_type, state", STATES)
def test_a_finite_input_is_taken(loaded, fmi_type, state):
    fmu, messages = instance_in(loaded, fmi_type, state)
    try:
        values = [0.01, -0.2, 1.5, 2.0, -3.0, 0.4]
        fmu.setReal([loaded.vr[n] for n in INPUTS], values)
        if state != "instantiated":      # FMI 2.0 has no fmi2GetReal before initialization
            assert list(fmu.getReal([loaded.vr[n] for n in INPUTS])) == values
        assert not [m for status, _, m in messages if status >= FMI2_ERROR]
    finally:
        fmu.freeInstance()


def test_in_co_simulation_the_floor_moves_on_at_w_floor_between_the_sets_of_y_floor(loaded):
    """After a step of h with y_floor = 0 set at t = 0 and w_floor = W, the floor is at W h (the
    first-order hold of docs/si_model.md), so gap = y - W h; d gap/d w_floor is -h, the time the
    floor has moved; a new y_floor puts the floor there (d gap/d w_floor back to 0)."""
    W, h = 0.3, 2e-4
    fmu = loaded.instantiate(fmi_type="CoSimulation")
    try:
        vr = loaded.vr
        fmu.setupExperiment(startTime=0.0)
        fmu.setReal([vr["y"], vr["w"]], [0.05, 0.0])                # in flight, far above the floor
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        fmu.setReal([vr["y_floor"], vr["w_floor"]], [0.0, W])
        fmu.doStep(0.0, h)
        y, gap = fmu.getReal([vr["y"], vr["gap"]])
        assert gap == pytest.approx(y - W * h, rel=0, abs=1e-15)
        d = fmu.getDirectionalDerivative([vr["gap"]], [vr["w_floor"]], [1.0])[0]
        assert d == pytest.approx(-h, rel=1e-12)
        fmu.setReal([vr["y_floor"]], [W * h])                        # the master's new floor
        assert fmu.getReal([vr["gap"]])[0] == pytest.approx(y - W * h, rel=0, abs=1e-15)
        assert fmu.getDirectionalDerivative([vr["gap"]], [vr["w_floor"]], [1.0])[0] == 0
    finally:
        fmu.freeInstance()
