# SPDX-License-Identifier: BSD-2-Clause
"""TwoLinkArm, the contact core's second body: its description validates (FMI 2.0
and 3.0), its energy is conserved in flight and dissipated in contact, and its coefficients
a, b, p_plus, p_minus, q_plus, q_minus, S_w are those of an independent computation from the
links' centres of mass (tests/helpers/two_link_arm.py; the Delassus matrix W M^-1 W^T of
tests/helpers/delassus.py) at random configurations, in the documented scaling."""
import ctypes

import fmpy
import numpy as np
import pytest
from fmpy import extract, instantiate_fmu, read_model_description
from fmpy.validation import validate_fmu

from helpers import delassus
from helpers import two_link_arm as arm

COEFFICIENTS = ("a", "b", "p_plus", "p_minus", "q_plus", "q_minus", "S_w")
RNG = np.random.default_rng(2708)


@pytest.mark.parametrize("which", ["arm_path", "arm3_path"])
def test_fmpy_validation_finds_no_problem(which, request):
    assert validate_fmu(request.getfixturevalue(which)) == []


def run(path, fmi_type, stop, output, **start):
    return fmpy.simulate_fmu(path, fmi_type=fmi_type, stop_time=stop, start_values=start, output=list(output),
                             relative_tolerance=1e-10 if fmi_type == "ModelExchange" else None, output_interval=stop / 500)


@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
def test_energy_is_conserved_in_flight(arm_path, fmi_type):
    """Pivot 2 m up: the tip never reaches the floor; the arm swings as a double pendulum."""
    r = run(arm_path, fmi_type, 2.0, ("energy", "y", "F_N", "theta1", "omega2"), H=2.0, theta1=-0.3, theta2=0.4,
            omega1=2.0, omega2=-3.0)
    assert np.all(r["y"] > 0.5) and np.all(r["F_N"] == 0)
    assert np.ptp(r["theta1"]) > 0.5   # it moved
    p = dict(arm.DEFAULTS, H=2.0)
    e0 = arm.energy(np.array([-0.3, 0.4]), np.array([2.0, -3.0]), p)
    assert r["energy"][0] == pytest.approx(e0, rel=1e-12)   # the FMU's energy is the links' (independent)
    scale = np.ptp(r["theta1"]) * p["g"] * (p["m1"] + p["m2"]) * (p["l1"] + p["l2"])
    assert np.max(np.abs(r["energy"] - e0)) < 1e-5 * scale


@pytest.mark.parametrize("which", ["arm_path", "arm3_path"])
@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
def test_energy_is_dissipated_in_contact(which, fmi_type, request):
    """The default start: the tip slipping forward on the floor in the paradox region. Friction and the
    damper take energy; it never grows beyond the solver's error, and it drops by a finite amount
    (FMI 2.0 and 3.0 alike)."""
    r = run(request.getfixturevalue(which), fmi_type, 0.2, ("energy", "F_N", "F_T", "v", "contact"))
    assert np.any(r["F_N"] > 0) and np.any(r["contact"])
    e = r["energy"]
    assert np.all(np.diff(e) <= 1e-6 * abs(e[0]))
    assert e[-1] < e[0] - 1e-3 * abs(e[0])
    slipping = (r["F_N"] > 0) & (np.abs(r["v"]) > 1e-6)
    assert np.all(np.abs(r["F_T"][slipping]) <= 0.8 * r["F_N"][slipping] * (1 + 1e-12))


