# SPDX-License-Identifier: BSD-2-Clause
"""TwoLinkArm as an FMI 3.0 FMU (build/fmi3/TwoLinkArm.fmu): the same core and instance as its FMI
2.0 FMU under FMI 3.0's layer, its model description made from the FMI 2.0 one
(cmake/fmi3_model_description.py). As test_fmi3_coupled_models.py does for PainleveRodSI and
ShakerTable: the variables and token are the FMI 2.0 FMU's, runs agree with it to round-off,
fmi-sim (a second importer) runs it as fmpy does; and, the arm having no partial derivatives,
the capability flags say so and the calls are errors."""
import fmpy
import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi3 import FMU3Model

from helpers.fmi_sim import fmi3_fmu_fmi_sim_can_read, run_fmi_sim
from helpers.fmi_versions import assert_same_variables_and_token

STATES = ("theta1", "theta2", "omega1", "omega2")
OUTPUTS = STATES + ("x", "y", "v", "w", "F_N", "F_T", "energy", "p_plus", "a")


def test_the_variables_token_and_capabilities_are_the_fmi2_fmus(arm_path, arm3_path):
    md2, md3 = assert_same_variables_and_token(arm_path, arm3_path)
    assert len(md3.eventIndicators) == md2.numberOfEventIndicators == 4
    time = next(v for v in md3.modelVariables if v.causality == "independent")
    assert (time.name, time.unit) == ("time", "s")
    for interface in (md2.modelExchange, md2.coSimulation, md3.modelExchange, md3.coSimulation):
        assert interface.providesDirectionalDerivative is False   # fmpy's name for both versions' flag


@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
def test_fmi3_runs_as_the_fmi2_fmu_does(arm_path, arm3_path, fmi_type):
    kw = dict(fmi_type=fmi_type, stop_time=0.05, output_interval=1e-4, output=list(OUTPUTS))
    if fmi_type == "ModelExchange":
        kw.update(solver="Euler", step_size=1e-6)
    two, three = fmpy.simulate_fmu(arm_path, **kw), fmpy.simulate_fmu(arm3_path, **kw)
    assert len(two) == len(three)
    for name in OUTPUTS:
        scale = 1 + float(np.max(np.abs(two[name])))
        np.testing.assert_allclose(three[name], two[name], rtol=1e-12, atol=1e-12 * scale, err_msg=name)


@pytest.mark.parametrize("interface", ["CS", "ME"])
def test_fmi_sim_runs_it_as_fmpy_does(arm3_path, interface, tmp_path):
    readable = fmi3_fmu_fmi_sim_can_read(arm3_path, tmp_path, nominals=0)
    stop = float(read_model_description(arm3_path).defaultExperiment.stopTime)
    h = stop / 500 if interface == "CS" else 1e-5   # forward Euler is stable at 1e-5 s (eps = 1e-3)
    theirs = run_fmi_sim(readable, tmp_path, interface, output_interval=h)
    kw = dict(fmi_type="CoSimulation") if interface == "CS" else \
        dict(fmi_type="ModelExchange", solver="Euler", step_size=h)
    ours = fmpy.simulate_fmu(arm3_path, output_interval=h, **kw)
    assert theirs["time"][-1] == pytest.approx(stop)
    for name in STATES:
        scale = 1 + float(np.max(np.abs(ours[name])))
        assert theirs[name][-1] == pytest.approx(ours[name][-1], rel=1e-9, abs=1e-9 * scale), name


def test_directional_and_adjoint_derivatives_are_errors(arm3_path):
    md = read_model_description(arm3_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    m = FMU3Model(guid=md.guid, unzipDirectory=extract(arm3_path), modelIdentifier=md.modelExchange.modelIdentifier)
    m.instantiate()
    m.enterInitializationMode()
    m.exitInitializationMode()
    for call in (m.getDirectionalDerivative, m.getAdjointDerivative):
        with pytest.raises(Exception, match="3|[Ee]rror"):
            call([vr["der(omega1)"]], [vr["theta1"]], [1.0], 1)
    m.freeInstance()
