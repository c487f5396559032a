"""Tests of painleve.theory.analytic against the paper's laws and independent computations.

Expected values are recomputed here from the paper's definitions (eq coeffs,
eq lambdapm, eq initStick, ...) or are laws (identities, orders of
convergence, eigenvector relations), never numbers copied from the module.
"""
import dataclasses
import math

import numpy as np
import pytest
import scipy.integrate
import scipy.linalg
import scipy.optimize

from painleve.theory import analytic as A

CASES = [(3.0, 3.0), (3.0, 1.4), (2.0, 3.0)]  # (alpha, mu) with a Painleve wedge


# ------------------------------------------------ independent reimplementation
def coef(theta, alpha, mu):
    """The paper's eq coeffs and eq Sw, written out again."""
    s, c = np.sin(theta), np.cos(theta)
    d = dict(qp=alpha * s * c - mu * (1 + alpha * s * s), qm=alpha * s * c + mu * (1 + alpha * s * s),
             pp=1 + alpha * c * c - mu * alpha * s * c, pm=1 + alpha * c * c + mu * alpha * s * c,
             cp=-alpha * (c - mu * s), cm=-alpha * (c + mu * s))
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 when mu = 0
        d["Sw"] = (d["qm"] * d["pp"] - d["qp"] * d["pm"]) / (d["qm"] - d["qp"])  # general form of eq Sw
        d["Sphi"] = (d["qm"] * d["cp"] - d["qp"] * d["cm"]) / (d["qm"] - d["qp"])
    return d


def lam_plus(p, delta):
    """Positive root of lambda^2 + delta p lambda + p = 0 (eq lambdapm2), via numpy.roots."""
    return max(np.roots([1.0, delta * p, p]).real)


def wedge(alpha, mu):
    """Zeros of p_+ on (0, pi/2) found by bracketing, independent of eq thetacrit."""
    pp = lambda t: coef(t, alpha, mu)["pp"]  # noqa: E731
    tmin = scipy.optimize.minimize_scalar(pp, bounds=(0.01, 1.56), method="bounded").x
    return (scipy.optimize.brentq(pp, 1e-6, tmin, xtol=1e-15),
            scipy.optimize.brentq(pp, tmin, np.pi / 2 - 1e-9, xtol=1e-15))


def interior(alpha, mu, n):
    t1, t2 = wedge(alpha, mu)
    return np.linspace(t1, t2, n + 2)[1:-1]


def slope(x, y):
    return np.polyfit(np.log(x), np.log(y), 1)[0]


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
