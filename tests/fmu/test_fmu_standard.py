# SPDX-License-Identifier: BSD-2-Clause
"""The FMU as an FMI 2.0 component: validation, importers, source build,
the state machine, bad input, logging, independent instances."""
import shutil
import threading
from ctypes import POINTER, c_double

import fmpy
import numpy as np
import pytest
from fmpy.build import build_platform_binary
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from helpers.raw_instances import Rod
from helpers.rod_sim import OUTPUTS, phases

FMI2_ERROR = 3


def default_experiment(fmu, fmi_type="ModelExchange", **kw):
    r = fmpy.simulate_fmu(fmu, fmi_type=fmi_type, output=list(OUTPUTS), **kw)
    for name in ("x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "energy"):
        assert np.all(np.isfinite(r[name])), name
    return r


def test_fmpy_validation_finds_no_problem(fmu_path):
    assert validate_fmu(fmu_path) == []


@pytest.mark.parametrize("solver", ["CVode", "Euler"])
def test_default_experiment_shows_an_iwc_under_fmpy_solvers(fmu_path, solver):
    kw = dict(step_size=1e-5, output_interval=1e-5) if solver == "Euler" else {}
    r = default_experiment(fmu_path, solver=solver, **kw)
    seen = [ph for ph in phases(r) if ph != (True, -1)]
    assert seen[:3] == [(True, 1), (True, 0), (False, -1)]
    assert r["y"][-1] > 0 and r["w"][-1] > 0, "the run ends after the rod is back above y = 0"


def test_source_fmu_builds_and_simulates_like_the_binary(fmu_path, tmp_path):
    unzipped = fmpy.extract(fmu_path, tmp_path / "src")
    shutil.rmtree(tmp_path / "src" / "binaries")
    (tmp_path / "build").mkdir()
    build_platform_binary(unzipped, build_dir=tmp_path / "build")
    a = default_experiment(fmu_path)
    b = default_experiment(unzipped)
    for name in ("y", "w", "v", "phi"):
        np.testing.assert_allclose(b[name], a[name], rtol=1e-9, atol=1e-12)


BAD_PARAMETERS = [
    ("epsilon", 0.0), ("epsilon", -1e-3), ("epsilon", float("nan")), ("epsilon", float("inf")),
    ("delta", -0.5), ("alpha", 0.0), ("alpha", -3.0), ("mu", -0.1), ("mu", float("nan")),
    ("theta", float("-inf")),
]


@pytest.mark.parametrize("name, value", BAD_PARAMETERS)
def test_bad_value_is_an_error_naming_variable_value_and_range(loaded, name, value):
    rod = Rod(loaded)
    rod.fmu.enterInitializationMode()
    before = rod.get(name)
    with pytest.raises(FMICallException) as err:
        rod.set(**{name: value})
    assert err.value.status == FMI2_ERROR
    status, category, message = rod.messages[-1]
    assert status == FMI2_ERROR and category == "logStatusError"
    assert message.startswith(f"fmi2SetReal: {name} = ") and "allowed range is [" in message
    # Nothing was lost: in the Error state the old value still reads back, and a reset recovers the instance.
    assert rod.get(name) == before
    rod.fmu.reset()
    rod.initialize()
    rod.free()


def test_a_rejected_call_changes_nothing(loaded):
    rod = Rod(loaded)
    with pytest.raises(FMICallException):
        rod.set(delta=2.0, epsilon=-1.0)
    # The good half of the call was not applied either.
    assert rod.get("delta", "epsilon") == [1.0, 1e-3]
    rod.free()


WRONG_STATE = [
    ("fmi2GetReal", lambda rod: rod.get("y")),                    # Instantiated
    ("fmi2ExitInitializationMode", lambda rod: rod.fmu.exitInitializationMode()),
    ("fmi2NewDiscreteStates", lambda rod: rod.fmu.newDiscreteStates()),
    ("fmi2SetTime", lambda rod: rod.fmu.setTime(0.5)),
    ("fmi2Terminate", lambda rod: rod.fmu.terminate()),
]


@pytest.mark.parametrize("call, action", WRONG_STATE, ids=[c for c, _ in WRONG_STATE])
def test_call_in_the_wrong_state_is_an_error_naming_call_and_state(loaded, call, action):
    rod = Rod(loaded)
    with pytest.raises(FMICallException):
        action(rod)
    assert rod.messages[-1][2] == f"{call}: not allowed in state Instantiated"
    rod.free()


def test_parameters_cannot_change_after_initialization(loaded):
    rod = Rod(loaded)
    rod.initialize()
    with pytest.raises(FMICallException):
        rod.set(epsilon=1e-4)
    assert "epsilon can be set only before initialization ends" in rod.messages[-1][2]
    assert rod.get("epsilon") == [1e-3]
    rod.free()


@pytest.mark.parametrize("action, words", [
    (lambda rod: rod.fmu.getReal([999]), "value reference 999 is not a Real variable"),
    (lambda rod: rod.set(F_N=1.0), "F_N is calculated by the model and cannot be set"),
    # In Event Mode (FMI 2.0.4 allows no fmi2SetInteger at all in Continuous-Time Mode)
    (lambda rod: (rod.fmu.enterEventMode(), rod.fmu.setInteger([rod.vr["mode"]], [0])), "not a settable Integer variable"),
    (lambda rod: rod.fmu.setDebugLogging(True, ["logNonsense"]), "unknown log category 'logNonsense'"),
])
def test_bad_arguments_are_errors_with_a_message(loaded, action, words):
    rod = Rod(loaded)
    rod.initialize()
    with pytest.raises(FMICallException):
        action(rod)
    assert words in rod.messages[-1][2]
    rod.free()


def test_nan_continuous_state_from_an_importer_is_rejected(loaded):
    rod = Rod(loaded)
    rod.initialize()
    x = np.array([0, 1, np.nan, 0, 1, 0.5])
    with pytest.raises(FMICallException):
        rod.fmu.setContinuousStates(x.ctypes.data_as(POINTER(c_double)), 6)
    assert "y = nan must be finite" in rod.messages[-1][2]
    rod.free()


def test_wrong_guid_is_refused_with_a_message(loaded):
    with pytest.raises(Exception, match="Failed to instantiate"):
        Rod(loaded, guid="{00000000-0000-0000-0000-000000000000}")


def test_reset_restores_start_values_and_time(loaded):
    rod = Rod(loaded, logging_on=True)
    rod.initialize(start_time=5.0, epsilon=1e-4, theta=1.1)
    for _ in range(50):
        rod.euler_step(1e-6)
    rod.fmu.reset()
    rod.fmu.enterInitializationMode()
    assert rod.get("epsilon", "theta", "y", "v") == [1e-3, 1.0, 0.0, 1.0]
    rod.fmu.exitInitializationMode()
    assert rod.messages[-1][2].startswith("t = 0: initial mode")
    rod.free()


def test_events_are_logged_with_indicator_and_modes(loaded):
    rod = Rod(loaded)
    rod.fmu.setDebugLogging(True, ["logEvents"])
    rod.initialize(epsilon=1e-3)
    while rod.t < 6e-3:
        rod.euler_step(1e-5)
    events = [m for s, c, m in rod.messages if c == "logEvents"]
    assert any("indicator 'v'" in m and "mode +1 -> +0" in m for m in events), events
    assert any("contact 1 -> 0" in m for m in events), events
    rod.free()


def run_alone(loaded, steps, **start):
    rod = Rod(loaded)
    rod.initialize(**start)
    trajectory = []
    for _ in range(steps):
        rod.euler_step(1e-5)
        trajectory.append(rod.x.copy())
    rod.free()
    return np.array(trajectory)


A = dict(epsilon=1e-3, delta=1.0, theta=1.0)
B = dict(epsilon=1e-2, delta=0.3, theta=1.1, mu=2.5)


def test_two_instances_alternately_equal_each_alone(loaded):
    alone = [run_alone(loaded, 400, **A), run_alone(loaded, 400, **B)]
    rods = [Rod(loaded, "a"), Rod(loaded, "b")]
    rods[0].initialize(**A)
    rods[1].initialize(**B)
    together = [[], []]
    for _ in range(400):
        for k, rod in enumerate(rods):
            rod.euler_step(1e-5)
            together[k].append(rod.x.copy())
    for k in range(2):
        assert np.array_equal(np.array(together[k]), alone[k])
    assert not np.allclose(alone[0], alone[1])


def test_instances_in_threads_equal_serial_runs(loaded):
    cases = [dict(epsilon=10.0**-k, theta=1.0 + 0.05 * k) for k in range(2, 6)]
    serial = [default_experiment(loaded.unzipdir, start_values=c)["w"] for c in cases]
    parallel = [None] * len(cases)

    def work(k):
        parallel[k] = default_experiment(loaded.unzipdir, start_values=cases[k])["w"]

    threads = [threading.Thread(target=work, args=(k,)) for k in range(len(cases))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for s, p in zip(serial, parallel):
        assert np.array_equal(s, p)
