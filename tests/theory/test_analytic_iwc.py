# SPDX-License-Identifier: BSD-2-Clause
"""Tests of painleve.theory.analytic's impact without collision (IWC) against the paper's
laws and independent computations: e two ways, its asymptotes in delta, the rest of
Theorem 1, Theorem 2's w1*. The coefficients, the wedge, the eigenvalues and the
hypotheses are in test_analytic.py; expected values, as there, are recomputed from
the paper's definitions (tests/helpers/paper_formulas.py) or are laws.
"""
import dataclasses
import math

import numpy as np
import pytest
import scipy.integrate
import scipy.linalg

from helpers.paper_formulas import CASES, coef, interior, lam_plus, slope
from painleve.theory import analytic as A


# --------------------------------------------------------------- e, two ways
@pytest.mark.parametrize("alpha,mu", CASES)
def test_e_closed_form_equals_integration(alpha, mu):
    th = interior(alpha, mu, 7)
    regimes = set()
    for t in th:
        sw = coef(t, alpha, mu)["Sw"]
        dc = 2 / math.sqrt(sw)  # critical damping
        deltas = [0.0, 1e-3, 0.1, 0.5, 0.9 * dc, dc * (1 - 1e-9), dc, dc * (1 + 1e-9),
                  dc * (1 - 1e-13), dc * (1 + 1e-13), 1.2 * dc, 3.0, 10.0, 30.0]
        for d in deltas:
            e1 = A.e_closed_form(d, t, alpha=alpha, mu=mu)
            e2 = A.e_integrated(d, t, alpha=alpha, mu=mu)
            assert e1 == pytest.approx(e2, rel=1e-10, abs=0), (t, d)
            regimes.add("over" if d * d * sw * sw > 4 * sw else "under" if d < dc else "crit")
        assert A.e(dc, t, alpha=alpha, mu=mu) == A.e_closed_form(dc, t, alpha=alpha, mu=mu)
    assert regimes == {"over", "under", "crit"}


def test_e_exactly_critical_matches_double_root_solution():
    """At delta = 2/sqrt(S_w) the sticking solution is (y0 + (w0 - xi y0) tau) e^{xi tau}."""
    alpha, mu = 3.0, 3.0
    exact_zero_disc = 0
    for t in interior(alpha, mu, 25):
        d = coef(t, alpha, mu)
        sw, p, q = A.S_w(t, alpha=alpha), d["pp"], d["qp"]
        dc = 2 / math.sqrt(sw)
        exact_zero_disc += (dc * dc * sw * sw - 4 * sw == 0)
        lp = lam_plus(p, dc)
        w0 = -p / q
        y0 = w0 / lp  # eq initStick, v0 = 1
        xi = -math.sqrt(sw)
        # -(yhat + delta w) = 0 is linear in tau after dividing by e^{xi tau}
        tau = -(y0 + dc * w0) / ((w0 - xi * y0) * (1 + dc * xi))
        w = math.exp(xi * tau) * (w0 + xi * (w0 - xi * y0) * tau)
        assert A.e_closed_form(dc, t, alpha=alpha, mu=mu) == pytest.approx(w, rel=1e-11)
        assert A.e_integrated(dc, t, alpha=alpha, mu=mu) == pytest.approx(w, rel=1e-11)
    assert exact_zero_disc > 0  # the double-root branch itself was exercised


@pytest.mark.parametrize("alpha,mu,theta0,phi0", [(3.0, 3.0, 1.0, 0.5), (3.0, 1.4, 1.1, 0.3),
                                                  (2.0, 3.0, 0.7, 0.2)])
def test_e_and_phi_against_generic_ode_solver(alpha, mu, theta0, phi0):
    """Third, independent check: DOP853 on eq stickEps0 from eq initStick with an event on Gamma_0."""
    d = coef(theta0, alpha, mu)
    v0 = 0.8
    for delta in (0.0, 0.4, 2 / math.sqrt(d["Sw"]), 4.0):
        lp = lam_plus(d["pp"], delta)
        w0 = -d["pp"] / d["qp"] * v0
        x0 = [w0 / lp, w0, phi0 - d["cp"] / d["qp"] * v0]
        def rhs(t, x):
            force = -x[0] - delta * x[1]
            return [x[1], d["Sw"] * force, d["Sphi"] * force]

        def ev(t, x):
            return -x[0] - delta * x[1]

        ev.terminal, ev.direction = True, -1
        sol = scipy.integrate.solve_ivp(rhs, (0, 100), x0, method="DOP853", events=ev,
                                        rtol=1e-12, atol=1e-14)
        y_s, w_s, phi_s = sol.y_events[0][0]
        ee = A.e(delta, theta0, alpha=alpha, mu=mu)
        assert w_s / v0 == pytest.approx(ee, rel=1e-8)
        assert y_s == pytest.approx(-delta * ee * v0, abs=1e-9)  # prop:stick: yhat(tau_s) = -delta e v0
        assert A.phi_after_iwc(theta0, phi0, v0, delta, alpha=alpha, mu=mu) == pytest.approx(phi_s, abs=1e-9)


