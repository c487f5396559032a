# SPDX-License-Identifier: BSD-2-Clause
"""The solve_ivp reference's integrator (painleve.experiments.reference) piece by piece, and
its refusals: sticking friction against slip friction at the folds, the coefficients against
analytic.py's, the Jacobian against the right-hand side, a grazing dip caught within one step,
the run's end; unknown methods, cases outside the theorems or the model, bad arguments. Its
runs against the paper and the FMU are in test_reference.py.
"""
import math

import numpy as np
import pytest
import scipy.optimize

from painleve.theory import analytic as an
from painleve.experiments.case import Case
from painleve.experiments.reference import (FLIGHT, METHODS, SLIP_BACKWARD, SLIP_FORWARD, STICK, ReferenceSimulationError,
                                Rod, default_rtol, run_reference, simulate)


# ----------------------------------------------------------- the integrator
@pytest.mark.parametrize("theta", [0.7, 1.3, 2.0, 2.5])    # a < 0: backward fold; a > 0: forward fold
def test_sticking_friction_meets_the_slip_friction_at_the_folds(theta):
    # docs/model.md: F_T = s mu F_N slipping, (a + alpha sin cos F_N)/(1 + alpha sin^2) sticking;
    # on the fold a + q_s F_N = 0 the two are equal, and inside the cone |F_T| < mu F_N.
    rod, phi, eps = Rod(), 0.9, 1e-3
    k = rod.coefficients(theta, phi)
    folds = [(s, q) for s, q in ((+1, k["q_plus"]), (-1, k["q_minus"])) if -k["a"] / q > 0]
    assert len(folds) == 1
    for s, q in folds:
        F = -k["a"] / q                                          # the fold's normal force
        x = np.array([0.0, 0.0, -eps * eps * F, 0.0, theta, phi])   # w = 0: F_N = -y/eps^2
        assert rod.friction_force(STICK, x) == pytest.approx(s * rod.mu * F, rel=1e-12)
        x[2] *= 1 + 1e-3 if (s > 0) == (q < 0) else 1 - 1e-3    # a step into the cone
        assert rod.at_rest(x) == STICK
        assert abs(rod.friction_force(STICK, x)) < rod.mu * rod.normal_force(STICK, x)


def test_coefficients_are_analytic_pys():
    rod = Rod(alpha=2.0, mu=1.7)
    for th in np.linspace(0.1, 3.0, 7):
        for ph in (-1.3, 0.0, 0.7):
            k = rod.coefficients(th, ph)
            kw = dict(alpha=2.0, mu=1.7)
            assert k["a"] == pytest.approx(an.a(th, ph)) and k["b"] == pytest.approx(an.b(th, ph))
            for name in ("q_plus", "q_minus", "p_plus", "p_minus", "c_plus", "c_minus"):
                assert k[name] == pytest.approx(getattr(an, name)(th, **kw), abs=1e-14), name
            assert k["S_w"] == pytest.approx(an.S_w(th, alpha=2.0))
            assert k["S_phi"] == pytest.approx(an.S_phi(th, alpha=2.0), abs=1e-14)


@pytest.mark.parametrize("filippov", ["paper", "exact"])
@pytest.mark.parametrize("mode", [FLIGHT, SLIP_FORWARD, SLIP_BACKWARD, STICK])
def test_jacobian_is_the_derivative_of_the_right_hand_side(mode, filippov):
    rod = Rod(alpha=3.0, mu=3.0, delta=1.0, epsilon=1e-2, filippov=filippov)
    f, J = rod.rhs(mode), rod.jacobian(mode)
    x = np.array([0.1, 0.4, -2e-5, -3e-3, 1.1, 0.8])
    h = 1e-6 * np.array([1, 1, rod.epsilon ** 2, rod.epsilon, 1, 1])
    fd = np.column_stack([(f(0, x + e) - f(0, x - e)) / (2 * e[j]) for j, e in enumerate(np.diag(h))])
    np.testing.assert_allclose(J(0, x), fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max())


