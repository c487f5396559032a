# SPDX-License-Identifier: BSD-2-Clause
"""TwoLinkArm.fmu through the generic body path, against the independent numpy arm
(helpers.arm_lagrange, helpers.two_link_arm_iwc) and the theory (painleve.theory.general):
its outputs are the numpy model's, its IWC converges to e of its own coefficients as eps falls,
at the same eps it does what the numpy simulation does, and `painleve iwc/validate/figures`
run it with nothing but the FMU."""
import json

import numpy as np
import pytest

from conftest import built_fmu
from helpers.cli_run import run
from helpers import arm_filippov as AF
from helpers.arm_lagrange import Arm, coefficients, floor_angle, jacobian, rates, tip
from helpers.two_link_arm_iwc import lift_off_ratio
from painleve.fmu.body import Body
from painleve.theory import general as G

ARM = Arm(H=0.3, mu=1.5)        # tests/theory/test_two_link_arm_theory.py's arm: L = M = g = 1
PARAMS = dict(H=ARM.H, m1=ARM.m1, l1=ARM.l1, J1=ARM.J1, m2=ARM.m2, l2=ARM.l2, J2=ARM.J2, g=ARM.g, mu=ARM.mu)
THETA1, V0 = 2.9, 0.3
THETA2 = floor_angle(ARM, THETA1, 1)


@pytest.fixture(scope="module")
def arm_fmu():
    return built_fmu("TwoLinkArm.fmu")


@pytest.fixture(scope="module")
def body(arm_fmu):
    with Body(arm_fmu) as b:
        yield b


def test_the_fmus_outputs_are_the_numpy_arms(body):
    rng = np.random.default_rng(27)
    for _ in range(20):
        th, om = rng.uniform(-np.pi, np.pi, 2), rng.uniform(-2, 2, 2)
        arm = ARM.with_(H=rng.uniform(0.1, 1.0), mu=rng.uniform(0.2, 2.0), m1=rng.uniform(0.2, 2.0),
                        l2=rng.uniform(0.2, 1.0), g=rng.uniform(0.5, 10.0))
        given = dict(H=arm.H, m1=arm.m1, l1=arm.l1, J1=arm.J1, m2=arm.m2, l2=arm.l2, J2=arm.J2, g=arm.g, mu=arm.mu,
                     theta1=th[0], theta2=th[1], omega1=om[0], omega2=om[1])
        out = body.outputs(given, ("x", "y", "v", "w") + G.NAMES)
        want = coefficients(arm, th, om)
        (x, y), (v, w) = tip(arm, th), jacobian(arm, th) @ om
        np.testing.assert_allclose([out[k] for k in ("x", "y", "v", "w")], [x, y, v, w], rtol=1e-12, atol=1e-13)
        for k in G.NAMES:
            assert out[k] == pytest.approx(want[k], rel=1e-9, abs=1e-11), k


def test_the_start_is_solved_on_the_floor(body):
    start = body.floor_start(dict(PARAMS, theta1=THETA1), V0, guess=dict(theta2=THETA2 + 0.05))
    assert start["theta2"] == pytest.approx(THETA2, abs=1e-12)
    np.testing.assert_allclose([start["omega1"], start["omega2"]],
                               rates(ARM, np.array([THETA1, THETA2]), V0, 0.0), rtol=1e-10)


def test_the_fmus_iwc_converges_to_e_and_matches_the_numpy_arm(body):
    delta, errors = 1.0, []
    th = np.array([THETA1, THETA2])
    for eps in (1e-4, 1e-5, 1e-6):
        start = body.floor_start(body.compliance(dict(PARAMS, theta1=THETA1), eps, delta), V0,
                                 guess=dict(theta2=THETA2))
        co, got_eps, got_delta = body.coefficients(start)
        assert (got_eps, got_delta) == (pytest.approx(eps, rel=1e-9), pytest.approx(delta, rel=1e-9))
        e = G.e(delta, co)
        out = body.iwc(start)
        assert out.iwc
        errors.append(abs(out.w / V0 - e))
        if eps >= 1e-5:    # the same compliant arm in numpy: the same lift-off, far closer than to the limit
            numpy_ratio = lift_off_ratio(ARM, th, V0, eps, delta)[0]
            assert abs(out.w / V0 - numpy_ratio) < 0.05 * errors[-1] + 1e-6
    assert errors[-1] < 3e-3 * e and errors[-1] < errors[0] / 10


@pytest.mark.parametrize("eps", [1e-4, 1e-5])
def test_the_arm_through_co_simulation_does_what_the_numpy_arm_and_model_exchange_do(arm_fmu, body, eps):
    """The FMU's own integrator, the return bisected on its steps: w/v0 at the return is the independent
    numpy arm's, as Model Exchange's is, the return's time the event-driven reference arm's, and the two
    interfaces see the same phases. The return's time within 1e-5: the start on the floor at rest is a
    grazing one, whose times move by the square root of the rounding the angles put in the tip's height
    (1e-15 m against eps^2 = 1e-10 here: docs/general_body.md §1)."""
    start = body.floor_start(body.compliance(dict(PARAMS, theta1=THETA1), eps, 1.0), V0, guess=dict(theta2=THETA2))
    me = body.iwc(start, relative_tolerance=1e-10)
    with Body(arm_fmu, fmi_type="CoSimulation") as cs_body:
        cs = cs_body.iwc(start, relative_tolerance=1e-10)
    numpy_ratio = lift_off_ratio(ARM, np.array([THETA1, THETA2]), V0, eps, 1.0)[0]
    e = G.e(1.0, body.coefficients(start)[0])
    assert cs.iwc and me.iwc and cs.y >= 0 and cs.state.keys() == me.state.keys()
    assert abs(cs.w / V0 - numpy_ratio) < 0.05 * abs(numpy_ratio - e) + 1e-6
    reference = AF.simulate({k: start[k] for k in ("m1", "m2", "l1", "l2", "J1", "J2", "g", "mu", "H", "k", "c")},
                            np.array([start["theta1"], start["theta2"]]), np.array([start["omega1"], start["omega2"]]))
    assert cs.w == pytest.approx(me.w, rel=1e-6) and cs.w == pytest.approx(reference.w, rel=1e-6)
    assert cs.t_return == pytest.approx(reference.t, rel=1e-5) and me.t_return == pytest.approx(reference.t, rel=1e-5)
    for phase in ("compression", "stick", "lift_off", "flight_back"):
        assert getattr(cs, phase) == pytest.approx(getattr(me, phase), abs=1e-5 * me.t_return)