@pytest.mark.parametrize("alpha,mu", CASES)
def test_e_positive_and_decreasing_in_delta(alpha, mu):
    th = interior(alpha, mu, 9)[None, :]
    de = np.concatenate([[0.0], np.logspace(-3, 2, 60)])[:, None]
    ee = A.e(de, th, alpha=alpha, mu=mu)
    assert np.all(ee > 0)
    assert np.all(np.diff(ee, axis=0) < 0)


# --------------------------------------------------------------- asymptotes
@pytest.mark.parametrize("alpha,mu,theta0", [(3.0, 1.4, 1.0), (3.0, 1.4, 1.2), (3.0, 3.0, 1.0),
                                             (2.0, 3.0, 0.7)])
def test_large_delta_error_order(alpha, mu, theta0):
    de = np.logspace(1, 3, 9)
    rel = np.abs(A.e(de, theta0, alpha=alpha, mu=mu) / A.e_large_delta(de, theta0, alpha=alpha, mu=mu) - 1)
    assert -2.3 < slope(de, rel) < -1.6  # O(delta^-2 ln delta)
    # the log factor is there: rel * delta^2 / ln(delta) stays bounded while rel * delta^2 grows
    assert np.all(np.diff(rel * de ** 2) > 0)
    assert np.ptp(rel * de ** 2 / np.log(de)) < np.max(rel * de ** 2 / np.log(de))


@pytest.mark.parametrize("alpha,mu,theta0", [(3.0, 1.4, 1.0), (3.0, 1.4, 1.2), (3.0, 3.0, 1.0),
                                             (2.0, 3.0, 0.7)])
def test_small_delta_error_order(alpha, mu, theta0):
    de = np.logspace(-4, -2, 5)
    ee = A.e(de, theta0, alpha=alpha, mu=mu)
    err2 = np.abs(ee - A.e_small_delta(de, theta0, alpha=alpha, mu=mu))
    err1 = np.abs(ee - A.e_zero(theta0, alpha=alpha, mu=mu))
    assert 1.8 < slope(de, err2) < 2.2  # two-term eq eDeltaSmall: O(delta^2)
    assert 0.9 < slope(de, err1) < 1.1  # one term only: O(delta)


@pytest.mark.parametrize("alpha,mu", CASES + [(5.0, 1.5)])
def test_large_delta_forms_agree(alpha, mu):
    th = interior(alpha, mu, 11)
    de = 7.0
    d = coef(th, alpha, mu)
    e_large_sw = -(d["Sw"] - d["pp"]) / (d["qp"] * d["Sw"]) * de ** -2  # eq eLarge
    rod = alpha * np.sin(2 * th) / (2 * (1 + alpha)) * de ** -2        # Discussion's eq eDeltaLarge
    np.testing.assert_allclose(A.e_large_delta(de, th, alpha=alpha, mu=mu), e_large_sw, rtol=1e-12)
    np.testing.assert_allclose(A.e_large_delta_rod(de, th, alpha=alpha, mu=mu), rod, rtol=1e-12)
    np.testing.assert_allclose(A.e_large_delta(de, th, alpha=alpha, mu=mu),
                               A.e_large_delta_rod(de, th, alpha=alpha, mu=mu), rtol=1e-12)


@pytest.mark.parametrize("alpha,mu", CASES)
def test_small_delta_forms_agree(alpha, mu):
    th = interior(alpha, mu, 11)
    d = coef(th, alpha, mu)
    p, q, sw = d["pp"], d["qp"], d["Sw"]
    e0_low = -np.sqrt(p * (p - sw)) / q                                   # eq eLow, leading term
    k_low = np.sqrt(sw) / 2 * (np.pi - np.arctan(np.sqrt(-sw / p)))
    s, c = np.sin(th), np.cos(th)
    e0_zero = np.sqrt(p / q * alpha * s * c / (1 + alpha * s * s))       # eq eDeltaZero, sin theta0
    np.testing.assert_allclose(A.e_zero(th, alpha=alpha, mu=mu), e0_low, rtol=1e-12)
    np.testing.assert_allclose(A.e_zero(th, alpha=alpha, mu=mu), e0_zero, rtol=1e-12)
    np.testing.assert_allclose(A.e_small_delta(0.0, th, alpha=alpha, mu=mu), e0_low, rtol=1e-12)
    np.testing.assert_allclose(A.e(0.0, th, alpha=alpha, mu=mu), e0_low, rtol=1e-12)
    np.testing.assert_allclose(A.e_small_delta(0.03, th, alpha=alpha, mu=mu),
                               e0_low * (1 - k_low * 0.03), rtol=1e-12)


