# SPDX-License-Identifier: BSD-2-Clause
"""The paper's theory for d = 2 (docs/general_body_theory.md) against direct simulation of an
independent numpy model of the compliant two-link arm (helpers.arm_lagrange, helpers.two_link_arm_iwc).

The model is first checked on its own (energy of free motion, contact responses), then the
theory's claims: the stick is the Filippov combination with the a-term the paper drops, the
lift-off velocity converges to e of eq eGeneral like eps ln(1/eps), the generalized velocities jump
by {-c_+/q_+ + (S_phi/S_w)(e + p_+/q_+)} v0 with vector c_+, S_phi, the angles do not move in the
limit, and Theorem 2's separatrix w1* splits IWC from lift-off."""
import numpy as np
import pytest
import scipy.integrate

from helpers.arm_lagrange import (Arm, applied, coefficients, floor_angle, jacobian, mass_matrix, rates, tip,
                                  velocity_products)
from helpers.two_link_arm_iwc import _accel, lift_off_ratio, simulate
from painleve.theory import general as G

# Plausible parameters (the 2008 experiment's are not in the paper's references): two equal uniform
# links, L = M = g = 1, pivot 0.3 L above the floor, mu = 1.5; the elbow up-left of the pivot.
ARM = Arm(H=0.3, mu=1.5)
TH = np.array([2.9, floor_angle(ARM, 2.9, 1)])
V0 = 0.3


def test_the_start_is_on_the_floor_in_the_inconsistent_quadrant():
    assert tip(ARM, TH)[1] == pytest.approx(0.0, abs=1e-15)
    co = G.Coefficients.of(coefficients(ARM, TH, rates(ARM, TH, V0, 0.0)))
    G.check(co, 1, delta=1.0, v0=V0)
    assert G.quadrant(co) == "inconsistent"


def test_free_motion_conserves_energy():
    """The mass matrix and the velocity terms are Lagrange's: T + V is constant without contact."""
    def energy(z):
        th, om = z[:2], z[2:]
        ycm = (ARM.m1 * ARM.l1 / 2 * np.sin(th[0]) + ARM.m2 * (ARM.l1 * np.sin(th[0]) + ARM.l2 / 2 * np.sin(th[1])))
        return 0.5 * om @ mass_matrix(ARM, th) @ om + ARM.g * ycm

    def rhs(t, z):
        return np.concatenate([z[2:], np.linalg.solve(mass_matrix(ARM, z[:2]), applied(ARM, z[:2], z[2:]))])
    z0 = np.array([0.3, -1.0, 1.2, -2.0])
    sol = scipy.integrate.solve_ivp(rhs, (0, 5), z0, method="DOP853", rtol=1e-12, atol=1e-12)
    drift = max(abs(energy(sol.y[:, i]) - energy(z0)) for i in range(sol.y.shape[1]))
    assert drift < 1e-9 * (1 + abs(energy(z0)))
    # and the tip's velocity products are d/dt of J omega at zero angular acceleration
    h = 1e-6
    om = np.array([1.2, -2.0])
    dj = (jacobian(ARM, TH + h * om) - jacobian(ARM, TH - h * om)) / (2 * h) @ om
    np.testing.assert_allclose(velocity_products(ARM, TH, om), dj, rtol=1e-8)


def test_slip_and_stick_responses_are_the_coefficients_and_their_filippov_combination():
    om = rates(ARM, TH, V0, 0.0)
    c = coefficients(ARM, TH, om)
    co = G.Coefficients.of(c)
    J, scale = jacobian(ARM, TH), ARM.M * ARM.g  # F_N in units of M g
    for s, name in ((1, "plus"), (-1, "minus")):
        for fn in (0.0, 3.0):
            acc, _ = _accel(ARM, TH, om, fn * scale, s)
            np.testing.assert_allclose(J @ acc + velocity_products(ARM, TH, om),
                                       [c["a"] + c[f"q_{name}"] * fn, c["b"] + c[f"p_{name}"] * fn], rtol=1e-11)
    # sticking: v' = 0 and w' = b + a (p_+ - p_-)/(q_- - q_+) + S_w F_N; omega' has S_phi = eq Sw's c-combination
    s_phi = G.filippov_combination(co, c["c_plus"], c["c_minus"])
    acc0 = _accel(ARM, TH, om, 0.0, 0)[0]
    acc1 = _accel(ARM, TH, om, 2.0 * scale, 0)[0]
    wdot = lambda acc: (J @ acc + velocity_products(ARM, TH, om))  # noqa: E731
    assert wdot(acc1)[0] == pytest.approx(0.0, abs=1e-12) and wdot(acc0)[0] == pytest.approx(0.0, abs=1e-12)
    assert (wdot(acc1)[1] - wdot(acc0)[1]) / 2.0 == pytest.approx(float(co.S_w), rel=1e-11)
    drop = c["a"] * (c["p_plus"] - c["p_minus"]) / (c["q_minus"] - c["q_plus"])
    assert wdot(acc0)[1] == pytest.approx(c["b"] + drop, rel=1e-11)
    np.testing.assert_allclose((acc1 - acc0) / 2.0 * ARM.L, s_phi, rtol=1e-11)


EPS = [1e-3, 1e-4, 1e-5, 1e-6]