@pytest.fixture(scope="module")
def instance(arm_path):
    md = read_model_description(arm_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = instantiate_fmu(extract(arm_path), md, fmi_type="ModelExchange")
    yield fmu, vr
    fmu.freeInstance()


def read(instance, start, names):
    fmu, vr = instance
    fmu.reset()
    fmu.setupExperiment(startTime=0.0)
    fmu.setReal([vr[k] for k in start], list(start.values()))
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    return dict(zip(names, fmu.getReal([vr[k] for k in names])))


@pytest.mark.parametrize("k", range(10))
def test_coefficients_are_the_delassus_matrix_of_an_independent_arm(instance, k):
    p = dict(m1=RNG.uniform(0.1, 3), l1=RNG.uniform(0.1, 1), m2=RNG.uniform(0.1, 3), l2=RNG.uniform(0.1, 1),
             H=RNG.uniform(0.1, 2), g=RNG.uniform(1, 20), mu=RNG.uniform(0, 2))
    p["J1"], p["J2"] = p["m1"] * p["l1"] ** 2 * RNG.uniform(0.02, 0.2), p["m2"] * p["l2"] ** 2 * RNG.uniform(0.02, 0.2)
    q, u = RNG.uniform(-np.pi, np.pi, 2), RNG.uniform(-4, 4, 2)
    got = read(instance, dict(p, theta1=q[0], theta2=q[1], omega1=u[0], omega2=u[1]), COEFFICIENTS + ("epsilon",))
    M_ref, L_ref = p["m1"] + p["m2"], p["l1"] + p["l2"]
    W = arm.jacobian(lambda qq: arm.tip(qq, p), q)   # rows: x, y
    # Scaled form (docs/general_body.md): accelerations by g, forces by M g, so G_scaled = M G.
    coefficients = delassus.coefficients(arm.mass_matrix(q, p) / M_ref, W[0], W[1], p["mu"])
    a, b = arm.tip_acceleration(q, u, arm.free_acceleration(q, u, p), p) / p["g"]
    expected = dict(a=a, b=b, **coefficients)
    size = max(abs(v) for v in expected.values())
    for name in COEFFICIENTS:
        assert got[name] == pytest.approx(expected[name], rel=1e-6, abs=1e-7 * size), name
    k_default = 1.5696e7   # the start value of k: epsilon = sqrt(M g/(k L))
    assert got["epsilon"] == pytest.approx(np.sqrt(M_ref * p["g"] / (k_default * L_ref)), rel=1e-14)


def test_the_default_start_is_in_the_paradox_region_on_the_floor(instance):
    got = read(instance, {}, ("p_plus", "p_minus", "q_plus", "q_minus", "a", "b", "y", "v", "w", "epsilon", "delta"))
    assert got["p_plus"] < 0 < got["p_minus"] and got["q_plus"] < 0 < got["q_minus"]
    assert got["b"] < 0 < got["a"]   # Theorem 1's quadrant
    assert abs(got["y"]) < 1e-12 and got["v"] == pytest.approx(0.2, rel=1e-3) and abs(got["w"]) < 1e-4
    assert got["epsilon"] == pytest.approx(1e-3, rel=1e-4) and got["delta"] == pytest.approx(1.0, rel=1e-4)


@pytest.mark.parametrize("k", range(5))
def test_y_is_a_state_calculated_from_the_angles_that_no_one_sets(instance, k):
    # y starts at the tip's height H + l1 sin theta1 + l2 sin theta2 (the arm of helpers.two_link_arm),
    # is the fifth continuous state, and its derivative is w.
    fmu, vr = instance
    p = dict(l1=RNG.uniform(0.1, 1), l2=RNG.uniform(0.1, 1), H=RNG.uniform(0.1, 2))
    q, u = RNG.uniform(-np.pi, 0, 2), RNG.uniform(-4, 4, 2)
    got = read(instance, dict(p, theta1=q[0], theta2=q[1], omega1=u[0], omega2=u[1]), ("y", "w", "der(y)"))
    tip_y = arm.tip(q, p)[1]
    tip_w = p["l1"] * np.cos(q[0]) * u[0] + p["l2"] * np.cos(q[1]) * u[1]   # d/dt of the tip's height
    assert got["y"] == pytest.approx(tip_y, abs=1e-14 * (p["H"] + 2))
    assert got["der(y)"] == got["w"] == pytest.approx(tip_w, abs=1e-13 * (1 + abs(tip_w)))
    x = np.zeros(5)
    fmu.getContinuousStates(x.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), 5)
    assert x[4] == got["y"]


def test_y_cannot_be_set_before_initialization_and_the_error_names_it(arm_path):
    # Its own instance and logger: fmpy's logging proxy keeps one logger for every instance, the last
    # one installed, which the shared default callbacks would call after its owner is gone.
    md = read_model_description(arm_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    said = []
    fmu = instantiate_fmu(extract(arm_path), md, fmi_type="ModelExchange",
                          logger=lambda env, name, status, category, message: said.append(message.decode()))
    try:
        with pytest.raises(fmpy.fmi1.FMICallException):
            fmu.setReal([vr["y"]], [0.1])
        assert any("y can be set only in Continuous-Time Mode" in m for m in said), said
    finally:
        fmu.freeInstance()


def test_a_tip_placed_on_the_floor_starts_exactly_on_it(instance):
    # H from the angles in double precision leaves the tip an ulp-sized bit off the floor;
    # the FMU reads it as on the floor: y = 0 exactly.
    for q in RNG.uniform(-np.pi, 0, (20, 2)):
        p = dict(l1=0.3, l2=0.2)
        p["H"] = -(p["l1"] * np.sin(q[0]) + p["l2"] * np.sin(q[1]))
        assert read(instance, dict(p, theta1=q[0], theta2=q[1]), ("y",))["y"] == 0.0
