# SPDX-License-Identifier: BSD-2-Clause
"""Tests of painleve.theory.general, the paper's results for any body from its coefficients.

The rod is a special case: its coefficients written out again (helpers.paper_formulas.coef)
must give, through the general path, the rod's own closed forms (analytic: eq eDeltaZero,
the rod form of eq eDeltaLarge, eq Sw's rod form, eq w1star, Theorem 1's phi). For bodies
that are not the rod (coefficient sets that no rod has), the closed form eq eGeneral is checked
against an independent integration of the fast system in time and the asymptotes against their
orders."""
import numpy as np
import pytest
import scipy.integrate

from helpers.paper_formulas import CASES, coef, interior, slope
from painleve.theory import analytic as A
from painleve.theory import general as G
from painleve.theory.hypotheses import HypothesisError


def rod(theta, phi, alpha, mu):
    d = coef(theta, alpha, mu)
    return G.Coefficients(a=-phi ** 2 * np.cos(theta), b=-1 + phi ** 2 * np.sin(theta), p_plus=d["pp"],
                          p_minus=d["pm"], q_plus=d["qp"], q_minus=d["qm"])


def from_delassus(g_tt, g_tn, g_nn, mu):
    """(p_+, p_-, q_+, q_-) of a body whose contact point has the inverse inertia (Delassus matrix)
    [[g_tt, g_tn], [g_tn, g_nn]] (positive definite): q_s = g_tn - s mu g_tt, p_s = g_nn - s mu g_tn
    (docs/general_body_theory.md)."""
    return g_nn - mu * g_tn, g_nn + mu * g_tn, g_tn - mu * g_tt, g_tn + mu * g_tt


# Bodies that are not rods (a rod's Delassus matrix has determinant 1 + alpha and g_tt + g_nn = 2 + alpha),
# each in the paradox: p_+ < 0, q_+ < 0 < q_-.
OTHERS = [from_delassus(*x) for x in [(1.0, 0.9, 1.0, 2.0), (2.0, 1.0, 0.8, 1.5), (0.5, 1.2, 3.0, 4.0),
                                      (1.0, 0.3, 0.2, 1.0)]]


def test_S_w_is_the_normal_inverse_inertia_with_the_tangent_stuck():
    for g in [(1.0, 0.9, 1.0), (2.0, 1.0, 0.8), (0.5, 1.2, 3.0)]:
        pp, pm, qp, qm = from_delassus(*g, mu=1.7)
        sw = G.filippov_S_w(G.Coefficients(0, 0, pp, pm, qp, qm))
        assert sw == pytest.approx(1 / np.linalg.inv([[g[0], g[1]], [g[1], g[2]]])[1, 1], rel=1e-13)


def other(pp, pm, qp, qm, a=-0.5, b=-1.0):
    return G.Coefficients(a=a, b=b, p_plus=pp, p_minus=pm, q_plus=qp, q_minus=qm)


@pytest.mark.parametrize("alpha,mu", CASES)
def test_the_general_path_reproduces_the_rods_closed_forms(alpha, mu):
    th = interior(alpha, mu, 7)
    co = rod(th, 0.3, alpha, mu)
    np.testing.assert_allclose(co.S_w, (1 + alpha) / (1 + alpha * np.sin(th) ** 2), rtol=1e-12)  # eq Sw, rod form
    np.testing.assert_allclose(G.e_zero(co), A.e_zero(th, alpha=alpha, mu=mu), rtol=1e-12)          # eq eDeltaZero
    np.testing.assert_allclose(G.e_large_delta(7.0, co), A.e_large_delta_rod(7.0, th, alpha=alpha, mu=mu),
                               rtol=1e-12)
    for delta in (0.0, 0.3, 2 / np.sqrt(co.S_w[3]), 1.0, 6.0):
        np.testing.assert_allclose(G.e(delta, co), A.e(delta, th, alpha=alpha, mu=mu), rtol=1e-13)
    assert list(G.quadrant(co)) == list(A.quadrant(th, 0.3, alpha=alpha, mu=mu))
    # Theorem 1's phi: the scalar rod's c_+ and S_phi as one-coordinate vectors
    d = coef(th, alpha, mu)
    jump = G.velocity_jump(1.0, co, d["cp"][:, None], d["Sphi"][:, None], v0=0.8)[:, 0]
    for k, t in enumerate(th):
        assert 0.2 + jump[k] == pytest.approx(A.phi_after_iwc(t, 0.2, 0.8, 1.0, alpha=alpha, mu=mu), rel=1e-12)


def test_w1_star_matches_the_rods():
    th, ph = 0.9463, 1.6654  # figure `video`'s grazing state, indeterminate
    co = rod(th, ph, 3.0, 3.0)
    assert G.w1_star(1.0, co) == pytest.approx(A.w1_star(th, ph, 1.0, alpha=3, mu=3), rel=1e-13)
    with pytest.raises(HypothesisError, match="b > 0"):
        G.w1_star(1.0, rod(th, 0.3, 3.0, 3.0))