@pytest.mark.parametrize("method", METHODS)
def test_a_grazing_dip_inside_one_step_is_caught_at_the_closed_form_touch_down(method):
    # Free flight from above the floor with b > 0 (the end decelerates): y dips to about
    # -1e-4 and would come back up within one step of a high-order method.
    th, ph, y0, w0 = 0.9463, 1.6654, 9e-4, -0.05     # the video's rod (fig_video.png)
    run = simulate(Rod(epsilon=1e-3), [0, 1, y0, w0, th, ph], 0.2, method=method, rtol=1e-9)
    mode, _, t_touch, name = run.segments[0]
    assert (mode, name) == (FLIGHT, "touch-down") and run.modes[1] == SLIP_FORWARD

    def height(s):   # centre of mass in free fall, uniform spin
        return y0 + np.sin(th) + (w0 + ph * np.cos(th)) * s - s * s / 2 - np.sin(th + ph * s)
    s = np.linspace(0, 0.1, 10001)
    first = np.flatnonzero(height(s) < 0)[0]
    exact = scipy.optimize.brentq(height, s[first - 1], s[first], xtol=1e-15)
    assert t_touch == pytest.approx(exact, rel=1e-6)


def test_the_run_ends_at_the_return_with_default_tolerances_of_the_harness():
    case = Case(epsilon=1e-4)
    ref = run_reference(case, "DOP853")
    assert ref.solver_stats["relative_tolerance"] == default_rtol(case.epsilon) == 1e-6
    stats = ref.solver_stats
    assert stats["nevents"] == len(stats["modes"]) - 1 and stats["nsteps"] > 0 and stats["nfev"] > stats["nsteps"]
    # back on the floor moving up, within the IWC's time scale
    assert ref.w > 0 and ref.t_return < 20 * an.predict(case).time_scale


# ----------------------------------------------------------------- bad input
def test_an_unknown_method_is_refused_naming_the_allowed_ones():
    with pytest.raises(ValueError, match="LSODA, DOP853, Radau, BDF"):
        run_reference(Case(), "RK45")


@pytest.mark.parametrize("case, words", [
    (dict(theta0=1.5), "p_+"),                           # outside the Painleve wedge
    (dict(v0=-1.0), "v0"),
    (dict(theta0=0.9463, phi0=1.6654, w10=0.5), "w10"),  # Theorem 2 needs the rod moving down
    (dict(epsilon=0.0), "epsilon"),
])
def test_a_case_outside_the_theorems_is_refused_saying_why(case, words):
    with pytest.raises(an.HypothesisError, match=words):
        run_reference(Case(**case))


@pytest.mark.parametrize("kwargs, words", [
    (dict(alpha=0.0), "alpha"), (dict(mu=-1.0), "mu"), (dict(delta=math.nan), "delta"),
    (dict(epsilon=-1e-3), "epsilon"), (dict(filippov="smooth"), "paper, exact"),
])
def test_a_rod_outside_the_model_is_refused(kwargs, words):
    with pytest.raises(ValueError, match=words):
        Rod(**kwargs)


@pytest.mark.parametrize("kwargs, words", [
    (dict(x0=[0, 1, 0]), "6 finite"), (dict(x0=[0, 1, 0, math.inf, 1, 0.5]), "6 finite"),
    (dict(t_end=-1.0), "t_end"), (dict(rtol=0.0), "rtol"), (dict(method="Euler"), "LSODA"),
])
def test_simulate_refuses_bad_arguments(kwargs, words):
    args = dict(x0=[0, 1, 0, 0, 1.0, 0.5], t_end=0.01) | kwargs
    with pytest.raises(ValueError, match=words):
        simulate(Rod(), args.pop("x0"), args.pop("t_end"), **args)


def test_a_case_outside_the_asymptotic_regime_fails_as_on_the_fmu():
    # eps delta = 0.1: the rod sticks quasi-statically, rotates through the floor, slips and sticks
    # again and does not come back up within the horizon (test_theorems_on_fmu.py: the FMU neither)
    with pytest.raises(ReferenceSimulationError, match="did not return to y = 0 within"):
        run_reference(Case(theta0=0.5908, delta=10.0, epsilon=1e-2), "DOP853")
