# SPDX-License-Identifier: BSD-2-Clause
"""Tests of painleve.theory.analytic against the paper's laws and independent computations.

Expected values are recomputed here from the paper's definitions (eq coeffs,
eq lambdapm, eq initStick, ...) or are laws (identities, orders of
convergence, eigenvector relations), never numbers copied from the module.
"""
import math

import numpy as np
import pytest

from helpers.paper_formulas import CASES, coef, interior, lam_plus, wedge
from painleve.theory import analytic as A


# ------------------------------------------------------------- coefficients
def test_coefficients_are_the_papers():
    th = np.linspace(0.05, 3.0, 17)[:, None]
    ph = np.linspace(-2, 2, 5)[None, :]
    for alpha, mu in CASES + [(1.0, 0.0)]:
        d = coef(th, alpha, mu)
        kw = dict(alpha=alpha, mu=mu)
        for f, key in ((A.q_plus, "qp"), (A.q_minus, "qm"), (A.p_plus, "pp"),
                       (A.p_minus, "pm"), (A.c_plus, "cp"), (A.c_minus, "cm")):
            np.testing.assert_allclose(f(th, **kw), d[key], rtol=1e-13, atol=1e-13)
        if mu == 0:
            continue  # q_+ = q_-: the Filippov combinations below are 0/0
        # the rod forms of eq Sw equal the general Filippov combinations
        np.testing.assert_allclose(A.S_w(th, alpha=alpha), d["Sw"], rtol=1e-12)
        np.testing.assert_allclose(A.S_phi(th, alpha=alpha), d["Sphi"], rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(A.a(th, ph), -ph ** 2 * np.cos(th))
    np.testing.assert_allclose(A.b(th, ph), -1 + ph ** 2 * np.sin(th))


def test_scalar_in_float_out_and_broadcasting():
    assert isinstance(A.e(1.0, 1.0), float)
    assert isinstance(A.p_plus(1.0), float)
    assert isinstance(A.quadrant(1.0, 0.5), str)
    lp, lm = A.lambda_pm(1.0, 1.0)
    assert isinstance(lp, float) and isinstance(lm, float)
    th = np.array([0.8, 1.0, 1.2])
    de = np.array([[0.0], [0.7], [5.0]])
    grid = A.e(de, th)
    assert grid.shape == (3, 3)
    for i in range(3):
        for j in range(3):
            assert grid[i, j] == pytest.approx(A.e(float(de[i, 0]), float(th[j])), rel=1e-14)
    al = np.array([[2.0], [3.0]])
    np.testing.assert_allclose(A.e(1.0, 1.0, alpha=al)[:, 0],
                               [A.e(1.0, 1.0, alpha=2.0), A.e(1.0, 1.0, alpha=3.0)], rtol=1e-14)


def test_video_figure_numbers():
    # figure `video`: theta ~ 0.9463, phi ~ 1.6654, mu = alpha = 3: b ~ 1.2500, p_+ ~ -2.243
    bv = A.b(0.9463, 1.6654)
    pv = A.p_plus(0.9463, alpha=3, mu=3)
    assert round(bv, 4) == 1.2500 or abs(bv - 1.25) < 1e-4
    assert round(pv, 3) == -2.243
    A.check_theorem2(0.9463, 1.6654, 1.0, alpha=3, mu=3)  # indeterminate quadrant
    assert A.quadrant(0.9463, 1.6654, alpha=3, mu=3) == "indeterminate"


# ---------------------------------------------------------- Painleve wedge
def test_mu_P():
    assert A.mu_P(3) == pytest.approx(4 / 3, rel=1e-15)
    for alpha in (0.5, 2.0, 3.0, 10.0):
        # mu_P is the smallest mu with min_theta p_+ < 0: just above it a wedge exists, below none
        mup = A.mu_P(alpha)
        ths = np.linspace(0.01, 1.56, 4001)
        assert coef(ths, alpha, mup * 1.001)["pp"].min() < 0
        assert coef(ths, alpha, mup * 0.999)["pp"].min() > 0


@pytest.mark.parametrize("alpha,mu", CASES)
def test_theta_1_2_are_zeros_of_p_plus(alpha, mu):
    t1, t2 = A.theta_1(alpha=alpha, mu=mu), A.theta_2(alpha=alpha, mu=mu)
    w1, w2 = wedge(alpha, mu)
    assert t1 == pytest.approx(w1, abs=1e-12) and t2 == pytest.approx(w2, abs=1e-12)
    assert abs(A.p_plus(t1, alpha=alpha, mu=mu)) < 1e-13
    assert abs(A.p_plus(t2, alpha=alpha, mu=mu)) < 1e-13
    assert np.all(A.p_plus(np.linspace(t1, t2, 50)[1:-1], alpha=alpha, mu=mu) < 0)


def test_wedge_values_of_docs_model_md():
    assert round(A.theta_1(alpha=3, mu=1.4), 4) == 0.9702
    assert round(A.theta_2(alpha=3, mu=1.4), 4) == 1.2209
    # docs/model.md §3: "wide wedge (0.4384, 1.454)"
    assert round(A.theta_1(alpha=3, mu=3), 4) == 0.4384
    assert round(A.theta_2(alpha=3, mu=3), 3) == 1.454
    th = np.linspace(0.9702, 1.2209, 200)[1:-1]
    assert np.max(-A.p_plus(th, alpha=3, mu=1.4)) <= 0.09  # "thin (|p_+| <= 0.09)"


def test_no_wedge_raises():
    for mu in (1.0, 4 / 3):
        with pytest.raises(A.HypothesisError, match="mu_P"):
            A.theta_1(alpha=3, mu=mu)
        with pytest.raises(ValueError, match="mu_P"):
            A.theta_2(alpha=3, mu=mu)


def test_quadrants_around_P():
    alpha, mu = 3.0, 1.4
    t1 = A.theta_1(alpha=alpha, mu=mu)
    phiP = math.sqrt(1 / math.sin(t1))  # P = (theta_1, sqrt(csc theta_1)), fig:GB
    h = 1e-3
    expect = {(+1, +1): "indeterminate", (-1, +1): "lift-off",
              (-1, -1): "slipping", (+1, -1): "inconsistent"}
    for (dt, dp), name in expect.items():
        th, ph = t1 + dt * h, phiP + dp * h
        assert A.quadrant(th, ph, alpha=alpha, mu=mu) == name
        bb, pp = -1 + ph ** 2 * math.sin(th), coef(th, alpha, mu)["pp"]  # the caption's signs
        assert {"indeterminate": bb > 0 > pp, "lift-off": bb > 0 and pp > 0,
                "slipping": bb < 0 < pp, "inconsistent": bb < 0 and pp < 0}[name]
    arr = A.quadrant(t1 + h * np.array([1, -1, -1, 1]), phiP + h * np.array([1, 1, -1, -1]),
                     alpha=alpha, mu=mu)
    assert list(arr) == ["indeterminate", "lift-off", "slipping", "inconsistent"]


def test_fmu_default_state_is_a_theorem1_case():
    A.check_theorem1(1.0, 0.5, 1.0, alpha=3, mu=3, delta=1.0)
    assert A.quadrant(1.0, 0.5) == "inconsistent"


# ------------------------------------------------------------- eigenvalues
@pytest.mark.parametrize("alpha,mu", CASES)
def test_lambda_pm(alpha, mu):
    th = interior(alpha, mu, 7)[:, None]
    de = np.array([0.0, 0.1, 1.0, 10.0, 1e3])[None, :]
    lp, lm = A.lambda_pm(th, de, alpha=alpha, mu=mu)
    p = coef(th, alpha, mu)["pp"]
    for lam in (lp, lm):  # eq lambdapm2, residual relative to the size of its terms
        resid = lam ** 2 + p * (1 + de * lam)
        assert np.all(np.abs(resid) <= 1e-13 * (lam ** 2 + np.abs(p) + np.abs(p * de * lam)))
    assert np.all(lm < 0) and np.all(lp > 0)
    np.testing.assert_allclose(lp * lm, np.broadcast_to(p, lp.shape), rtol=1e-13)
    np.testing.assert_allclose(lp + lm, -de * p + 0 * lp, rtol=1e-12, atol=1e-14)
    assert A.lambda_pm(float(th[3, 0]), 0.7, alpha=alpha, mu=mu)[0] == pytest.approx(
        lam_plus(float(p[3, 0]), 0.7), rel=1e-12)


# --------------------------------------------------------------- hypotheses
def test_hypothesis_error_p_plus():
    for f in (lambda: A.e(1.0, 1.3, alpha=3, mu=1.4),
              lambda: A.e_integrated(1.0, 1.3, alpha=3, mu=1.4),
              lambda: A.phi_after_iwc(1.3, 0.1, 1.0, 1.0, alpha=3, mu=1.4),
              lambda: A.slip_compression_end(1.3, 0.1, 1.0, 1.0, alpha=3, mu=1.4),
              lambda: A.lambda_pm(1.3, 1.0, alpha=3, mu=1.4),
              lambda: A.check_theorem1(1.3, 0.1, 1.0, alpha=3, mu=1.4)):
        with pytest.raises(A.HypothesisError) as exc:
            f()
        msg = str(exc.value)
        assert "p_+(theta0) < 0" in msg and "(0.9702, 1.2209)" in msg and "p_+(1.3)" in msg
        assert isinstance(exc.value, ValueError)
    with pytest.raises(A.HypothesisError, match="mu_P"):
        A.e(1.0, 1.0, alpha=3, mu=1.0)  # no wedge at all
    with pytest.raises(A.HypothesisError, match=r"at element \(0, 2\)"):
        A.e(1.0, np.array([[1.0, 1.1, 1.3]]), alpha=3, mu=1.4)


def test_hypothesis_error_q_plus():
    # theta0 = 0.2, mu = 0.1: q_+ = alpha sin cos - mu (1 + alpha sin^2) > 0
    assert coef(0.2, 3.0, 0.1)["qp"] > 0
    with pytest.raises(A.HypothesisError, match=r"q_\+\(theta0\) < 0 < q_-\(theta0\)") as exc:
        A.e(0.5, 0.2, alpha=3, mu=0.1)
    assert "q_+(theta0) < 0 < q_-(theta0)" in exc.value.hypotheses


def test_hypothesis_error_v0_delta_epsilon_params():
    for v0 in (0.0, -1.0):
        with pytest.raises(A.HypothesisError, match="v0 > 0"):
            A.phi_after_iwc(1.0, 0.5, v0, 1.0)
        with pytest.raises(A.HypothesisError, match="v0 > 0"):
            A.slip_compression_end(1.0, 0.5, v0, 1.0)
    with pytest.raises(A.HypothesisError, match=r"v0 > 0; got v0 = -1 at element \(1,\)"):
        A.check_theorem1(1.0, 0.5, np.array([1.0, -1.0]))
    with pytest.raises(A.HypothesisError, match="delta >= 0"):
        A.e(-0.1, 1.0)
    with pytest.raises(A.HypothesisError, match="delta > 0"):
        A.e_large_delta(0.0, 1.0)
    with pytest.raises(A.HypothesisError, match="epsilon"):
        A.iwc_time_scale(0.0, 1.0, 1.0)
    with pytest.raises(A.HypothesisError, match="alpha > 0"):
        A.p_plus(1.0, alpha=0.0)
    with pytest.raises(A.HypothesisError, match="mu >= 0"):
        A.e(1.0, 1.0, mu=-1.0)


def test_hypothesis_error_b_sign_and_a():
    # (1.0, 0.5) is inconsistent (b < 0); (1.0, 2.0) indeterminate (b > 0)
    with pytest.raises(A.HypothesisError, match=r"Theorem 2 needs b\(theta0, phi0\) > 0"):
        A.w1_star(1.0, 0.5, 1.0)
    with pytest.raises(A.HypothesisError, match=r"Theorem 2 needs b\(theta0, phi0\) > 0"):
        A.check_theorem2(1.0, 0.5, 1.0)
    with pytest.raises(A.HypothesisError, match=r"Theorem 1 needs b\(theta0, phi0\) < 0"):
        A.check_theorem1(1.0, 2.0, 1.0)
    with pytest.raises(A.HypothesisError, match=r"a\(theta0, phi0\) != 0"):
        A.check_theorem1(1.0, 0.0, 1.0)  # phi0 = 0 makes a = 0
    A.check_theorem1(1.0, 0.5, 1.0)
    A.check_theorem2(1.0, 2.0, 1.0, delta=1.0)
