# SPDX-License-Identifier: BSD-2-Clause
"""The relative tolerances for which Co-Simulation answers right (docs/bounded_calls.md):
1e-12 to 1e-3. Outside, the FMU clamps with a warning, so no tolerance turns the mode
logic into a wrong answer: the IWC at either end of the range, and at the fuzzer's
tolerance 48.125, lifts off with the paper's e to within the theorem's error."""
import math

import numpy as np
import pytest
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Warning
from scipy.integrate import solve_ivp

from painleve import Case, Experiment
from helpers.raw_instances import Slave

RANGE = (1e-12, 1e-3)


def e_from_the_sticking_system(theta0, delta, alpha, mu):
    """e of Proposition prop:stick, integrated apart from the harness: y' = w, w' = S_w (-y - delta w)
    from y = -p v0/(q lambda_+), w = -p v0/q (eq initStick, v0 = 1) to y + delta w = 0."""
    s, c = math.sin(theta0), math.cos(theta0)
    p = 1 + alpha * c * c - mu * alpha * s * c
    q = alpha * s * c - mu * (1 + alpha * s * s)
    S_w = (1 + alpha) / (1 + alpha * s * s)
    lam = -delta * p / 2 + math.sqrt(delta**2 * p**2 - 4 * p) / 2
    leave = lambda t, u: u[0] + delta * u[1]
    leave.terminal, leave.direction = True, 1
    sol = solve_ivp(lambda t, u: [u[1], S_w * (-u[0] - delta * u[1])], (0, 100), [-p / (q * lam), -p / q],
                    events=leave, rtol=1e-12, atol=1e-14)
    return sol.y_events[0][0][1]


@pytest.mark.parametrize("tolerance", [RANGE[0], RANGE[1], 48.125])
def test_the_iwc_lifts_off_with_e_at_both_ends_of_the_range_and_beyond(fmu_path, tolerance):
    case = Case(theta0=1.0, phi0=0.5, v0=1.0, delta=1.0, epsilon=1e-5)
    with Experiment(fmu_path, fmi_type="CoSimulation", relative_tolerance=tolerance) as experiment:
        outcome = experiment.run(case)
    e = e_from_the_sticking_system(case.theta0, case.delta, case.alpha, case.mu)
    # Theorem 1's error is O(eps ln 1/eps): 3 eps ln(1/eps) = 3.5e-4 bounds it here.
    assert abs(outcome.w / case.v0 - e) < 3 * case.epsilon * math.log(1 / case.epsilon)


def test_a_tolerance_outside_the_range_is_clamped_with_a_warning_naming_the_range(loaded):
    inside = Slave(loaded, tolerance=RANGE[1])
    beyond = Slave(loaded, tolerance=48.125)
    warnings = [m for m in beyond.messages if "tolerance = 48.125 is outside 1e-12 to 0.001" in m[2]]
    assert len(warnings) == 1 and warnings[0][0] == fmi2Warning
    assert not [m for m in inside.messages if "tolerance" in m[2]]
    for rod in (inside, beyond):
        for h in (0.02, 0.069):
            rod.step(h)
    # The clamped run is the run at the range's end, bit for bit, and it is in flight, not stuck
    # below the floor (the tolerance-10 answer: y = -9.5e-7, still in contact).
    assert np.array_equal(inside.states(), beyond.states())
    assert beyond.fmu.getReal([beyond.vr["y"]])[0] > 0 and not beyond.fmu.getBoolean([beyond.vr["contact"]])[0]


def test_the_fuzzers_hang_returns_promptly_through_fmi2(loaded):
    # The fuzzer's hang through FMI 2.0: start 48.125, tolerance 48.125, steps 0.02 and 0.069.
    rod = loaded.instantiate(fmi_type="CoSimulation")
    assert rod.setupExperiment(tolerance=48.125, startTime=48.125) == fmi2Warning
    rod.enterInitializationMode()
    rod.exitInitializationMode()
    rod.doStep(48.125, 0.02)      # fmpy raises on a status above fmi2Warning
    rod.doStep(48.145, 0.069)
    assert rod.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(48.214, rel=1e-14)
    rod.terminate()
    rod.freeInstance()


def test_the_model_descriptions_state_the_range_the_fmu_clamps_to(loaded):
    import xml.etree.ElementTree as ET
    from conftest import ROOT
    xmls = [ROOT / "modelDescription.xml", *sorted((ROOT / "fmu_src" / "models").glob("*/modelDescription.xml"))]
    ranges = [ET.parse(x).find("VendorAnnotations/Tool[@name='painleve']/ToleranceRange") for x in xmls]
    assert all(r is not None and (float(r.get("min")), float(r.get("max"))) == RANGE for r in ranges)
    for tolerance, warned in ((RANGE[0], False), (RANGE[1], False), (RANGE[0] / 2, True), (RANGE[1] * 2, True)):
        rod = Slave(loaded, tolerance=tolerance)
        assert any("is outside" in m[2] for m in rod.messages) == warned