# ------------------------------------------------------------- Theorem 1 rest
@pytest.mark.parametrize("alpha,mu", CASES)
def test_slip_compression_end_lies_on_unstable_manifold(alpha, mu):
    th = interior(alpha, mu, 5)[:, None]
    de = np.array([0.0, 1.0, 6.0])[None, :]
    phi0, v0 = 0.3, 1.7
    end = A.slip_compression_end(th, phi0, v0, de, alpha=alpha, mu=mu)
    d = coef(th, alpha, mu)
    lp = np.vectorize(lam_plus)(d["pp"], de)
    # gamma^u of eq unstableManifoldHaty, cut by Pi: v = 0
    np.testing.assert_allclose(end.w, lp * end.yhat, rtol=1e-12)
    np.testing.assert_allclose(v0 + d["qp"] / d["pp"] * lp * end.yhat, 0, atol=1e-12)
    np.testing.assert_allclose(end.phi, phi0 - d["cp"] / lp * (1 + de * lp) * end.yhat, rtol=1e-12)
    assert np.all(end.yhat < 0) and np.all(end.w < 0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        end.w = 0.0


def test_phi_after_iwc_follows_sticking_law():
    """phi' = (S_phi/S_w) w' while sticking: phi jumps by (S_phi/S_w)(e v0 - w_start)."""
    alpha, mu, phi0, v0 = 3.0, 3.0, 0.5, 1.3
    th = interior(alpha, mu, 6)
    for delta in (0.0, 1.0, 5.0):
        end = A.slip_compression_end(th, phi0, v0, delta, alpha=alpha, mu=mu)
        d = coef(th, alpha, mu)
        expect = end.phi + d["Sphi"] / d["Sw"] * (A.e(delta, th, alpha=alpha, mu=mu) * v0 - end.w)
        np.testing.assert_allclose(A.phi_after_iwc(th, phi0, v0, delta, alpha=alpha, mu=mu), expect,
                                   rtol=1e-12)
        # linear in v0
        dphi = A.phi_after_iwc(th, phi0, np.array([[1.0], [2.0]]), delta, alpha=alpha, mu=mu) - phi0
        np.testing.assert_allclose(dphi[1], 2 * dphi[0], rtol=1e-12)


def test_iwc_time_scale():
    eps = np.array([1e-2, 1e-3, 1e-5])
    for theta0, delta in ((1.0, 1.0), (0.7, 0.0), (1.2, 5.0)):
        T = A.iwc_time_scale(eps, theta0, delta)
        lp = lam_plus(coef(theta0, 3.0, 3.0)["pp"], delta)
        np.testing.assert_allclose(T * lp / (eps * np.log(1 / eps)), 1.0, rtol=1e-12)


# ---------------------------------------------------------------- Theorem 2
def test_w1_star_is_the_stable_manifold_of_C1():
    alpha, mu, theta0, phi0 = 3.0, 3.0, 0.9463, 1.6654  # the `video` grazing state
    for delta in (0.0, 1.0, 4.0):
        ws = A.w1_star(theta0, phi0, delta, alpha=alpha, mu=mu)
        assert ws < 0
        bb, p = -1 + phi0 ** 2 * math.sin(theta0), coef(theta0, alpha, mu)["pp"]
        J = np.array([[0.0, 1.0], [-p, -p * delta]])  # eq haty2 with F = -yhat1 - delta w1
        vec = np.array([-bb / p, ws])                 # (0, w1*) minus C1 = (b/p, 0)
        lm = min(np.roots([1.0, delta * p, p]).real)
        np.testing.assert_allclose(J @ vec, lm * vec, rtol=1e-12)
        # the separatrix: just below w1* the orbit is carried to yhat1 -> -inf (IWC),
        # just above it turns back to yhat1 > 0 (lift-off)
        tau = 15 / max(np.roots([1.0, delta * p, p]).real)
        for w10, sign in ((ws * (1 + 1e-4), -1), (ws * (1 - 1e-4), +1)):
            x = np.array([bb / p, 0.0]) + scipy.linalg.expm(J * tau) @ (np.array([0.0, w10]) - [bb / p, 0.0])
            assert np.sign(x[0]) == sign
