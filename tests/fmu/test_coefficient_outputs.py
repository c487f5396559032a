# SPDX-License-Identifier: BSD-2-Clause
"""The coefficient outputs a, b, p_plus, p_minus, q_plus, q_minus, S_w of PainleveRod and
PainleveRodSI at random states, against the paper's closed forms (eq coeffs,
eq Sw: tests/helpers/paper_formulas.py), a second derivation from the mass matrix and the
contact point's Jacobians (tests/helpers/delassus.py), and the kinematics of the contact end
(a, b are its accelerations with no contact force: the rod's centre of mass falls freely,
the torque turns it)."""
import numpy as np
import pytest
from fmpy import extract, instantiate_fmu, read_model_description

from helpers import delassus
from helpers.paper_formulas import coef

NAMES = ("a", "b", "p_plus", "p_minus", "q_plus", "q_minus", "S_w")
RNG = np.random.default_rng(27)


class Instance:
    def __init__(self, path):
        self.md = read_model_description(path)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.fmu = instantiate_fmu(extract(path), self.md, fmi_type="ModelExchange")

    def at(self, start, inputs=None):
        """Values of NAMES after initialization from `start` (parameters, states) and `inputs`."""
        self.fmu.reset()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.setReal([self.vr[k] for k in start], list(start.values()))
        self.fmu.enterInitializationMode()
        if inputs:
            self.fmu.setReal([self.vr[k] for k in inputs], list(inputs.values()))
        self.fmu.exitInitializationMode()
        return dict(zip(NAMES, self.fmu.getReal([self.vr[k] for k in NAMES])))


@pytest.fixture(scope="module")
def rod(fmu_path):
    return Instance(fmu_path)


@pytest.fixture(scope="module")
def si_rod(si_fmu_path):
    return Instance(si_fmu_path)


def kinematic_a_b(theta, phi, alpha, f_x=0.0, f_y=0.0, tau=0.0):
    """The contact end (X + cos theta, Y - sin theta) accelerated with no contact force:
    X'' = f_x, Y'' = -1 + f_y, theta'' = alpha tau (scaled units)."""
    s, c = np.sin(theta), np.cos(theta)
    return f_x - s * alpha * tau - c * phi ** 2, -1 + f_y - c * alpha * tau + s * phi ** 2


@pytest.mark.parametrize("k", range(8))
def test_rod_coefficients_are_the_papers_at_random_states(rod, k):
    alpha, mu = RNG.uniform(0.5, 6), RNG.uniform(0, 4)
    theta, phi = RNG.uniform(-np.pi, np.pi), RNG.uniform(-3, 3)
    # in flight, in contact (slipping either way): the coefficients are the body's, not the mode's
    y, v = [(0.5, 1.0), (-1e-5, 0.7), (-1e-5, -0.7), (1e-3, 0.0)][k % 4]
    got = rod.at(dict(alpha=alpha, mu=mu, theta=theta, phi=phi, y=y, v=v, w=0.0))
    paper = coef(theta, alpha, mu)
    second = delassus.rod(theta, alpha, mu)
    a, b = kinematic_a_b(theta, phi, alpha)
    expected = dict(a=a, b=b, p_plus=paper["pp"], p_minus=paper["pm"], q_plus=paper["qp"], q_minus=paper["qm"],
                    S_w=(1 + alpha) / (1 + alpha * np.sin(theta) ** 2))
    for name in NAMES:
        assert got[name] == pytest.approx(expected[name], rel=1e-12, abs=1e-12), name
        if name in second:
            assert got[name] == pytest.approx(second[name], rel=1e-10, abs=1e-12), name
    if mu > 0:  # the paper's general form of eq Sw
        assert got["S_w"] == pytest.approx(paper["Sw"], rel=1e-10)


@pytest.mark.parametrize("k", range(6))
def test_si_rod_coefficients_are_the_scaled_rods_at_random_states(si_rod, k):
    m, l, J, g = RNG.uniform(0.2, 5), RNG.uniform(0.1, 2), RNG.uniform(0.01, 1), RNG.uniform(1, 20)
    mu, theta, phi = RNG.uniform(0, 3), RNG.uniform(-np.pi, np.pi), RNG.uniform(-5, 5)
    loads = dict(F_x=RNG.uniform(-5, 5), F_y=RNG.uniform(-5, 5), tau=RNG.uniform(-2, 2))
    floor = dict(y_floor=RNG.uniform(-1, 1), w_floor=RNG.uniform(-1, 1), v_floor=RNG.uniform(-1, 1))
    got = si_rod.at(dict(m=m, l=l, J=J, g=g, mu=mu, theta=theta, phi=phi, y=floor["y_floor"] + 0.3 * l,
                         v=0.2, w=0.0), {**loads, **floor})
    # docs/si_model.md: alpha = m l^2/J, time by sqrt(l/g), forces by m g, torques by m g l
    alpha, mg = m * l * l / J, m * g
    a, b = kinematic_a_b(theta, phi * np.sqrt(l / g), alpha, loads["F_x"] / mg, loads["F_y"] / mg,
                         loads["tau"] / (mg * l))
    expected = dict(a=a, b=b, **delassus.rod(theta, alpha, mu))
    for name in NAMES:
        assert got[name] == pytest.approx(expected[name], rel=1e-10, abs=1e-12), name


def test_the_default_rod_starts_in_the_paradox_region(rod):
    """PainleveRod's defaults (alpha = mu = 3, theta = 1) are a Theorem 1 case: p_plus < 0."""
    got = rod.at({})
    assert got["p_plus"] < 0 < got["p_minus"]
    assert got["p_plus"] == pytest.approx(coef(1.0, 3.0, 3.0)["pp"], rel=1e-14)
