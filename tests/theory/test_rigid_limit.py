# SPDX-License-Identifier: BSD-2-Clause
"""The rigid limit of IWC for a nonlinear compliance law (painleve.theory.rigid_limit),
against the paper's closed forms for the linear law, an energy argument for the
undamped law, the scaling of the law, and a second, independent integration."""
import numpy as np
import pytest

from painleve.theory import analytic as an
from painleve.theory import rigid_limit as rl

WEDGES = [dict(alpha=3.0, mu=3.0), dict(alpha=3.0, mu=1.4), dict(alpha=2.0, mu=3.0)]


def thetas(alpha, mu, n=7):
    t1, t2 = an.theta_1(alpha=alpha, mu=mu), an.theta_2(alpha=alpha, mu=mu)
    return t1 + (t2 - t1) * np.linspace(0.05, 0.95, n)


@pytest.mark.parametrize("params", WEDGES)
def test_linear_law_reproduces_the_closed_form_e_to_1e_10(params):
    th = thetas(**params)
    sw = an.S_w(th, alpha=params["alpha"])
    # over-damped, critically damped (delta = 2/sqrt(S_w): the double root) and oscillatory
    for delta in [0.0, 0.1, 0.5, 1.0, 2.0, 5.0, 20.0, 2 / np.sqrt(sw)]:
        got = rl.e(delta, th, **params)
        np.testing.assert_allclose(got, an.e(delta, th, **params), rtol=1e-10, atol=0, err_msg=f"delta {delta}")


@pytest.mark.parametrize("delta", [0.0, 0.7, 3.0])
def test_linear_law_ends_slipping_compression_at_eq_initStick(delta):
    th = thetas(3.0, 3.0)
    yh, w = rl.stick_start(delta, th, v0=1.3)
    end = an.slip_compression_end(th, 0.5, 1.3, delta)
    np.testing.assert_allclose(yh, end.yhat, rtol=1e-10)
    np.testing.assert_allclose(w, end.w, rtol=1e-14)


@pytest.mark.parametrize("params", WEDGES[:2])
@pytest.mark.parametrize("kappa", [0.0, 0.5, 3.0, 40.0])
def test_undamped_e_is_the_energy_balance_whatever_the_spring(params, kappa):
    # delta = 0: both phases conserve w^2/(2 p_+) + V(yh) and w^2/(2 S_w) + V(yh), V the spring's
    # potential (V(0) = 0). Compression from the saddle stores V = -w*^2/(2 p_+) at w* = -p_+ v0/q_+;
    # the stick ends at h = 0, i.e. yh = 0, V = 0: e = (p_+/q_+) sqrt(1 - S_w/p_+), for any spring.
    th = thetas(**params)
    pp, qp = an.p_plus(th, **params), an.q_plus(th, **params)
    sw = an.S_w(th, alpha=params["alpha"])
    expected = pp / qp * np.sqrt(1 - sw / pp)
    np.testing.assert_allclose(rl.e(0.0, th, kappa=kappa, beta=2.0, **params), expected, rtol=1e-10)
    np.testing.assert_allclose(an.e_zero(th, **params), expected, rtol=1e-12)   # the paper's eq eDeltaZero


def test_e_depends_on_kappa_v0_and_beta_v0_only():
    # yh = v0 Y, w = v0 W turns h(yh, w; kappa, beta) into v0 h(Y, W; kappa v0, beta v0).
    th = np.array([0.6, 1.0, 1.3])
    for v0 in (0.25, 4.0):
        np.testing.assert_allclose(rl.e(1.0, th, kappa=2.0, beta=1.5, v0=v0),
                                   rl.e(1.0, th, kappa=2.0 * v0, beta=1.5 * v0), rtol=1e-9)
    # and the law matters: e moves by far more than that tolerance
    assert np.all(np.abs(rl.e(1.0, th, kappa=2.0, beta=1.5, v0=4.0) - rl.e(1.0, th, kappa=2.0, beta=1.5)) > 1e-3)


def test_vectorised_over_theta0_and_the_law_equals_case_by_case():
    th = np.array([0.6, 0.9, 1.2])[:, None, None]
    kappa = np.array([0.0, 1.0, 10.0])[None, :, None]
    beta = np.array([0.0, 2.0])[None, None, :]
    grid = rl.e(1.5, th, kappa=kappa, beta=beta)
    assert grid.shape == (3, 3, 2)
    for i, j, k in np.ndindex(grid.shape):
        one = rl.e(1.5, th[i, 0, 0], kappa=kappa[0, j, 0], beta=beta[0, 0, k])
        assert one == pytest.approx(grid[i, j, k], rel=1e-10)


@pytest.mark.parametrize("params", WEDGES[:2])
@pytest.mark.parametrize("law", [dict(kappa=2.0), dict(beta=2.0), dict(kappa=5.0, beta=1.0), dict(kappa=0.3, beta=8.0)])
@pytest.mark.parametrize("delta", [0.0, 0.5, 2.0, 6.0])
def test_two_independent_integrations_agree(params, law, delta):
    # rigid_limit.e_rigid: the manifold in ln w from its tangent, w = -p_+ v0/q_+ assumed, DOP853,
    # the stick's end by dense output; e_shooting: (yh, w, v) from the floor in time, v = 0 and h = 0
    # by solve_ivp's events, LSODA.
    th = thetas(**params, n=4)
    got = rl.e(delta, th, **law, **params)
    e2, yh2, w2 = rl.shooting(delta, th, v0=0.8, **law, **params)
    np.testing.assert_allclose(e2, rl.e(delta, th, v0=0.8, **law, **params), rtol=2e-8)
    # the second method, integrating v, finds v = 0 where w = -p_+ v0/q_+, at the manifold's depth
    np.testing.assert_allclose(w2, -an.p_plus(th, **params) * 0.8 / an.q_plus(th, **params), rtol=1e-8)
    np.testing.assert_allclose(yh2, rl.stick_start(delta, th, v0=0.8, **law, **params)[0], rtol=1e-8)
    # the agreement is far finer than what the law changes (delta = 0 excepted: see the energy test)
    if delta > 0:
        assert np.all(np.abs(got / an.e(delta, th, **params) - 1) > 5e-3)


def test_bad_laws_are_refused():
    with pytest.raises(ValueError, match="kappa"):
        rl.e(1.0, 1.0, kappa=-0.1)
    with pytest.raises(ValueError, match="beta"):
        rl.e(1.0, 1.0, beta=-0.1)
    with pytest.raises(an.HypothesisError):
        rl.e(1.0, 1.6)                  # outside the Painleve wedge
