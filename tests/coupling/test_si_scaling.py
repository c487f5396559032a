# SPDX-License-Identifier: BSD-2-Clause
"""painleve.coupling.si: the SI rod's parameters and starts in the paper's units and back
(docs/si_model.md §5, §7), checked against numbers worked by hand from the definitions
alpha = m l^2/J, epsilon = sqrt(m g/(k l)), delta = c/sqrt(m k), T = sqrt(l/g)."""
import math
from dataclasses import replace

import numpy as np
import pytest

from painleve.theory import analytic as an
from painleve.coupling import si
from painleve.experiments.case import Case


def test_the_default_rod_is_a_uniform_rod_in_the_papers_regime():
    rod = si.SIRod()
    assert rod.alpha == pytest.approx(3.0, rel=1e-15)                    # J = m l^2/3
    assert rod.epsilon == pytest.approx(math.sqrt(9.81e-7), rel=1e-15)    # 1 * 9.81/(2e7 * 0.5)
    assert rod.delta == pytest.approx(4500 / math.sqrt(2e7), rel=1e-15)
    assert rod.time_scale == pytest.approx(math.sqrt(0.5 / 9.81), rel=1e-15)
    assert rod.speed_scale * rod.time_scale == pytest.approx(rod.l, rel=1e-15)


def test_the_default_start_is_a_theorem1_case():
    case = si.case_of(si.SIRod(), si.SIState())
    assert case.v0 == pytest.approx(2 / math.sqrt(9.81 * 0.5), rel=1e-15)
    assert case.phi0 == pytest.approx(2 * math.sqrt(0.5 / 9.81), rel=1e-15)
    assert an.quadrant(case.theta0, case.phi0, alpha=case.alpha, mu=case.mu) == "inconsistent"
    case.check()


@pytest.mark.parametrize("m, l, g", [(1.0, 0.5, 9.81), (0.2, 0.05, 9.81), (30.0, 2.0, 1.62)])
def test_si_of_then_case_of_is_the_identity(m, l, g):
    case = Case(theta0=0.9, phi0=0.7, v0=1.3, delta=2.5, epsilon=1e-5, w10=-0.4, alpha=2.0, mu=3.5)
    floor = si.Floor(y0=0.3, w=-0.2, v=1.7)
    rod, state = si.si_of(case, m=m, l=l, g=g, floor=floor)
    assert (rod.m, rod.l, rod.g) == (m, l, g)
    assert rod.k == pytest.approx(m * g / (l * 1e-10), rel=1e-14)        # eps^2 = m g/(k l)
    assert rod.J == pytest.approx(m * l ** 2 / 2, rel=1e-14)
    assert state.v - floor.v == pytest.approx(1.3 * math.sqrt(g * l), rel=1e-14)
    assert state.w - floor.w == pytest.approx(-0.4e-5 * math.sqrt(g * l), rel=1e-9)
    back = si.case_of(rod, state, floor)
    for name in ("theta0", "phi0", "v0", "delta", "epsilon", "w10", "alpha", "mu"):
        assert getattr(back, name) == pytest.approx(getattr(case, name), rel=1e-9), name


def test_a_case_starts_on_the_floor():
    with pytest.raises(ValueError, match="on the floor"):
        si.case_of(si.SIRod(), si.SIState(y=1e-3))


def test_to_paper_scales_a_trajectory_relative_to_the_floor():
    rod, floor = si.SIRod(), si.Floor(y0=0.1, w=0.5, v=-1.0)
    T, V = rod.time_scale, rod.speed_scale
    dtype = [(n, float) for n in ("time", "x", "v", "y", "w", "theta", "phi", "F_N", "F_T")] + [("mode", int)]
    r = np.array([(2 * T, 3.0, 4.0, 0.1 + 0.5 * 2 * T + 0.25, 0.5 + V, 0.7, 1 / T, 9.81, -4.905, -1)], dtype=dtype)
    p = si.to_paper(rod, r, floor)[0]
    assert p["time"] == pytest.approx(2.0)
    assert p["x"] == pytest.approx((3.0 + 2 * T) / 0.5)        # x - v_floor t, in l
    assert p["v"] == pytest.approx(5.0 / V)
    assert p["y"] == pytest.approx(0.5)                          # the gap 0.25 m in l = 0.5 m
    assert p["w"] == pytest.approx(1.0)
    assert (p["theta"], p["phi"], p["F_N"], p["F_T"], p["mode"]) == pytest.approx((0.7, 1.0, 1.0, -0.5, -1))


def test_predict_in_si_is_the_papers_prediction_in_si_units():
    rod, state, floor = si.SIRod(c=9000.0), si.SIState(v=3.0, w=0.25, y=0.1), si.Floor(y0=0.1, w=0.25, v=1.0)
    p, case = si.predict(rod, state, floor), si.case_of(rod, state, floor)
    paper = an.predict(case)
    assert p.theorem == paper.theorem == 1
    assert p.e == pytest.approx(paper.e, rel=1e-14)
    assert p.w == pytest.approx(0.25 + paper.e * 2.0, rel=1e-14)                 # w_floor + e (v - v_floor)
    assert p.phi == pytest.approx(paper.phi / rod.time_scale, rel=1e-14)
    assert p.duration == pytest.approx(paper.time_scale * rod.time_scale, rel=1e-12)


def test_loads_move_b_and_with_it_the_theorem():
    rod, state = si.SIRod(), si.SIState()
    phi_hat = state.phi * rod.time_scale
    b0 = -1 + phi_hat ** 2 * math.sin(1.0)
    # F_y = m g cancels gravity in b; a clockwise torque tau removes alpha cos(theta) tau/(m g l) more
    lifted = si.predict(rod, state, loads=si.Loads(F_y=rod.m * rod.g, tau=0.1))
    assert lifted.b == pytest.approx(b0 + 1 - 3 * math.cos(1.0) * 0.1 / rod.energy_scale, rel=1e-14)
    assert lifted.theorem == 2
    case = replace(si.case_of(rod, state), phi0=math.sqrt((1 + lifted.b) / math.sin(1.0)))   # unloaded b = lifted.b
    assert lifted.w1_star == pytest.approx(an.w1_star(case.theta0, case.phi0, case.delta) * rod.epsilon *
                                           rod.speed_scale, rel=1e-12)
    assert lifted.e == pytest.approx(si.predict(rod, state).e, rel=1e-15)          # e: geometry and delta only


def test_predict_refuses_a_start_outside_the_wedge():
    with pytest.raises(an.HypothesisError, match="p_\\+"):
        si.predict(si.SIRod(), si.SIState(theta=1.5))