@pytest.mark.parametrize("delta", [0.5, 1.0, 2.0])
def test_arm_iwc_converges_to_e_like_eps_ln_eps(delta):
    co = G.Coefficients.of(coefficients(ARM, TH, rates(ARM, TH, V0, 0.0)))
    e = G.e(delta, co)
    runs = [lift_off_ratio(ARM, TH, V0, eps, delta) for eps in EPS]
    err = np.array([abs(r - e) for r, _ in runs])
    scaled = err / (np.array(EPS) * np.log(1 / np.array(EPS)))
    assert err[-1] < 3e-3 * e                       # e to a few parts in 1e3 at eps = 1e-6
    assert err[-1] < err[0] / 100                   # three decades of eps: the error falls > 100 times
    assert np.all(scaled[1:] < 3 * scaled[0])       # and no slower than eps ln(1/eps)
    for eps, (_, out) in zip(EPS, runs):            # the IWC: stick, a fold (which one: the test below), flight
        assert [p[0] for p in out["phases"]][0] == "v=0" and [p[0] for p in out["phases"]][2:] == ["lift", "return"]
        assert abs(out["v"]) < 100 * eps * V0
        assert np.max(np.abs(out["th"] - TH)) < 20 * eps * np.log(1 / eps)


def test_arm_rates_jump_by_the_vector_form_of_theorem_1():
    delta = 1.0
    om0 = rates(ARM, TH, V0, 0.0)
    c = coefficients(ARM, TH, om0)
    co = G.Coefficients.of(c)
    jump = G.velocity_jump(delta, co, c["c_plus"], G.filippov_combination(co, c["c_plus"], c["c_minus"]), v0=V0)
    predicted = om0 + jump  # L = M = g = 1: scaled rates are SI rates
    errs = [np.max(np.abs(lift_off_ratio(ARM, TH, V0, eps, delta)[1]["om"] - predicted)) for eps in EPS[:3]]
    assert errs[-1] < 1e-3 * np.max(np.abs(predicted)) and errs[-1] < errs[0] / 20
    # the jump is the one that takes the tip to (0, e v0): J(theta0) Delta omega = (-v0, e v0)
    np.testing.assert_allclose(jacobian(ARM, TH) @ jump, [-V0, G.e(delta, co) * V0], rtol=1e-12)


def test_theorem_2_separatrix_on_the_arm():
    v0, eps, delta = 1.0, 1e-4, 1.0
    co = G.Coefficients.of(coefficients(ARM, TH, rates(ARM, TH, v0, 0.0)))
    assert G.quadrant(co) == "indeterminate"
    w1s = G.w1_star(delta, co)
    for f, iwc in ((0.8, False), (1.2, True)):
        out = simulate(ARM, TH, rates(ARM, TH, v0, eps * f * w1s), eps, delta)
        if iwc:
            assert out["w"] / v0 == pytest.approx(G.e(delta, co), rel=0.01)
        else:
            assert [p[0] for p in out["phases"]] == ["lift", "return"] and out["w"] < 20 * eps * v0


def test_an_si_arm_of_unequal_links_converges_to_its_e():
    """SI units (g = 9.81, L = 0.7 m, M = 3 kg), unequal links, the elbow on the other side: the scaled
    coefficients and delta = c/sqrt(M k) give the e that the SI simulation's w/v0 converges to."""
    arm = Arm(H=0.15, m1=2.0, l1=0.4, J1=2.0 * 0.4 ** 2 / 12, m2=1.0, l2=0.3, J2=0.3 ** 2 / 12, g=9.81, mu=1.5)
    th = np.array([0.2, floor_angle(arm, 0.2, 1)])
    v0, delta = 0.3 * np.sqrt(arm.g * arm.L), 0.7
    co = G.Coefficients.of(coefficients(arm, th, rates(arm, th, v0, 0.0)))
    G.check(co, 1, delta=delta, v0=v0)
    e = G.e(delta, co)
    runs = [lift_off_ratio(arm, th, v0, eps, delta) for eps in EPS[1:]]
    err = [abs(r - e) for r, _ in runs]
    assert err[-1] < 3e-3 * e and err[-1] < err[0] / 30


@pytest.mark.parametrize("theta1,v0", [(2.9, 0.3), (0.2, 0.5)])
def test_the_stick_ends_at_the_fold_that_the_sign_of_a_at_its_end_picks(theta1, v0):
    """§2: as F_N -> 0 the sticking friction tends to a/G_TT, so the stick ends in forward slip if a > 0
    and backward slip if a < 0, a taken where the stick ends: theta0 and the rates after the impulses of §3
    (a is quadratic in the rates, which jump by O(1)). The second case starts with a < 0 and still ends
    forward: a(theta0, omega0) does not decide. Either way w/v0 -> e."""
    th = np.array([theta1, floor_angle(ARM, theta1, 1)])
    om0 = rates(ARM, th, v0, 0.0)
    c = coefficients(ARM, th, om0)
    co = G.Coefficients.of(c)
    G.check(co, 1, delta=1.0, v0=v0)
    om_end = om0 + G.velocity_jump(1.0, co, c["c_plus"], G.filippov_combination(co, c["c_plus"], c["c_minus"]), v0=v0)
    a_end = coefficients(ARM, th, om_end)["a"]
    ratio, out = lift_off_ratio(ARM, th, v0, 1e-5, 1.0)
    assert [p[0] for p in out["phases"]] == ["v=0", "slip+" if a_end > 0 else "slip-", "lift", "return"]
    assert ratio == pytest.approx(G.e(1.0, co), rel=2e-3)
    if theta1 == 0.2:
        assert c["a"] < 0 < a_end