def test_painleve_iwc_validate_and_figures_run_the_arm(arm_fmu, tmp_path):
    sets = [a for k, v in dict(PARAMS, theta1=THETA1).items() for a in ("--set", f"{k}={v!r}")]
    r = run("iwc", "--fmu", arm_fmu, *sets, "--guess", f"theta2={THETA2}", "--v0", V0, "--eps", "1e-5", "--json",
            check_rc=0)
    out = json.loads(r.stdout)
    assert out["predicted"]["quadrant"] == "inconsistent" and out["simulated"]["iwc"]
    assert out["simulated"]["w"] / V0 == pytest.approx(out["predicted"]["e"], rel=5e-3)
    r = run("validate", "--fmu", arm_fmu, *sets, "--guess", f"theta2={THETA2}", "--v0", V0, "--json", check_rc=0)
    assert json.loads(r.stdout)["passed"]
    run("figures", "--fmu", arm_fmu, *[a for k, v in PARAMS.items() for a in ("--set", f"{k}={v!r}")],
        "--out", tmp_path, "--points", "41", check_rc=0)
    data = json.loads((tmp_path / "paradox_region.json").read_text())
    assert data["axes"] == ["theta1", "theta2"]
    t1, t2 = np.meshgrid(*data["grids"], indexing="ij")
    numpy_pp = np.vectorize(lambda a, b: coefficients(ARM, np.array([a, b]), np.zeros(2))["p_plus"])(t1, t2)
    np.testing.assert_allclose(data["p_plus"], numpy_pp, rtol=1e-9, atol=1e-11)
    assert 0 < data["paradox_fraction"] < 1


def test_the_fmus_own_start_validates_and_bad_starts_are_named(arm_fmu):
    r = run("validate", "--fmu", arm_fmu, "--json", check_rc=0)          # its defaults: a Theorem 1 case
    checks = json.loads(r.stdout)["checks"]
    errors = next(c for c in checks if c["id"].endswith("convergence"))["numbers"]["errors"]
    assert errors[-1] < errors[0] / 10
    r = run("iwc", "--fmu", arm_fmu, "--set", "theta1=0.5")               # the tip cannot reach the floor
    assert r.returncode == 2 and "no state with y = 0" in r.stderr
    r = run("iwc", "--fmu", arm_fmu, "--set", "theta1=-1.9", "--guess", "theta2=-2.2")   # on the floor, p_+ > 0
    assert r.returncode == 2 and "paradox region" in r.stderr


def test_theorem_2_on_the_fmu_splits_at_w1_star(body):
    """v0 = 1 puts the configuration in the indeterminate quadrant (b > 0); with L = M = g = 1 the FMU's
    velocities are the scaled ones, so w0 = eps w10 with the paper's w10."""
    eps, delta = 1e-5, 1.0
    values = body.compliance(dict(PARAMS, theta1=THETA1), eps, delta)
    co = body.coefficients(body.floor_start(values, 1.0, guess=dict(theta2=THETA2)))[0]
    assert G.quadrant(co) == "indeterminate"
    w1s = G.w1_star(delta, co)
    for f, iwc in ((0.8, False), (1.2, True)):
        out = body.iwc(body.floor_start(values, 1.0, eps * f * w1s, guess=dict(theta2=THETA2)))
        assert out.iwc == iwc
        assert (out.w == pytest.approx(G.e(delta, co), rel=0.01)) if iwc else (0 < out.w < 20 * eps)


def test_the_fmi3_arm_through_simulate_fmu_does_what_the_fmi2_arm_does(body):
    """build/fmi3/TwoLinkArm.fmu runs through fmpy's simulate_fmu (FMI 3.0), the FMI 2.0 one through the fast
    loop: the same start, the same e, the same IWC to the solvers' tolerance, converging to e."""
    with Body(built_fmu("fmi3", "TwoLinkArm.fmu")) as arm3:
        errors = []
        for eps in (1e-4, 1e-5, 1e-6):
            values = dict(PARAMS, theta1=THETA1)
            start3 = arm3.floor_start(arm3.compliance(values, eps, 1.0), V0, guess=dict(theta2=THETA2))
            start2 = body.floor_start(body.compliance(values, eps, 1.0), V0, guess=dict(theta2=THETA2))
            assert start3 == pytest.approx(start2, rel=1e-12, abs=1e-14)
            e = G.e(1.0, arm3.coefficients(start3)[0])
            out3, out2 = arm3.iwc(start3), body.iwc(start2)
            assert out3.iwc and out3.w == pytest.approx(out2.w, rel=1e-4)
            errors.append(abs(out3.w / V0 - e))
        assert errors[-1] < errors[0] / 10 and errors[-1] < 3e-3 * e