def fast_e(delta, pp, qp, sw):
    """e by the fast system in time from the floor: slip (yhat, w, v) until v = 0, then stick
    until F_N = -yhat - delta w = 0 (solve_ivp's event location), v0 = 1."""
    def slip(t, z):
        f = -z[0] - delta * z[1]
        return [z[1], pp * f, qp * f]
    stopped = lambda t, z: z[2]  # noqa: E731
    stopped.terminal, stopped.direction = True, -1
    one = scipy.integrate.solve_ivp(slip, (0, 1e3), [0.0, -1e-9, 1.0], events=stopped, method="LSODA",
                                    rtol=1e-12, atol=1e-15)
    yh, w, _ = one.y_events[0][0]

    def stick(t, z):
        return [z[1], sw * (-z[0] - delta * z[1])]
    lift = lambda t, z: -z[0] - delta * z[1]  # noqa: E731
    lift.terminal, lift.direction = True, -1
    two = scipy.integrate.solve_ivp(stick, (0, 1e3), [yh, w], events=lift, method="LSODA", rtol=1e-12, atol=1e-15)
    return two.y_events[0][0][1]


@pytest.mark.parametrize("pp,pm,qp,qm", OTHERS)
def test_e_of_a_body_that_is_not_a_rod_against_the_fast_system(pp, pm, qp, qm):
    co = other(pp, pm, qp, qm)
    crit = 2 / np.sqrt(float(co.S_w))
    for delta in (0.0, 0.4, crit, 1.7, 5.0):
        closed = G.e(delta, co)
        assert closed == pytest.approx(G.e_integrated(delta, co), rel=1e-9)
        assert closed == pytest.approx(fast_e(delta, pp, qp, float(co.S_w)), rel=1e-6)
    assert G.e(0.0, co) == pytest.approx(G.e_zero(co), rel=1e-12)


@pytest.mark.parametrize("pp,pm,qp,qm", OTHERS)
def test_asymptotes_of_a_body_that_is_not_a_rod(pp, pm, qp, qm):
    co = other(pp, pm, qp, qm)
    big = np.array([40.0, 80.0, 160.0, 320.0])
    rel = np.abs(G.e(big, co) / G.e_large_delta(big, co) - 1)
    assert rel[-1] < 0.05 and slope(big, rel) < -1.5          # O(delta^-2 ln delta)
    small = np.array([1e-3, 2e-3, 4e-3, 8e-3])
    err = np.abs(G.e(small, co) - G.e_small_delta(small, co))
    assert slope(small, err) == pytest.approx(2.0, abs=0.2)   # O(delta^2)


def test_hypotheses_and_the_paradox_test():
    good = other(*OTHERS[0])
    G.check(good, 1, delta=1.0, v0=1.0)
    assert G.paradox(good) and G.quadrant(good) == "inconsistent" and G.theorem_of(good) == 1
    up = other(*OTHERS[0], b=0.5)
    assert G.quadrant(up) == "indeterminate" and G.w1_star(1.0, up) < 0
    assert G.quadrant(other(0.5, 2.0, -0.2, 2.0, b=0.5)) == "lift-off"
    assert not G.paradox(other(0.5, 2.0, -0.2, 2.0))
    with pytest.raises(HypothesisError, match=r"p_\+ < 0"):
        G.e(1.0, other(0.5, 2.0, -0.2, 2.0))
    with pytest.raises(HypothesisError, match=r"q_\+ < 0 < q_-"):
        G.check(other(-0.3, 2.0, 0.5, 2.5), 1)
    with pytest.raises(HypothesisError, match="a != 0"):
        G.check(other(*OTHERS[0], a=0.0), 1)
    with pytest.raises(HypothesisError, match="delta >= 0"):
        G.e(-1.0, good)
    lp, lm = G.lambda_pm(good, 1.0)
    np.testing.assert_allclose(sorted([lp, lm]), sorted(np.roots([1, OTHERS[0][0], OTHERS[0][0]]).real), rtol=1e-12)
    assert G.iwc_time_scale(1e-4, 1.0, good) == pytest.approx(1e-4 * np.log(1e4) / lp)


def test_coefficients_from_a_mapping_take_the_fmus_S_w_or_eq_Sw():
    values = dict(a=-0.5, b=-1.0, p_plus=-0.3, p_minus=2.0, q_plus=-1.5, q_minus=2.5)
    assert G.Coefficients.of(values).S_w == pytest.approx((2.5 * -0.3 + 1.5 * 2.0) / 4.0)  # eq Sw
    assert G.Coefficients.of(dict(values, S_w=0.9)).S_w == 0.9
    yh, w = G.stick_start(G.Coefficients.of(values), 1.0, v0=2.0)
    assert w == pytest.approx(-(-0.3) * 2.0 / -1.5) and yh == pytest.approx(w / G.lambda_pm(G.Coefficients.of(values), 1.0)[0])
